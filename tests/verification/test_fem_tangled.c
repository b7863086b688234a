/* A tangled element converts (fem/element_force.c, docs/theory/fem.md §9b): one 1 mm hexahedron of
 * a soft elastic material with `erosion: {min_volume_ratio: 0.01, convert_to_particles: true}`,
 * its corner node at (+h, +h, +h) thrown at 1000 m/s along (-1, -1, -1), the other nodes at rest.
 * The node reaches the plane of its three edge neighbours, x + y + z = 2h, after h / (sqrt 3 v)
 * = 0.58 us (29 steps of 20 ns); past it the element is folded over at that corner, while its
 * volume ratio stays above 0.6 — far from the volume limit, and the centre Jacobian of the
 * one-point element stays positive, so no other limit deletes it.
 * Asserted, against the geometry alone (the signed distance of the node to the plane of its three
 * neighbours, from the positions): the element converts in the first step at whose end the node is
 * beyond that plane, not before; its volume ratio then is above 0.5; the particle carries the
 * element's mass rho h^3 to 1e-12. Without the corner check it never converts. */
#include "sim/sim.h"
#include "fem/fem_impl.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The cube's eight node positions in the hexahedron's corner order (pf_hex8_node_sign, from the
 * reference coordinates), gathered from their owners. Collective. */
static void corners(const pf_points *p, double h, double x[8][3]) {
  double buf[24] = {0};
  for (pf_int i = 0; i < p->n_owned; i++) {
    if (p->body[i] != 0) continue;
    for (int I = 0; I < 8; I++) {
      int match = 1;
      for (int k = 0; k < 3; k++) match &= (p->X[3 * i + k] > 0.5 * h) == (pf_hex8_node_sign[I][k] > 0);
      if (match) memcpy(&buf[3 * I], &p->y[3 * i], sizeof(double[3]));
    }
  }
  for (int k = 0; k < 24; k++) x[k / 3][k % 3] = pf_sum_all(buf[k]);
}

/* Signed distance of corner 6 (+1, +1, +1), the thrown one, to the plane through its three edge
 * neighbours 2, 5, 7, positive on the side it started on. */
static double corner_side(double x[8][3], double h) {
  double a[3], b[3], n[3], sc = 0, so = 0;
  for (int k = 0; k < 3; k++) a[k] = x[5][k] - x[2][k], b[k] = x[7][k] - x[2][k];
  n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
  for (int k = 0; k < 3; k++) sc += n[k] * (x[6][k] - x[2][k]), so += n[k] * (0.5 * h - x[2][k]);
  return so < 0 ? sc : -sc; /* (the cube's centre lies on the far side) */
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double h = 1e-3, rho = 1000, lo[3] = {0, 0, 0}, hi[3] = {h, h, h};
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials:\n  soft: {model: elastic, density: 1000, youngs_modulus: 1.0e6, poissons_ratio: 0.3}\n"
           "bodies:\n"
           "  - name: cube\n    type: finite_element\n    material: soft\n%s"
           "    initial_velocity: ['x + y + z > 2.5e-3 ? -577.35026918962576 : 0',"
           " 'x + y + z > 2.5e-3 ? -577.35026918962576 : 0', 'x + y + z > 2.5e-3 ? -577.35026918962576 : 0']\n"
           "    erosion: {min_volume_ratio: 0.01, convert_to_particles: true}\n"
           "  - {name: cube_particles, type: particles, from: cube}\n"
           "time: {dt: 2.0e-8, final_time: 1.0e-6}\n",
           pf_test_pamgen_box(1, 1, 1, lo, hi));
  pf_sim *sim = pf_test_sim("fem_tangled", deck);
  const pf_fem_body *cube = pf_sim_fem_body(sim, 0);
  pf_points *p = pf_sim_points(sim);
  PF_TEST_OK(pf_sim_step(sim, 0));
  long steps = 0, at = -1, beyond_at = -1;
  double J_at = 0;
  while (!pf_sim_finished(sim) && at < 0) {
    double B[8][3], x[8][3];
    PF_TEST_OK(pf_sim_step(sim, 1));
    steps++;
    corners(p, h, x);
    const double V = pf_hex8_mean_gradient(x, B);
    if (corner_side(x, h) < 0 && beyond_at < 0) beyond_at = steps;
    long n;
    pf_fem_body_eroded(cube, &n);
    if (n > 0) at = steps, J_at = V / (h * h * h);
  }
  double M = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    if (p->body[i] == 1) M += p->m[i];
  M = pf_sum_all(M);
  PF_TEST_TRUE(at > 0);
  PF_TEST_TRUE(at == beyond_at && at >= 29); /* (not before the free flight of the node: 28.9 steps) */
  PF_TEST_TRUE(J_at > 0.5);
  PF_TEST_CLOSE(M, rho * h * h * h, 1e-12, 0);
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("fem tangled: converted at step %ld (node beyond its neighbours' plane at step %ld, closed form %.1f), "
           "V/V0 %.4f, particle mass %.6g kg\n",
           at, beyond_at, h / (sqrt(3.0) * 1000) / 2e-8, J_at, M);
  pf_test_print_digest("fem_tangled", sim);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
