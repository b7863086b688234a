/* PMB micromodulus and critical stretch against their closed forms (Silling & Askari 2005,
 * eqs. 7 and 9; REFERENCES.md), and the influence-function moments against hand integrals. */
#include "test_common.h"

#include <math.h>

#include "pd/pd.h"

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double K = 14.9e9, delta = 1.5e-3;
  pf_influence one = {PF_INFLUENCE_CONSTANT, 0}, inv = {PF_INFLUENCE_INVERSE_DISTANCE, 0};
  /* c = 18 K / (pi delta^4) = 1.68634e22 (REFERENCES.md; LAMMPS Howto_peri). */
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &one, delta), 1.68634e22, 1e-5, 0);
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &one, delta), 18 * K / (PF_PI * pow(delta, 4)), 1e-13, 0);
  /* omega = 1/r: c = 18 K / (4 pi delta^3 / 3) */
  PF_TEST_CLOSE(pf_pd_pmb_micromodulus(K, &inv, delta), 18 * K / (4 * PF_PI * pow(delta, 3) / 3), 1e-13, 0);
  /* s0 = sqrt(5 G0 / (9 K delta)); G0 = 9 K delta s00^2 / 5 = 10.0575 J/m^2 for s00 = 5e-4. */
  double G0 = 9 * K * delta * 5e-4 * 5e-4 / 5;
  PF_TEST_CLOSE(G0, 10.0575, 1e-12, 0);
  PF_TEST_CLOSE(pf_pd_pmb_critical_stretch(G0, K, delta), 5e-4, 1e-13, 0);
  /* Gaussian moment: 4 pi int_0^d exp(-r^2/s^2) r^2 dr = pi^(3/2) s^3 erf(d/s)
   *  - 2 pi s^2 d exp(-d^2/s^2) (integration by parts). */
  double s = 0.5 * delta;
  pf_influence gau = {PF_INFLUENCE_GAUSSIAN, s};
  double exact = pow(PF_PI, 1.5) * pow(s, 3) * erf(delta / s) - 2 * PF_PI * s * s * delta * exp(-delta * delta / (s * s));
  PF_TEST_CLOSE(pf_pd_influence_moment(&gau, delta, 2), exact, 1e-12, 0);
  return pf_test_finish();
}
