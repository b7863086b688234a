/* Patch tests of the partial-stress form (Littlewood 2014, "Patch tests for partial
 * stress formulation"; issue 7, tests 1-2): an elastic correspondence bar (rho = 7800,
 * E = 200 GPa, nu = 0, no hourglass control) under a prescribed displacement, with a constant
 * horizon (3.01 dx) and with one that tapers from 3.01 dx to 1.01 dx along the bar, in the
 * standard and in the partial-stress form.
 *
 * Fields: "1-D" u = u(x) e_x (uniaxial), "3-D" a general u(x, y, z). Linear u = G X: every point
 * has Fbar = I + G, so the partial stress is the same everywhere and the acceleration must vanish
 * to round-off (below 1e-9 of the scale E eps / (rho dx)); the standard form with the varying
 * horizon must show ghost forces (above 1e-3 of it), or the test could not tell the forms apart.
 * Quadratic u_a = (1/2) Q_abc X_b X_c: sigma = E eps (nu = 0), so rho a_a = E sum_b (Q_abb + Q_bab) / 2,
 * a constant (derived here, not taken from the code); the partial-stress form must give it within
 * 1 % at every interior point for both horizons, the standard form with the varying horizon must
 * miss it by more. formulation: auto (partial stress at the interior points whose family reaches
 * another horizon, standard elsewhere) must pass both, the standard points next to partial-stress
 * ones included. formulation: corrected (the standard force less its uniform-stress ghost force)
 * must pass the linear test; under the quadratic field it is not exact, and must only beat the
 * standard form by a factor of 4 (its error is printed). formulation: consistent (the energy
 * form with ghost-free gradient weights, docs/theory/coupling.md §2.6) must pass the linear test
 * and beat the standard form by a factor of 2 under the quadratic field (its error is printed). Interior: at least 2 delta_max from every face (a point's neighbours' families
 * are complete there).
 *
 * The displacement is imposed as the integrator would move the body: one step of dt with
 * v = u / dt from the reference state (tests/unit/test_pd_conformance.c explains why a rate-form
 * model needs it), strains ~1e-6 so the rate form's O(eps^2) departure from C : eps is far below
 * the tolerances. The LPS partial stress is measured too (printed, and checked to reduce the
 * standard form's ghost force): on a lattice its partial stress depends on the family's shape, so
 * it is not exact under a varying horizon (docs/theory/coupling.md §2.3). Any number of ranks
 * (the displacement is imposed on the ghosts too; the worst values are reduced). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/sim.h"

enum { NX = 46, NY = 17 };
static const double h = 1e-3, E = 200e9, RHO = 7800, EPS = 1e-6, DT = 1e-7;
static const char *VARYING = "3.01e-3 - 2e-3 * min(max((x - 0.014) / 0.016, 0), 1)";

static pf_sim *make(const char *model, const char *horizon, const char *form) {
  char deck[2048];
  const char *mat = !strcmp(model, "lps")
                        ? "{model: lps, density: 7800, bulk_modulus: 66.6666666666667e9, shear_modulus: 100e9}"
                        : "{model: elastic, density: 7800, youngs_modulus: 200e9, poissons_ratio: 0}";
  snprintf(deck, sizeof deck,
           "materials: {steel: %s}\n"
           "bodies:\n  - {name: bar, material: steel, horizon: \"%s\", formulation: %s,%s\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           mat, horizon, form, strcmp(model, "lps") ? " hourglass: {type: none}," : "",
           (NX - 1) * h, (NY - 1) * h, (NY - 1) * h, h);
  return pf_test_sim("partial_stress", deck);
}

typedef struct {
  double G[3][3];    /* linear part */
  double Q[3][3][3]; /* quadratic part, symmetric in the last two indices */
} field;

static void displacement(const field *u, const double X[3], double out[3]) {
  for (int a = 0; a < 3; a++) {
    out[a] = 0;
    for (int b = 0; b < 3; b++) {
      out[a] += u->G[a][b] * X[b];
      for (int c = 0; c < 3; c++) out[a] += 0.5 * u->Q[a][b][c] * X[b] * X[c];
    }
  }
}

/* rho a_a = E sum_b (Q_abb + Q_bab) / 2 for sigma = E eps (nu = 0). */
static void exact_acceleration(const field *u, double a_out[3]) {
  for (int a = 0; a < 3; a++) {
    a_out[a] = 0;
    for (int b = 0; b < 3; b++) a_out[a] += 0.5 * (u->Q[a][b][b] + u->Q[b][a][b]) * E / RHO;
  }
}

