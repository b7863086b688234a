/* A [0/90]s laminate's in-plane stiffness against classical laminate theory (docs/theory/
 * laminate.md). The lamina: T300/914C carbon/epoxy, E1 = 138 GPa, E2 = 11 GPa, G12 = 5.5 GPa,
 * nu12 = 0.28 (Soden, Hinton & Kaddour 1998, Table 3), model orthotropic.
 *
 * FE plies: a plate L x L x 4t of hexahedra, one element per ply through the thickness, the two
 * outer plies at 0 degrees (the body's material), the two inner ones at 90 (material_regions),
 * free top and bottom faces. Quasi-static runs, each one load step (Newton-Krylov):
 *  - run X: the faces x = 0, x = L (and y = 0, y = L) held along their normal only (rollers),
 *    the face x = L moved by eps L; run Y: the same along y. A symmetric cross-ply has no
 *    extension-shear coupling (A16 = A26 = 0, B = 0), so each ply's state is uniform: in-plane
 *    strains (eps_x, eps_y) everywhere, sigma_z = 0 and its own eps_z. The far faces' reactions
 *    give the laminate's A11, A21 (run X) and A12, A22 (run Y): N = A eps (Jones 1999, sec. 4.2);
 *  - run S: every lateral node moved as u = (gamma y, 0) (simple shear, a uniform gamma_xy), z
 *    free; the x reaction of the nodes of y = L is N_xy L = A66 gamma L.
 *  - run U: run X with the face y = L free (a literal uniaxial pull, y = 0 a symmetry plane): E_x
 *    = F / (L H eps) differs from CLT's by the free-edge effect (Pipes & Pagano 1970), asserted
 *    within 2 % as well.
 * The laminate's engineering constants under a uniaxial N_x (N_y = 0):
 *   E_x = (A11 A22 - A12 A21) / (H A22), nu_xy = A21 / A22, G_xy = A66 / H   (H = 4t).
 * Reference: CLT computed here from E1, E2, G12, nu12 alone: Q of the lamina (Jones 1999, sec. 2.5),
 * rotated by the ply angle (sec. 2.6), A = sum_k Qbar_k t_k (sec. 4.2). Asserted
 * within 2 % (E_x, nu_xy, G_xy). The out-of-plane constants (E3, G13, G23, nu13, nu23) do not
 * enter: a second material set with other values must give the same A (asserted within 1e-4: the
 * model is finite-strain and the strain 1e-5, so the small-strain statement holds to O(eps)).
 *
 * PD plies: a correspondence plate of one ply orientation, 0 or 90 degrees, the same runs with the lateral
 * faces' rollers as layers of points beyond each face following the face's normal motion
 * (docs/theory/fibre_rve.md §2), free top and bottom. Each plate's A over its thickness is that
 * ply's Q, asserted within 2 % of Jones's Q (Q11, Q12, Q22, Q66); the laminate's A is then
 * assembled from the two measured plates as CLT does, and its E_x, nu_xy, G_xy asserted within
 * 2 % of CLT's. Run U on each plate (its lattice ends at the free edge y = L): E_x within 2 % of
 * E1 (0 degrees) and E2 (90). Then the laminate in one correspondence body, its plies bonded: the
 * plate's points in the inner half of its thickness a 90-degree material (material_regions), the
 * outer ones 0, each end of a bond between plies with its own material's force state (docs/theory/
 * interfaces.md sec. 3a): runs X, Y, S give its A, and E_x, nu_xy, G_xy are asserted within 2 % of
 * CLT's.
 * usage: test_laminate [N]: N PD points across the plate (default 8; 0: the FE plies only). */
#include "test_common.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "include/perifem.h"

/* T300/914C (Soden, Hinton & Kaddour 1998, Table 3) */
static const double E1 = 138e9, E2 = 11e9, G12 = 5.5e9, NU12 = 0.28;
/* two sets of out-of-plane constants (the first transversely isotropic with nu23 = 0.4, its G23 =
 * E2 / 2 (1 + nu23); the second arbitrary but admissible, Jones 1999, sec. 2.4): CLT ignores them */
