/* Short-range contact of two particles (Peridigm's regression Contact_2x1x1): two one-point
 * PMB bodies on the x axis, 2 mm apart, V = 2e-9 m^3 each,
 * rho = 7800 kg/m^3, approaching at +-1 m/s; contact radius r_c = 2 mm (they touch from the
 * start), spring constant k_s = 1.95e12 Pa, horizon delta = 1 mm.
 *
 * The pair force is f = C (r_c - r) V_i V_j with C = 18 k_s / (pi delta^5) (contact/contact.c),
 * a linear spring of stiffness k = C V^2 on the separation r. With m = rho V the relative
 * coordinate r obeys (m/2) r'' = k (r_c - r) (reduced mass m m / (m + m) = m/2), so while
 * r < r_c it moves as a harmonic oscillator of angular frequency omega = sqrt(2 k / m): the
 * particles enter at r = r_c with r' = -2 m/s and leave at r = r_c with r' = +2 m/s after half a
 * period, T/2 = pi / omega = pi / sqrt(2 k / m) (Peridigm's gold value 4.150386640644e-8 s).
 * The largest overlap is 2 / omega, about 26 nm.
 *
 * The run lasts 1.5 T/2: the contact, then T/4 (2000 steps) apart, in which it must not resume.
 * Checks, with a fixed dt = (T/2) / 4000: after the contact the velocities are exactly reversed
 * (+-1 m/s to 1e-6 relative) and the kinetic energy is back to its initial value (1e-6
 * relative: a linear spring conserves energy up to O((omega dt)^2) ~ 1e-7 in velocity Verlet);
 * the contact lasts T/2 within 2 dt (steps counted while the contact energy is positive or the
 * separation is below r_c); the total momentum stays zero (1e-12 kg m/s, it is 1.56e-5 kg m/s
 * per particle). Every check is on owned points reduced over the ranks (on 3 ranks one rank
 * owns nothing). */
#include "sim/sim.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double V = 2e-9, rho = 7800, rc = 2e-3, ks = 1.95e12, delta = 1e-3, v0 = 1.0;
  const double m = rho * V, C = 18 * ks / (PF_PI * pow(delta, 5)), k = C * V * V;
  const double half = PF_PI / sqrt(2 * k / m), dt = half / 4000;
  PF_TEST_CLOSE(half, 4.150386640644e-8, 1e-9, 0);

  const char *pts = pf_test_write_file(0, "contact_pair_pts", "-0.001 0 0 2.0e-9 1\n0.001 0 0 2.0e-9 2\n");
  char deck[2048];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: pmb, density: %.17g, bulk_modulus: 1.0e11}}\n"
           "bodies:\n"
           "  - {name: left, material: steel, horizon: %.17g, initial_velocity: [%g, 0, 0],\n"
           "     geometry: {shape: points_file, file: %s, block: 1}}\n"
           "  - {name: right, material: steel, horizon: %.17g, initial_velocity: [%g, 0, 0],\n"
           "     geometry: {shape: points_file, file: %s, block: 2}}\n"
           "contact:\n"
           "  pairs:\n"
           "    - {bodies: [left, right], radius: %.17g, spring_constant: %.17g, horizon: %.17g}\n"
           "time: {dt: %.17g, final_time: %.17g}\n"
           "output: {interval: 0}\n",
           rho, delta, v0, pts, delta, -v0, pts, rc, ks, delta, dt, 1.5 * half);
  pf_sim *sim = pf_test_sim("contact_pair", deck);
  remove(pts);
  PF_TEST_CLOSE(pf_sim_dt(sim), dt, 1e-14, 0);

  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_step(sim, 0));
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  PF_TEST_CLOSE(g0.kinetic, m * v0 * v0, 1e-12, 0);
  long in_contact = 0, first = -1, last = -1, step = 0;
  double pmax = 0, ymin = INFINITY;
  while (!pf_sim_finished(sim)) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    step++;
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    for (int a = 0; a < 3; a++) pmax = fmax(pmax, fabs(g.momentum[a]));
    /* separation from the owned x positions: left has the smaller global id */
    const pf_points *p = pf_sim_points(sim);
    double x[2] = {0, 0};
    for (pf_int i = 0; i < p->n_owned; i++) x[p->body[i]] = p->y[3 * i];
    double r = pf_sum_all(x[1]) - pf_sum_all(x[0]);
    ymin = fmin(ymin, r);
    if (g.contact > 0 || r < rc) {
      in_contact++;
      if (first < 0) first = step;
      last = step;
    }
  }
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  const pf_points *p = pf_sim_points(sim);
  double vx[2] = {0, 0}, vyz = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    vx[p->body[i]] = p->v[3 * i], vyz = fmax(vyz, fmax(fabs(p->v[3 * i + 1]), fabs(p->v[3 * i + 2])));
  vx[0] = pf_sum_all(vx[0]), vx[1] = pf_sum_all(vx[1]), vyz = pf_max_all(vyz);

  /* the contact starts at t = 0 (the force is zero at r = r_c exactly, positive after the
   * first drift); the steps in contact span the half-period */
  double duration = (double)in_contact * dt;
  PF_TEST_CLOSE(duration, half, 0, 2 * dt);
  PF_TEST_TRUE(first == 1 && last == in_contact); /* one contiguous contact from the start */
  PF_TEST_CLOSE(vx[0], -v0, 1e-6, 0);
  PF_TEST_CLOSE(vx[1], v0, 1e-6, 0);
  PF_TEST_CLOSE(vyz, 0, 0, 1e-15);
  PF_TEST_CLOSE(g.kinetic, g0.kinetic, 1e-6, 0);
  PF_TEST_CLOSE(g.contact, 0, 0, 0);
  PF_TEST_CLOSE(pmax, 0, 0, 1e-12);
  PF_TEST_CLOSE(rc - ymin, 2 * v0 / sqrt(2 * k / m), 1e-3, 0); /* largest overlap 2 v0 / omega */
  pf_test_measure("steps_in_contact", (double)in_contact, "1");
  pf_test_measure("dt_off", (duration - half) / dt, "1");
  pf_test_measure("ke_error", fabs(g.kinetic - g0.kinetic) / g0.kinetic, "1");
  pf_test_measure("velocity_error", fmax(fabs(fabs(vx[0]) - v0), fabs(fabs(vx[1]) - v0)), "m/s");
  pf_test_measure("momentum_max", pmax, "kg m/s");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("contact_pair: half period %.12e s (Peridigm 4.150386640644e-8), in contact %ld steps = %.12e s "
           "(%.2f dt off), v %.12f %.12f, KE error %.3e rel, |p| max %.3e, overlap %.6e m\n",
           half, in_contact, duration, (duration - half) / dt, vx[0], vx[1], (g.kinetic - g0.kinetic) / g0.kinetic,
           pmax, rc - ymin);
  pf_test_print_digest("contact_pair", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
