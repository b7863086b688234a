/* A 1-D longitudinal wave in an FE bar (meshes/bar.geo, 10 x 1 x 1 mm, 0.1 mm hexahedra):
 * uniaxial strain (every node's lateral velocity held at zero), elastic steel, no bulk
 * viscosity. The first millimetre starts at v0 = 100 m/s; the pulse splits into two halves of
 * amplitude v0/2, and the right-going front (starting at x = 1 mm) reaches the probe plane
 * x = 8 mm at t = 7 mm / c, c = sqrt((lambda + 2 mu) / rho) (the dilatational speed). The time
 * at which the probe's velocity first reaches v0/4 (interpolated between steps) must be within
 * 1 % of 7 mm / c, and the total energy (centred kinetic + stress work) must drift by less than
 * 0.5 % over 3 us (the front's reflection from the far end included).
 * Second, the same bar at rest driven at x = 0 by a prescribed velocity ramp (1 - cos) to
 * 10 m/s over 1 us: the work the prescribed motion books must equal the energy the bar gains,
 * kinetic + stress work, to 0.1 % (the balance of docs/theory/pd.md §10). */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <stdlib.h>
#include <unistd.h>

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  char cwd[3000], mesh[3100], deck[4096];
  if (!getcwd(cwd, sizeof cwd)) return 1;
  snprintf(mesh, sizeof mesh, "%s/../meshes/bar.geo", cwd); /* ctest runs from tests/ */
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}\n"
           "bodies:\n"
           "  - name: bar\n    type: finite_element\n    material: steel\n"
           "    mesh: {file: %s, element_size: 0.1e-3}\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    initial_velocity: [\"x < 0.001000001 ? 100 : 0\", \"0\", \"0\"]\n"
           "boundary_conditions:\n  - velocity: [\"free\", \"0\", \"0\"]\n"
           "time: {final_time: 3.0e-6, safety_factor: 0.8}\n",
           mesh);
  pf_sim *sim = pf_test_sim("fem_wave", deck);
  const double E = 200e9, nu = 0.3, rho = 7800, v0 = 100;
  const double M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), c = sqrt(M / rho), want = 7e-3 / c;
  pf_points *p = pf_sim_points(sim);
  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_step(sim, 0));
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  double arrival = -1, tprev = 0, vprev = 0, drift = 0;
  while (!pf_sim_finished(sim)) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    double vs = 0, n = 0;
    for (pf_int i = 0; i < p->n_owned; i++)
      if (fabs(p->X[3 * i] - 8e-3) < 1e-9) vs += p->v[3 * i], n++;
    double v = pf_sum_all(vs) / pf_sum_all(n);
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    if (arrival < 0 && v >= 0.25 * v0) arrival = tprev + (g.time - tprev) * (0.25 * v0 - vprev) / (v - vprev);
    tprev = g.time, vprev = v;
    double e = g.kinetic_centred + g.fe_internal + g.hourglass + g.bulk_viscosity;
    drift = fmax(drift, fabs(e - g0.kinetic_centred));
  }
  PF_TEST_CLOSE(arrival, want, 0.01, 0);
  PF_TEST_CLOSE(drift, 0.0, 0, 5e-3 * g0.kinetic);
  PF_TEST_CLOSE(g0.kinetic, 0.5 * rho * 1e-3 * 1e-6 * v0 * v0, 0.06, 0); /* nodes at x = 1 mm: +1/20 */
  pf_test_measure("arrival_error", arrival / want - 1, "1");
  pf_test_measure("energy_drift", drift / g0.kinetic, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("fem wave: arrival %.5g s (L/c %.5g s, %+.3f %%), energy drift %.3g %% of KE0\n", arrival, want,
           100 * (arrival / want - 1), 100 * drift / g0.kinetic);
  pf_test_print_digest("fem_wave", sim);
  pf_sim_destroy(&sim);

  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}\n"
           "bodies:\n"
           "  - {name: bar, type: finite_element, material: steel, mesh: {file: %s, element_size: 0.2e-3},\n"
           "     bulk_viscosity: {linear: 0, quadratic: 0}}\n"
           "boundary_conditions:\n"
           "  - region: {shape: box, lo: [-1.0e-6, -1, -1], hi: [1.0e-6, 1, 1]}\n"
           "    velocity: [\"t < 1e-6 ? 5 * (1 - cos(_pi * t / 1e-6)) : 10\", \"free\", \"free\"]\n"
           "time: {final_time: 2.0e-6}\n",
           mesh);
  sim = pf_test_sim("fem_driven", deck);
  while (!pf_sim_finished(sim)) PF_TEST_OK(pf_sim_step(sim, 1));
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  double gained = g.kinetic_centred + g.fe_internal + g.hourglass + g.bulk_viscosity;
  PF_TEST_TRUE(g.external_work > 0);
  PF_TEST_CLOSE(gained, g.external_work, 1e-3, 0);
  pf_test_measure("driven_balance", gained / g.external_work - 1, "1");
  pf_test_print_digest("fem_driven", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
