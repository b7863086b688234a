/* The energy form of the PD/FE overlap (docs/theory/coupling.md §3.4): the forces of
 * E = sum_i beta_i W_i V_i + sum_e (1 - beta_e) W_e V_e against force blending, on one hexahedral
 * mesh of h = 1 mm whose nodes also carry a correspondence operator (constant horizon 3.01 h,
 * standard form, so the overlap alone is under test).
 * (a) Conservation. An elastic steel bar 30 x 8 x 8 mm, PD for x < 14 mm, beta falling linearly
 *     to 0 at 20 mm, FE beyond; its first 4 mm start at -150 m/s. The references are the laws
 *     themselves: no external force acts, so the linear momentum and the energy (kinetic plus
 *     the booked stored energies) must stay at their initial values. The step's own error
 *     (velocity Verlet on the velocity jump, bounded, not a drift) is that of the same bar all
 *     peridynamic (beta = 1), about 1.5e-3 of the initial kinetic energy. Energy form, over 150
 *     steps: momentum within 1e-12 of |p0| (round-off), energy within 1.5 times the all-PD
 *     bar's error. Force form, to show that the test discriminates: both must miss by more than
 *     1e-3.
 * (b) Ghost forces. A linear displacement (every component of grad u set) imposed in one step from
 *     rest on a 40 x 14 x 14 mesh with the overlap from 12 to 28 mm: the accelerations of the
 *     interior nodes, against zero. In the overlap's interior (beta linear over the whole
 *     horizon) the PD operator's ghost force +V_i sigma grad beta and the elements'
 *     -V_i sigma grad beta cancel exactly for a uniform stress on a uniform mesh: below 1e-9 of
 *     E eps / (rho h). Where the horizon reaches a kink of beta (its two ends) they do not: that
 *     error is printed, with the force form's (zero). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

static const double h = 1e-3, E = 200e9, RHO = 7800, EPS = 1e-6, DT = 1e-7;

static pf_sim *bar(const char *form, const char *beta, const char *formulation) {
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200e9, poissons_ratio: 0.3}}\n"
           "bodies:\n"
           "  - name: bar\n"
           "    type: finite_element\n"
           "    material: steel\n"
           "    initial_velocity: [\"x < 0.004 ? -150 : 0\", \"0\", \"0\"]\n"
           "    peridynamic:\n"
           "      horizon: 3.01e-3\n"
           "      blending: \"%s\"\n"
           "      formulation: %s\n"
           "      overlap: %s\n"
           "%s"
           "time: {steps: 150}\n",
           beta, formulation, form, pf_test_pamgen_box(30, 8, 8, (const double[3]){0, 0, 0}, (const double[3]){0.030, 0.008, 0.008}));
  return pf_test_sim("overlap_bar", deck);
}

static double stored(const pf_sim_globals *g) {
  return g->kinetic_centred + g->elastic + g->fe_internal + g->hourglass + g->bulk_viscosity;
}

/* Largest momentum change over |p0| and energy change over KE0 in any step. */
static void conservation(const char *form, const char *beta, const char *formulation, double *dp, double *de) {
  pf_sim *sim = bar(form, beta, formulation);
  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_step(sim, 1));
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  const double p0 = sqrt(g0.momentum[0] * g0.momentum[0] + g0.momentum[1] * g0.momentum[1] +
                         g0.momentum[2] * g0.momentum[2]);
  *dp = *de = 0;
  while (!pf_sim_finished(sim)) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    for (int a = 0; a < 3; a++) *dp = fmax(*dp, fabs(g.momentum[a] - g0.momentum[a]) / p0);
    *de = fmax(*de, fabs(stored(&g) - stored(&g0)) / g0.kinetic);
  }
  pf_test_print_digest(form, sim);
  pf_sim_destroy(&sim);
}

enum { NX = 40, NY = 14 };
static const double X0 = 0.012, X1 = 0.028; /* the overlap */

static pf_sim *block(const char *form, const char *formulation) {
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200e9, poissons_ratio: 0}}\n"
           "bodies:\n"
           "  - name: block\n"
           "    type: finite_element\n"
           "    material: steel\n"
           "    hourglass: {type: stiffness, coefficient: 0.05}\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    peridynamic:\n"
           "      horizon: 3.01e-3\n"
           "      blending: \"1 - min(max((x - %g) / %g, 0), 1)\"\n"
           "      formulation: %s\n"
           "      overlap: %s\n"
           "      hourglass: {type: none}\n"
           "%s"
           "time: {steps: 0, dt: 1e-9}\n",
           X0, X1 - X0, formulation, form,
           pf_test_pamgen_box(NX, NY, NY, (const double[3]){0, 0, 0}, (const double[3]){NX * h, NY * h, NY * h}));
  return pf_test_sim("overlap_block", deck);
}

