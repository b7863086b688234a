/* A new interaction kind is one file: this one defines a spring between the centres of mass of a
 * simulation's two bodies, registers it, and runs a deck with it, nothing else changed.
 *
 * The spring: U = k (|d| - L0)^2 / 2 with d = c_A - c_B the centres of mass, L0 their distance at
 * the start; the force -dU/dc_A = -k (|d| - L0) d/|d| is spread over A's points by mass (f_i = m_i
 * / M_A F), the opposite one over B's, so that each body takes a uniform acceleration and moves
 * rigidly. Its books: the energy U (stored, <name>_energy) and its force (<name>_force).
 *
 * The check (a closed form, not the code's output): two PMB blocks of masses M_A and M_B, at rest
 * length, flying apart along x at relative speed w oscillate as a harmonic pair, reduced mass
 * mu = M_A M_B / (M_A + M_B), omega = sqrt(k / mu):
 *   x_A - x_B = L0 + (w / omega) sin(omega t).
 * Over 400 steps (a quarter period and a little more) the separation is within 1e-4 of w/omega
 * of it, the energy balance closes to 1e-6 of the energy in play (velocity Verlet on a linear
 * force conserves its centred energy), the total momentum stays as it was to round-off, and the
 * spring's
 columns are in the history. */
#include "sim/sim_impl.h"
#include "test_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SPRING_K 2.0e5 /* N/m */

typedef struct {
  int a, b;                /* the bodies */
  double L0;               /* rest length, m */
  int energy, force;       /* accounts */
  const pf_sim *sim;
} spring;

extern const pf_interaction_ops spring_kind;

static int build(pf_sim *sim) {
  if (sim->nbodies != 2) return 0;
  spring *s = calloc(1, sizeof *s);
  PF_CHECK(s, PF_ERR_MEMORY, "out of memory");
  s->a = 0, s->b = 1, s->L0 = -1, s->sim = sim;
  return pf_sim_interaction_add(sim, &spring_kind, s);
}

static int destroy(void **data) {
  PF_FREE(*data);
  return 0;
}

static int open_accounts(void *data, pf_sim *sim) {
  spring *s = data;
  PF_CALL(pf_ledger_open(&sim->ledger, "spring_energy", "J", 1, 1, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &s->energy));
  return pf_ledger_open(&sim->ledger, "spring_force", "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &s->force);
}

/* The centres of mass of the two bodies (one reduction) and their masses. */
static void centres(const spring *s, const pf_points *p, double c[2][3], double M[2]) {
  double x[8] = {0};
  const int body[2] = {s->a, s->b};
  for (int q = 0; q < 2; q++)
    for (pf_int i = s->sim->body_start[body[q]]; i < s->sim->body_start[body[q] + 1]; i++) {
      for (int k = 0; k < 3; k++) x[4 * q + k] += p->m[i] * p->y[3 * i + k];
      x[4 * q + 3] += p->m[i];
    }
  MPI_Allreduce(MPI_IN_PLACE, x, 8, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (int q = 0; q < 2; q++) {
    M[q] = x[4 * q + 3];
    for (int k = 0; k < 3; k++) c[q][k] = x[4 * q + k] / M[q];
  }
}

static int force(void *data, const pf_interaction_step *st, double *sums) {
  (void)sums;
  spring *s = data;
  double c[2][3], M[2], d[3], r = 0;
  centres(s, st->pts, c, M);
  for (int k = 0; k < 3; k++) d[k] = c[0][k] - c[1][k], r += d[k] * d[k];
  r = sqrt(r);
  if (s->L0 < 0) s->L0 = r; /* at rest at the start */
  double F[3], U = 0.5 * SPRING_K * (r - s->L0) * (r - s->L0);
  for (int k = 0; k < 3; k++) F[k] = -SPRING_K * (r - s->L0) * d[k] / r; /* on A */
  const int body[2] = {s->a, s->b};
  for (int q = 0; q < 2; q++)
    for (pf_int i = s->sim->body_start[body[q]]; i < s->sim->body_start[body[q] + 1]; i++)
      for (int k = 0; k < 3; k++) st->pts->f[3 * i + k] += (q ? -1 : 1) * st->pts->m[i] / M[q] * F[k];
  pf_ledger_set(st->ledger, s->energy, &U);
  pf_ledger_set(st->ledger, s->force, F);
  return 0;
}

const pf_interaction_ops spring_kind = {
    .kind = "spring", .build = build, .destroy = destroy, .open_accounts = open_accounts, .force = force};

static const char *const deck =
    "materials: {glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
    "bodies:\n"
    "  - {name: a, material: glass, horizon: 0.0015001, initial_velocity: ['1', '0', '0'],\n"
    "     geometry: {shape: box, lo: [0.004, 0, 0], hi: [0.006, 0.002, 0.002], spacing: 0.0005}}\n"
    "  - {name: b, material: glass, horizon: 0.0015001, initial_velocity: ['-1', '0', '0'],\n"
    "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.003, 0.002, 0.002], spacing: 0.0005}}\n"
    "time: {steps: 400}\n"
    "output: {interval: 0, history_interval: 10}\n";

static double column(pf_sim *sim, const char *name) {
  pf_sim_history_row *g = pf_sim_history(sim);
  for (int k = 0; g && k < g->n + 2; k++)
    if (!strcmp(g->names[k], name)) return g->values[k];
  pf_test_true(0, name, __FILE__, __LINE__);
  return NAN;
}

static void spring_pair(void) {
  PF_TEST_OK(pf_interaction_kind_register(&spring_kind));
  pf_sim *sim = pf_test_sim("spring", deck);
  PF_TEST_OK(pf_sim_run_begin(sim));
  const double p0 = column(sim, "momentum_x"); /* (M_A - M_B) 1 m/s */
  double c[2][3], M[2];
  spring probe = {0, 1, 0, 0, 0, sim};
  centres(&probe, sim->pts, c, M);
  const double L0 = c[0][0] - c[1][0], w = 2.0, mu = M[0] * M[1] / (M[0] + M[1]), omega = sqrt(SPRING_K / mu);
  const double E = 0.5 * mu * w * w; /* the energy in play */
  double worst_x = 0, worst_e = 0, worst_p = 0;
  for (int row = 0; row < 40; row++) {
    PF_TEST_OK(pf_sim_run_advance(sim, 10));
    const double t = column(sim, "time");
    const double sep = column(sim, "a_position_x") - column(sim, "b_position_x");
    worst_x = fmax(worst_x, fabs(sep - (L0 + w / omega * sin(omega * t))));
    worst_e = fmax(worst_e, fabs(column(sim, "energy_error")));
    worst_p = fmax(worst_p, fabs(column(sim, "momentum_x") - p0));
    PF_TEST_TRUE(isfinite(column(sim, "spring_energy")) && isfinite(column(sim, "spring_force_x")));
  }
  PF_TEST_TRUE(omega * column(sim, "time") > 2 * atan(1.0)); /* past a quarter period */
  PF_TEST_CLOSE(worst_x, 0, 0, 1e-4 * w / omega);
  PF_TEST_CLOSE(worst_e, 0, 0, 1e-6 * E);
  PF_TEST_CLOSE(worst_p, 0, 0, 1e-12 * mu * w);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  spring_pair();
  return pf_test_finish();
}
