/* Rigid analytic surfaces (contact/rigid.c) against closed forms, on points placed by hand:
 *   quadratic sphere: a point at depth d = R - |y - c| gets F = k d^2 V along (y - c)/|y - c|,
 *     the energy is sum k d^3 V / 3 and the reaction is minus the sum of the forces;
 *   linear plane: F = k d n, U = k d^2 / 2, only on the points of the bodies it names;
 *   cylinders: radial push-out F = k d e_r (e_r the unit radial direction from the axis), none
 *     beyond |s| = L/2 along the axis and none outside the radius;
 *   friction: F_t = -min(mu F_n, m |v_t| / dt) v_t / |v_t| with v_t the tangential velocity
 *     relative to the surface (whose velocity is that of the last advance), dissipation
 *     |F_t| |v_t| dt;
 *   advance: x += dt v(t + dt/2), work -= reaction . v(t + dt/2) dt;
 *   stable step of the linear law 2 sqrt(m_min / k) over the selected bodies;
 *   bad decks are input errors naming the key. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact.h"

static const char *const names[] = {"a", "b"};

/* Validate and create a surface from a deck whose root mapping is the surface. */
static int load(const char *text, pf_rigid **r) {
  *r = NULL;
  pf_deck *d = NULL;
  int ierr = pf_test_deck_text("rigid", text, pf_rigid_keys, "rigid_surfaces[0]", &d);
  if (!ierr) ierr = pf_rigid_create(d, pf_deck_root(d), 2, names, r);
  pf_deck_destroy(&d);
  return ierr;
}

static pf_rigid *must_load(const char *text) {
  pf_rigid *r = NULL;
  if (load(text, &r)) {
    fprintf(stderr, "cannot load rigid surface deck:\n%s\n", text);
    pf_test_failures++;
  }
  return r;
}

/* The force on point i is want[3] (relative tolerance on the largest component). */
static void check_force(const pf_points *p, pf_int i, const double want[3], double tol) {
  double scale = fabs(want[0]) + fabs(want[1]) + fabs(want[2]);
  for (int a = 0; a < 3; a++) PF_TEST_CLOSE(p->f[3 * i + a], want[a], 0, tol * scale + 1e-300);
}

static void check_reaction(const pf_points *p, const double R[3], double tol) {
  for (int a = 0; a < 3; a++) {
    double sum = 0;
    for (pf_int i = 0; i < p->n_owned; i++) sum += p->f[3 * i + a];
    PF_TEST_CLOSE(R[a], -sum, tol, 1e-300);
  }
}

/* Sphere c = 0, R = 10 mm, k = 1e17 N/m^5 (default), V = 1e-12 m^3:
 *   y0 = (8, 0, 0) mm:            d = 2 mm,   F = 1e17 * 4e-6 * 1e-12 = 0.4 N along +x;
 *   y1 = 5 mm (1, 1, 1)/sqrt 3:   d = 5 mm,   F = 2.5 N along (1, 1, 1)/sqrt 3;
 *   y2 = (0, 0, -9.9) mm:         d = 0.1 mm, F = 1e-3 N along -z;
 *   y3 = (12, 0, 0) mm:           outside, no force.
 * U = 1e17 * 1e-12 (8e-9 + 1.25e-7 + 1e-12) / 3. Bodies 0 and 1: no `bodies` key, both pushed. */
static void sphere_quadratic(void) {
  pf_rigid *r = must_load("shape: sphere\ncenter: [0, 0, 0]\nradius: 0.01\n");
  if (!r) return;
  const double s3 = 0.005 / sqrt(3.0);
  const double y[4][3] = {{0.008, 0, 0}, {s3, s3, s3}, {0, 0, -0.0099}, {0.012, 0, 0}};
  pf_points *p = pf_test_points(4, y, 1e-12, 1e-6);
  p->body[1] = 1;
  double R[3], U = 0, W = 0;
  PF_TEST_OK(pf_rigid_force(r, p, 1e-6, R, &U, &W));
  const double u3 = 1 / sqrt(3.0);
  check_force(p, 0, (double[3]){0.4, 0, 0}, 1e-13);
  check_force(p, 1, (double[3]){2.5 * u3, 2.5 * u3, 2.5 * u3}, 1e-13);
  check_force(p, 2, (double[3]){0, 0, -1e-3}, 1e-10); /* d = 1e-4 from 9.9e-3: cancellation */
  check_force(p, 3, (double[3]){0, 0, 0}, 0);
  check_reaction(p, R, 1e-14);
  PF_TEST_CLOSE(U, 1e17 * 1e-12 * (8e-9 + 1.25e-7 + 1e-12) / 3, 1e-12, 0);
  PF_TEST_TRUE(W == 0);
  PF_TEST_TRUE(!strcmp(pf_rigid_name(r), "indenter"));
  PF_TEST_TRUE(isinf(pf_rigid_stable_dt(r, p)));
  pf_points_destroy(&p);
  pf_rigid_destroy(&r);
}

