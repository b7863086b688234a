/* Waves in PMB.
 * 1. inputs/wave_in_bar.yaml as shipped: the total energy (the leapfrog-conserved kinetic part
 *    plus the stored elastic energy) stays within 0.1 % of its initial value over the run.
 * 2. Phase speed: a standing wave u_x = U sin(k x) cos(w t) in a block (lateral motion held,
 *    k delta = 1) is started by v_x = -U w sin(kx) ... here as v_x = V sin(k x) at t = 0, so the
 *    velocity at an interior point crosses zero at t = pi / (2 w). The measured w / k is checked
 *    against the PMB dispersion relation on this lattice,
 *      rho w^2 = c sum_j V_j (xi_x^2 / |xi|^3) (1 - cos(k xi_x))   (linearized PMB, plane wave),
 *    summed here independently over the lattice offsets, to 2 %; and against the continuum PMB
 *    value c_p / c_L = 0.98035 at k delta = 1 (docs/theory/pd.md §7), c_L = sqrt(1.8 K / rho),
 *    to 3 %. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"

static double total_energy(pf_sim *sim) {
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  return g.kinetic_centred + g.elastic;
}

static void energy_test(void) {
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  PF_TEST_OK(pf_sim_create("../inputs/wave_in_bar.yaml", &opt, &sim));
  if (!sim) return;
  PF_TEST_OK(pf_sim_step(sim, 0));
  double e0 = total_energy(sim), worst = 0;
  long n = pf_sim_nsteps(sim);
  for (long s = 0; s < n; s += 10) {
    PF_TEST_OK(pf_sim_step(sim, s + 10 <= n ? 10 : n - s));
    worst = fmax(worst, fabs(total_energy(sim) - e0) / e0);
  }
  PF_TEST_CLOSE(e0, 0.5 * 2200 * 1e-12 * 100 * 100 * 300, 1e-12, 0); /* 3 layers x 100 points at 100 m/s */
  PF_TEST_TRUE(worst < 1e-3);
  if (!(worst < 1e-3)) fprintf(stderr, "energy drift %g\n", worst);
  pf_test_measure("energy_initial", e0, "J");
  pf_test_measure("energy_drift", worst, "1");
  pf_test_print_digest("energy", sim);
  pf_sim_destroy(&sim);
}

static void speed_test(void) {
  const double h = 1e-4, delta = 3.0001 * h, K = 14.9e9, rho = 2200, k = 1.0 / delta;
  const int nx = 60, ny = 16;
  const double x0 = (PF_PI / 2 + 4 * PF_PI) / k; /* sin(k x0) = 1, far from both ends */
  char deck[2048];
  snprintf(deck, sizeof deck,
           "materials: {g: {model: pmb, density: %g, bulk_modulus: %g}}\n"
           "bodies:\n  - {name: block, material: g, horizon: %.17g,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g},\n"
           "     initial_velocity: [\"0.01 * sin(%.17g * x)\", \"0\", \"0\"]}\n"
           "boundary_conditions: [{velocity: [free, \"0\", \"0\"]}]\n"
           "time: {steps: 400, dt: 5e-10}\n",
           rho, K, delta, (nx - 1) * h, (ny - 1) * h, (ny - 1) * h, h, k);
  pf_sim *sim = pf_test_sim("wave_speed", deck);
  pf_points *p = pf_sim_points(sim);
  pf_int probe = -1; /* the lattice point nearest to (x0, centre, centre), on the rank that owns it */
  double mid = 0.5 * (ny - 1) * h;
  struct {
    double d;
    int rank;
  } best = {INFINITY, pf_comm_rank()}, all;
  for (pf_int i = 0; i < p->n_owned; i++) {
    double d = fabs(p->X[3 * i] - x0) + fabs(p->X[3 * i + 1] - mid) + fabs(p->X[3 * i + 2] - mid);
    if (d < best.d) best.d = d, probe = i;
  }
  MPI_Allreduce(&best, &all, 1, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD);
  const int mine = all.rank == pf_comm_rank();
  double prev = pf_sum_all(mine ? p->v[3 * probe] : 0), t = 0, dt = pf_sim_dt(sim), tcross = -1;
  for (int s = 0; s < 400 && tcross < 0; s++) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    t += dt;
    double v = pf_sum_all(mine ? p->v[3 * probe] : 0);
    if ((v < 0) != (prev < 0)) tcross = t - dt * v / (v - prev);
    prev = v;
  }
  PF_TEST_TRUE(tcross > 0);
  double w_measured = PF_PI / (2 * tcross);
  /* the lattice dispersion relation */
  double c = 18 * K / (PF_PI * pow(delta, 4)), sum = 0;
  for (int a = -3; a <= 3; a++)
    for (int b = -3; b <= 3; b++)
      for (int e = -3; e <= 3; e++) {
        double r = h * sqrt(a * a + b * b + e * e), xx = a * h;
        if (r > 0 && r <= delta) sum += h * h * h * xx * xx / (r * r * r) * (1 - cos(k * xx));
      }
  double w_lattice = sqrt(c * sum / rho);
  PF_TEST_CLOSE(w_measured / k, w_lattice / k, 0.02, 0);
  PF_TEST_CLOSE(w_measured / k, 0.98035 * sqrt(1.8 * K / rho), 0.03, 0);
  pf_test_measure("phase_speed", w_measured / k, "m/s");
  pf_test_measure("phase_speed_lattice", w_lattice / k, "m/s");
  pf_test_measure("phase_speed_continuum", 0.98035 * sqrt(1.8 * K / rho), "m/s");
  pf_test_print_digest("speed", sim);
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("phase speed: measured %.2f m/s, lattice %.2f, continuum %.2f\n", w_measured / k, w_lattice / k,
           0.98035 * sqrt(1.8 * K / rho));
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  energy_test();
  speed_test();
  return pf_test_finish();
}
