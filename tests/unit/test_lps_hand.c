/* LPS against hand calculations (the cases of Peridigm's LPS unit test; derivation in
 * docs/theory/pd.md): two points, K = 130 GPa, G = 78 GPa, delta = 10, V = 1, the bond
 * stretched from length 1 to 2: m = 1, theta = 3, e^d = 0, t = 3 K theta / m = 1.17e12 at each
 * end, force density 2 t = 2.34e12. Eight points on a unit cube, z scaled by 0.98: m = 3*1 +
 * 3*2 + 3 = 12 and theta = (3/12) [-0.02 + 2 sqrt2 (sqrt(1.9604) - sqrt2) + sqrt3 (sqrt(2.9604)
 * - sqrt3)] = -0.01991593994643333. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

static pf_sim *make(const char *points) {
  char deck[1024];
  const char *file = pf_test_write_file(0, "lps_points", points);
  snprintf(deck, sizeof deck,
           "materials: {m: {model: lps, density: 1000, bulk_modulus: 130.0e9, shear_modulus: 78.0e9}}\n"
           "bodies:\n  - {name: b, material: m, horizon: 10.0, geometry: {shape: points_file, file: %s}}\n"
           "time: {steps: 0, dt: 1}\n", file);
  pf_sim *sim = pf_test_sim("lps_hand", deck);
  remove(file);
  return sim;
}

static void forces(pf_sim *sim) {
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < 3 * p->n_owned; i++) p->y[i] = p->X[i] + p->u[i], p->f[i] = 0;
  PF_TEST_OK(pf_pd_body_force(pf_sim_body(sim, 0), p, 0.0));
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pf_sim *sim = make("0 0 0 1 0\n1 0 0 1 0\n");
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < 2; i++) p->u[3 * i] = p->X[3 * i]; /* x -> 2x: length 1 -> 2 */
  forces(sim);
  const double *m = pf_points_field_get(p, "weighted_volume"), *th = pf_points_field_get(p, "dilatation");
  double err_m = 0, err_th = 0, err_f = 0, err_fy = 0; /* the largest errors over the points */
  for (pf_int i = 0; i < 2; i++) {
    PF_TEST_CLOSE(m[i], 1.0, 1e-15, 0);
    PF_TEST_CLOSE(th[i], 3.0, 1e-15, 0);
    double sign = p->X[3 * i] > 0.5 ? -1 : 1; /* the bond pulls the points together */
    PF_TEST_CLOSE(p->f[3 * i], sign * 2.34e12, 1e-14, 0);
    PF_TEST_CLOSE(p->f[3 * i + 1], 0, 0, 1e-3);
    err_m = fmax(err_m, fabs(m[i] - 1.0)), err_th = fmax(err_th, fabs(th[i] / 3.0 - 1));
    err_f = fmax(err_f, fabs(p->f[3 * i] / (sign * 2.34e12) - 1)), err_fy = fmax(err_fy, fabs(p->f[3 * i + 1]));
  }
  pf_test_measure("pair_m_error", err_m, "1");
  pf_test_measure("pair_theta_error", err_th, "1");
  pf_test_measure("pair_fx_error", err_f, "1");
  pf_test_measure("pair_fy", err_fy, "N");
  pf_sim_destroy(&sim);

  sim = make("0 0 0 1\n1 0 0 1\n0 1 0 1\n1 1 0 1\n0 0 1 1\n1 0 1 1\n0 1 1 1\n1 1 1 1\n");
  p = pf_sim_points(sim);
  for (pf_int i = 0; i < 8; i++) p->u[3 * i + 2] = -0.02 * p->X[3 * i + 2];
  forces(sim);
  m = pf_points_field_get(p, "weighted_volume");
  th = pf_points_field_get(p, "dilatation");
  double exact = 0.25 * (-0.02 + 2 * sqrt(2) * (sqrt(1.9604) - sqrt(2)) + sqrt(3) * (sqrt(2.9604) - sqrt(3)));
  PF_TEST_CLOSE(exact, -0.01991593994643333, 1e-14, 0);
  err_m = 0, err_th = 0;
  for (pf_int i = 0; i < 8; i++) {
    PF_TEST_CLOSE(m[i], 12.0, 1e-15, 0);
    PF_TEST_CLOSE(th[i], -0.01991593994643333, 0, 1e-12);
    err_m = fmax(err_m, fabs(m[i] / 12.0 - 1)), err_th = fmax(err_th, fabs(th[i] + 0.01991593994643333));
  }
  pf_test_measure("cube_m_error", err_m, "1");
  pf_test_measure("cube_theta_error", err_th, "1");
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