/* Plane through p = (1, 2, 3) with normal (0, 3, 4) -> n = (0, 0.6, 0.8), linear law
 * k = 1e6 N/m, acting on body b (index 1) only. With the tangent t = (1, 0, 0):
 *   y0 = p - 1 mm n + 50 mm t, body b: d = 1 mm, F = 1000 N n, U = 0.5 J;
 *   y1 = the same place, body a: no force;
 *   y2 = p + 1 mm n, body b: in front, no force.
 * Stable step: m_min over body b = 2e-3 kg (body a's 1e-6 kg does not count):
 * 2 sqrt(2e-3 / 1e6) = 8.944e-5 s. */
static void plane_linear(void) {
  pf_rigid *r = must_load("name: floor\nshape: plane\npoint: [1, 2, 3]\nnormal: [0, 3, 4]\n"
                          "law: linear\nstiffness: 1e6\nbodies: [b]\n");
  if (!r) return;
  const double y[3][3] = {{1.05, 2 - 0.6e-3, 3 - 0.8e-3}, {1.05, 2 - 0.6e-3, 3 - 0.8e-3},
                          {1, 2 + 0.6e-3, 3 + 0.8e-3}};
  pf_points *p = pf_test_points(3, y, 1e-9, 2e-3);
  p->body[0] = 1;
  p->body[1] = 0;
  p->body[2] = 1;
  p->m[1] = 1e-6;
  p->m[2] = 5e-3;
  double R[3], U = 0, W = 0;
  PF_TEST_OK(pf_rigid_force(r, p, 0, R, &U, &W));
  check_force(p, 0, (double[3]){0, 600, 800}, 1e-11); /* d from 3 - 0.8e-3: rounding of 1e-13 m */
  check_force(p, 1, (double[3]){0, 0, 0}, 0);
  check_force(p, 2, (double[3]){0, 0, 0}, 0);
  check_reaction(p, R, 1e-14);
  PF_TEST_CLOSE(U, 0.5, 1e-11, 0);
  PF_TEST_TRUE(!strcmp(pf_rigid_name(r), "floor"));
  PF_TEST_CLOSE(pf_rigid_stable_dt(r, p), 2 * sqrt(2e-3 / 1e6), 1e-15, 0);
  pf_points_destroy(&p);
  pf_rigid_destroy(&r);
}

/* Infinite cylinder along z (axis given as [0, 0, 2]) through the origin, R = 10 mm,
 * k = 1e15 N/m^5, V = 1e-12 m^3:
 *   y0 = (4, 3, 1e5) mm: radial distance 5 mm whatever the height, d = 5 mm,
 *     F = 1e15 * 25e-6 * 1e-12 = 0.025 N along (0.8, 0.6, 0);
 *   y1 = (20, 0, 0) mm: outside the radius, no force. */
static void cylinder_infinite(void) {
  pf_rigid *r = must_load("shape: cylinder\ncenter: [0, 0, 0]\naxis: [0, 0, 2]\nradius: 0.01\n"
                          "stiffness: 1e15\n");
  if (!r) return;
  const double y[2][3] = {{0.004, 0.003, 100.0}, {0.02, 0, 0}};
  pf_points *p = pf_test_points(2, y, 1e-12, 1e-6);
  double R[3], U = 0, W = 0;
  PF_TEST_OK(pf_rigid_force(r, p, 0, R, &U, &W));
  check_force(p, 0, (double[3]){0.02, 0.015, 0}, 1e-13);
  check_force(p, 1, (double[3]){0, 0, 0}, 0);
  check_reaction(p, R, 1e-14);
  PF_TEST_CLOSE(U, 1e15 * 1.25e-7 * 1e-12 / 3, 1e-13, 0);
  pf_points_destroy(&p);
  pf_rigid_destroy(&r);
}

/* Finite cylinder: centre c = (1, 1, 1), axis a = (1, 1, 0)/sqrt 2, R = 0.1 m, L = 0.4 m,
 * linear law k = 2e5 N/m. Points c + s a + rho e with e = (0, 0, 1) or e2 = (1, -1, 0)/sqrt 2:
 *   s = 0.1,   rho = 0.05 e:  d = 0.05, F = 1e4 N along e, U = 250 J;
 *   s = 0.25,  rho = 0.05 e:  beyond L/2 = 0.2 (no end-cap force), none;
 *   s = -0.19, rho = 0.15 e:  outside the radius, none;
 *   s = -0.19, rho = 0.03 e2: d = 0.07, F = 1.4e4 N along e2, U = 490 J. */
