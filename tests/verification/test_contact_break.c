/* Self-contact of one body's points: the contact radius of a pair within a body (contact/pairs.c
 * pair_radius, docs/theory/contact.md sec. 1.1). Two points of one PMB body on the x axis,
 * 1 mm apart in the reference configuration, V = 1e-9 m^3, rho = 7800 kg/m^3, self-contact
 * pair with spring constant k_s = 1.95e12 Pa and horizon delta = 1 mm, so that the pair is a
 * linear spring of stiffness k = C V^2, C = 18 k_s / (pi delta^5) (contact/contact.c).
 *
 * 1. Never bonded: each of the two points has a partner 0.4 mm away along y (body horizon
 *    0.5 mm: those are its only bonds), contact radius 1.5 mm given, at rest. A pair of one body
 *    touches only below 0.9 of its reference distance (Parks et al. 2008), so nothing moves: the
 *    kinetic energy stays exactly zero over 200 steps. With the radius alone the points across
 *    would be 0.5 mm inside it, and fly apart with 1.4 kJ.
 * 2. Bonded (horizon 1.5 mm), put at rest 0.7 mm apart (30 % compressed) and the bond broken by
 *    hand there, as a damage law breaks bonds in a crushed zone. Its rest length is 0.7 mm, so
 *    again nothing moves for 200 steps; with the default radius (0.9 of the reference distance)
 *    the points would be pushed apart from 0.2 mm inside it with the energy
 *    C V^2 (0.2 mm)^2 / 2 = 223 J, from nothing.
 * 3. Then the points are given +-1 m/s towards each other: they touch from the start, at
 *    r = 0.7 mm, and bounce as the harmonic oscillator of Peridigm's Contact_2x1x1 (see
 *    test_contact_pair.c): half period pi / sqrt(2 k / m), velocities reversed, kinetic energy
 *    back, largest overlap 2 v0 / omega below the rest length.
 * 4. Bonds broken by the material, PMB and LPS: a line of 6 points 1 mm apart (horizon 2.5 mm:
 *    bonds of 1 and 2 mm) stretched uniformly until every bond passes its critical stretch. A
 *    bond's rest length is its length at the positions of the step it failed in, rounded down
 *    to a float: on the x axis |x_j - x_i| exactly (the models record it as they release the
 *    bond, pf_pd_body_rest_at_break; the contact's scan would give the same).
 * The points are owned by whichever rank; every check is reduced over the ranks. */
#include "sim/sim.h"
#include "pd/pd.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const double V = 1e-9, RHO = 7800, KS = 1.95e12, DELTA = 1e-3, V0 = 1.0;

static pf_sim *points(const char *tag, const char *cloud, double horizon, const char *radius, double dt,
                      double final_time) {
  const char *pts = pf_test_write_file(0, tag, cloud);
  char deck[2048];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: pmb, density: %.17g, bulk_modulus: 1.0e11}}\n"
           "bodies:\n"
           "  - {name: bar, material: steel, horizon: %.17g, geometry: {shape: points_file, file: %s, block: 1}}\n"
           "contact:\n"
           "  pairs:\n"
           "    - {bodies: [bar, bar], spring_constant: %.17g, horizon: %.17g%s}\n"
           "time: {dt: %.17g, final_time: %.17g}\n"
           "output: {interval: 0}\n",
           RHO, horizon, pts, KS, DELTA, radius, dt, final_time);
  pf_sim *sim = pf_test_sim(tag, deck);
  remove(pts);
  return sim;
}

/* Separation of the two points (the body's owned points over the ranks). */
static double separation(pf_sim *sim) {
  const pf_points *p = pf_sim_points(sim);
  double x[2] = {0, 0};
  for (pf_int i = 0; i < p->n_owned; i++) x[p->X[3 * i] > 0] = p->y[3 * i];
  return pf_sum_all(x[1]) - pf_sum_all(x[0]);
}

/* Move the owned points to +-r/2 on the x axis with velocity -+v (towards each other). */
static void place(pf_sim *sim, double r, double v) {
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double s = p->X[3 * i] > 0 ? 1.0 : -1.0;
    p->u[3 * i] = s * 0.5 * r - p->X[3 * i];
    p->y[3 * i] = p->X[3 * i] + p->u[3 * i];
    p->v[3 * i] = -s * v;
  }
}

/* The largest kinetic energy over n steps. */
static double max_kinetic(pf_sim *sim, int n) {
  pf_sim_globals g;
  double ke = 0;
  for (int s = 0; s < n; s++) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    ke = fmax(ke, g.kinetic);
  }
  return ke;
}

