/* The whole chain PD -> transition -> overlap -> FE in 3-D (issue 7, test 3): one hexahedral
 * mesh (Pamgen, 48 x 18 x 18 elements of h = 1 mm) of elastic steel (rho = 7800, E = 200 GPa,
 * nu = 0) whose nodes also carry a correspondence operator (docs/theory/coupling.md §3):
 *   PD region x < 14 mm (horizon 3.01 h, beta = 1, no elements),
 *   transition 14-24 mm (horizon tapering to 1.01 h: partial stress at interior nodes),
 *   overlap 24-34 mm (beta falls linearly from 1 to 0),
 *   FE region x > 34 mm (beta = 0).
 * A linear displacement must give zero force at every interior node (at least 2 x 3.01 h from
 * the faces) to round-off: below 1e-9 of E eps / (rho h). A quadratic u_a = (1/2) Q_abc X_b X_c
 * must give the constant rho a_a = E sum_b (Q_abb + Q_bab) / 2 (sigma = E eps at nu = 0, derived
 * here) within 2 % at every interior node, on both sides of every interface. To show that the
 * test discriminates, the same chain with the standard PD form (ghost forces in the taper) must
 * miss both; the corrected form (the standard one less its uniform-stress ghost force) and the
 * consistent form (the energy form with ghost-free gradient weights) must pass the linear test;
 * their quadratic errors are printed (docs/theory/coupling.md §2.5, §2.6), the consistent form's
 * must be below half the standard form's. The displacement is imposed as one step of dt from rest (v = u / dt), as in
 * tests/verification/test_partial_stress.c, on owned and ghost nodes: any number of ranks. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/sim.h"
#include "fem/fem.h"

enum { NX = 48, NY = 18 };
static const double h = 1e-3, E = 200e9, RHO = 7800, EPS = 1e-6, DT = 1e-7;

static pf_sim *make(const char *form, const char *overlap) {
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200e9, poissons_ratio: 0}}\n"
           "bodies:\n"
           "  - name: bar\n"
           "    type: finite_element\n"
           "    material: steel\n"
           "    hourglass: {type: stiffness, coefficient: 0.05}\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    peridynamic:\n"
           "      horizon: \"3.01e-3 - 2e-3 * min(max((x - 0.014) / 0.010, 0), 1)\"\n"
           "      blending: \"1 - min(max((x - 0.024) / 0.010, 0), 1)\"\n"
           "      formulation: %s\n"
           "      overlap: %s\n"
           "      hourglass: {type: none}\n"
           "%s"
           "time: {steps: 0, dt: 1e-9}\n",
           form, overlap, pf_test_pamgen_box(NX, NY, NY, (const double[3]){0, 0, 0}, (const double[3]){NX * h, NY * h, NY * h}));
  return pf_test_sim("coupling_patch", deck);
}

typedef struct {
  double G[3][3], Q[3][3][3];
} field;

static int interior(const double X[3]) {
  const double d = 2 * 3.01 * h - 1e-9, L[3] = {NX * h, NY * h, NY * h};
  for (int a = 0; a < 3; a++)
    if (X[a] < d || X[a] > L[a] - d) return 0;
  return 1;
}

/* Impose u in one step; the largest |a - want| over interior nodes, and over those of each region. */
static double run(const char *form, const char *overlap, const field *u, const double want[3],
                  double worst_by_region[4]) {
  pf_sim *sim = make(form, overlap);
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_total; i++) /* owned and ghost nodes: the kernels read both */
    for (int a = 0; a < 3; a++) {
      const double *X = &p->X[3 * i];
      double d = 0;
      for (int b = 0; b < 3; b++) {
        d += u->G[a][b] * X[b];
        for (int c = 0; c < 3; c++) d += 0.5 * u->Q[a][b][c] * X[b] * X[c];
      }
      p->v[3 * i + a] = d / DT, p->u[3 * i + a] = d, p->y[3 * i + a] = X[a] + d, p->f[3 * i + a] = 0;
    }
  PF_TEST_OK(pf_sim_body_force(sim, 0, DT));
  double worst = 0;
  for (int r = 0; r < 4; r++) worst_by_region[r] = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double *X = &p->X[3 * i];
    if (!interior(X)) continue;
    double e2 = 0;
    for (int a = 0; a < 3; a++) e2 += pow(p->f[3 * i + a] / p->m[i] - want[a], 2);
    const int r = X[0] < 0.014 ? 0 : X[0] < 0.024 ? 1 : X[0] <= 0.034 ? 2 : 3;
    worst_by_region[r] = fmax(worst_by_region[r], sqrt(e2));
    worst = fmax(worst, sqrt(e2));
  }
  pf_test_print_digest(form, sim);
  pf_sim_destroy(&sim);
  for (int r = 0; r < 4; r++) worst_by_region[r] = pf_max_all(worst_by_region[r]);
  return pf_max_all(worst);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double L = NX * h, zero[3] = {0, 0, 0}, scale = E * EPS / (RHO * h);
  field lin = {{{EPS, 0.4 * EPS, -0.3 * EPS}, {0.2 * EPS, -0.7 * EPS, 0.5 * EPS}, {-0.6 * EPS, 0.3 * EPS, 0.8 * EPS}}, {{{0}}}};
  field quad = {{{0}}, {{{0}}}};
  const double q[3][3][3] = {{{1.0, 0.3, -0.2}, {0.3, 0.5, 0.4}, {-0.2, 0.4, -0.6}},
                             {{0.2, -0.5, 0.1}, {-0.5, 0.9, 0.3}, {0.1, 0.3, 0.4}},
                             {{-0.4, 0.2, 0.6}, {0.2, 0.3, -0.1}, {0.6, -0.1, 0.7}}};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) quad.Q[a][b][c] = q[a][b][c] * EPS / L;
  double want[3] = {0, 0, 0}, reg[4];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) want[a] += 0.5 * (quad.Q[a][b][b] + quad.Q[b][a][b]) * E / RHO;
  const double amag = sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]);

  /* the old defaults (partial stress in the transition, force blending), the discriminating
   * standard form, the corrected form, the consistent form with force blending; then the
   * default, the consistent form with the energy overlap, and the energy overlap uncorrected */
  const double lin_auto = run("auto", "force", &lin, zero, reg) / scale;
  if (pf_comm_rank() == 0) printf("linear, auto + force: max|a| / (E eps / rho h) %.2e (PD %.1e, transition %.1e, overlap %.1e, FE %.1e)\n",
         lin_auto, reg[0] / scale, reg[1] / scale, reg[2] / scale, reg[3] / scale);
  const double lin_std = run("standard", "force", &lin, zero, reg) / scale;
  if (pf_comm_rank() == 0) printf("linear, standard + force: %.2e\n", lin_std);
  const double quad_auto = run("auto", "force", &quad, want, reg) / amag;
  if (pf_comm_rank() == 0) printf("quadratic, auto + force: max|a - a_exact| / |a_exact| (|a_exact| = %.4g m/s^2) %.2e (PD %.1e, transition "
         "%.1e, overlap %.1e, FE %.1e)\n", amag, quad_auto, reg[0] / amag, reg[1] / amag, reg[2] / amag, reg[3] / amag);
  const double quad_std = run("standard", "force", &quad, want, reg) / amag;
  if (pf_comm_rank() == 0) printf("quadratic, standard + force: %.2e\n", quad_std);
  const double lin_corr = run("corrected", "force", &lin, zero, reg) / scale, quad_corr = run("corrected", "force", &quad, want, reg) / amag;
  if (pf_comm_rank() == 0) printf("corrected + force: linear %.2e, quadratic %.2e\n", lin_corr, quad_corr);
  const double lin_cons = run("consistent", "force", &lin, zero, reg) / scale, quad_cons = run("consistent", "force", &quad, want, reg) / amag;
  if (pf_comm_rank() == 0) printf("consistent + force: linear %.2e, quadratic %.2e\n", lin_cons, quad_cons);
  const double lin_en = run("consistent", "energy", &lin, zero, reg) / scale;
  if (pf_comm_rank() == 0) printf("linear, consistent + energy: %.2e (PD %.1e, transition %.1e, overlap %.1e, FE %.1e)\n",
         lin_en, reg[0] / scale, reg[1] / scale, reg[2] / scale, reg[3] / scale);
  const double quad_en = run("consistent", "energy", &quad, want, reg) / amag;
  if (pf_comm_rank() == 0) printf("quadratic, consistent + energy: %.2e (PD %.1e, transition %.1e, overlap %.1e, FE %.1e); standard + force %.2e\n",
         quad_en, reg[0] / amag, reg[1] / amag, reg[2] / amag, reg[3] / amag, quad_std);
  const char *regions[4] = {"pd", "transition", "overlap", "fe"};
  char key[64];
  for (int r = 0; r < 4; r++) {
    snprintf(key, sizeof key, "quadratic_default_%s", regions[r]);
    pf_test_measure(key, reg[r] / amag, "1");
  }
  pf_test_measure("linear_default", lin_en, "1");
  pf_test_measure("quadratic_default", quad_en, "1");
  pf_test_measure("linear_auto", lin_auto, "1");
  pf_test_measure("quadratic_auto", quad_auto, "1");
  pf_test_measure("linear_consistent_force", lin_cons, "1");
  pf_test_measure("quadratic_consistent_force", quad_cons, "1");
  pf_test_measure("linear_corrected_force", lin_corr, "1");
  pf_test_measure("quadratic_corrected_force", quad_corr, "1");
  pf_test_measure("linear_standard", lin_std, "1");
  pf_test_measure("quadratic_standard", quad_std, "1");
  PF_TEST_TRUE(lin_corr < 1e-9);
  PF_TEST_TRUE(lin_cons < 1e-9);
  PF_TEST_TRUE(quad_cons < 0.5 * quad_std);
  PF_TEST_TRUE(lin_en < 1e-9);
  PF_TEST_TRUE(quad_en < 0.5 * quad_std);
  PF_TEST_TRUE(lin_auto < 1e-9);
  PF_TEST_TRUE(quad_auto < 0.02);
  PF_TEST_TRUE(lin_std > 1e-3);
  PF_TEST_TRUE(quad_std > 0.02);
  return pf_test_finish();
}
