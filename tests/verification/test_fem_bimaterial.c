/* A stress pulse crossing the interface of a bi-material FE bar (`material_regions`: steel in
 * Pamgen block_1, x in [0, L1], aluminium in block_2, x in [L1, L1 + L2]; one element across,
 * docs/theory/fem.md §9c). Poisson's ratio 0 and every node's lateral velocity held at zero: a
 * one-dimensional bar, whose wave speed is c = sqrt(E / rho) (at nu = 0 the bar speed and the
 * P-wave speed sqrt((lambda + 2 mu) / rho) are one). The end x = 0 is driven by the velocity
 * v(t) = v0 (1 - cos(2 pi t / tau)) / 2 for t < tau, then held; no bulk viscosity.
 * Closed forms (Graff 1975; docs/theory/fem.md §9c), Z = rho c:
 *   - the momentum the transmitted pulse carries into material 2, once the pulse has passed the
 *     interface, is T = 2 Z2 / (Z1 + Z2) times the incident pulse's momentum (momentum is
 *     -int sigma dt of the pulse, and the transmitted stress is T times the incident);
 *   - its energy is E_T / E_I = 4 Z1 Z2 / (Z1 + Z2)^2 of the incident pulse's.
 * The incident pulse's momentum and energy are measured at t_I = 1.3 tau, when it is all in
 * material 1 (its front at 6.6 mm of the 20 mm); the transmitted pulse's at t_T = 8 us, when it
 * is all in material 2 and neither the reflection from the held end (back at the interface at
 * 3 L1 / c1 = 11.8 us) nor that from the free far end (at L1/c1 + 2 L2/c2 = 11.8 us) has come
 * back. Both are integral measures that dispersion does not change. Momentum sum m v of the nodes
 * (those right of the interface for material 2: the interface's own, at rest by then, are left
 * out); energy: kinetic sum m v^2 / 2 plus the strain
 * energy E A h / 2 ((u_{k+1} - u_k) / h)^2 of each element from the mean displacement u_k of its
 * node planes (the exact element energy of a laterally uniform field). Both within 1 % at
 * h = 0.25 mm and 0.125 mm. The energy balance: the driven end's work equals the energy of the
 * bar (kinetic + stress work + hourglass) within 1e-3, as test_fem_wave holds it. */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <stdlib.h>

enum { MAXPLANES = 2000 };
static const double L1 = 0.02, L2 = 0.02, tau = 2e-6, v0 = 1.0;
static const double E1 = 200e9, rho1 = 7800, E2 = 70e9, rho2 = 2700;

/* Momentum (x) and energy of the nodes in x > xnode and of the elements in x >= xelem, summed
 * over ranks. */
static void pulse_measures(const pf_points *p, double h, double A, double xnode, double xelem, double *mom,
                           double *energy) {
  static double usum[MAXPLANES], cnt[MAXPLANES];
  double m = 0, ke = 0;
  for (int k = 0; k < MAXPLANES; k++) usum[k] = cnt[k] = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const int k = (int)lround(p->X[3 * i] / h);
    usum[k] += p->u[3 * i], cnt[k] += 1;
    if (p->X[3 * i] <= xnode) continue;
    m += p->m[i] * p->v[3 * i], ke += 0.5 * p->m[i] * p->v[3 * i] * p->v[3 * i];
  }
  const int np = (int)lround((L1 + L2) / h) + 1;
  MPI_Allreduce(MPI_IN_PLACE, usum, np, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, cnt, np, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double se = 0;
  for (int k = 0; k + 1 < np; k++) {
    if (k * h < xelem - 1e-9) continue;
    const double E = (k + 0.5) * h < L1 ? E1 : E2, eps = (usum[k + 1] / cnt[k + 1] - usum[k] / cnt[k]) / h;
    se += 0.5 * E * A * h * eps * eps;
  }
  *mom = pf_sum_all(m), *energy = pf_sum_all(ke) + se;
}