static int interior(const double X[3]) {
  const double d = 2 * 3.01 * h, L[3] = {(NX - 1) * h, (NY - 1) * h, (NY - 1) * h};
  for (int a = 0; a < 3; a++)
    if (X[a] < d || X[a] > L[a] - d) return 0;
  return 1;
}

/* Impose u in one step and return the largest |a - want| over the interior points. */
static double run(const char *model, const char *horizon, const char *form, const field *u, const double want[3]) {
  pf_sim *sim = make(model, horizon, form);
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_total; i++) { /* owned and ghost points: the kernels read both */
    double d[3];
    displacement(u, &p->X[3 * i], d);
    for (int a = 0; a < 3; a++) {
      p->v[3 * i + a] = d[a] / DT;
      p->u[3 * i + a] = d[a];
      p->y[3 * i + a] = p->X[3 * i + a] + d[a];
      p->f[3 * i + a] = 0;
    }
  }
  PF_TEST_OK(pf_pd_body_force(pf_sim_body(sim, 0), p, DT));
  double worst = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    if (!interior(&p->X[3 * i])) continue;
    double e2 = 0;
    for (int a = 0; a < 3; a++) e2 += pow(p->f[3 * i + a] / p->m[i] - want[a], 2);
    worst = fmax(worst, sqrt(e2));
  }
  pf_test_print_digest(form, sim);
  pf_sim_destroy(&sim);
  return pf_max_all(worst);
}

static void linear_cases(const char *name, const field *u) {
  const double zero[3] = {0, 0, 0}, scale = E * EPS / (RHO * h);
  const double ps_c = run("elastic", "3.01e-3", "partial_stress", u, zero);
  const double ps_v = run("elastic", VARYING, "partial_stress", u, zero);
  const double st_c = run("elastic", "3.01e-3", "standard", u, zero);
  const double st_v = run("elastic", VARYING, "standard", u, zero);
  const double au_v = run("elastic", VARYING, "auto", u, zero);
  const double co_v = run("elastic", VARYING, "corrected", u, zero);
  const double cn_v = run("elastic", VARYING, "consistent", u, zero);
  if (pf_comm_rank() == 0) printf("%s linear: max|a| / (E eps / rho dx): partial stress %.2e (constant delta) %.2e (varying); "
         "standard %.2e (constant) %.2e (varying); auto %.2e, corrected %.2e, consistent %.2e (varying)\n", name, ps_c / scale,
         ps_v / scale, st_c / scale, st_v / scale, au_v / scale, co_v / scale, cn_v / scale);
  PF_TEST_TRUE(cn_v < 1e-9 * scale);
  PF_TEST_TRUE(au_v < 1e-9 * scale);
  PF_TEST_TRUE(co_v < 1e-9 * scale);
  PF_TEST_TRUE(ps_c < 1e-9 * scale);
  PF_TEST_TRUE(ps_v < 1e-9 * scale);
  PF_TEST_TRUE(st_c < 1e-9 * scale);
  PF_TEST_TRUE(st_v > 1e-3 * scale); /* ghost forces: the test discriminates */
}

static void quadratic_cases(const char *name, const field *u) {
  double want[3];
  exact_acceleration(u, want);
  const double amag = sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]);
  const double ps_c = run("elastic", "3.01e-3", "partial_stress", u, want) / amag;
  const double ps_v = run("elastic", VARYING, "partial_stress", u, want) / amag;
  const double st_c = run("elastic", "3.01e-3", "standard", u, want) / amag;
  const double st_v = run("elastic", VARYING, "standard", u, want) / amag;
  const double au_v = run("elastic", VARYING, "auto", u, want) / amag;
  const double co_v = run("elastic", VARYING, "corrected", u, want) / amag;
  const double cn_v = run("elastic", VARYING, "consistent", u, want) / amag;
  if (pf_comm_rank() == 0) printf("%s quadratic: max|a - a_exact| / |a_exact| (|a_exact| = %.4g m/s^2): partial stress %.2e "
         "(constant delta) %.2e (varying); standard %.2e (constant) %.2e (varying); auto %.2e, corrected %.2e, "
         "consistent %.2e (varying)\n", name, amag, ps_c, ps_v, st_c, st_v, au_v, co_v, cn_v);
  PF_TEST_TRUE(au_v < 0.01);
  PF_TEST_TRUE(co_v < 0.25 * st_v); /* the corrected form is not exact here (coupling.md §2.5) */
  PF_TEST_TRUE(cn_v < 0.5 * st_v);  /* nor the consistent form (§2.6) */
  PF_TEST_TRUE(ps_c < 0.01);
  PF_TEST_TRUE(ps_v < 0.01);
  PF_TEST_TRUE(st_c < 0.01);
  PF_TEST_TRUE(st_v > 0.01);
}

