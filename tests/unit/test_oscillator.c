/* Two PMB particles joined by one bond: a linear oscillator. Each particle (mass rho V) feels
 * V c s V along the bond, s = d / r0, so the separation d obeys rho d'' = -2 c V d / r0 and the
 * period is T = 2 pi / sqrt(2 c V / (rho r0)) (small amplitude). The relative velocity,
 * 2 v0 cos(2 pi t / T), crosses zero at T/4 and 3T/4: their distance is T/2. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double K = 14.9e9, rho = 2200, delta = 1.5e-3, V = 1e-9, r0 = 1e-3;
  const double c = 18 * K / (PF_PI * pow(delta, 4));
  const double T = 2 * PF_PI / sqrt(2 * c * V / (rho * r0)), dt = T / 2000;
  const char *file = pf_test_write_file(0, "osc_points", "-0.0005 0 0 1e-9\n0.0005 0 0 1e-9\n");
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {g: {model: pmb, density: %g, bulk_modulus: %g}}\n"
           "bodies:\n  - {name: pair, material: g, horizon: %g, geometry: {shape: points_file, file: %s},\n"
           "     initial_velocity: [\"x > 0 ? 0.01 : -0.01\", \"0\", \"0\"]}\n"
           "time: {steps: 3000, dt: %.17g}\n", rho, K, delta, file, dt);
  pf_sim *sim = pf_test_sim("oscillator", deck);
  remove(file);
  pf_points *p = pf_sim_points(sim);
  pf_int right = p->X[0] > 0 ? 0 : 1, left = 1 - right;
  double prev = p->v[3 * right] - p->v[3 * left], t = 0, cross[2];
  int ncross = 0;
  for (int s = 0; s < 3000 && ncross < 2; s++) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    t += dt;
    double vr = p->v[3 * right] - p->v[3 * left];
    if ((vr < 0) != (prev < 0)) cross[ncross++] = t - dt * vr / (vr - prev); /* linear interpolation */
    prev = vr;
  }
  PF_TEST_TRUE(ncross == 2);
  if (ncross == 2) {
    PF_TEST_CLOSE(cross[0], T / 4, 1e-4, 0);
    PF_TEST_CLOSE(cross[1] - cross[0], T / 2, 1e-4, 0);
    pf_test_measure("first_crossing_error", cross[0] / (T / 4) - 1, "1");
    pf_test_measure("spacing_error", (cross[1] - cross[0]) / (T / 2) - 1, "1");
  }
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