static int interior(const double X[3]) {
  const double d = 2 * 3.01 * h - 1e-9, L[3] = {NX * h, NY * h, NY * h};
  for (int a = 0; a < 3; a++)
    if (X[a] < d || X[a] > L[a] - d) return 0;
  return 1;
}

/* Largest |a| over interior nodes: [0] where beta is linear over the whole horizon, [1] where the
 * horizon reaches one of beta's kinks, [2] elsewhere (PD and FE regions). */
static void ghost(const char *form, const char *formulation, double worst[3]) {
  static const double G[3][3] = {{1.0, 0.4, -0.3}, {0.2, -0.7, 0.5}, {-0.6, 0.3, 0.8}};
  pf_sim *sim = block(form, formulation);
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_total; i++) /* owned and ghost nodes: the kernels read both */
    for (int a = 0; a < 3; a++) {
      const double *X = &p->X[3 * i];
      const double d = EPS * (G[a][0] * X[0] + G[a][1] * X[1] + G[a][2] * X[2]);
      p->v[3 * i + a] = d / DT, p->u[3 * i + a] = d, p->y[3 * i + a] = X[a] + d, p->f[3 * i + a] = 0;
    }
  PF_TEST_OK(pf_sim_body_force(sim, 0, DT));
  worst[0] = worst[1] = worst[2] = 0;
  const double delta = 3.01 * h + 1e-9;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double *X = &p->X[3 * i];
    if (!interior(X)) continue;
    const double a = sqrt(pow(p->f[3 * i], 2) + pow(p->f[3 * i + 1], 2) + pow(p->f[3 * i + 2], 2)) / p->m[i];
    const int where = X[0] >= X0 + delta && X[0] <= X1 - delta ? 0 : X[0] > X0 - delta && X[0] < X1 + delta ? 1 : 2;
    worst[where] = fmax(worst[where], a);
  }
  pf_test_print_digest(form, sim);
  pf_sim_destroy(&sim);
  for (int r = 0; r < 3; r++) worst[r] = pf_max_all(worst[r]) / (E * EPS / (RHO * h));
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *overlap = "1 - min(max((x - 0.014) / 0.006, 0), 1)";
  double dp_e, de_e, dp_c, de_c, dp_f, de_f, dp_pd, de_pd;
  conservation("energy", overlap, "standard", &dp_e, &de_e);
  conservation("energy", overlap, "consistent", &dp_c, &de_c); /* the kinks' weights corrected */
  conservation("force", overlap, "standard", &dp_f, &de_f);
  conservation("energy", "1", "standard", &dp_pd, &de_pd); /* the same bar all peridynamic */
  double ge[3], gc[3], gf[3];
  ghost("energy", "standard", ge);
  ghost("energy", "consistent", gc);
  ghost("force", "standard", gf);
  if (pf_comm_rank() == 0) {
    printf("conservation over 150 steps: energy form momentum %.2e of |p0|, energy %.2e of KE0; corrected "
           "kinks %.2e, %.2e; force form %.2e, %.2e; all PD %.2e, %.2e\n", dp_e, de_e, dp_c, de_c, dp_f, de_f,
           dp_pd, de_pd);
    printf("ghost accelerations / (E eps / rho h): energy form overlap interior %.2e, near beta's kinks "
           "%.2e, PD and FE regions %.2e; corrected kinks (consistent) %.2e, %.2e, %.2e; force form %.2e, "
           "%.2e, %.2e\n", ge[0], ge[1], ge[2], gc[0], gc[1], gc[2], gf[0], gf[1], gf[2]);
  }
  PF_TEST_TRUE(dp_e < 1e-12);
  PF_TEST_TRUE(de_e < 1.5 * de_pd && de_pd < 5e-3);
  PF_TEST_TRUE(dp_c < 1e-12);
  PF_TEST_TRUE(de_c < 1.5 * de_pd);
  PF_TEST_TRUE(dp_f > 1e-3);
  PF_TEST_TRUE(de_f > 1e-3);
  PF_TEST_TRUE(ge[0] < 1e-9);
  PF_TEST_TRUE(ge[1] > 1e-3); /* the uncorrected kinks: the test discriminates */
  PF_TEST_TRUE(ge[2] < 1e-9);
  PF_TEST_TRUE(gc[0] < 1e-9 && gc[1] < 1e-9 && gc[2] < 1e-9);
  PF_TEST_TRUE(gf[0] < 1e-9 && gf[1] < 1e-9 && gf[2] < 1e-9);
  return pf_test_finish();
}