static void cylinder_finite(void) {
  pf_rigid *r = must_load("shape: cylinder\ncenter: [1, 1, 1]\naxis: [1, 1, 0]\nradius: 0.1\n"
                          "length: 0.4\nlaw: linear\nstiffness: 2e5\n");
  if (!r) return;
  const double h = 1 / sqrt(2.0), s[4] = {0.1, 0.25, -0.19, -0.19}, rho[4] = {0.05, 0.05, 0.15, 0.03};
  const double e[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {h, -h, 0}};
  double y[4][3];
  for (int i = 0; i < 4; i++)
    for (int a = 0; a < 3; a++) y[i][a] = 1 + s[i] * (a < 2 ? h : 0) + rho[i] * e[i][a];
  pf_points *p = pf_test_points(4, (const double(*)[3])y, 1e-9, 1e-6);
  double R[3], U = 0, W = 0;
  PF_TEST_OK(pf_rigid_force(r, p, 0, R, &U, &W));
  check_force(p, 0, (double[3]){0, 0, 1e4}, 1e-12);
  check_force(p, 1, (double[3]){0, 0, 0}, 0);
  check_force(p, 2, (double[3]){0, 0, 0}, 0);
  check_force(p, 3, (double[3]){1.4e4 * h, -1.4e4 * h, 0}, 1e-12);
  check_reaction(p, R, 1e-14);
  PF_TEST_CLOSE(U, 250 + 490, 1e-12, 0);
  double x[3];
  pf_rigid_position(r, x);
  PF_TEST_TRUE(x[0] == 1 && x[1] == 1 && x[2] == 1);
  pf_points_destroy(&p);
  pf_rigid_destroy(&r);
}

/* Friction on the plane z = 0 (normal +z), linear law k = 1e3 N/m: a point at z = -10 mm has
 * F_n = 10 N. Mass m = 1e-3 kg, velocity (3, 4, -5) m/s: v_t = (3, 4, 0), |v_t| = 5 m/s (the
 * normal part does not count), dt = 1e-3 s, so the stick limit m |v_t| / dt = 5 N.
 *   mu = 10:  mu F_n = 100 N > 5 N: F_t = 5 N (-0.6, -0.8, 0), which stops the sliding in one
 *             step (v_t + F_t dt / m = 0); dissipation 5 * 5 * 1e-3 = 0.025 J.
 *   mu = 0.1: F_t = 1 N (-0.6, -0.8, 0); dissipation 1 * 5 * 1e-3 = 0.005 J.
 *   dt = 0 or mu = 0: no friction.
 *   Plane moving with velocity (20, 0, 0) (after one advance; parallel to itself, the depth is
 *   unchanged), mu = 0.1: v_rel = (-17, 4, -5), |v_t| = sqrt 305, stick limit 17.5 N > 1 N,
 *   F_t = 1 N (17, -4, 0)/sqrt 305, dissipation 1 * sqrt 305 * 1e-3. */
static double friction_case(const char *deck, double dt, int advance, double ft[3], double *diss) {
  memset(ft, 0, 3 * sizeof(double));
  *diss = 0;
  pf_rigid *r = must_load(deck);
  if (!r) return 0;
  const double y[1][3] = {{0, 0, -0.01}};
  pf_points *p = pf_test_points(1, y, 1e-9, 1e-3);
  p->v[0] = 3, p->v[1] = 4, p->v[2] = -5;
  double R[3] = {0, 0, 0}, U = 0, dx[3];
  if (advance) pf_rigid_advance(r, 0, dt, dx);
  *diss = 0.125; /* added to */
  PF_TEST_OK(pf_rigid_force(r, p, dt, R, &U, diss));
  *diss -= 0.125;
  for (int a = 0; a < 3; a++) ft[a] = p->f[a] - (a == 2 ? 10.0 : 0.0);
  check_reaction(p, R, 1e-14);
  PF_TEST_CLOSE(p->f[2], 10.0, 1e-12, 0);
  double vt_after = hypot(p->v[0] - (advance ? 20 : 0) + ft[0] * dt / p->m[0], p->v[1] + ft[1] * dt / p->m[0]);
  pf_points_destroy(&p);
  pf_rigid_destroy(&r);
  return vt_after;
}

