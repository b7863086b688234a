/* Kalthoff-Winkler (slow; tests/data/kalthoff_winkler.yaml): the edge-notched steel plate struck
 * at 16 m/s between its notches, PMB with critical-energy bond failure (G0 = 42,408 J/m^2,
 * delta = 3.015 h, h = 1 mm), to 70 us. usage: test_kalthoff_winkler [h]: another spacing h (m),
 * with delta = 3.015 h and the lattice placed so that the notch planes y = +-25 mm lie halfway
 * between two rows of points (50 mm / h must be a whole number; h = 2 mm is the coarse run).
 * Reference: the cracks leave the notch tips at 65-72 degrees to the notch axis (Kalthoff &
 * Winkler 1988 measured about 70; the band is the issue's, from the experiment and published PD
 * runs, e.g. Silling 2003's 68).
 *
 * Measurement, for each notch (tip at x = 50 mm, y = +-25 mm): the points with bond damage
 * phi >= 0.3 beyond the tip (x > 50 mm, |y| > 25 mm + 2 h) are binned by their reference row |y|
 * (rows of h, every layer of the thickness); the crack's path is the mean x of each row, from
 * the tip up to the first empty row. Checks:
 *  - the crack has run at least 20 mm (rows) from the tip, one crack per row (its damaged points
 *    of a row within 4 h of x: a sharp crack through the thickness, not a diffuse zone);
 *  - the least-squares line x = a + b |y| through the path meets the notch plane within one
 *    horizon of the tip;
 *  - its angle to the notch axis, atan(1 / b), lies in 65-72 degrees, and the two cracks agree
 *    to 1 degree (the problem is symmetric about y = 0).
 * With PF_TEST_VERBOSE the angles are printed (docs/verification.md): 70.19 degrees at h = 1 mm,
 * 68.72 at 2 mm (the test verification/test_kalthoff_winkler_coarse), 70.81 at 1.25 mm; at
 * 5/6 mm the two cracks part (71.12 and 68.94: the 1 degree check fails there). */
#include "sim/sim.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { ROWS = 400 }; /* rows of points beyond the notch plane, |y| = 25 mm + (k + 1/2) h */

/* The crack above (sign +1) or below (-1) the plate's centre line on the lattice of spacing h:
 * its angle in degrees, or NAN when the checks on its shape fail (they are reported). */
static double crack_angle(const pf_points *p, const double *phi, int sign, double h) {
  const int first = 2, rows = (int)floor(0.075 / h + 0.5); /* the path starts 2 rows above the tip */
  double n[ROWS] = {0}, sx[ROWS] = {0}, xmin[ROWS], xmax[ROWS];
  for (int k = 0; k < ROWS; k++) xmin[k] = INFINITY, xmax[k] = -INFINITY;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double x = p->X[3 * i], y = sign * p->X[3 * i + 1];
    if (phi[i] < 0.3 || x <= 0.050 || y <= 0.025) continue;
    const int k = (int)floor((y - 0.025) / h); /* (y - 25 mm) / h is k + 1/2 on the lattice */
    if (k < first || k >= rows || k >= ROWS) continue;
    n[k] += 1, sx[k] += x, xmin[k] = fmin(xmin[k], x), xmax[k] = fmax(xmax[k], x);
  }
  MPI_Allreduce(MPI_IN_PLACE, n, ROWS, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, sx, ROWS, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, xmin, ROWS, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, xmax, ROWS, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  double s1 = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  int k = first, ok = 1;
  for (; k < rows && k < ROWS && n[k] > 0; k++) {
    const double y = 0.025 + (k + 0.5) * h, x = sx[k] / n[k];
    if (xmax[k] - xmin[k] > 4 * h) {
      fprintf(stderr, "kalthoff-winkler: crack %+d, row y = %.1f mm: damage spread over x = %.1f..%.1f mm\n",
              sign, y * 1e3, xmin[k] * 1e3, xmax[k] * 1e3);
      ok = 0;
    }
    s1 += 1, sy += y, sxx += x, syy += y * y, sxy += x * y;
  }
  const double len = (k - first) * h;
  if (len < 0.020) {
    fprintf(stderr, "kalthoff-winkler: crack %+d ran %.1f mm from the tip (want >= 20 mm)\n", sign, len * 1e3);
    return NAN;
  }
  const double b = (s1 * sxy - sy * sxx) / (s1 * syy - sy * sy), a = (sxx - b * sy) / s1;
  const double x_at_notch = a + b * 0.025, angle = atan2(1.0, b) * 180.0 / PF_PI;
  pf_test_measure(sign > 0 ? "angle_upper" : "angle_lower", angle, "deg");
  pf_test_measure(sign > 0 ? "length_upper" : "length_lower", len * 1e3, "mm");
  pf_test_measure(sign > 0 ? "x_at_notch_upper" : "x_at_notch_lower", x_at_notch * 1e3, "mm");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("kalthoff-winkler: h = %g mm, crack %+d: %.1f mm long, angle %.2f deg, meets the notch plane at x = %.2f mm\n",
           h * 1e3, sign, len * 1e3, angle, x_at_notch * 1e3);
  if (fabs(x_at_notch - 0.050) > 3.015 * h) {
    fprintf(stderr, "kalthoff-winkler: crack %+d meets the notch plane at x = %.2f mm, not at the tip (50 mm)\n",
            sign, x_at_notch * 1e3);
    ok = 0;
  }
  return ok ? angle : NAN;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double h = argc > 1 ? atof(argv[1]) : 1e-3;
  if (!(h > 0) || fabs(0.05 / h - floor(0.05 / h + 0.5)) > 1e-9) {
    fprintf(stderr, "usage: test_kalthoff_winkler [h]: 50 mm / h must be a whole number\n");
    return 2;
  }
  /* the deck's lattice is h = 1 mm; another h is set with the lattice's origin at x = h/2 (the tip
   * x = 50 mm halfway between two columns), y = (25 mm + h/2) mod h (the notch planes halfway
   * between two rows) and z = 4.5 mm mod h (the layers centred on the plate's mid-plane) */
  char set_h[96], set_delta[96], set_origin[160];
  snprintf(set_h, sizeof set_h, "bodies.plate.geometry.spacing=%.17g", h);
  snprintf(set_delta, sizeof set_delta, "bodies.plate.horizon=%.17g", 3.015 * h);
  snprintf(set_origin, sizeof set_origin, "bodies.plate.geometry.origin=[%.17g, %.17g, %.17g]", h / 2,
           fmod(0.025 + h / 2, h), fmod(0.0045, h));
  const char *sets[] = {set_h, set_delta, set_origin};
  pf_sim_options opt = {.no_output = 1, .sets = argc > 1 ? sets : NULL, .nsets = argc > 1 ? 3 : 0};
  pf_sim *sim = NULL;
  if (pf_sim_create("data/kalthoff_winkler.yaml", &opt, &sim)) return 1;
  pf_sim_globals g; /* (also brings the bond damage field up to date) */
  pf_test_run_to_end(sim, NULL, &g);
  const pf_points *p = pf_sim_points(sim);
  const double *phi = pf_points_field_get(p, "damage");
  PF_TEST_TRUE(phi != NULL);
  if (phi) {
    const double up = crack_angle(p, phi, +1, h), down = crack_angle(p, phi, -1, h);
    PF_TEST_TRUE(up >= 65 && up <= 72);
    PF_TEST_TRUE(down >= 65 && down <= 72);
    PF_TEST_CLOSE(up, down, 0, 1.0);
  }
  pf_test_print_digest("kalthoff_winkler", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