static const double OUT[2][5] = {{11e9, 5.5e9, 11e9 / 2.8, 0.28, 0.4}, /* E3, G13, G23, nu13, nu23 */
                                 {16.5e9, 4.0e9, 3.0e9, 0.2, 0.3}};
static const double T_PLY = 0.125e-3, L = 1e-3, EPS = 1e-5;

/* ---- classical laminate theory -------------------------------------------------------------- */

/* The lamina's reduced stiffness in plane stress (Jones 1999, sec. 2.5):
 * Q11 = E1 / (1 - nu12 nu21), Q12 = nu12 E2 / (1 - nu12 nu21), Q22 = E2 / (1 - nu12 nu21),
 * Q66 = G12, nu21 = nu12 E2 / E1. Q = {Q11, Q12, Q22, Q66}. */
static void lamina_q(double Q[4]) {
  const double nu21 = NU12 * E2 / E1, d = 1 - NU12 * nu21;
  Q[0] = E1 / d, Q[1] = NU12 * E2 / d, Q[2] = E2 / d, Q[3] = G12;
}

/* Q rotated by the ply angle theta (fibre at theta from x; Jones 1999, sec. 2.6), m = cos, n = sin:
 * Qb11 = Q11 m^4 + 2 (Q12 + 2 Q66) m^2 n^2 + Q22 n^4,
 * Qb12 = (Q11 + Q22 - 4 Q66) m^2 n^2 + Q12 (m^4 + n^4),
 * Qb22 = Q11 n^4 + 2 (Q12 + 2 Q66) m^2 n^2 + Q22 m^4,
 * Qb66 = (Q11 + Q22 - 2 Q12 - 2 Q66) m^2 n^2 + Q66 (m^4 + n^4)
 * (Qb16 and Qb26 vanish at 0 and 90 degrees). Qb = {11, 12, 22, 66}. */
static void rotated_q(const double Q[4], double theta_deg, double Qb[4]) {
  const double m = cos(theta_deg * PF_PI / 180), n = sin(theta_deg * PF_PI / 180);
  const double m2n2 = m * m * n * n, m4 = m * m * m * m, n4 = n * n * n * n;
  Qb[0] = Q[0] * m4 + 2 * (Q[1] + 2 * Q[3]) * m2n2 + Q[2] * n4;
  Qb[1] = (Q[0] + Q[2] - 4 * Q[3]) * m2n2 + Q[1] * (m4 + n4);
  Qb[2] = Q[0] * n4 + 2 * (Q[1] + 2 * Q[3]) * m2n2 + Q[2] * m4;
  Qb[3] = (Q[0] + Q[2] - 2 * Q[1] - 2 * Q[3]) * m2n2 + Q[3] * (m4 + n4);
}

/* The laminate's engineering constants from A = {A11, A12, A21, A22, A66} (N/m) and its thickness
 * H: under N_x alone, eps_y = -A21 / A22 eps_x, so E_x = (A11 - A12 A21 / A22) / H,
 * nu_xy = A21 / A22, G_xy = A66 / H (Jones 1999, ch. 4: E_x = 1 / (H a11), a = A^-1). */
static void engineering(const double A[5], double H, double c[3]) {
  c[0] = (A[0] - A[1] * A[2] / A[3]) / H, c[1] = A[2] / A[3], c[2] = A[4] / H;
}

/* CLT's A of the [0/90]s laminate: sum over the plies of Qb t (Jones 1999, sec. 4.2). */
static void clt_a(double A[5]) {
  const double angle[4] = {0, 90, 90, 0};
  double Q[4], Qb[4];
  lamina_q(Q);
  for (int k = 0; k < 5; k++) A[k] = 0;
  for (int p = 0; p < 4; p++) {
    rotated_q(Q, angle[p], Qb);
    A[0] += Qb[0] * T_PLY, A[1] += Qb[1] * T_PLY, A[2] += Qb[1] * T_PLY, A[3] += Qb[2] * T_PLY;
    A[4] += Qb[3] * T_PLY;
  }
}

