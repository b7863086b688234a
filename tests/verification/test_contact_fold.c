/* A particle beyond a fold of an FE surface (contact/pairs.c `surface`, docs/theory/contact.md
 * sec. 2, "Folds"): one hexahedron whose cross-section is a kite with a 4-degree angle at its edge
 * E (the two faces meeting there face nearly opposite ways, as a sheet one crushed element thick
 * does after deletions), 2 mm long along E. A particle 0.4 mm from E, in the plane normal to E at
 * 87 degrees from the kite's axis (above it, then mirrored below it), has E as the closest point
 * of both faces, at the same distance; it lies in front of one face's plane and behind the
 * other's, and over both (its offset along the face, 0.4 sin 4 deg = 0.03 mm, is below a tenth of
 * the face's size). By geometry it is outside the body, 0.4 mm from it, within the contact radius
 * r_c = 0.5 mm: the penalty energy must be k (r_c - 0.4 mm)^2 / 2 (hand value; the face that sees
 * it behind gave k (r_c + 0.4 mm)^2 / 2, 81 times more). A particle inside the kite, 0.5 mm from E
 * on its axis, is behind both faces at depth 0.5 sin 2 deg mm: the energy must be
 * k (r_c + 0.5 sin 2 deg mm)^2 / 2 (hand value), so the test tells inside from outside. Before the
 * rule the two faces tied and round-off chose the side (the expanding tube's Lexan at 1.0 mm with
 * element conversion ran away from it). */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define HALF_ANGLE (2.0 * PF_PI / 180)
#define RC 5.0e-4
#define K 1.0e6

/* The kite E (0, 0), A (-cos a, sin a), C (-1.5, 0), B (-cos a, -sin a) mm in the xz plane,
 * extruded along y over 2 mm. */
static const char *write_kite(void) {
  pf_mesh m;
  memset(&m, 0, sizeof m);
  m.nnodes = 8, m.nelem = 1, m.nblocks = 1;
  const double a = HALF_ANGLE, ca = cos(a), sa = sin(a);
  const double xz[4][2] = {{0, 0}, {-ca, -sa}, {-1.5, 0}, {-ca, sa}}; /* E, B, C, A: +y by the right-hand rule */
  double X[8][3];
  for (int I = 0; I < 8; I++) X[I][0] = 1e-3 * xz[I % 4][0], X[I][1] = I < 4 ? 0 : 2e-3, X[I][2] = 1e-3 * xz[I % 4][1];
  pf_int conn[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  int32_t block[1] = {0};
  char name[1][64] = {"kite"};
  m.X = &X[0][0], m.conn = conn, m.block = block, m.block_name = name;
  return pf_test_write_mesh("contact_fold", &m);
}

/* The contact energy of the initial forces with the particle at (x, 1 mm, z) (its digest under tag). */
static double energy_at(const char *tag, const char *mesh, double x, double z) {
  char pts[128], deck[2048];
  snprintf(pts, sizeof pts, "%.17g 1.0e-3 %.17g 1.0e-10 1\n", x, z);
  const char *file = pf_test_write_file(0, "contact_fold_pts", pts);
  snprintf(deck, sizeof deck,
           "materials:\n"
           "  lexan: {model: elastic, density: 1190, youngs_modulus: 2.54e9, poissons_ratio: 0.344}\n"
           "  steel: {model: pmb, density: 7870, bulk_modulus: 1.62e11}\n"
           "bodies:\n"
           "  - {name: kite, type: finite_element, material: lexan, mesh: {file: %s}}\n"
           "  - {name: ball, material: steel, horizon: 3.0e-4, geometry: {shape: points_file, file: %s, block: 1}}\n"
           "contact:\n  pairs:\n    - {bodies: [kite, ball], radius: %.17g, stiffness: %.17g}\n"
           "time: {steps: 1}\n"
           "output: {interval: 0}\n",
           mesh, file, RC, K);
  pf_sim *sim = pf_test_sim(tag, deck);
  remove(file);
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_step(sim, 0)); /* the initial forces */
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  pf_test_print_digest(tag, sim);
  pf_sim_destroy(&sim);
  return g.contact;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *mesh = write_kite();
  const double r = 0.4e-3, th = 87.0 * PF_PI / 180;
  const double above = energy_at("fold_above", mesh, r * cos(th), r * sin(th)), below = energy_at("fold_below", mesh, r * cos(th), -r * sin(th));
  const double depth = 0.5e-3 * sin(HALF_ANGLE), want = 0.5 * K * (RC + depth) * (RC + depth);
  const double inside = energy_at("fold_inside", mesh, -0.5e-3, 0);
  pf_test_remove_shared(mesh);
  const double out = 0.5 * K * (RC - r) * (RC - r);
  printf("beyond the fold: contact energy above %.6e J, below %.6e J (hand, outside %.6e J); "
         "inside at depth %.3e m: %.6e J (hand %.6e J)\n",
         above, below, out, depth, inside, want);
  PF_TEST_CLOSE(above, out, 1e-9, 0);
  PF_TEST_CLOSE(below, out, 1e-9, 0);
  PF_TEST_CLOSE(inside, want, 1e-9, 0);
  pf_test_measure("fold_error", fmax(fabs(above - out), fabs(below - out)) / out, "");
  return pf_test_finish();
}
