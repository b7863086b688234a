/* The ledger (docs/architecture.md §4b): one book of every energy, work, impulse and figure the
 * run reports. Bodies and interactions open accounts at set-up and book into them during the
 * step; the history's columns, the checkpoint's records, the energy balance and the run-health
 * monitor's figures are all generated from the accounts, so adding a quantity is one
 * pf_ledger_open and its bookings. Private to sim/.
 *
 * An account is a scalar or a 3-vector with a name (its history column; a vector's columns are
 * name_x, name_y, name_z), units and:
 *   sign   its place in the energy balance: +1 energy held or gone (kinetic as velocity Verlet
 *          conserves it, stored, dissipated), -1 work done on the points from outside, 0 a figure
 *          that is not an energy (momentum, force, impulse, a count, a ratio);
 *   kind   PF_BOOK_RUNNING: a running sum booked step by step (work, dissipation, impulse),
 *          kept in checkpoints; PF_BOOK_STATE: set at each evaluation from the state (kinetic or
 *          stored energy, momentum); PF_BOOK_LAST: set at the last force evaluation (a reaction,
 *          a penalty energy), kept in checkpoints because a restart does not evaluate the forces
 *          again before its first row;
 *   flags  PF_BOOK_SHARED: every rank holds the same value (else each rank books the part of its
 *          own points and the ledger sums the ranks); PF_BOOK_HIDDEN: in the balance, not a
 *          column; PF_BOOK_NO_BALANCE: a column only (a total's parts are in the balance).
 * An account may add into a total (another account, e.g. each body's damage dissipation into
 * the run's): totals are filled at each evaluation and stay out of the balance.
 *
 * One rule for work and impulse (time-centred, second order in the step): the work of a force
 * R over a step in which its point of application moves by dx is booked as -(R^n + R^(n+1))/2 .
 * dx (R the force on the surface or wall, so minus that on the points), its impulse as
 * -(R^n + R^(n+1)) dt / 2 (pf_ledger_book_centred). */
#ifndef PF_SIM_LEDGER_H
#define PF_SIM_LEDGER_H

#include "core/core.h"

typedef enum { PF_BOOK_RUNNING, PF_BOOK_STATE, PF_BOOK_LAST } pf_book_kind;
enum { PF_BOOK_SHARED = 1, PF_BOOK_HIDDEN = 2, PF_BOOK_NO_BALANCE = 4 };

typedef struct {
  char name[128];
  const char *units;
  int ncomp;  /* 1 or 3 */
  int sign;   /* +1, -1, 0 (see above) */
  pf_book_kind kind;
  int flags;
  int total;          /* the account it adds into, or -1 */
  double local[3];    /* this rank's booking (PF_BOOK_SHARED: the value) */
  double value[3];    /* over the ranks, at the last pf_ledger_evaluate */
} pf_account;

typedef struct pf_ledger {
  int n, cap;
  pf_account *a;
  int error_id;    /* the energy_error column */
  double e0;       /* the balance at the start of the run (kept across restarts) */
  int have_e0;
  double *buf;     /* [2 n] the reduction's buffer */
} pf_ledger;

/* Open an account; *id its handle. units: a string literal. An account of a name already open
 * is an input error naming the column (two owners named alike). */
int pf_ledger_open(pf_ledger *l, const char *name, const char *units, int ncomp, int sign, pf_book_kind kind,
                   int flags, int total, int *id);
/* The energy_error column (the balance minus its initial value); opened once, where it stands. */
int pf_ledger_open_error(pf_ledger *l);
void pf_ledger_free(pf_ledger *l);
/* Every account's booking on this rank into v[3 n] (n the accounts open now), and back from it:
 * the quasi-static solver keeps them at a load step's start and puts them back when a signal
 * abandons the load step. */
void pf_ledger_keep(const pf_ledger *l, double *v);
void pf_ledger_put_back(pf_ledger *l, const double *v);

/* Book x[ncomp] into an account (added to this rank's part), or set it. */
static inline void pf_ledger_book(pf_ledger *l, int id, const double *x) {
  pf_account *a = &l->a[id];
  for (int c = 0; c < a->ncomp; c++) a->local[c] += x[c];
}
static inline void pf_ledger_add(pf_ledger *l, int id, double x) { l->a[id].local[0] += x; }
static inline void pf_ledger_set(pf_ledger *l, int id, const double *x) {
  pf_account *a = &l->a[id];
  for (int c = 0; c < a->ncomp; c++) a->local[c] = x[c];
}
/* The time-centred rule: add -(r_old + r_new) / 2 . w to a scalar account (work: w the step's
 * displacement of the point of application; r the force of the points on it), or
 * -(r_old + r_new) / 2 * s to each component of a vector account (impulse: s = dt). */
void pf_ledger_book_centred(pf_ledger *l, int id, const double r_old[3], const double r_new[3], const double w[3]);
void pf_ledger_book_impulse(pf_ledger *l, int id, const double r_old[3], const double r_new[3], double dt);
/* This rank's part of an account into x[ncomp] (a shared account's value: a reaction). */
static inline void pf_ledger_get(const pf_ledger *l, int id, double *x) {
  for (int c = 0; c < l->a[id].ncomp; c++) x[c] = l->a[id].local[c];
}
/* This rank's part, and the value over the ranks at the last evaluation. */
static inline double pf_ledger_local(const pf_ledger *l, int id, int c) { return l->a[id].local[c]; }
static inline double pf_ledger_value(const pf_ledger *l, int id, int c) { return l->a[id].value[c]; }

/* Sum every account over the ranks (one reduction), fill the totals and the energy error.
 * first: the balance now is the run's initial one (unless a restart gave it). Collective. */
int pf_ledger_evaluate(pf_ledger *l, int first);
/* The balance: the signed sum of the accounts in it, J (after pf_ledger_evaluate). */
double pf_ledger_balance(const pf_ledger *l);

/* The history's columns: count, each one's name into buf and units, and the values in the same
 * order (after pf_ledger_evaluate). */
int pf_ledger_columns(const pf_ledger *l);
void pf_ledger_column(const pf_ledger *l, int k, char *buf, size_t len, const char **units);
void pf_ledger_values(const pf_ledger *l, double *v);
/* The index of column `name` in that order, or -1. */
int pf_ledger_find_column(const pf_ledger *l, const char *name);

/* The checkpoint's records: the running and last-evaluated accounts, one scalar per component,
 * named "ledger:<column>", then "ledger:initial_energy". _records counts them; _record_names
 * writes them into names[k] (96 characters); _record_values fills v (the sums over the ranks:
 * collective); _restore takes them back (rank 0 carries the summed parts). */
int pf_ledger_records(const pf_ledger *l);
void pf_ledger_record_names(const pf_ledger *l, char (*names)[96]);
int pf_ledger_record_values(pf_ledger *l, double *v);
void pf_ledger_restore(pf_ledger *l, const double *v);

#endif
