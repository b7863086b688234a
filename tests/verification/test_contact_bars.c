/* Contact between two finite-element bodies: a steel bar (10 x 1 x 1 mm, 0.25 mm hexahedra,
 * nu = 0, so that uniaxial stress is uniaxial strain and the bar is exactly one-dimensional)
 * at v0 = 100 m/s along x hits an identical bar at rest across a 0.05 mm gap. The 1-D elastic
 * solution (e.g. Graff, Wave Motion in Elastic Solids, 1975, sec. 2.4; Johnson, Impact Strength
 * of Materials, 1972, sec. 1.6): the contact stress is rho c v0 / 2, so the contact force is
 * F0 = rho c A v0 / 2, with c = sqrt(E / rho); the two release waves return to the contact
 * face after 2 L / c, when the bars part with the velocities exchanged (the striker at rest,
 * the struck bar at v0).
 * The first touches chatter (the front nodes bounce on the penalty a few times over the first
 * 0.5 us), so the contact is taken from the first time the force exceeds 1e-3 F0 to the last
 * time it falls below that.
 * Asserted: the contact lasts 2 L / c within 3 %; the mean force over the middle half of it
 * is F0 within 3 %; after the run the striker's mean velocity is below 3 % of v0 and the struck
 * bar's within 3 % of v0; linear momentum is conserved to 1e-12 of m v0 (the pair's forces are
 * equal and opposite); the bars never overlap by more than 1 % of an element (the default
 * penalty, 10 K h); the kinetic energy at the end is that of the start within 3 %. */
#include "sim/sim.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double E = 200e9, rho = 7800, v0 = 100, L = 10e-3, A = 1e-6, h = 0.25e-3, gap = 0.05e-3;

/* The x-force the contact puts on body b, its mean x-velocity, and its extreme x (max for the
 * striker 0, min for the struck bar 1). Collective. */
static void body_state(const pf_points *p, int b, double *force, double *vel, double *edge) {
  const double *fc = pf_points_field_get(p, "contact_force");
  double f = 0, mv = 0, m = 0, x = b == 0 ? -INFINITY : INFINITY;
  for (pf_int i = 0; i < p->n_owned; i++) {
    if (p->body[i] != b) continue;
    if (fc) f += fc[3 * i];
    mv += p->m[i] * p->v[3 * i], m += p->m[i];
    x = b == 0 ? fmax(x, p->y[3 * i]) : fmin(x, p->y[3 * i]);
  }
  *force = pf_sum_all(f), *vel = pf_sum_all(mv) / pf_sum_all(m);
  *edge = b == 0 ? pf_max_all(x) : -pf_max_all(-x);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  char deck[4096], box[2][600];
  const double lo0[3] = {0, 0, 0}, hi0[3] = {L, 1e-3, 1e-3}, lo1[3] = {L + gap, 0, 0}, hi1[3] = {2 * L + gap, 1e-3, 1e-3};
  snprintf(box[0], sizeof box[0], "%s", pf_test_pamgen_box(40, 4, 4, lo0, hi0));
  snprintf(box[1], sizeof box[1], "%s", pf_test_pamgen_box(40, 4, 4, lo1, hi1));
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0}}\n"
           "bodies:\n"
           "  - name: striker\n    type: finite_element\n    material: steel\n%s"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    initial_velocity: [100, 0, 0]\n"
           "  - name: struck\n    type: finite_element\n    material: steel\n%s"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "contact:\n  pairs:\n    - {bodies: [striker, struck]}\n"
           "time: {final_time: 6.0e-6, safety_factor: 0.8}\n",
           box[0], box[1]);
  pf_sim *sim = pf_test_sim("contact_bars", deck);
  const double c = sqrt(E / rho), F0 = 0.5 * rho * c * A * v0, T = 2 * L / c, p0 = rho * A * L * v0;
  pf_points *p = pf_sim_points(sim);
  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_step(sim, 0));
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  double t_on = -1, t_off = -1, tprev = 0, fprev = 0, overlap = 0, dp = 0;
  double *ts = NULL, *fs = NULL; /* the force history from the first touch */
  long n = 0, cap = 0;
  while (!pf_sim_finished(sim)) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    double f, v, x0, x1;
    body_state(p, 0, &f, &v, &x0);
    body_state(p, 1, &f, &v, &x1);
    overlap = fmax(overlap, x0 - x1);
    dp = fmax(dp, fabs(g.momentum[0] - g0.momentum[0]));
    const double on = 1e-3 * F0; /* contact begins and ends where the force crosses this */
    if (t_on < 0 && f > on) t_on = tprev + (g.time - tprev) * (on - fprev) / (f - fprev);
    if (t_on >= 0 && f <= on && fprev > on) t_off = tprev + (g.time - tprev) * (fprev - on) / (fprev - f);
    if (t_on >= 0) {
      if (n == cap) {
        cap = 2 * cap + 1024;
        ts = realloc(ts, sizeof *ts * (size_t)cap), fs = realloc(fs, sizeof *fs * (size_t)cap);
        if (!ts || !fs) return 1;
      }
      ts[n] = g.time, fs[n++] = f;
    }
    tprev = g.time, fprev = f;
  }
  double mean = 0, span = 0; /* time-weighted mean force over the middle half of the contact */
  for (long k = 1; k < n; k++) {
    const double dt = ts[k] - ts[k - 1], mid = 0.5 * (ts[k] + ts[k - 1]);
    if (mid < t_on + 0.25 * T || mid > t_on + 0.75 * T) continue;
    mean += 0.5 * (fs[k] + fs[k - 1]) * dt, span += dt;
  }
  mean /= span > 0 ? span : 1;
  double f, v_striker, v_struck, x;
  body_state(p, 0, &f, &v_striker, &x);
  body_state(p, 1, &f, &v_struck, &x);
  PF_TEST_TRUE(t_on > 0 && t_off > t_on);
  PF_TEST_CLOSE(t_off - t_on, T, 0.03, 0);
  PF_TEST_CLOSE(mean, F0, 0.03, 0);
  PF_TEST_CLOSE(v_striker, 0.0, 0, 0.03 * v0);
  PF_TEST_CLOSE(v_struck, v0, 0.03, 0);
  PF_TEST_CLOSE(dp, 0.0, 0, 1e-12 * p0);
  PF_TEST_TRUE(overlap < 0.01 * h);
  PF_TEST_CLOSE(g.kinetic, g0.kinetic, 0.03, 0);
  pf_test_measure("duration_error", (t_off - t_on) / T - 1, "1");
  pf_test_measure("mean_force_error", mean / F0 - 1, "1");
  pf_test_measure("v_striker", v_striker, "m/s");
  pf_test_measure("v_struck", v_struck, "m/s");
  pf_test_measure("overlap", overlap / h, "h");
  pf_test_measure("momentum_error", dp / p0, "1");
  pf_test_measure("ke_change", g.kinetic / g0.kinetic - 1, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("contact bars: contact %.4g s (2L/c %.4g s, %+.2f %%), mean force %.5g N (F0 %.5g N, %+.2f %%), "
           "velocities %.3f / %.3f m/s, overlap %.3g h, momentum %.3g of m v0, KE %+.3f %%\n",
           t_off - t_on, T, 100 * ((t_off - t_on) / T - 1), mean, F0, 100 * (mean / F0 - 1), v_striker, v_struck,
           overlap / h, dp / p0, 100 * (g.kinetic / g0.kinetic - 1));
  free(ts), free(fs);
  pf_test_print_digest("contact_bars", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
