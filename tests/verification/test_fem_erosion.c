/* Element erosion (fem/erosion.c) with contact between two FE bodies: an elastic steel sphere
 * (meshes/sphere.geo, R = 2.5 mm, 0.6 mm hexahedra) at 800 m/s through a 16 x 16 x 2 mm J2
 * aluminium plate (0.5 mm hexahedra, yield 300 MPa, linear hardening 100 MPa) whose elements are
 * deleted at an equivalent plastic strain of 0.5, nothing held, 8 us.
 * Asserted:
 *  - elements are deleted (the sphere punches a plug out) but not the whole plate;
 *  - a deleted element is one that reached the limit and a live one one that did not: at the
 *    end every deleted element's frozen eqps (its state no longer changes) is >= 0.5 at some
 *    quadrature point and every live element's is < 0.5 (the decision follows the state
 *    exactly, on every rank);
 *  - a deleted element gives no force (its nodal forces are zero);
 *  - linear momentum is conserved to 1e-12 of the sphere's (the contact forces are internal and
 *    the deleted elements' nodes keep their masses);
 *  - the contact follows the eroded surface: at every 10th step no node of the sphere lies
 *    inside a live element of the plate (inside the six planes through its face centres) by more
 *    than 0.1 h, h = 0.5 mm the plate's element: the penalty's give is about v / omega with
 *    omega^2 = 2 k / m_node, 0.04 h for a sphere node (4.2e-7 kg) at 800 m/s on k = 10 K h;
 *    measured 0.06 h. Without the surfaces following the erosion the sphere's nodes sink into
 *    the elements behind the deleted ones, the step collapses and the run does not reach its end
 *    in 5,000 steps (it takes 920);
 *  - the sphere is slowed (it does work on the plate) but passes (its mean velocity stays
 *    downward).
 * The state digest goes to mpi_verify (1, 2 and 3 ranks). */
#include "sim/sim.h"
#include "fem/fem_impl.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static const double limit = 0.5, h_plate = 0.5e-3;

/* How far point p lies inside hexahedron x (the least depth behind its six face planes through
 * the face centres, outward normals); negative when outside. */
static double depth_in_hex(double x[8][3], const double p[3]) {
  double depth = INFINITY;
  for (int f = 0; f < 6; f++) {
    double c[3] = {0, 0, 0}, n[3], a[3], b[3];
    const int *q = pf_hex8_face[f];
    for (int k = 0; k < 4; k++)
      for (int i = 0; i < 3; i++) c[i] += 0.25 * x[q[k]][i];
    for (int i = 0; i < 3; i++) a[i] = x[q[2]][i] - x[q[0]][i], b[i] = x[q[3]][i] - x[q[1]][i];
    n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    depth = fmin(depth, -((p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2]) / len);
  }
  return depth;
}

/* The deepest a sphere node lies in a live plate element: the plate's local elements against
 * the sphere's nodes gathered from every rank. Collective. */
