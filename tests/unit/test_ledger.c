/* The ledger (sim/ledger.h) on hand-made accounts, every number worked out here:
 *  - totals are the sums of their parts and stay out of the balance; hidden accounts are in the
 *    balance but not columns; a work account enters with a minus sign;
 *  - the time-centred rule: a force ramping linearly from R0 = (2, 0, 0) N to R1 = (4, 0, 0) N
 *    while its point moves dx = (0.5, 0, 0) m books -(2 + 4)/2 * 0.5 = -1.5 J, the exact work
 *    -int R . dx of the linear ramp, and the impulse -(R0 + R1) dt / 2 = (-0.3, 0, 0) N s for
 *    dt = 0.1 s;
 *  - the energy error is the balance less its first value;
 *  - the checkpoint's records come back unchanged (running and last-evaluated accounts only),
 *    with the initial energy;
 *  - two columns of one name are refused, naming it. */
#include "sim/ledger.h"
#include "test_common.h"

#include <string.h>

static void books(void) {
  pf_ledger l = {0};
  int total, a, b, hidden, work, force, impulse, state;
  PF_TEST_OK(pf_ledger_open(&l, "stored_total", "J", 1, 0, PF_BOOK_STATE, PF_BOOK_NO_BALANCE, -1, &total));
  PF_TEST_OK(pf_ledger_open_error(&l));
  PF_TEST_OK(pf_ledger_open(&l, "a_stored", "J", 1, 1, PF_BOOK_STATE, 0, total, &a));
  PF_TEST_OK(pf_ledger_open(&l, "b_stored", "J", 1, 1, PF_BOOK_LAST, PF_BOOK_SHARED, total, &b));
  PF_TEST_OK(pf_ledger_open(&l, "a_centred", "J", 1, 1, PF_BOOK_STATE, PF_BOOK_HIDDEN, -1, &hidden));
  PF_TEST_OK(pf_ledger_open(&l, "grip_work", "J", 1, -1, PF_BOOK_RUNNING, PF_BOOK_SHARED, -1, &work));
  PF_TEST_OK(pf_ledger_open(&l, "grip_force", "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &force));
  PF_TEST_OK(pf_ledger_open(&l, "grip_impulse", "N s", 3, 0, PF_BOOK_RUNNING, PF_BOOK_SHARED, -1, &impulse));
  PF_TEST_OK(pf_ledger_open(&l, "a_state", "J", 1, 0, PF_BOOK_STATE, 0, -1, &state));
  /* columns: total, error, a, b, grip work, force (3), impulse (3), state; the hidden one not */
  PF_TEST_TRUE(pf_ledger_columns(&l) == 12);
  PF_TEST_TRUE(pf_ledger_find_column(&l, "grip_force_y") == 6);
  PF_TEST_TRUE(pf_ledger_find_column(&l, "a_centred") == -1);
  pf_ledger_add(&l, a, 3.0);
  pf_ledger_set(&l, b, (const double[]){2.0});
  pf_ledger_add(&l, hidden, 5.0);
  pf_ledger_add(&l, state, 100.0); /* not in the balance */
  PF_TEST_OK(pf_ledger_evaluate(&l, 1));
  PF_TEST_CLOSE(pf_ledger_value(&l, total, 0), 3.0 * pf_comm_size() + 2.0, 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_balance(&l), 3.0 * pf_comm_size() + 2.0 + 5.0 * pf_comm_size(), 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_value(&l, l.error_id, 0), 0, 0, 1e-15);
  /* one step of a grip: the force ramps 2 -> 4 N over dx = 0.5 m, dt = 0.1 s */
  pf_ledger_book_centred(&l, work, (const double[]){2, 0, 0}, (const double[]){4, 0, 0}, (const double[]){0.5, 0, 0});
  pf_ledger_book_impulse(&l, impulse, (const double[]){2, 0, 0}, (const double[]){4, 0, 0}, 0.1);
  pf_ledger_set(&l, force, (const double[]){4, 0, 0});
  PF_TEST_OK(pf_ledger_evaluate(&l, 0));
  PF_TEST_CLOSE(pf_ledger_value(&l, work, 0), -1.5, 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_value(&l, impulse, 0), -0.3, 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_value(&l, l.error_id, 0), 1.5, 1e-15, 0); /* - W: -(-1.5) */
  double v[16];
  PF_TEST_OK(pf_ledger_evaluate(&l, 0));
  pf_ledger_values(&l, v);
  PF_TEST_CLOSE(v[4], -1.5, 1e-15, 0);
  PF_TEST_CLOSE(v[5], 4.0, 1e-15, 0);
  /* records: b (1), grip work (1), force (3), impulse (3), then the initial energy */
  const int nr = pf_ledger_records(&l);
  PF_TEST_TRUE(nr == 9);
  char names[9][96];
  pf_ledger_record_names(&l, names);
  PF_TEST_TRUE(!strcmp(names[0], "ledger:b_stored") && !strcmp(names[4], "ledger:grip_force_z") &&
               !strcmp(names[8], "ledger:initial_energy"));
  double rec[9];
  PF_TEST_OK(pf_ledger_record_values(&l, rec));
  PF_TEST_CLOSE(rec[1], -1.5, 1e-15, 0);
  pf_ledger copy = {0};
  int id;
  PF_TEST_OK(pf_ledger_open(&copy, "b_stored", "J", 1, 1, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &id));
  PF_TEST_OK(pf_ledger_open(&copy, "grip_work", "J", 1, -1, PF_BOOK_RUNNING, PF_BOOK_SHARED, -1, &id));
  PF_TEST_OK(pf_ledger_open(&copy, "grip_force", "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &id));
  PF_TEST_OK(pf_ledger_open(&copy, "grip_impulse", "N s", 3, 0, PF_BOOK_RUNNING, PF_BOOK_SHARED, -1, &id));
  PF_TEST_OK(pf_ledger_open_error(&copy));
  pf_ledger_restore(&copy, rec);
  PF_TEST_OK(pf_ledger_evaluate(&copy, 1)); /* the restored initial energy stays */
  PF_TEST_CLOSE(copy.e0, l.e0, 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_value(&copy, 1, 0), -1.5, 1e-15, 0);
  PF_TEST_CLOSE(pf_ledger_value(&copy, 3, 0), -0.3, 1e-15, 0);
  /* a second column of one name */
  pf_error_set_quiet(1);
  pf_error_clear();
  PF_TEST_TRUE(pf_ledger_open(&l, "grip_force", "N", 3, 0, PF_BOOK_LAST, 0, -1, &id) != 0);
  PF_TEST_TRUE(strstr(pf_error_message(), "two columns named 'grip_force'") != NULL);
  pf_error_set_quiet(0);
  pf_ledger_free(&copy);
  pf_ledger_free(&l);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  books();
  return pf_test_finish();
}
