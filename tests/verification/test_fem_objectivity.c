/* Objectivity: one hexahedron driven through prescribed node displacements.
 * (a) A rigid rotation about z by 90 degrees produces no stress (every model).
 * (b) A uniaxial stretch eps along x, then a rigid rotation by 90 degrees about z: the stress
 *     must be the stretched state rotated, sigma_end = R sigma_1 R^T, i.e. sigma_yy(end) =
 *     sigma_xx(t1), sigma_xx(end) = sigma_yy(t1), sigma_xy(end) = 0. For the hypoelastic models
 *     this holds to round-off because the mid-step velocity gradient of a rigid rotation is
 *     exactly skew and the Hughes-Winget rotation reproduces the increment exactly
 *     (docs/theory/fem.md §1); for neo-Hookean sigma(RU) = R sigma(U) R^T. Both integration
 *     options. */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <string.h>

#define N1 40
#define N2 200
#define DT 1.0e-8

/* The largest stress errors over the runs, relative to 200 GPa x max(eps, 1e-3): after a rigid
 * rotation (zero stress), and after a stretch then a rotation (the rotated stress). */
static double worst_rigid, worst_rotated;

static const char *write_cube(void) {
  pf_mesh m;
  memset(&m, 0, sizeof m);
  m.nnodes = 8, m.nelem = 1, m.nblocks = 1;
  double X[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  pf_int conn[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  int32_t block[1] = {0};
  char name[1][64] = {"cube"};
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) X[I][i] *= 1e-3;
  m.X = &X[0][0], m.conn = conn, m.block = block, m.block_name = name;
  return pf_test_write_mesh("objectivity", &m);
}

static void run(const char *mesh, const char *model, const char *element, double eps) {
  const double t1 = N1 * DT, w = (PF_PI / 2) / (N2 * DT);
  char th[128], sx[128], deck[4000];
  snprintf(th, sizeof th, "(t < %.17g ? 0 : %.17g * (t - %.17g))", t1, w, t1);
  snprintf(sx, sizeof sx, "(t < %.17g ? %.17g * t : %.17g)", t1, eps / t1, eps);
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3%s}}\n"
           "bodies:\n  - {name: cube, type: finite_element, material: m, mesh: {file: %s}, element: %s,\n"
           "     bulk_viscosity: {linear: 0, quadratic: 0}}\n"
           "boundary_conditions:\n"
           "  - displacement: [\"cos(%s) * (1 + %s) * x - sin(%s) * y - x\",\n"
           "                   \"sin(%s) * (1 + %s) * x + cos(%s) * y - y\", \"0\"]\n"
           "time: {steps: %d, dt: %g}\n",
           model, strcmp(model, "j2") ? "" : ", yield_stress: 1.0e9, hardening_modulus: 1.0e9", mesh, element, th,
           sx, th, th, sx, th, N1 + N2, DT);
  pf_sim *sim = pf_test_sim(model, deck);
  pf_points *p = pf_sim_points(sim);
  pf_fem_body *b = pf_sim_fem_body(sim, 0);
  PF_TEST_OK(pf_sim_step(sim, N1));
  PF_TEST_OK(pf_fem_body_output_fields(b, p));
  double s1[6];
  memcpy(s1, pf_points_field_get(p, "stress"), sizeof s1);
  PF_TEST_OK(pf_sim_step(sim, N2));
  PF_TEST_OK(pf_fem_body_output_fields(b, p));
  const double *s = pf_points_field_get(p, "stress");
  double scale = 200e9 * fmax(eps, 1e-3);
  if (eps == 0) {
    for (int c = 0; c < 6; c++) {
      PF_TEST_CLOSE(s[c], 0.0, 0, 1e-12 * scale);
      worst_rigid = fmax(worst_rigid, fabs(s[c]) / scale);
    }
  } else {
    const double err[4] = {s[0] - s1[1], s[1] - s1[0], s[2] - s1[2], s[5]};
    for (int c = 0; c < 4; c++) worst_rotated = fmax(worst_rotated, fabs(err[c]) / scale);
    PF_TEST_TRUE(s1[0] > 0.5 * 200e9 * eps); /* the stretch did load the element */
    PF_TEST_CLOSE(s[0], s1[1], 0, 1e-9 * scale);
    PF_TEST_CLOSE(s[1], s1[0], 0, 1e-9 * scale);
    PF_TEST_CLOSE(s[2], s1[2], 0, 1e-9 * scale);
    PF_TEST_CLOSE(s[5], 0.0, 0, 1e-9 * scale);
  }
  /* the nodes went where the prescribed motion put them: node 1 (1, 0, 0) mm -> (0, 1 + eps, 0) mm */
  for (pf_int i = 0; i < p->n_owned; i++)
    if (p->X[3 * i] > 0.5e-3 && p->X[3 * i + 1] < 0.5e-3 && p->X[3 * i + 2] < 0.5e-3) {
      PF_TEST_CLOSE(p->y[3 * i], 0.0, 0, 1e-15);
      PF_TEST_CLOSE(p->y[3 * i + 1], 1e-3 * (1 + eps), 1e-12, 0);
    }
  char tag[96];
  snprintf(tag, sizeof tag, "%s %s %g", model, element, eps);
  pf_test_print_digest(tag, sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  worst_rigid = worst_rotated = 0;
  char mesh[256];
  snprintf(mesh, sizeof mesh, "%s", write_cube());
  const char *models[] = {"elastic", "neo_hookean", "j2"}, *elements[] = {"reduced", "bbar"};
  for (int k = 0; k < 3; k++)
    for (int e = 0; e < 2; e++) {
      run(mesh, models[k], elements[e], 0.0);
      run(mesh, models[k], elements[e], 1e-3);
    }
  pf_test_remove_shared(mesh);
  pf_test_measure("rigid_rotation_stress", worst_rigid, "200 GPa x 1e-3");
  pf_test_measure("rotated_stress_error", worst_rotated, "200 GPa x 1e-3");
  return pf_test_finish();
}