/* ---- runs -------------------------------------------------------------------------------- */

/* One orthotropic material at angles [deg, 0, 0] with out-of-plane set o (the density, a typical
 * carbon/epoxy value, does not enter the statics). */
static void material(char *out, size_t cap, const char *name, double deg, int o) {
  snprintf(out, cap,
           "  %s: {model: orthotropic, density: 1560, E1: %.17g, E2: %.17g, E3: %.17g, G12: %.17g, G13: %.17g,\n"
           "       G23: %.17g, nu12: %.17g, nu13: %.17g, nu23: %.17g, angles: [%g, 0, 0]}\n",
           name, E1, E2, OUT[o][0], G12, OUT[o][1], OUT[o][2], NU12, OUT[o][3], OUT[o][4], deg);
}

/* A run's state digest, printed with PF_TEST_DIGESTS and appended to PF_TEST_DIGEST_FILE as
 * pf_test_print_digest does (mpi_verify.sh leaves this test out; its runs on 1 and 3 ranks by hand
 * give the same digests: docs/theory/laminate.md). */
static void print_digest(const char *tag, perifem_sim *sim) {
  uint64_t h = 0;
  if (perifem_digest(sim, &h)) fprintf(stderr, "perifem_digest: %s\n", perifem_last_error());
  if (getenv("PF_TEST_DIGESTS") && pf_comm_rank() == 0) printf("state digest (%s): %016" PRIx64 "\n", tag, h);
  const char *path = getenv("PF_TEST_DIGEST_FILE");
  FILE *f = path && pf_comm_rank() == 0 ? fopen(path, "a") : NULL;
  if (f) fprintf(f, "state digest (%s): %016" PRIx64 "\n", tag, h), fclose(f);
}

/* Run a deck to its end and read the history columns names[k] into F[k]. */
static int run_deck(const char *tag, const char *deck, int n, const char *const *names, double *F) {
  perifem_options opt = {0};
  opt.no_output = 1, opt.quiet = 1;
  perifem_sim *sim = NULL;
  if (perifem_create_from_string(deck, "laminate.yaml", &opt, &sim) || perifem_run(sim)) {
    fprintf(stderr, "perifem (%s): %s\n%s", tag, perifem_last_error(), deck);
    perifem_destroy(&sim);
    return -1;
  }
  int ierr = 0;
  for (int k = 0; k < n; k++) ierr = ierr || perifem_history_value(sim, names[k], &F[k]);
  print_digest(tag, sim);
  perifem_destroy(&sim);
  return ierr;
}

static const char *SOLVER = "solver: {type: quasi_static, method: newton_krylov, load_steps: 1, tolerance: 1.0e-10}\n"
                            "time: {final_time: 1}\n";

/* The FE plate's conditions. run 0 (X) and 1 (Y): on each lateral face the nodes held along its
 * normal (nx, ny) or moved by eps times the plate's size (fx, fy: x = L, y = L when it is the
 * run's axis); run 2 (S): the nodes of y = L (top) and the other lateral nodes (x0, x1, y0) moved
 * as u = (gamma y, 0), gamma = eps; run 3 (U): run X with the face y = L free (uniaxial tension, a free edge).
 * In every run the mid-plane's nodes are held in z (the laminate's symmetry
 * plane: it fixes the rigid translation along z only). h: the element size in x and y. */
