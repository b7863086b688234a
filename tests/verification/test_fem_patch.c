/* Constant-strain patch test on a distorted hexahedral mesh (Belytschko, Liu & Moran 2000,
 * §8.5): a 3x3x3-element cube whose 8 interior nodes are moved off the lattice; the boundary
 * nodes follow the linear velocity field v = A X, the interior nodes start on it and are free.
 * A linear field is reproduced exactly by the trilinear element and the mean (or B-bar) gradient
 * of a linear field is exact on any element, so every element sees the same D, the stress is
 * uniform, the interior nodes feel zero net force and stay on the linear field: to round-off,
 * for one-point elements with hourglass control (whose vectors are orthogonal to linear fields)
 * and for the B-bar elements. The uniform stress is the hypoelastic integral of C : D, which to
 * first order in the strain is C : sym(A) t (checked to 1e-3 relative at a strain of 1e-6). */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <string.h>

#define NE 3
#define H 1.0e-3

static const double A[3][3] = {{1.0, 0.4, -0.2}, {0.3, -0.6, 0.5}, {-0.1, 0.2, 0.8}}; /* 1/s */

static int node_id(int i, int j, int k) { return i + (NE + 1) * (j + (NE + 1) * k); }

static const char *write_mesh(void) {
  pf_mesh m;
  memset(&m, 0, sizeof m);
  m.nnodes = (NE + 1) * (NE + 1) * (NE + 1);
  m.nelem = NE * NE * NE;
  m.X = calloc(3 * (size_t)m.nnodes, sizeof(double));
  m.conn = calloc(8 * (size_t)m.nelem, sizeof(pf_int));
  m.block = calloc((size_t)m.nelem, sizeof(int32_t));
  m.nblocks = 1;
  m.block_name = calloc(1, sizeof *m.block_name);
  snprintf(m.block_name[0], sizeof m.block_name[0], "cube");
  for (int k = 0; k <= NE; k++)
    for (int j = 0; j <= NE; j++)
      for (int i = 0; i <= NE; i++) {
        double *x = &m.X[3 * node_id(i, j, k)];
        x[0] = i * H, x[1] = j * H, x[2] = k * H;
        if (i > 0 && i < NE && j > 0 && j < NE && k > 0 && k < NE) { /* interior: distort */
          x[0] += 0.21 * H * ((i + 2 * j + k) % 3 - 1);
          x[1] += 0.17 * H * ((2 * i + j + 3 * k) % 3 - 1);
          x[2] += 0.19 * H * ((i + j + 2 * k) % 3 - 1);
        }
      }
  static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  int e = 0;
  for (int k = 0; k < NE; k++)
    for (int j = 0; j < NE; j++)
      for (int i = 0; i < NE; i++, e++)
        for (int I = 0; I < 8; I++)
          m.conn[8 * e + I] = node_id(i + corner[I][0], j + corner[I][1], k + corner[I][2]);
  const char *path = pf_test_write_mesh("patch", &m);
  free(m.X), free(m.conn), free(m.block), free(m.block_name);
  return path;
}

