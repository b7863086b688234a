/* PMB micromodulus and critical stretch against their closed forms (Silling & Askari 2005,
 * eqs. 7 and 9), the influence-function moments against hand integrals, the
 * critical stretch s0(G0) that a deck's `energy_release_rate` gives each material and influence
 * function (PMB sqrt(5 G0 / (9 K delta)); LPS omega = 1: sqrt(8 G0 / (15 K delta)), omega = 1/|xi|:
 * sqrt(5 G0 / (9 K delta)); CabanaPD's LPS), and the critical-energy constant
 * w_c = 4 G0 / (pi delta^4) against a quadrature of the crossing-bond integral. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"
#include "pd/pd.h"

/* The s0 field of a 4 x 4 x 4 body of the given model and influence function, built from a deck
 * with damage {law: critical_stretch, energy_release_rate: G0}. */
static double deck_s0(const char *model, const char *influence, double K, double G, double delta,
                      double G0) {
  char deck[1024];
  const double h = delta / 3.0001;
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 2200, bulk_modulus: %.17g, shear_modulus: %.17g}}\n"
           "bodies:\n  - {name: b, material: m, horizon: %.17g, influence: %s,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g},\n"
           "     damage: {law: critical_stretch, energy_release_rate: %.17g}}\n"
           "time: {steps: 1}\n",
           model, K, G, delta, influence, 3 * h, 3 * h, 3 * h, h, G0);
  pf_sim *sim = pf_test_sim("closed_forms_s0", deck);
  pf_points *p = pf_sim_points(sim);
  const double *s0 = pf_points_field_get(p, "critical_stretch");
  double v = p->n_owned > 0 && s0 ? s0[0] : 0;
  v = pf_max_all(v); /* every point has the same s0; ranks without points give 0 */
  pf_sim_destroy(&sim);
  return v;
}

/* G0 = energy of the bonds crossing a unit area of a plane, each storing w_c:
 * int_0^delta dz int_z^delta dxi 2 pi xi^2 (1 - z / xi) w_c (the polar integral done: the bonds
 * of length xi from a point at depth z that cross make the cap cos(phi) > z / xi of the sphere),
 * by the midpoint rule on an n x n grid of the triangle z < xi. */
static double crossing_energy(double wc, double delta, int n) {
  double sum = 0, hz = delta / n;
  for (int a = 0; a < n; a++)
    for (int c = 0; c < n; c++) {
      double z = (a + 0.5) * hz, xi = z + (c + 0.5) * (delta - z) / n;
      sum += 2 * PF_PI * xi * xi * (1 - z / xi) * wc * (delta - z) / n * hz;
    }
  return sum;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double K = 14.9e9, delta = 1.5e-3;
  pf_influence one = {PF_INFLUENCE_CONSTANT, 0}, inv = {PF_INFLUENCE_INVERSE_DISTANCE, 0};
  /* c = 18 K / (pi delta^4) = 1.68634e22 (LAMMPS Howto_peri). */
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &one, delta), 1.68634e22, 1e-5, 0);
  pf_test_measure("c_pmb", pf_pd_pmb_micromodulus(K, &one, delta), "N/m^6");
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &one, delta), 18 * K / (PF_PI * pow(delta, 4)), 1e-13, 0);
  /* omega = 1/r: c = 18 K / (4 pi delta^3 / 3) */
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &inv, delta), 18 * K / (4 * PF_PI * pow(delta, 3) / 3), 1e-13, 0);
  pf_test_measure("c_inverse_distance", pf_pd_pmb_micromodulus(K, &inv, delta), "N/m^5");
  /* s0 = sqrt(5 G0 / (9 K delta)); G0 = 9 K delta s00^2 / 5 = 10.0575 J/m^2 for s00 = 5e-4. */
  double G0 = 9 * K * delta * 5e-4 * 5e-4 / 5;
  PF_TEST_CLOSE(G0, 10.0575, 1e-12, 0);
  PF_TEST_CLOSE(pf_pd_pmb_critical_stretch(G0, K, delta), 5e-4, 1e-13, 0);
  pf_test_measure("G0", G0, "J/m^2");
  pf_test_measure("s0", pf_pd_pmb_critical_stretch(G0, K, delta), "1");
  /* Gaussian moment: 4 pi int_0^d exp(-r^2/s^2) r^2 dr = pi^(3/2) s^3 erf(d/s)
   *  - 2 pi s^2 d exp(-d^2/s^2) (integration by parts). */
  double s = 0.5 * delta;
  pf_influence gau = {PF_INFLUENCE_GAUSSIAN, s};
  double exact = pow(PF_PI, 1.5) * pow(s, 3) * erf(delta / s) - 2 * PF_PI * s * s * delta * exp(-delta * delta / (s * s));
  PF_TEST_CLOSE(pf_pd_influence_moment(&gau, delta, 2), exact, 1e-12, 0);
  pf_test_measure("gaussian_moment_error", pf_pd_influence_moment(&gau, delta, 2) / exact - 1, "1");

  /* s0 from energy_release_rate through the deck, G0 = 10.0575 (s0 = 5e-4 for PMB):
   * LPS omega = 1: 8 G0 / (15 K delta) = (8 / 15) (9 / 5) s00^2 = 0.96 s00^2. */
  const double G = 8.94e9;
  PF_TEST_CLOSE(deck_s0("pmb", "constant", K, G, delta, G0), 5e-4, 1e-12, 0);
  PF_TEST_CLOSE(deck_s0("lps", "constant", K, G, delta, G0), 5e-4 * sqrt(0.96), 1e-12, 0);
  PF_TEST_CLOSE(deck_s0("lps", "inverse_distance", K, G, delta, G0), 5e-4, 1e-12, 0);

  /* Critical energy: the crossing integral of w_c = 4 G0 / (pi delta^4) gives back G0 (the
   * midpoint rule on the triangle converges at second order: 1e-5 at n = 400). */
  PF_TEST_CLOSE(crossing_energy(4 * G0 / (PF_PI * pow(delta, 4)), delta, 400), G0, 1e-5, 0);
  return pf_test_finish();
}