static void fe_conditions(int run, double h, char *out, size_t cap) {
  const double a = L - h / 2, b = h / 2;
  size_t len = 0;
  if (run != 2)
    for (int ax = 0; ax < 2; ax++) {
      char c0[2][16] = {"free", "free"}, c1[2][64] = {"free", "free"};
      snprintf(c0[ax], sizeof c0[ax], "\"0\"");
      snprintf(c1[ax], sizeof c1[ax], "\"%.17g * t\"", ax == run % 3 ? EPS * L : 0.0);
      double hi0[2] = {1, 1}, lo1[2] = {-1, -1}; /* the near face x (y) < h/2, the far one > L - h/2 */
      hi0[ax] = b, lo1[ax] = a;
      len += snprintf(out + len, cap - len,
                      "  - {name: n%c, region: {shape: box, lo: [-1, -1, -1], hi: [%.17g, %.17g, 1]}, displacement: [%s, %s, free]}\n",
                      'x' + ax, hi0[0], hi0[1], c0[0], c0[1]);
      if (run == 3 && ax == 1) continue; /* run U: the edge y = L free */
      len += snprintf(out + len, cap - len,
                      "  - {name: f%c, region: {shape: box, lo: [%.17g, %.17g, -1], hi: [1, 1, 1]}, displacement: [%s, %s, free]}\n",
                      'x' + ax, lo1[0], lo1[1], c1[0], c1[1]);
    }
  else {
    char u[64];
    snprintf(u, sizeof u, "\"%.17g * y * t\"", EPS);
    len += snprintf(out + len, cap - len,
                    "  - {name: top, region: {shape: box, lo: [-1, %.17g, -1], hi: [1, 1, 1]}, displacement: [%s, \"0\", free]}\n"
                    "  - {name: x0, region: {shape: box, lo: [-1, -1, -1], hi: [%.17g, %.17g, 1]}, displacement: [%s, \"0\", free]}\n"
                    "  - {name: x1, region: {shape: box, lo: [%.17g, -1, -1], hi: [1, %.17g, 1]}, displacement: [%s, \"0\", free]}\n"
                    "  - {name: y0, region: {shape: box, lo: [%.17g, -1, -1], hi: [%.17g, %.17g, 1]}, displacement: [%s, \"0\", free]}\n",
                    a, u, b, a, u, a, a, u, b, a, b, u);
  }
  snprintf(out + len, cap - len,
           "  - {name: mid, region: {shape: box, lo: [-1, -1, %.17g], hi: [1, 1, %.17g]}, displacement: [free, free, \"0\"]}\n",
           -T_PLY / 2, T_PLY / 2);
}

/* The FE laminate, n x n x 4 B-bar hexahedra over [0, L]^2 x [-2t, 2t]: the outer plies 0
 * degrees, the inner (|z| < t, by centroid) 90. run: as fe_conditions; o: the out-of-plane set.
 * F: the reactions {fx_x, fy_y} (runs X, Y), {top_x} (run S) or {fx_x} (run U). */
static int fe_run(int n, int run, int o, double F[2]) {
  const double lo[3] = {0, 0, -2 * T_PLY}, hi[3] = {L, L, 2 * T_PLY};
  char deck[8192], bcs[4096], m0[512], m90[512], tag[32];
  material(m0, sizeof m0, "ply_0", 0, o), material(m90, sizeof m90, "ply_90", 90, o);
  fe_conditions(run, L / n, bcs, sizeof bcs);
  snprintf(deck, sizeof deck,
           "materials:\n%s%s"
           "bodies:\n  - name: plate\n    type: finite_element\n    material: ply_0\n    element: bbar\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    material_regions:\n"
           "      - {material: ply_90, region: {shape: box, lo: [-1, -1, %.17g], hi: [1, 1, %.17g]}}\n"
           "%sboundary_conditions:\n%s%s",
           m0, m90, -T_PLY, T_PLY, pf_test_pamgen_box(n, n, 4, lo, hi), bcs, SOLVER);
  snprintf(tag, sizeof tag, "fe_%c_%d", "XYSU"[run], o);
  const char *xy[2] = {"fx_reaction_x", "fy_reaction_y"}, *s[1] = {"top_reaction_x"};
  return run == 2 ? run_deck(tag, deck, 1, s, F) : run_deck(tag, deck, run == 3 ? 1 : 2, xy, F);
}