/* initial_displacement: an LPS block started at u = eps X has y = X + u and, after the initial
 * forces, theta = 3 eps at every point (m and theta share their quadrature, docs/theory/pd.md). */
static void initial_displacement_case(void) {
  const double eps = 1e-4;
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: {model: lps, density: 7800, bulk_modulus: 66.7e9, shear_modulus: 100e9}}\n"
           "bodies:\n  - {name: b, material: m, horizon: \"3.01e-3 - 1e-3 * x / 0.009\",\n"
           "     initial_displacement: [\"%g * x\", \"%g * y\", \"%g * z\"],\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.009, 0.009, 0.009], spacing: 0.001}}\n"
           "time: {steps: 1}\n", eps, eps, eps);
  pf_sim *sim = pf_test_sim("initial_displacement", deck);
  pf_points *p = pf_sim_points(sim);
  PF_TEST_OK(pf_sim_step(sim, 0));
  const double *th = pf_points_field_get(p, "dilatation");
  for (pf_int i = 0; i < p->n_owned; i++) {
    PF_TEST_CLOSE(p->u[3 * i + 1], eps * p->X[3 * i + 1], 1e-14, 0);
    PF_TEST_CLOSE(p->y[3 * i + 2], (1 + eps) * p->X[3 * i + 2], 1e-14, 0);
    PF_TEST_CLOSE(th[i], 3 * eps, 1e-9, 0);
  }
  pf_test_print_digest("initial_displacement", sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double L = (NX - 1) * h;
  field lin1 = {{{EPS, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {{{0}}}};
  field lin3 = {{{EPS, 0.4 * EPS, -0.3 * EPS}, {0.2 * EPS, -0.7 * EPS, 0.5 * EPS}, {-0.6 * EPS, 0.3 * EPS, 0.8 * EPS}}, {{{0}}}};
  field quad1 = {{{0}}, {{{0}}}}, quad3 = {{{0}}, {{{0}}}};
  quad1.Q[0][0][0] = EPS / L; /* u_x = (eps / 2L) x^2 */
  const double q[3][3][3] = {{{1.0, 0.3, -0.2}, {0.3, 0.5, 0.4}, {-0.2, 0.4, -0.6}},
                             {{0.2, -0.5, 0.1}, {-0.5, 0.9, 0.3}, {0.1, 0.3, 0.4}},
                             {{-0.4, 0.2, 0.6}, {0.2, 0.3, -0.1}, {0.6, -0.1, 0.7}}};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) quad3.Q[a][b][c] = q[a][b][c] * EPS / L;
  linear_cases("1-D", &lin1);
  linear_cases("3-D", &lin3);
  quadratic_cases("1-D", &quad1);
  quadratic_cases("3-D", &quad3);
  /* LPS (E = 200 GPa, nu = 0: K = E / 3 (1 - 2 nu), G = E / 2). Under an isotropic expansion
   * e = eps |xi| on every bond, so theta = 3 eps and nu = K theta I on any family with cubic
   * symmetry, whatever its horizon: the partial stress is exact and the force vanishes, while the
   * standard form shows ghost forces. (A general linear field is not reproduced on families of
   * few bonds: their deviatoric response differs, docs/theory/coupling.md §2.3; printed.) */
  const double zero[3] = {0, 0, 0}, eps = 1e-3, scale = E * eps / (RHO * h);
  field iso = {{{eps, 0, 0}, {0, eps, 0}, {0, 0, eps}}, {{{0}}}};
  const double lps_st = run("lps", VARYING, "standard", &iso, zero) / scale;
  const double lps_ps = run("lps", VARYING, "partial_stress", &iso, zero) / scale;
  const double lps_st3 = run("lps", VARYING, "standard", &lin3, zero) / (scale * 1e-3);
  const double lps_ps3 = run("lps", VARYING, "partial_stress", &lin3, zero) / (scale * 1e-3);
  if (pf_comm_rank() == 0) printf("LPS linear, varying horizon: max|a| / (E eps / rho dx): isotropic expansion: standard %.2e, partial "
         "stress %.2e; general 3-D field: standard %.2e, partial stress %.2e\n", lps_st, lps_ps, lps_st3, lps_ps3);
  PF_TEST_TRUE(lps_ps < 1e-9);
  PF_TEST_TRUE(lps_st > 1e-3);
  initial_displacement_case();
  return pf_test_finish();
}
