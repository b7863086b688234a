/* The rigid planar wall (contact/wall.c) on points placed by hand, against what a kinematic,
 * frictionless wall must do (LS-DYNA *RIGIDWALL_PLANAR; Abaqus NO SEPARATION for the bilateral
 * form):
 *   position: a point found behind the plane is put back on it along the normal, its inward
 *     normal velocity is removed and m (v.n)^2 / 2 is booked; its tangential velocity is kept;
 *     a point in front of the plane, or moving outward, is left alone;
 *   force, default (separation: true): a point on the plane loses the inward normal part of its
 *     force (which is the reaction) and keeps the outward part, so it can leave;
 *   force, separation: false: a point on the plane loses both normal parts (the reaction may
 *     pull), and keeps the tangential part (frictionless);
 *   only the bodies the wall names;
 *   bad decks are input errors naming the key. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact.h"

static const char *const names[] = {"a", "b"};

static int load(const char *text, pf_wall **w) {
  *w = NULL;
  pf_deck *d = NULL;
  int ierr = pf_test_deck_text("wall", text, pf_wall_keys, "walls[0]", &d);
  if (!ierr) ierr = pf_wall_create(d, pf_deck_root(d), 2, names, w);
  pf_deck_destroy(&d);
  return ierr;
}

static pf_wall *must_load(const char *text) {
  pf_wall *w = NULL;
  if (load(text, &w)) {
    fprintf(stderr, "cannot load wall deck:\n%s\n", text);
    pf_test_failures++;
  }
  return w;
}

#define PLANE_Z "name: w\npoint: [0, 0, 0.5]\nnormal: [0, 0, 2]\n"

/* The plane z = 0.5 with the given separation. */
static pf_wall *plane_wall(int separation) {
  char text[256];
  snprintf(text, sizeof text, PLANE_Z "separation: %s\n", separation ? "true" : "false");
  return must_load(text);
}

/* A point 1 mm behind z = 0.5 moving in and sideways is put back, keeps its sideways velocity,
 * and the energy and momentum of its inward velocity are booked; one moving outward keeps all of it. */
static void position(void) {
  pf_wall *w = must_load(PLANE_Z);
  const double y[3][3] = {{0.1, 0.2, 0.499}, {0, 0, 0.499}, {0, 0, 0.6}};
  pf_points *p = pf_test_points(3, y, 1e-9, 2.0);
  const double v0[3][3] = {{3, -4, -5}, {1, 0, 2}, {0, 0, -7}};
  memcpy(p->v, v0, sizeof v0);
  double loss = 0.25, impulse[3] = {0, 0, 0};
  pf_wall_enforce_position(w, p, &loss, impulse);
  /* the momentum given: the first point's inward 5 m/s of its 2 kg, along +z, nothing else */
  PF_TEST_TRUE(impulse[0] == 0 && impulse[1] == 0);
  PF_TEST_CLOSE(impulse[2], 2.0 * 5.0, 1e-15, 0);
  PF_TEST_CLOSE(p->y[2], 0.5, 1e-15, 0);
  PF_TEST_CLOSE(p->u[2], 1e-3, 1e-12, 0);
  PF_TEST_TRUE(p->y[0] == 0.1 && p->y[1] == 0.2);
  PF_TEST_TRUE(p->v[0] == 3 && p->v[1] == -4 && p->v[2] == 0);
  PF_TEST_CLOSE(loss, 0.25 + 0.5 * 2.0 * 25.0, 1e-15, 0);
  PF_TEST_CLOSE(p->y[5], 0.5, 1e-15, 0); /* put back, but moving out: velocity kept */
  PF_TEST_TRUE(p->v[3] == 1 && p->v[5] == 2);
  PF_TEST_TRUE(p->y[8] == 0.6 && p->v[8] == -7); /* in front: untouched */
  pf_points_destroy(&p);
  pf_wall_destroy(&w);
}