/* The FE laminate's A = {A11, A12, A21, A22, A66} from runs X, Y, S: N = F / (side), over eps. */
static int fe_a(int n, int o, int shear, double A[5]) {
  double FX[2], FY[2], FS[2] = {0, 0};
  if (fe_run(n, 0, o, FX) || fe_run(n, 1, o, FY) || (shear && fe_run(n, 2, o, FS))) return -1;
  A[0] = FX[0] / (L * EPS), A[2] = FX[1] / (L * EPS), A[1] = FY[0] / (L * EPS), A[3] = FY[1] / (L * EPS);
  A[4] = FS[0] / (L * EPS);
  return 0;
}

/* ---- PD plies ----------------------------------------------------------------------------- */

/* The PD plate's conditions: the points beyond each lateral face (a layer k spacings thick, twice
 * a family's reach, so that the points a horizon beyond the face have whole families) follow the
 * face's motion: runs X, Y the normal motion u_a = eps_a X_a (the mirror image of the plate's,
 * as a roller on a symmetry plane), tangentially free; run S u = (gamma y, 0), z free. Then the
 * measured sets, after the others (each its own condition): the points beyond the far face within
 * the plate's span (mx, my; top in run S). Run U: run X without the layers beyond y = L (that
 * edge free; the lattice ends there). */
static void pd_conditions(int run, char *out, size_t cap) {
  size_t len = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int ax = 0; ax < 2; ax++)
      for (int s = pass; s < 2; s++) {
        if (pass && run == 2 && ax == 0) continue; /* run S measures only the top */
        if (run == 3 && ax == 1 && (s || pass)) continue; /* run U: the edge y = L free, mx only */
        double lo[2] = {-1, -1}, hi[2] = {1, 1};
        if (pass) lo[0] = lo[1] = 0, hi[0] = hi[1] = L; /* within the plate's span */
        if (s) lo[ax] = L, hi[ax] = 1;
        else lo[ax] = -1, hi[ax] = 0;
        char c[2][64] = {"free", "free"}, name[8];
        if (run != 2) snprintf(c[ax], sizeof c[ax], "\"%.17g * %c * t\"", ax == run % 3 ? EPS : 0.0, 'x' + ax);
        else snprintf(c[0], sizeof c[0], "\"%.17g * y * t\"", EPS), snprintf(c[1], sizeof c[1], "\"0\"");
        snprintf(name, sizeof name, pass ? (run == 2 ? "top" : "m%c") : "g%c%d", 'x' + ax, s);
        len += snprintf(out + len, cap - len,
                        "  - {name: %s, region: {shape: box, lo: [%.17g, %.17g, -1], hi: [%.17g, %.17g, 1]}, "
                        "displacement: [%s, %s, free]}\n",
                        name, lo[0], lo[1], hi[0], hi[1], c[0], c[1]);
      }
}

/* A correspondence plate of one ply at deg degrees: points at the centroids of an n x n x nz
 * grid over [0, L]^2 x [0, nz h] (h = L / n), horizon 3.015 h, the layers beyond the lateral
 * faces; free top and bottom. deg < 0: the [0/90]s laminate in one body, the points of the inner
 * half of the thickness (nz / 4 < z / h < 3 nz / 4) 90-degree plies (material_regions), the
 * outer ones 0. F: the measured reactions {mx_x, my_y} (runs X, Y), {top_x} (S), {mx_x} (U,
 * whose lattice ends at y = L). */
