/* Several materials in one FE body (fem/materials.c) on tests/data/bimaterial_bar_mixed.yaml: a
 * 20 x 2 x 2 mm bar of 0.5 x 1 x 1 mm hexahedra, steel (the body's material) for x < 10 mm,
 * aluminium on block_2 (x > 10 mm), J2 copper for 12 < x < 16 mm (a later region entry).
 *  - each element's material is the one its centroid's position gives;
 *  - the lumped masses sum to the closed form sum_m rho_m V_m (1e-12);
 *  - the reference stable step is l / c_max, l = V / A_max = 0.5 mm, c_max the fastest of the
 *    three P-wave speeds sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu)) / rho) (aluminium's, 6198 m/s;
 *    steel's, the body's own material, is 5875 m/s) (1e-12);
 *  - after the run: elements were deleted by erosion (plastic_strain 0.01), every one of them
 *    copper (the elastic materials have no eqps); the output field eqps exists though the body's
 *    own material has none (the union of state names), is zero at every node with no copper
 *    element and positive at some copper node. */
#include "fem/fem_impl.h"
#include "sim/sim.h"
#include "test_common.h"

#include <math.h>
#include <string.h>

static const double Lx = 0.02, A = 4e-6, x_al = 0.01, cu_lo = 0.012, cu_hi = 0.016;

static double centroid_x(const pf_mesh *m, pf_int e) {
  double c = 0;
  for (int I = 0; I < 8; I++) c += m->X[3 * (size_t)m->conn[8 * (size_t)e + I]] / 8;
  return c;
}

static const char *expected_material(double x) { return x < x_al ? "steel" : x > cu_lo && x < cu_hi ? "copper" : "aluminium"; }

static double p_wave_speed(double E, double nu, double rho) {
  return sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *keys[] = {"restart:", "output:"}, *lines[] = {"restart: {interval: 0}", "output: {interval: 0}"};
  const char *deck = pf_test_deck_variant("data/bimaterial_bar_mixed.yaml", 2, keys, lines);
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  PF_TEST_OK(pf_sim_create(deck, &opt, &sim));
  pf_test_remove_shared(deck);
  if (!sim) return pf_test_finish();
  pf_fem_body *fe = pf_sim_fem_body(sim, 0);
  pf_points *p = pf_sim_points(sim);
  const pf_mesh *m = pf_fem_body_mesh(fe);
  int wrong = 0;
  for (pf_int e = 0; e < fe->nel; e++)
    wrong += strcmp(pf_material_name(pf_fem_element_material(fe, e)->mat), expected_material(centroid_x(m, fe->eid[e])));
  PF_TEST_TRUE(wrong == 0);
  double mass = 0;
  for (pf_int i = 0; i < p->n_owned; i++) mass += p->m[i];
  const double want = A * (x_al * 7800 + (Lx - x_al - (cu_hi - cu_lo)) * 2700 + (cu_hi - cu_lo) * 8930);
  PF_TEST_CLOSE(pf_sum_all(mass), want, 1e-12, 0);
  const double c_max = fmax(p_wave_speed(200e9, 0.3, 7800), fmax(p_wave_speed(70e9, 0.33, 2700), p_wave_speed(117e9, 0.35, 8930)));
  double dt = pf_fem_body_stable_dt(fe); /* (this rank's elements': the least over ranks) */
  MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  PF_TEST_CLOSE(dt, 0.5e-3 / c_max, 1e-12, 0);

  pf_test_run_to_end(sim, NULL, NULL);
  long n_eroded = 0, not_copper = 0;
  const uint8_t *dead = pf_fem_body_eroded(fe, &n_eroded);
  for (pf_int e = 0; e < m->nelem && dead; e++) not_copper += dead[e] && strcmp(expected_material(centroid_x(m, e)), "copper");
  PF_TEST_TRUE(dead && n_eroded > 0 && not_copper == 0);
  PF_TEST_OK(pf_fem_body_output_fields(fe, p));
  const double *eqps = pf_points_field_get(p, "eqps");
  PF_TEST_TRUE(eqps != NULL);
  double outside = 0, inside = 0;
  for (pf_int i = 0; i < p->n_owned && eqps; i++) {
    const double x = p->X[3 * (size_t)i];
    if (x < cu_lo - 1e-9 || x > cu_hi + 1e-9) outside = fmax(outside, fabs(eqps[i]));
    else inside = fmax(inside, eqps[i]);
  }
  double extremes[2] = {outside, inside}; /* (over ranks: a rank may hold no copper node) */
  MPI_Allreduce(MPI_IN_PLACE, extremes, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  PF_TEST_TRUE(extremes[0] == 0 && extremes[1] > 0);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