/* Part 4 for model (its constants in mat): the bonds that failed, each checked at its step. */
static void rest_at_break(const char *model, const char *mat) {
  char tag[64], deck[2048];
  snprintf(tag, sizeof tag, "contact_break_%s", model);
  const char *pts = pf_test_write_file(0, tag, "0 0 0 1e-9 1\n0.001 0 0 1e-9 1\n0.002 0 0 1e-9 1\n"
                                       "0.003 0 0 1e-9 1\n0.004 0 0 1e-9 1\n0.005 0 0 1e-9 1\n");
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 7800, %s}}\n"
           "bodies:\n"
           "  - {name: bar, material: m, horizon: 2.5e-3, geometry: {shape: points_file, file: %s, block: 1},\n"
           "     damage: {law: critical_stretch, critical_stretch: 0.01}}\n"
           "contact: {pairs: [{bodies: [bar, bar]}]}\n"
           "time: {dt: 1e-8, final_time: 1}\n"
           "output: {interval: 0}\n",
           model, mat, pts);
  pf_sim *sim = pf_test_sim(tag, deck);
  remove(pts);
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_owned; i++) p->v[3 * i] = 1e5 * (p->X[3 * i] - 0.0025); /* strain rate 1e5 / s */
  const pf_family *fam = pf_pd_body_family(pf_sim_body(sim, 0));
  const int64_t nbonds = pf_pd_family_nbonds(fam);
  uint8_t *seen = calloc((size_t)nbonds + 1, 1);
  double checked = 0, wrong = 0;
  PF_TEST_OK(pf_sim_step(sim, 0));
  for (int s = 0; s < 2000 && pf_sum_all(checked) < 18; s++) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    for (pf_int r = 0; r < fam->n; r++)
      for (int64_t k = fam->offset[r]; k < fam->offset[r + 1]; k++) {
        if (!fam->broken[k] || seen[k]) continue;
        seen[k] = 1, checked++;
        const double len = fabs(p->y[3 * fam->neighbor[k]] - p->y[3 * (fam->first + r)]);
        float expect = (float)len;
        if ((double)expect > len) expect = nextafterf(expect, 0.0f);
        wrong += fam->rest[k] != expect;
      }
  }
  free(seen);
  PF_TEST_CLOSE(pf_sum_all(checked), 18, 0, 0); /* every bond, from both ends: 2 (5 + 4) */
  PF_TEST_CLOSE(pf_sum_all(wrong), 0, 0, 0);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double m = RHO * V, C = 18 * KS / (PF_PI * pow(DELTA, 5)), k = C * V * V;
  const double omega = sqrt(2 * k / m), half = PF_PI / omega, dt = half / 4000, rest = 0.7e-3;

  /* 1. never bonded, radius 1.5 mm, 1 mm apart */
  const char *four = "-0.0005 0 0 1.0e-9 1\n-0.0005 0.0004 0 1.0e-9 1\n0.0005 0 0 1.0e-9 1\n0.0005 0.0004 0 1.0e-9 1\n";
  pf_sim *sim = points("contact_break_unbonded", four, 0.5e-3, ", radius: 1.5e-3", dt, 1.0);
  PF_TEST_OK(pf_sim_step(sim, 0));
  const double ke_unbonded = max_kinetic(sim, 200);
  PF_TEST_CLOSE(ke_unbonded, 0, 0, 0);
  pf_sim_destroy(&sim);

  /* 2. bonded, compressed to 0.7 mm at rest, the bond broken there */
  sim = points("contact_break_bonded", "-0.0005 0 0 1.0e-9 1\n0.0005 0 0 1.0e-9 1\n", 1.5e-3, "", dt, 1.0);
  place(sim, rest, 0);
  pf_family *fam = (pf_family *)pf_pd_body_family(pf_sim_body(sim, 0)); /* as a damage law would */
  int64_t nbonds = pf_pd_family_nbonds(fam);
  for (int64_t q = 0; q < nbonds; q++) fam->broken[q] = 1;
  PF_TEST_CLOSE(pf_sum_all((double)nbonds), 2, 0, 0); /* the bond, seen from both ends */
  PF_TEST_OK(pf_sim_step(sim, 0));
  const double ke_broken = max_kinetic(sim, 200);
  PF_TEST_CLOSE(ke_broken, 0, 0, 0);
  PF_TEST_CLOSE(separation(sim), rest, 1e-15, 0);
  for (int64_t q = 0; q < nbonds; q++) PF_TEST_CLOSE(fam->rest[q], rest, 1e-7, 0);

  /* 3. the bounce from the rest length */
  place(sim, separation(sim), V0);
  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  PF_TEST_CLOSE(g0.kinetic, m * V0 * V0, 1e-12, 0);
  long in_contact = 0;
  double rmin = INFINITY;
  for (long s = 0; s < 6000; s++) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    const double r = separation(sim);
    rmin = fmin(rmin, r);
    in_contact += g.contact > 0 || r < rest;
  }
  const pf_points *p = pf_sim_points(sim);
  double vx[2] = {0, 0};
  for (pf_int i = 0; i < p->n_owned; i++) vx[p->X[3 * i] > 0] = p->v[3 * i];
  vx[0] = pf_sum_all(vx[0]), vx[1] = pf_sum_all(vx[1]);
  const double duration = (double)in_contact * dt;
  PF_TEST_CLOSE(duration, half, 0, 2 * dt);
  PF_TEST_CLOSE(vx[0], -V0, 1e-6, 0);
  PF_TEST_CLOSE(vx[1], V0, 1e-6, 0);
  PF_TEST_CLOSE(g.kinetic, g0.kinetic, 1e-6, 0);
  PF_TEST_CLOSE(rest - rmin, 2 * V0 / omega, 1e-3, 0);
  pf_test_measure("ke_never_bonded", ke_unbonded, "J");
  pf_test_measure("ke_broken", ke_broken, "J");
  pf_test_measure("dt_off", (duration - half) / dt, "1");
  pf_test_measure("overlap", rest - rmin, "m");
  pf_test_measure("overlap_closed_form", 2 * V0 / omega, "m");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("contact_break: KE at rest %.3e J (never bonded), %.3e J (broken at 0.7 mm); bounce %.12e s "
           "(closed form %.12e, %.2f dt off), v %.12f %.12f, overlap %.6e m (closed form %.6e)\n",
           ke_unbonded, ke_broken, duration, half, (duration - half) / dt, vx[0], vx[1], rest - rmin, 2 * V0 / omega);
  pf_test_print_digest("contact_break", sim);
  pf_sim_destroy(&sim);

  /* 4. bonds broken by the material */
  rest_at_break("pmb", "bulk_modulus: 1.0e11");
  rest_at_break("lps", "bulk_modulus: 1.0e11, shear_modulus: 7.0e10");
  return pf_test_finish();
}