static void run(int n1) {
  const double h = L1 / n1, A = h * h;
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials:\n"
           "  steel: {model: elastic, density: %g, youngs_modulus: %g, poissons_ratio: 0}\n"
           "  aluminium: {model: elastic, density: %g, youngs_modulus: %g, poissons_ratio: 0}\n"
           "bodies:\n"
           "  - name: bar\n    type: finite_element\n    material: steel\n"
           "    material_regions: [{block: block_2, material: aluminium}]\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    mesh:\n      pamgen: |\n        mesh\n          rectilinear\n"
           "            nx = %d\n            ny = 1\n            nz = 1\n"
           "            bx = 2\n            by = 1\n            bz = 1\n"
           "            gmin = 0 0 0\n            gmax = %.17g %.17g %.17g\n"
           "          end\n        end\n"
           "boundary_conditions:\n"
           "  - velocity: [\"free\", \"0\", \"0\"]\n"
           "  - region: {shape: box, lo: [-1.0e-9, -1, -1], hi: [1.0e-9, 1, 1]}\n"
           "    velocity: [\"t < %.17g ? %.17g * (1 - cos(2 * _pi * t / %.17g)) : 0\", \"0\", \"0\"]\n"
           "time: {final_time: 8.0e-6, safety_factor: 0.8}\n",
           rho1, E1, rho2, E2, n1, L1 + L2, h, h, tau, 0.5 * v0, tau);
  pf_sim *sim = pf_test_sim("fem_bimaterial", deck);
  pf_points *p = pf_sim_points(sim);
  pf_sim_globals g;
  double pI = 0, eI = 0, pT = 0, eT = 0, tI = 1.3 * tau;
  PF_TEST_OK(pf_sim_step(sim, 0));
  while (!pf_sim_finished(sim)) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    if (pI == 0 && g.time >= tI) pulse_measures(p, h, A, -1.0, 0.0, &pI, &eI);
  }
  pulse_measures(p, h, A, L1 + 0.5 * h, L1, &pT, &eT);
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  const double Z1 = sqrt(E1 * rho1), Z2 = sqrt(E2 * rho2), T = 2 * Z2 / (Z1 + Z2);
  const double eratio = 4 * Z1 * Z2 / ((Z1 + Z2) * (Z1 + Z2));
  const double gained = g.kinetic_centred + g.fe_internal + g.hourglass + g.bulk_viscosity;
  PF_TEST_TRUE(pI > 0 && eI > 0);
  PF_TEST_CLOSE(pT / pI, T, 0.01, 0);
  PF_TEST_CLOSE(eT / eI, eratio, 0.01, 0);
  PF_TEST_CLOSE(gained, g.external_work, 1e-3, 0);
  /* the incident pulse against its own closed form: momentum Z1 A int v dt = Z1 A v0 tau / 2 */
  PF_TEST_CLOSE(pI, Z1 * A * v0 * tau / 2, 0.01, 0);
  char key[64];
  snprintf(key, sizeof key, "momentum_ratio_error_n%d", n1);
  pf_test_measure(key, pT / pI / T - 1, "1");
  snprintf(key, sizeof key, "energy_ratio_error_n%d", n1);
  pf_test_measure(key, eT / eI / eratio - 1, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("bi-material bar, h = %g m: p_T/p_I = %.6f (T = %.6f, %+.3f %%), E_T/E_I = %.6f (4 Z1 Z2/(Z1+Z2)^2 = "
           "%.6f, %+.3f %%), p_I / (Z1 A v0 tau/2) = %.6f, work balance %.3g\n",
           h, pT / pI, T, 100 * (pT / pI / T - 1), eT / eI, eratio, 100 * (eT / eI / eratio - 1),
           pI / (Z1 * A * v0 * tau / 2), gained / g.external_work - 1);
  pf_test_print_digest(n1 == 80 ? "fem_bimaterial_h0.25mm" : "fem_bimaterial_h0.125mm", sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  run(80);  /* h = 0.25 mm: 40 elements over the pulse's length c tau = 10 mm */
  run(160); /* h = 0.125 mm */
  return pf_test_finish();
}