/* Three points: on the plane pushed in, on the plane pulled out, and 1 mm in front pushed in. */
static void force(int separation) {
  pf_wall *w = plane_wall(separation);
  const double y[3][3] = {{0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.501}};
  pf_points *p = pf_test_points(3, y, 1e-9, 1.0);
  const double f0[3][3] = {{1, 2, -3}, {-1, 5, 7}, {0, 0, -11}};
  memcpy(p->f, f0, sizeof f0);
  double reaction[3];
  pf_wall_enforce_force(w, p, reaction);
  PF_TEST_TRUE(p->f[0] == 1 && p->f[1] == 2 && p->f[2] == 0);
  PF_TEST_TRUE(p->f[3] == -1 && p->f[4] == 5);
  PF_TEST_TRUE(p->f[5] == (separation ? 7 : 0));
  PF_TEST_TRUE(p->f[6] == 0 && p->f[7] == 0 && p->f[8] == -11);
  PF_TEST_TRUE(reaction[0] == 0 && reaction[1] == 0);
  PF_TEST_CLOSE(reaction[2], separation ? -3.0 : -3.0 + 7.0, 1e-15, 0);
  pf_points_destroy(&p);
  pf_wall_destroy(&w);
}

/* A unit mass on the plane under a steady outward-and-sideways force, stepped with the central
 * difference as the time loop does: with separation it leaves at the rate of f/m; without, it
 * slides along the plane at the rate of the sideways force alone. */
static void slide_or_leave(int separation) {
  pf_wall *w = plane_wall(separation);
  const double y[1][3] = {{0, 0, 0.5}};
  pf_points *p = pf_test_points(1, y, 1e-9, 1.0);
  const double dt = 1e-3;
  const int n = 10;
  double loss = 0, reaction[3], impulse[3] = {0, 0, 0};
  for (int k = 0; k < n; k++) {
    p->f[0] = 2.0, p->f[1] = 0, p->f[2] = 4.0;
    pf_wall_enforce_force(w, p, reaction);
    for (int a = 0; a < 3; a++) p->v[a] += dt * p->f[a] / p->m[0];
    for (int a = 0; a < 3; a++) p->u[a] += dt * p->v[a], p->y[a] = p->X[a] + p->u[a];
    pf_wall_enforce_position(w, p, &loss, impulse);
  }
  const double s = 0.5 * dt * dt * n * (n + 1); /* sum over the steps of k dt^2 */
  PF_TEST_CLOSE(p->y[0], 2.0 * s, 1e-12, 0);
  PF_TEST_CLOSE(p->y[2], separation ? 0.5 + 4.0 * s : 0.5, 1e-12, 0);
  PF_TEST_TRUE(loss == 0);
  pf_points_destroy(&p);
  pf_wall_destroy(&w);
}

/* The wall acts only on the bodies it names. */
static void bodies(void) {
  pf_wall *w = must_load(PLANE_Z "bodies: [b]\n");
  const double y[2][3] = {{0, 0, 0.49}, {0, 0, 0.49}};
  pf_points *p = pf_test_points(2, y, 1e-9, 1.0);
  p->body[1] = 1;
  double loss = 0, impulse[3] = {0, 0, 0};
  pf_wall_enforce_position(w, p, &loss, impulse);
  PF_TEST_TRUE(p->y[2] == 0.49);
  PF_TEST_CLOSE(p->y[5], 0.5, 1e-15, 0);
  pf_points_destroy(&p);
  pf_wall_destroy(&w);
}

static void bad(const char *text, const char *mention) {
  pf_wall *w = NULL;
  pf_error_clear();
  const int ierr = load(text, &w);
  pf_test_refused(ierr, w != NULL, text, mention);
  pf_wall_destroy(&w);
}

static void bad_decks(void) {
  pf_error_set_quiet(1);
  bad(PLANE_Z "separation: sometimes\n", "key 'separation'");
  bad("name: w\npoint: [0, 0, 0]\nnormal: [0, 0, 0]\n", "key 'normal'");
  bad(PLANE_Z "bodies: [c]\n", "known: a, b");
  bad(PLANE_Z "friction: 0.1\n", "friction");
  pf_error_clear();
  pf_error_set_quiet(0);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  position();
  force(1);
  force(0);
  slide_or_leave(1);
  slide_or_leave(0);
  bodies();
  bad_decks();
  return pf_test_finish();
}