static void run(const char *mesh, const char *element) {
  char deck[6000], v[3][128], slabs[3000] = "";
  for (int i = 0; i < 3; i++)
    snprintf(v[i], sizeof v[i], "\"%g*x + %g*y + %g*z\"", A[i][0], A[i][1], A[i][2]);
  const double L = NE * H, eps = 1e-9;
  for (int a = 0; a < 3; a++)
    for (int side = 0; side < 2; side++) {
      double lo[3] = {-eps, -eps, -eps}, hi[3] = {L + eps, L + eps, L + eps};
      if (side == 0) hi[a] = eps;
      else lo[a] = L - eps;
      char one[600];
      snprintf(one, sizeof one,
               "  - region: {shape: box, lo: [%.12g, %.12g, %.12g], hi: [%.12g, %.12g, %.12g]}\n"
               "    velocity: [%s, %s, %s]\n",
               lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], v[0], v[1], v[2]);
      strcat(slabs, one);
    }
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}\n"
           "bodies:\n"
           "  - name: cube\n    type: finite_element\n    material: steel\n    mesh: {file: %s}\n"
           "    element: %s\n    hourglass: {type: stiffness, coefficient: 0.1}\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    initial_velocity: [%s, %s, %s]\n"
           "boundary_conditions:\n%s"
           "time: {steps: 50, dt: 2.0e-8}\n",
           mesh, element, v[0], v[1], v[2], slabs);
  pf_sim *sim = pf_test_sim(element, deck);
  PF_TEST_OK(pf_sim_step(sim, 50));
  pf_points *p = pf_sim_points(sim);
  const double T = 50 * 2.0e-8;
  /* interior nodes: on the linear field, zero force relative to the boundary forces */
  double fmax_boundary = 0, fmax_interior = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double *X = &p->X[3 * i];
    int interior = X[0] > 0.5 * H && X[0] < L - 0.5 * H && X[1] > 0.5 * H && X[1] < L - 0.5 * H &&
                   X[2] > 0.5 * H && X[2] < L - 0.5 * H;
    double fn = sqrt(p->f[3 * i] * p->f[3 * i] + p->f[3 * i + 1] * p->f[3 * i + 1] + p->f[3 * i + 2] * p->f[3 * i + 2]);
    if (!interior) {
      fmax_boundary = fmax(fmax_boundary, fn);
      continue;
    }
    fmax_interior = fmax(fmax_interior, fn);
    for (int a = 0; a < 3; a++) {
      double want = T * (A[a][0] * X[0] + A[a][1] * X[1] + A[a][2] * X[2]);
      PF_TEST_CLOSE(p->u[3 * i + a], want, 1e-9, 1e-12 * H);
    }
  }
  PF_TEST_TRUE(fmax_boundary > 0);
  PF_TEST_TRUE(fmax_interior <= 1e-9 * fmax_boundary);
  if (fmax_interior > 1e-9 * fmax_boundary)
    fprintf(stderr, "%s: interior force %g vs boundary %g\n", element, fmax_interior, fmax_boundary);
  /* uniform stress, equal to C : sym(A) T to first order */
  PF_TEST_OK(pf_fem_body_output_fields(pf_sim_fem_body(sim, 0), p));
  const double *s = pf_points_field_get(p, "stress");
  const double E = 200e9, nu = 0.3, lam = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  double tr = A[0][0] + A[1][1] + A[2][2];
  double ref[6] = {lam * tr + 2 * G * A[0][0], lam * tr + 2 * G * A[1][1], lam * tr + 2 * G * A[2][2],
                   G * (A[1][2] + A[2][1]), G * (A[0][2] + A[2][0]), G * (A[0][1] + A[1][0])};
  double scale = 0, uniform = 0, first_order = 0;
  for (int c = 0; c < 6; c++) scale = fmax(scale, fabs(ref[c] * T));
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int c = 0; c < 6; c++) {
      PF_TEST_CLOSE(s[6 * i + c], s[c], 0, 1e-10 * scale);          /* uniform */
      PF_TEST_CLOSE(s[6 * i + c], ref[c] * T, 0, 1e-3 * scale);     /* first order */
      uniform = fmax(uniform, fabs(s[6 * i + c] - s[c]) / scale);
      first_order = fmax(first_order, fabs(s[6 * i + c] - ref[c] * T) / scale);
    }
  char key[64];
  snprintf(key, sizeof key, "%s_interior_force", element);
  pf_test_measure(key, fmax_interior / fmax_boundary, "1");
  snprintf(key, sizeof key, "%s_stress_uniformity", element);
  pf_test_measure(key, uniform, "1");
  snprintf(key, sizeof key, "%s_stress_first_order", element);
  pf_test_measure(key, first_order, "1");
  pf_test_print_digest(element, sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  char mesh[256];
  snprintf(mesh, sizeof mesh, "%s", write_mesh());
  run(mesh, "reduced");
  run(mesh, "bbar");
  pf_test_remove_shared(mesh);
  return pf_test_finish();
}
