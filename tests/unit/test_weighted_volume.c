/* LPS weighted volume m (omega = 1, delta = 1) at the centre of an n^3 grid of cells on
 * [-1, 1]^3, against Peridigm's published convergence table (as quoted in the foundation
 * issue), with whole-cell and with partial volumes; the continuum value is 4 pi / 5. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

static double center_m(int n, int partial) {
  char deck[2048];
  double h = 2.0 / n, lo = -1 + h / 2;
  snprintf(deck, sizeof deck,
           "materials: {m: {model: lps, density: 1000, bulk_modulus: 1.0e9, shear_modulus: 1.0e9}}\n"
           "bodies:\n"
           "  - name: grid\n    material: m\n    horizon: 1.0\n    partial_volumes: %s\n"
           "    geometry: {shape: box, lo: [%.17g, %.17g, %.17g], hi: [%.17g, %.17g, %.17g],\n"
           "               spacing: %.17g, origin: [%.17g, %.17g, %.17g]}\n"
           "time: {steps: 0, dt: 1}\n",
           partial ? "true" : "false", lo, lo, lo, -lo, -lo, -lo, h, lo, lo, lo);
  pf_sim *sim = pf_test_sim("weighted_volume", deck);
  pf_points *p = pf_sim_points(sim);
  const double *m = pf_points_field_get(p, "weighted_volume");
  double best = -1;
  for (pf_int i = 0; i < p->n_owned; i++)
    if (fabs(p->X[3 * i]) + fabs(p->X[3 * i + 1]) + fabs(p->X[3 * i + 2]) < 1e-12) best = m[i];
  PF_TEST_TRUE(p->n_owned == n * n * n);
  pf_sim_destroy(&sim);
  return best;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const int n[5] = {3, 5, 7, 9, 17};
  const double whole[5] = {3.950617, 3.502080, 2.490391, 2.594726, 2.481106};
  const double partial[5] = {2.888889, 2.670720, 2.597088, 2.564678, 2.528185};
  for (int k = 0; k < 5; k++) {
    double m_whole = center_m(n[k], 0), m_partial = center_m(n[k], 1);
    PF_TEST_CLOSE(m_whole, whole[k], 0, 6e-7);
    PF_TEST_CLOSE(m_partial, partial[k], 0, 6e-7);
    char key[32];
    snprintf(key, sizeof key, "whole_n%d", n[k]);
    pf_test_measure(key, m_whole, "1");
    snprintf(key, sizeof key, "partial_n%d", n[k]);
    pf_test_measure(key, m_partial, "1");
  }
  /* The partial-volume values approach the continuum 4 pi delta^5 / 5 = 2.5133. */
  PF_TEST_TRUE(fabs(partial[4] - 4 * PF_PI / 5) < 0.02);
  return pf_test_finish();
}