static int pd_run(int n, int nz, double deg, int run, double F[2]) {
  const double h = L / n, delta = 3.015 * h, t = nz * h;
  const int k = 2 * (int)ceil(delta / h); /* twice a family's reach, in spacings */
  static char deck[16384];
  char bcs[8192], m[1024], regions[256] = "", tag[32];
  material(m, sizeof m, "ply", deg < 0 ? 0.0 : deg, 0);
  if (deg < 0) {
    material(m + strlen(m), sizeof m - strlen(m), "cross", 90.0, 0);
    snprintf(regions, sizeof regions,
             "    material_regions: [{material: cross, region: {shape: box, lo: [-1, -1, %.17g], hi: [1, 1, %.17g]}}]\n",
             t / 4, 3 * t / 4);
  }
  pd_conditions(run, bcs, sizeof bcs);
  snprintf(deck, sizeof deck,
           "materials:\n%s"
           "bodies:\n  - name: plate\n    material: ply\n%s    horizon: %.17g\n"
           "    geometry: {shape: box, lo: [%.17g, %.17g, 0], hi: [%.17g, %.17g, %.17g],\n"
           "               origin: [%.17g, %.17g, %.17g], spacing: %.17g}\n"
           "boundary_conditions:\n%s%s",
           m, regions, delta, -k * h, -k * h, L + k * h, run == 3 ? L : L + k * h, t, h / 2, h / 2, h / 2, h, bcs, SOLVER);
  if (deg < 0) snprintf(tag, sizeof tag, "pdlam_%c", "XYSU"[run]);
  else snprintf(tag, sizeof tag, "pd%g_%c", deg, "XYSU"[run]);
  const char *xy[2] = {"mx_reaction_x", "my_reaction_y"}, *s[1] = {"top_reaction_x"};
  return run == 2 ? run_deck(tag, deck, 1, s, F) : run_deck(tag, deck, run == 3 ? 1 : 2, xy, F);
}

/* The plate's Q = A / t = {Q11, Q12, Q21, Q22, Q66} from runs X, Y, S. */
static int pd_q(int n, int nz, double deg, double Q[5]) {
  double FX[2], FY[2], FS[2] = {0, 0};
  if (pd_run(n, nz, deg, 0, FX) || pd_run(n, nz, deg, 1, FY) || pd_run(n, nz, deg, 2, FS)) return -1;
  const double t = nz * L / n, f = 1 / (L * t * EPS);
  Q[0] = FX[0] * f, Q[2] = FX[1] * f, Q[1] = FY[0] * f, Q[3] = FY[1] * f, Q[4] = FS[0] * f;
  return 0;
}

/* Record E_x, nu_xy, G_xy's relative deviations from CLT as <what>_<key>_dev (docs/verification.md);
 * print both with PF_TEST_VERBOSE. */
