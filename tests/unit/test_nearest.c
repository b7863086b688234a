/* The distance to the nearest of a point set (core/nearest.c) and the horizon it gives a coupled
 * body (d_fe in a `peridynamic:` map's horizon expression; docs/theory/coupling.md §1).
 *   nearest: random sets of 1, 7 and 2,000 points (one of them flat, all of one coordinate
 *     alike), queried at random positions inside and well outside their box: the distance must
 *     equal the brute-force minimum over all points, computed with the same formula, bit for bit;
 *   d_fe: the coupled bar of tests/data/coupled_bar.yaml (1 mm hexahedra, x in [0, 30] mm,
 *     blending 1 - clamp((x - 14 mm) / 6 mm)): the elements act from the node column x = 15 mm
 *     on, so a node at x <= 14 mm is d_fe = 15 mm - x from them. The horizon
 *     "3.01e-3 - 2e-3 * min(max((0.007 - d_fe) / 0.006, 0), 1)" must then equal the deck's own
 *     "3.01e-3 - 2e-3 * min(max((x - 0.008) / 0.006, 0), 1)" at every node, to round-off;
 *   a PD body (not coupled) that names d_fe is an input error naming the key. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"

static double brute(const double *X, pf_int n, const double x[3]) {
  double best = INFINITY;
  for (pf_int k = 0; k < n; k++) {
    const double *y = &X[3 * k];
    best = fmin(best, sqrt((y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) + (y[2] - x[2]) * (y[2] - x[2])));
  }
  return best;
}

static void random_sets(void) {
  const pf_int sizes[3] = {1, 7, 2000};
  srand(12345);
  for (int s = 0; s < 3; s++) {
    const pf_int n = sizes[s];
    double *X = malloc(sizeof(double) * 3 * (size_t)n);
    for (pf_int k = 0; k < n; k++)
      for (int a = 0; a < 3; a++) X[3 * k + a] = (s == 2 && a == 2) ? 0.25 : (double)rand() / RAND_MAX;
    pf_nearest *q = NULL;
    PF_TEST_OK(pf_nearest_create(X, n, &q));
    for (int t = 0; t < 500; t++) {
      double x[3];
      for (int a = 0; a < 3; a++) x[a] = 4.0 * rand() / RAND_MAX - 1.5;
      const double want = brute(X, n, x), got = pf_nearest_distance(q, x);
      if (got != want) printf("set of %d points, query (%g, %g, %g): %.17g, brute force %.17g\n", (int)n, x[0], x[1], x[2], got, want);
      PF_TEST_TRUE(got == want);
    }
    pf_nearest_destroy(&q);
    free(X);
  }
}

static double *horizons(const char *horizon, pf_sim **sim) {
  static const char *const keys[1] = {"horizon:"};
  char line[160];
  snprintf(line, sizeof line, "      horizon: \"%s\"", horizon);
  const char *lines[1] = {line};
  const char *deck = pf_test_deck_variant("data/coupled_bar.yaml", 1, keys, lines);
  pf_sim_options opt = {.no_output = 1};
  PF_TEST_OK(pf_sim_create(deck, &opt, sim));
  pf_test_remove_shared(deck);
  return pf_points_field_get(pf_sim_points(*sim), "horizon");
}

static void distance_horizon(void) {
  pf_sim *a = NULL, *b = NULL;
  const double *ha = horizons("3.01e-3 - 2e-3 * min(max((x - 0.008) / 0.006, 0), 1)", &a);
  const double *hb = horizons("3.01e-3 - 2e-3 * min(max((0.007 - d_fe) / 0.006, 0), 1)", &b);
  const pf_points *pa = pf_sim_points(a), *pb = pf_sim_points(b);
  PF_TEST_TRUE(pa->n_owned == pb->n_owned);
  double worst = 0;
  for (pf_int i = 0; i < pa->n_owned && i < pb->n_owned; i++) {
    PF_TEST_TRUE(pa->gid[i] == pb->gid[i]);
    worst = fmax(worst, fabs(ha[i] - hb[i]) / ha[i]);
  }
  worst = pf_max_all(worst);
  if (pf_comm_rank() == 0) printf("d_fe horizon against the explicit taper: largest relative difference %.2e\n", worst);
  PF_TEST_TRUE(worst < 1e-12);
  pf_test_measure("d_fe_horizon_difference", worst, "1");
  pf_sim_destroy(&a);
  pf_sim_destroy(&b);
}

static void pd_body_refused(void) {
  const char *deck =
      "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.0}}\n"
      "bodies:\n  - {name: bar, material: steel, horizon: \"3.01e-3 - d_fe\",\n"
      "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.009, 0.003, 0.003], spacing: 0.001}}\n"
      "time: {steps: 1}\n";
  const char *path = pf_test_write_file(6, "d_fe_pd", deck);
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  pf_error_clear();
  const int ierr = pf_sim_create(path, &opt, &sim);
  pf_test_refused(ierr, sim != NULL, deck, "peridynamic: map of a finite_element body");
  pf_sim_destroy(&sim);
  remove(path);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  random_sets();
  distance_horizon();
  pd_body_refused();
  return pf_test_finish();
}
