/* Critical time step (Silling & Askari 2005; Peridigm's form dt = min_i sqrt(2 rho / sum_j V_j
 * c / |xi_ij|)) for K = 14.9 GPa, rho = 2200, h = 0.5 mm at an interior point, against the
 * values of REFERENCES.md (recomputed independently there): delta/h = 2, 3, 4, 5 -> 9.66e-8,
 * 1.355e-7, 1.863e-7, 2.298e-7 s. Bonds with |xi| = delta count (delta is taken 1e-9 above
 * ratio*h so that round-off in the lattice does not decide). */
#include "test_common.h"

#include <stdio.h>

#include "core/simulation.h"

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double h = 5e-4, want[4] = {9.66e-8, 1.355e-7, 1.863e-7, 2.298e-7};
  for (int r = 2; r <= 5; r++) {
    char deck[1024];
    snprintf(deck, sizeof deck,
             "materials: {g: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
             "bodies:\n  - {name: b, material: g, horizon: %.17g,\n"
             "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
             "time: {steps: 0, safety_factor: 1.0}\n",
             r * h * (1 + 1e-9), 12 * h, 12 * h, 12 * h, h);
    pf_sim *sim = pf_test_sim("stable_dt", deck);
    PF_TEST_CLOSE(pf_sim_dt(sim), want[r - 2], 5e-4, 0);
    pf_sim_destroy(&sim);
  }
  return pf_test_finish();
}