static void report(const char *what, const double c[3], const double ref[3]) {
  const char *key[3] = {"Ex", "nuxy", "Gxy"}, *unit[3] = {"GPa", "", "GPa"};
  const double scale[3] = {1e-9, 1, 1e-9};
  for (int k = 0; k < 3; k++) {
    char name[64];
    snprintf(name, sizeof name, "%s_%s_dev", what, key[k]);
    pf_test_measure(name, c[k] / ref[k] - 1, "1");
    if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
      printf("%s %s: %.6g %s (CLT %.6g, %+.2e)\n", what, key[k], c[k] * scale[k], unit[k], ref[k] * scale[k],
             c[k] / ref[k] - 1);
  }
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double H = 4 * T_PLY;
  double Aclt[5], clt[3];
  clt_a(Aclt);
  engineering(Aclt, H, clt);
  pf_test_measure("clt_Ex", clt[0] / 1e9, "GPa"), pf_test_measure("clt_nuxy", clt[1], "1");
  pf_test_measure("clt_Gxy", clt[2] / 1e9, "GPa");

  /* FE plies */
  double Afe[5], Afe2[5], fe[3];
  PF_TEST_OK(fe_a(4, 0, 1, Afe));
  engineering(Afe, H, fe);
  report("fe", fe, clt);
  for (int k = 0; k < 3; k++) PF_TEST_CLOSE(fe[k], clt[k], 0.02, 0);
  /* the out-of-plane constants do not enter (to the small-strain order: the model is finite-strain,
   * eps = 1e-5, and the two sets differ by 1e-6 in A11) */
  PF_TEST_OK(fe_a(4, 1, 0, Afe2));
  for (int k = 0; k < 4; k++) PF_TEST_CLOSE(Afe2[k], Afe[k], 1e-4, 0);
  pf_test_measure("fe_out_of_plane_dev", Afe2[0] / Afe[0] - 1, "1");
  /* uniaxial tension with a free edge: E_x = N_x / (H eps), the free-edge effect included */
  double FU[2];
  PF_TEST_OK(fe_run(4, 3, 0, FU));
  const double Ex_u = FU[0] / (L * H * EPS);
  pf_test_measure("fe_uniaxial_Ex_dev", Ex_u / clt[0] - 1, "1");
  PF_TEST_CLOSE(Ex_u, clt[0], 0.02, 0);
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("fe uniaxial with a free edge: Ex %.6g GPa (CLT %.6g, %+.2e)\n", Ex_u / 1e9, clt[0] / 1e9, Ex_u / clt[0] - 1);
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("fe A11 with the other out-of-plane set: %+.2e\n", Afe2[0] / Afe[0] - 1);

  /* PD plies: a plate of each orientation */
  const int n = argc > 1 ? atoi(argv[1]) : 8, nz = n / 2;
  if (n == 0) return pf_test_finish();
  double Qpd[2][5] = {{0}}, Q[4], Qb[4];
  lamina_q(Q);
  double qdev = 0; /* the largest |relative deviation| of the plates' Q from Jones's */
  for (int p = 0; p < 2; p++) {
    PF_TEST_OK(pd_q(n, nz, 90.0 * p, Qpd[p]));
    rotated_q(Q, 90.0 * p, Qb);
    const double want[5] = {Qb[0], Qb[1], Qb[1], Qb[2], Qb[3]};
    for (int k = 0; k < 5; k++) {
      if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
        printf("pd %d deg: Q[%d] %.6g GPa (Jones %.6g, %+.2e)\n", 90 * p, k, Qpd[p][k] / 1e9, want[k] / 1e9,
               Qpd[p][k] / want[k] - 1);
      PF_TEST_CLOSE(Qpd[p][k], want[k], 0.02, 0);
      qdev = fmax(qdev, fabs(Qpd[p][k] / want[k] - 1));
    }
  }
  pf_test_measure("pd_Q_dev", qdev, "1");
  /* each plate in uniaxial tension with a free edge: E_x = E1 (0 degrees), E2 (90) */
  double udev = 0;
  for (int p = 0; p < 2; p++) {
    double FU2[2];
    PF_TEST_OK(pd_run(n, nz, 90.0 * p, 3, FU2));
    const double Ex = FU2[0] / (L * nz * (L / n) * EPS), want = p ? E2 : E1;
    PF_TEST_CLOSE(Ex, want, 0.02, 0);
    udev = fmax(udev, fabs(Ex / want - 1));
    if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
      printf("pd %d deg uniaxial with a free edge: Ex %.6g GPa (%s %.6g, %+.2e)\n", 90 * p, Ex / 1e9, p ? "E2" : "E1",
             want / 1e9, Ex / want - 1);
  }
  pf_test_measure("pd_uniaxial_dev", udev, "1");
  double Apd[5], pd[3];
  for (int k = 0; k < 5; k++) Apd[k] = 2 * T_PLY * (Qpd[0][k] + Qpd[1][k]); /* [0/90]s: two plies of each */
  engineering(Apd, H, pd);
  report("pd", pd, clt);
  for (int k = 0; k < 3; k++) PF_TEST_CLOSE(pd[k], clt[k], 0.02, 0);

  /* PD plies bonded in one body: A = N / eps with N = F / L, over the plate's own thickness */
  double Qlam[5], lam[3];
  PF_TEST_OK(pd_q(n, nz, -1.0, Qlam)); /* (Q of the whole plate: A / t) */
  engineering(Qlam, 1.0, lam);
  report("pd_bonded", lam, clt);
  for (int k = 0; k < 3; k++) PF_TEST_CLOSE(lam[k], clt[k], 0.02, 0);
  return pf_test_finish();
}