static double deepest(pf_sim *sim, const pf_fem_body *plate) {
  const pf_points *p = pf_sim_points(sim);
  double *mine = malloc(sizeof(double) * 3 * ((size_t)p->n_owned + 1)), worst = -INFINITY;
  int n = 0, R = pf_comm_size();
  for (pf_int i = 0; i < p->n_owned; i++)
    if (p->body[i] == 0) mine[3 * n] = p->y[3 * i], mine[3 * n + 1] = p->y[3 * i + 1], mine[3 * n + 2] = p->y[3 * i + 2], n++;
  int *cnt = malloc(sizeof(int) * 2 * (size_t)R), *dis = cnt + R, total = 0, m3 = 3 * n;
  MPI_Allgather(&m3, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < R; r++) dis[r] = total, total += cnt[r];
  double *all = malloc(sizeof(double) * ((size_t)total + 1));
  MPI_Allgatherv(mine, m3, MPI_DOUBLE, all, cnt, dis, MPI_DOUBLE, MPI_COMM_WORLD);
  for (pf_int e = 0; e < plate->nel; e++) {
    if (pf_fem_element_eroded(plate, e)) continue;
    double x[8][3], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) {
        x[I][i] = p->y[3 * (size_t)plate->conn[8 * (size_t)e + I] + i];
        lo[i] = fmin(lo[i], x[I][i]), hi[i] = fmax(hi[i], x[I][i]);
      }
    for (int k = 0; k < total / 3; k++) {
      const double *q = &all[3 * k];
      if (q[0] < lo[0] || q[0] > hi[0] || q[1] < lo[1] || q[1] > hi[1] || q[2] < lo[2] || q[2] > hi[2]) continue;
      worst = fmax(worst, depth_in_hex(x, q));
    }
  }
  free(mine), free(cnt), free(all);
  return pf_max_all(worst);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  char cwd[3000], deck[8192], plate_box[600];
  if (!getcwd(cwd, sizeof cwd)) return 1;
  const double lo[3] = {-8e-3, -8e-3, -2e-3}, hi[3] = {8e-3, 8e-3, 0};
  snprintf(plate_box, sizeof plate_box, "%s", pf_test_pamgen_box(32, 32, 4, lo, hi));
  snprintf(deck, sizeof deck,
           "materials:\n"
           "  steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.25}\n"
           "  al: {model: j2, density: 2700, youngs_modulus: 70.0e9, poissons_ratio: 0.33, yield_stress: 300.0e6,\n"
           "       hardening_modulus: 100.0e6}\n"
           "bodies:\n"
           "  - name: sphere\n    type: finite_element\n    material: steel\n"
           "    mesh: {file: %s/../meshes/sphere.geo, scale: 0.5, element_size: 0.6e-3, translate: [0, 0, 0.00255]}\n"
           "    initial_velocity: [0, 0, -800]\n"
           "  - name: plate\n    type: finite_element\n    material: al\n%s"
           "    erosion: {plastic_strain: 0.5}\n"
           "contact:\n  pairs:\n    - {bodies: [sphere, plate]}\n"
           "time: {final_time: 8.0e-6}\n",
           cwd, plate_box);
  pf_sim *sim = pf_test_sim("fem_erosion", deck);
  const pf_fem_body *plate = pf_sim_fem_body(sim, 1);
  pf_points *p = pf_sim_points(sim);
  pf_sim_globals g0, g;
  PF_TEST_OK(pf_sim_step(sim, 0));
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  const double p0 = fabs(g0.momentum[2]);
  double dp = 0, worst = -INFINITY;
  long steps = 0;
  while (!pf_sim_finished(sim) && steps < 5000) {
    PF_TEST_OK(pf_sim_step(sim, 1));
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    for (int a = 0; a < 3; a++) dp = fmax(dp, fabs(g.momentum[a] - g0.momentum[a]));
    if (++steps % 10 == 0) worst = fmax(worst, deepest(sim, plate));
  }
  worst = fmax(worst, deepest(sim, plate));
  long n_eroded = 0;
  const uint8_t *dead = pf_fem_body_eroded(plate, &n_eroded);
  int wrong = 0, forced = 0;
  for (pf_int e = 0; e < plate->nel; e++) {
    double emax = 0;
    for (int q = 0; q < plate->nqp; q++)
      emax = fmax(emax, plate->state[(size_t)plate->nstate * ((size_t)plate->nqp * e + q) + pf_fem_element_material(plate, e)->eqps]);
    wrong += (emax >= limit) != (dead[plate->eid[e]] != 0);
    for (int k = 0; k < 24 && dead[plate->eid[e]]; k++) forced += plate->fe[24 * (size_t)e + k] != 0;
  }
  wrong = (int)pf_sum_all(wrong), forced = (int)pf_sum_all(forced);
  double mv = 0, m = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    if (p->body[i] == 0) mv += p->m[i] * p->v[3 * i + 2], m += p->m[i];
  const double vz = pf_sum_all(mv) / pf_sum_all(m);
  PF_TEST_TRUE(n_eroded > 0 && n_eroded < pf_fem_body_mesh(plate)->nelem / 2);
  PF_TEST_TRUE(wrong == 0);
  PF_TEST_TRUE(forced == 0);
  PF_TEST_CLOSE(dp, 0.0, 0, 1e-12 * p0);
  PF_TEST_TRUE(worst < 0.1 * h_plate);
  PF_TEST_TRUE(pf_sim_finished(sim));
  PF_TEST_TRUE(vz < 0 && vz > -800);
  pf_test_measure("deleted", (double)n_eroded, "1");
  pf_test_measure("elements", (double)pf_fem_body_mesh(plate)->nelem, "1");
  pf_test_measure("misjudged", (double)wrong, "1");
  pf_test_measure("momentum_error", dp / p0, "1");
  pf_test_measure("deepest", worst / h_plate, "h");
  pf_test_measure("sphere_vz", vz, "m/s");
  pf_test_measure("steps", (double)steps, "1");
  pf_test_measure("energy_error", (g.kinetic + g.fe_internal + g.hourglass + g.bulk_viscosity + g.contact - g0.kinetic) /
                                      g0.kinetic, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("fem erosion: %ld of %d elements deleted, %d misjudged, %d forces of deleted elements, momentum %.3g of p0, "
           "deepest sphere node in a live element %.3g h, sphere vz %.1f m/s, %ld steps, energy error %.3g of KE0\n",
           n_eroded, (int)pf_fem_body_mesh(plate)->nelem, wrong, forced, dp / p0, worst / h_plate, vz, steps,
           (g.kinetic + g.fe_internal + g.hourglass + g.bulk_viscosity + g.contact - g0.kinetic) / g0.kinetic);
  pf_test_print_digest("fem_erosion", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