static void friction(void) {
  const char *base = "shape: plane\npoint: [0, 0, 0]\nnormal: [0, 0, 1]\nlaw: linear\nstiffness: 1e3\n";
  char deck[512];
  double ft[3], diss;
  snprintf(deck, sizeof deck, "%sfriction: 10\n", base);
  double left = friction_case(deck, 1e-3, 0, ft, &diss);
  PF_TEST_CLOSE(ft[0], -3.0, 1e-12, 0);
  PF_TEST_CLOSE(ft[1], -4.0, 1e-12, 0);
  PF_TEST_CLOSE(left, 0, 0, 1e-12); /* stopped in one step */
  PF_TEST_CLOSE(diss, 0.025, 1e-12, 0);
  snprintf(deck, sizeof deck, "%sfriction: 0.1\n", base);
  friction_case(deck, 1e-3, 0, ft, &diss);
  PF_TEST_CLOSE(ft[0], -0.6, 1e-12, 0);
  PF_TEST_CLOSE(ft[1], -0.8, 1e-12, 0);
  PF_TEST_CLOSE(diss, 0.005, 1e-12, 0);
  friction_case(deck, 0, 0, ft, &diss); /* dt = 0 */
  PF_TEST_TRUE(ft[0] == 0 && ft[1] == 0 && diss == 0);
  friction_case(base, 1e-3, 0, ft, &diss); /* mu = 0 */
  PF_TEST_TRUE(ft[0] == 0 && ft[1] == 0 && diss == 0);
  snprintf(deck, sizeof deck, "%sfriction: 0.1\nvelocity: [\"20\", \"0\", \"0\"]\n", base);
  friction_case(deck, 1e-3, 1, ft, &diss);
  const double s305 = sqrt(305.0);
  PF_TEST_CLOSE(ft[0], 17 / s305, 1e-12, 0);
  PF_TEST_CLOSE(ft[1], -4 / s305, 1e-12, 0);
  PF_TEST_CLOSE(diss, s305 * 1e-3, 1e-12, 0);
}

/* Velocity (2, 0, 1000 t) m/s from t = 2 ms over dt = 1 ms: the midpoint velocity is
 * (2, 0, 2.5), so the motion is (2e-3, 0, 2.5e-3) and x goes from (0, 0, 0.1) to
 * (2e-3, 0, 0.1025). */
static void advance(void) {
  pf_rigid *r = must_load("shape: sphere\ncenter: [0, 0, 0.1]\nradius: 0.01\n"
                          "velocity: [\"2\", \"0\", \"t*1000\"]\n");
  if (!r) return;
  double dx[3], x[3];
  pf_rigid_advance(r, 2e-3, 1e-3, dx);
  PF_TEST_CLOSE(dx[0], 2e-3, 1e-14, 0);
  PF_TEST_CLOSE(dx[2], 2.5e-3, 1e-14, 0);
  pf_rigid_position(r, x);
  PF_TEST_CLOSE(x[0], 2e-3, 1e-14, 0);
  PF_TEST_CLOSE(x[1], 0, 0, 0);
  PF_TEST_CLOSE(x[2], 0.1025, 1e-14, 0);
  pf_rigid_set_position(r, (double[3]){0.5, 0.25, 0.125});
  pf_rigid_position(r, x);
  PF_TEST_TRUE(x[0] == 0.5 && x[1] == 0.25 && x[2] == 0.125);
  pf_rigid_destroy(&r);
}

/* A bad deck is an input error whose message names the key (and what is known). */
static void bad(const char *text, const char *mention) {
  pf_rigid *r = NULL;
  pf_error_clear();
  const int ierr = load(text, &r);
  pf_test_refused(ierr, r != NULL, text, mention);
  pf_rigid_destroy(&r);
}

static void bad_decks(void) {
  pf_error_set_quiet(1);
  bad("shape: cone\ncenter: [0, 0, 0]\nradius: 1\n", "known: sphere, plane, cylinder");
  bad("shape: cylinder\ncenter: [0, 0, 0]\naxis: [0, 0, 0]\nradius: 1\n", "key 'axis'");
  bad("shape: cylinder\ncenter: [0, 0, 0]\nradius: 1\n", "key 'axis'");
  bad("shape: cylinder\ncenter: [0, 0, 0]\naxis: [0, 0, 1]\nradius: 1\nlength: 0\n", "key 'length'");
  bad("shape: plane\npoint: [0, 0, 0]\nnormal: [0, 0, 1]\nlaw: linear\n", "key 'stiffness'");
  bad("shape: plane\npoint: [0, 0, 0]\nnormal: [0, 0, 1]\nlaw: cubic\n", "known: quadratic, linear");
  bad("shape: plane\npoint: [0, 0, 0]\nnormal: [0, 0, 1]\nbodies: [a, c]\n", "known: a, b");
  bad("shape: plane\npoint: [0, 0, 0]\nnormal: [0, 0, 1]\nfriction: -0.1\n", "key 'friction'");
  bad("shape: sphere\ncenter: [0, 0, 0]\nradius: -1\n", "key 'radius'");
  pf_error_clear();
  pf_error_set_quiet(0);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  sphere_quadratic();
  plane_linear();
  cylinder_infinite();
  cylinder_finite();
  friction();
  advance();
  bad_decks();
  return pf_test_finish();
}
