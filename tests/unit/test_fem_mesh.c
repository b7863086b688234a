/* Hexahedral mesh readers (mesh/) against independent references:
 *  - pf_mesh_hex_volume: unit cube, a square frustum (V = h (a^2 + b^2 + a b) / 3), an affine
 *    image of the unit cube (V = |det A|);
 *  - meshes/bar.geo: element count = nx ny nz with n = max(1, ceil(L/h - 1e-6)) (the .geo's
 *    formula), volume 10 x 1 x 1 mm^3, side and node sets on the right planes; scale/translate
 *    (element_size taken after scale);
 *  - meshes/panel_plate.geo: element count and volume exact, top and bottom side sets;
 *  - meshes/taylor_bar.geo: all hexahedra, volume = inscribed regular 4n-gon x L (boundary nodes
 *    evenly spaced on the circle) < pi R^2 L, lateral faces on r = R;
 *  - meshes/sphere.geo: pi-free bounds: every node in the ball of radius R, so V <= 4/3 pi R^3
 *    (each trilinear element lies in the convex hull of its nodes); every boundary patch lies
 *    outside the ball of radius r_min = R min_f min_i cos(x_i, c_f) (a point of a bilinear patch
 *    is a convex combination of its corners x_i, so p.c_f/|c_f| >= min_i x_i.c_f/|c_f|), so
 *    V >= 4/3 pi r_min^3; and V within 3 % of 4/3 pi R^3 at h = R/5 (2.3 % below);
 *  - tests/data/mesh/two_hexes.msh (hand-written msh 2.2): nodes by gmsh tag, unused node
 *    dropped, connectivity by coordinates, blocks, node sets, side sets (an interior surface
 *    gives both neighbours), the blocks: selection;
 *  - tests/data/mesh/tetrahedra.geo: all-hexahedra subdivision fallback, volume exact;
 *  - Exodus round trip (pf_mesh_write_exodus then pf_mesh_read) exact, and the side
 *    numbers in the file read with the Exodus API;
 *  - Pamgen: a rectilinear brick (count, volume, sets on the right planes), an annulus sector,
 *    as "radial" and as "cylindrical" (V = n_theta sin(dtheta) (ro^2 - ri^2) L / 2 exactly), a
 *    radial-trisection cylinder (inscribed polygon x L);
 *  - bad input: missing file, tetrahedra-only .msh, an Exodus file with one inverted element, a
 *    TETRA4 Exodus block, a .geo syntax error, an unknown extension, bad Pamgen text, file and
 *    pamgen together, element_size on a .msh, an unknown block: PF_ERR_INPUT naming the file;
 *    an Exodus block whose every element is inside out is turned over. */
#include "test_common.h"

#include <exodusII.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fem/fem.h"

static char tests_dir[2048]; /* the working directory: the tests/ folder of the source tree */

/* Read the mesh: mapping of a deck (text); returns the reader's error code. */
static int read_deck(const char *text, pf_mesh *m) {
  const char *path = pf_test_write_file(0, "fem_mesh", text);
  pf_deck *d = NULL;
  int ierr = pf_deck_load(path, &d);
  const pf_node *mn = ierr ? NULL : pf_node_get(pf_deck_root(d), "mesh");
  if (!ierr) ierr = pf_deck_validate(d, mn, pf_mesh_keys, "mesh");
  if (!ierr) ierr = pf_mesh_read(d, mn, m);
  pf_deck_destroy(&d);
  remove(path);
  return ierr;
}

/* Read a file (absolute path) with optional extra deck lines. */
static int read_file(const char *path, const char *extra, pf_mesh *m) {
  char text[8192];
  snprintf(text, sizeof text, "mesh:\n  file: %s\n%s", path, extra ? extra : "");
  return read_deck(text, m);
}

/* A shipped geometry meshes/<file> meshed at element size h. */
static int read_shipped(const char *file, double h, pf_mesh *m) {
  char path[4096], extra[256];
  snprintf(path, sizeof path, "%s/../meshes/%s", tests_dir, file);
  snprintf(extra, sizeof extra, "  element_size: %.17g\n", h);
  return read_file(path, extra, m);
}

static void element_nodes(const pf_mesh *m, pf_int e, double x[8][3]) {
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) x[a][i] = m->X[3 * (size_t)m->conn[8 * (size_t)e + a] + i];
}

static double mesh_volume(const pf_mesh *m) {
  double V = 0;
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3];
    element_nodes(m, e, x);
    V += pf_mesh_hex_volume((const double(*)[3])x);
  }
  return V;
}

/* Corner Jacobians as triple products of the three edges at each corner (Knupp, "Achieving
 * finite element mesh quality via optimization of the Jacobian matrix norm", 2000, the
 * right-handed neighbour table below): 1 when all are positive in every element. */
static int all_corners_positive(const pf_mesh *m) {
  static const int nb[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                               {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3];
    element_nodes(m, e, x);
    for (int k = 0; k < 8; k++) {
      double a[3], b[3], c[3];
      for (int i = 0; i < 3; i++) {
        a[i] = x[nb[k][0]][i] - x[k][i];
        b[i] = x[nb[k][1]][i] - x[k][i];
        c[i] = x[nb[k][2]][i] - x[k][i];
      }
      double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]);
      if (!(det > 0)) return 0;
    }
  }
  return 1;
}

/* Exodus HEX8 faces, 0-based sides (written out again here, from the Exodus II manual). */
static const int hex_face[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                   {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}};

static double face_coord(const pf_mesh *m, pf_int e, int f, int v, int comp) {
  return m->X[3 * (size_t)m->conn[8 * (size_t)e + hex_face[f][v]] + comp];
}

static const pf_mesh_set *find_set(const pf_mesh_set *sets, int n, const char *name) {
  for (int k = 0; k < n; k++)
    if (!strcmp(sets[k].name, name)) return &sets[k];
  return NULL;
}

/* Every face of side set `name` has its 4 nodes on the plane x_comp = value. */
static int sides_on_plane(const pf_mesh *m, const char *name, int comp, double value,
                          pf_int count) {
  const pf_mesh_set *s = find_set(m->sideset, m->nsidesets, name);
  if (!s || s->n != count) return 0;
  for (pf_int i = 0; i < s->n; i++)
    for (int v = 0; v < 4; v++)
      if (fabs(face_coord(m, s->item[i], s->face[i], v, comp) - value) > 1e-12 * (1 + fabs(value)))
        return 0;
  return 1;
}

static int nodes_on_plane(const pf_mesh *m, const char *name, int comp, double value,
                          pf_int count) {
  const pf_mesh_set *s = find_set(m->nodeset, m->nnodesets, name);
  if (!s || s->n != count) return 0;
  for (pf_int i = 0; i < s->n; i++)
    if (fabs(m->X[3 * (size_t)s->item[i] + comp] - value) > 1e-12 * (1 + fabs(value))) return 0;
  return 1;
}

static long divisions(double L, double h) {
  long n = (long)ceil(L / h - 1e-6);
  return n < 1 ? 1 : n;
}

/* ---- pf_mesh_hex_volume -------------------------------------------------------------------- */
static void test_hex_volume(void) {
  static const double cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  PF_TEST_CLOSE(pf_mesh_hex_volume(cube), 1.0, 1e-15, 0);
  /* square frustum: bottom side a at z = 0, top side b at z = h, both centred */
  double a = 2.0, b = 0.5, h = 1.5, fr[8][3];
  for (int k = 0; k < 8; k++) {
    double s = k < 4 ? a : b;
    fr[k][0] = (cube[k][0] - 0.5) * s;
    fr[k][1] = (cube[k][1] - 0.5) * s;
    fr[k][2] = cube[k][2] * h;
  }
  PF_TEST_CLOSE(pf_mesh_hex_volume((const double(*)[3])fr), h * (a * a + b * b + a * b) / 3, 1e-14,
                0);
  /* affine image x = A X + t of the unit cube */
  const double A[3][3] = {{1.2, 0.3, -0.1}, {0.2, 0.9, 0.4}, {-0.3, 0.1, 1.1}}, t[3] = {5, -2, 7};
  double af[8][3];
  for (int k = 0; k < 8; k++)
    for (int i = 0; i < 3; i++)
      af[k][i] = A[i][0] * cube[k][0] + A[i][1] * cube[k][1] + A[i][2] * cube[k][2] + t[i];
  double detA = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  PF_TEST_CLOSE(pf_mesh_hex_volume((const double(*)[3])af), detA, 1e-14, 0);
}

/* ---- gmsh .geo ------------------------------------------------------------------------------ */
static void test_bar(void) {
  const double Lx = 10e-3, Ly = 1e-3, Lz = 1e-3, h = 0.3e-3;
  long nx = divisions(Lx, h), ny = divisions(Ly, h), nz = divisions(Lz, h);
  pf_mesh m;
  PF_TEST_OK(read_shipped("bar.geo", h, &m));
  PF_TEST_TRUE(m.nelem == nx * ny * nz);
  PF_TEST_TRUE(m.nnodes == (nx + 1) * (ny + 1) * (nz + 1));
  PF_TEST_CLOSE(mesh_volume(&m), Lx * Ly * Lz, 1e-12, 0);
  PF_TEST_TRUE(all_corners_positive(&m));
  PF_TEST_TRUE(m.nblocks == 1 && !strcmp(m.block_name[0], "bar"));
  PF_TEST_TRUE(sides_on_plane(&m, "x0", 0, 0.0, (pf_int)(ny * nz)));
  PF_TEST_TRUE(sides_on_plane(&m, "x1", 0, Lx, (pf_int)(ny * nz)));
  PF_TEST_TRUE(sides_on_plane(&m, "y1", 1, Ly, (pf_int)(nx * nz)));
  PF_TEST_TRUE(sides_on_plane(&m, "z0", 2, 0.0, (pf_int)(nx * ny)));
  PF_TEST_TRUE(nodes_on_plane(&m, "x0", 0, 0.0, (pf_int)((ny + 1) * (nz + 1))));
  PF_TEST_TRUE(nodes_on_plane(&m, "z1", 2, Lz, (pf_int)((nx + 1) * (ny + 1))));
  pf_mesh_free(&m);
  /* scale and translate: the bar twice as large, moved; element_size is after scale, so the
   * file is meshed at 1e-3 / 2 */
  char path[4096];
  snprintf(path, sizeof path, "%s/../meshes/bar.geo", tests_dir);
  PF_TEST_OK(read_file(path, "  element_size: 1e-3\n  scale: 2\n  translate: [1, -2, 3]\n", &m));
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  for (pf_int i = 0; i < m.nnodes; i++)
    for (int c = 0; c < 3; c++) lo[c] = fmin(lo[c], m.X[3 * i + c]);
  PF_TEST_TRUE(m.nelem == 20 * 2 * 2);
  PF_TEST_CLOSE(mesh_volume(&m), 8 * Lx * Ly * Lz, 1e-12, 0);
  PF_TEST_CLOSE(lo[0], 1.0, 0, 1e-15);
  PF_TEST_CLOSE(lo[1], -2.0, 0, 1e-15);
  PF_TEST_CLOSE(lo[2], 3.0, 0, 1e-15);
  pf_mesh_free(&m);
}

/* meshes/panel_plate.geo (the monolithic plate of inputs/panel_plate.yaml): 60 x 80 x 8.5 mm at
 * h = 2 mm -> 30 x 40 x 5 elements, the volume exactly W L t (the sandwich's mass per area:
 * 2 tf + 4 th hc / W = 6 + 2.5 = 8.5 mm), top on z = 0 and bottom on z = -t. */
static void test_panel_plate(void) {
  const double W = 60e-3, L = 80e-3, t = 8.5e-3, h = 2e-3;
  const long nx = divisions(W, h), ny = divisions(L, h), nz = divisions(t, h);
  pf_mesh m;
  PF_TEST_OK(read_shipped("panel_plate.geo", h, &m));
  PF_TEST_TRUE(nx == 30 && ny == 40 && nz == 5 && m.nelem == nx * ny * nz);
  PF_TEST_CLOSE(mesh_volume(&m), W * L * t, 1e-12, 0);
  PF_TEST_CLOSE(2 * 3e-3 + 4 * 2.5e-3 * 15e-3 / W, t, 1e-12, 0);
  PF_TEST_TRUE(all_corners_positive(&m));
  PF_TEST_TRUE(m.nblocks == 1 && !strcmp(m.block_name[0], "panel"));
  PF_TEST_TRUE(sides_on_plane(&m, "top", 2, 0.0, (pf_int)(nx * ny)));
  PF_TEST_TRUE(sides_on_plane(&m, "bottom", 2, -t, (pf_int)(nx * ny)));
  pf_mesh_free(&m);
}

static void test_taylor_bar(void) {
  const double R = 3.2e-3, L = 32.4e-3, a = 0.5 * R, h = 0.8e-3;
  long n = divisions(PF_PI * R / 2, h), mr = divisions(R - a, h), nz = divisions(L, h);
  pf_mesh m;
  PF_TEST_OK(read_shipped("taylor_bar.geo", h, &m));
  PF_TEST_TRUE(m.nelem == (n * n + 4 * n * mr) * nz);
  PF_TEST_TRUE(all_corners_positive(&m));
  long N = 4 * n; /* boundary edges of the cross-section */
  double polygon = 0.5 * N * R * R * sin(2 * PF_PI / N) * L, circle = PF_PI * R * R * L;
  double V = mesh_volume(&m);
  PF_TEST_TRUE(V >= polygon * (1 - 1e-12) && V < circle);
  PF_TEST_CLOSE(V, polygon, 1e-12, 0);
  /* lateral faces: 4n per layer, every node on r = R */
  const pf_mesh_set *lat = find_set(m.sideset, m.nsidesets, "lateral");
  PF_TEST_TRUE(lat && lat->n == N * nz);
  for (pf_int i = 0; lat && i < lat->n; i++)
    for (int v = 0; v < 4; v++) {
      double x = face_coord(&m, lat->item[i], lat->face[i], v, 0);
      double y = face_coord(&m, lat->item[i], lat->face[i], v, 1);
      if (fabs(hypot(x, y) - R) > 1e-12 * R) {
        PF_TEST_CLOSE(hypot(x, y), R, 1e-12, 0);
        i = lat->n;
        break;
      }
    }
  PF_TEST_TRUE(sides_on_plane(&m, "impact_face", 2, 0.0, (pf_int)(n * n + 4 * n * mr)));
  PF_TEST_TRUE(sides_on_plane(&m, "rear_face", 2, L, (pf_int)(n * n + 4 * n * mr)));
  pf_mesh_free(&m);
}

/* meshes/expanding_tube_lexan.geo at h = 1.25 mm (the shipped deck's): two blocks, projectile
 * then plug, of (n^2 + 4 n m) nz elements each, conforming (one mesh: the nodes of the plane
 * z = L are shared, so there are (2 nz + 1) layers of nodes, not 2 (nz + 1)), the volume of the
 * inscribed 4n-gon times 2L, each block below or above z = L. */
static void test_expanding_tube_lexan(void) {
  const double R = 6.35e-3, L = 25.4e-3, a = 0.5 * R, h = 1.25e-3;
  long n = divisions(PF_PI * R / 2, h), mr = divisions(R - a, h), nz = divisions(L, h);
  pf_mesh m;
  PF_TEST_OK(read_shipped("expanding_tube_lexan.geo", h, &m));
  const long per = (n * n + 4 * n * mr) * nz, section_nodes = (n + 1) * (n + 1) + 4 * n * mr;
  PF_TEST_TRUE(m.nelem == 2 * per);
  PF_TEST_TRUE(m.nnodes == section_nodes * (2 * nz + 1));
  PF_TEST_TRUE(all_corners_positive(&m));
  PF_TEST_TRUE(m.nblocks == 2 && !strcmp(m.block_name[0], "projectile") && !strcmp(m.block_name[1], "plug"));
  long N = 4 * n, wrong = 0;
  PF_TEST_CLOSE(mesh_volume(&m), 0.5 * N * R * R * sin(2 * PF_PI / N) * 2 * L, 1e-12, 0);
  for (pf_int e = 0; e < m.nelem; e++)
    for (int I = 0; I < 8; I++) {
      double z = m.X[3 * (size_t)m.conn[8 * (size_t)e + I] + 2];
      wrong += m.block[e] == 0 ? z > L * (1 + 1e-12) : z < L * (1 - 1e-12);
    }
  PF_TEST_TRUE(wrong == 0);
  PF_TEST_TRUE(sides_on_plane(&m, "rear_face", 2, 0.0, (pf_int)(n * n + 4 * n * mr)));
  PF_TEST_TRUE(sides_on_plane(&m, "far_face", 2, 2 * L, (pf_int)(n * n + 4 * n * mr)));
  pf_mesh_free(&m);
}

static void test_sphere(void) {
  const double R = 5e-3, a = 0.35 * R, h = R / 5;
  long n = divisions(R * acos(1.0 / 3), h), mr = divisions(R - a, h);
  pf_mesh m;
  PF_TEST_OK(read_shipped("sphere.geo", h, &m));
  PF_TEST_TRUE(m.nelem == n * n * n + 6 * n * n * mr);
  PF_TEST_TRUE(all_corners_positive(&m));
  double rmax = 0;
  for (pf_int i = 0; i < m.nnodes; i++)
    rmax = fmax(rmax, sqrt(m.X[3 * i] * m.X[3 * i] + m.X[3 * i + 1] * m.X[3 * i + 1] +
                           m.X[3 * i + 2] * m.X[3 * i + 2]));
  PF_TEST_TRUE(rmax <= R * (1 + 1e-12));
  const pf_mesh_set *s = find_set(m.sideset, m.nsidesets, "surface");
  PF_TEST_TRUE(s && s->n == 6 * n * n);
  double rmin = R;
  for (pf_int i = 0; s && i < s->n; i++) {
    double x[4][3], c[3] = {0, 0, 0};
    for (int v = 0; v < 4; v++)
      for (int k = 0; k < 3; k++) {
        x[v][k] = face_coord(&m, s->item[i], s->face[i], v, k);
        c[k] += x[v][k] / 4;
      }
    double cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int v = 0; v < 4; v++) {
      double r = sqrt(x[v][0] * x[v][0] + x[v][1] * x[v][1] + x[v][2] * x[v][2]);
      PF_TEST_TRUE(fabs(r - R) <= 1e-12 * R); /* surface nodes on the sphere */
      rmin = fmin(rmin, (x[v][0] * c[0] + x[v][1] * c[1] + x[v][2] * c[2]) / cn);
    }
  }
  double V = mesh_volume(&m), ball = 4.0 / 3 * PF_PI * R * R * R;
  PF_TEST_TRUE(V <= ball);
  PF_TEST_TRUE(V >= 4.0 / 3 * PF_PI * rmin * rmin * rmin);
  PF_TEST_CLOSE(V, ball, 0.03, 0);
  pf_mesh_free(&m);
}

/* The .geo fallback: tetrahedra split into hexahedra; planar faces keep the volume exact. */
static void test_subdivision(void) {
  char path[4096];
  snprintf(path, sizeof path, "%s/data/mesh/tetrahedra.geo", tests_dir);
  pf_mesh m;
  PF_TEST_OK(read_file(path, NULL, &m));
  PF_TEST_TRUE(m.nelem == 4 * 24); /* tetrahedra.msh: the same mesh before subdivision */
  PF_TEST_CLOSE(mesh_volume(&m), 1e-9, 1e-12, 0);
  PF_TEST_TRUE(all_corners_positive(&m));
  pf_mesh_free(&m);
}

/* ---- gmsh .msh ------------------------------------------------------------------------------- */
/* two_hexes.msh: grid point (i, j, k), i < 3, j, k < 2, has tag 50 - 3 (i + 3 j + 6 k), so by
 * ascending tag node n is grid point 11 - n. */
static void grid_point(int n, double x[3]) {
  int g = 11 - n;
  x[0] = g % 3, x[1] = (g / 3) % 2, x[2] = g / 6;
}

static void test_msh(void) {
  char path[4096];
  snprintf(path, sizeof path, "%s/data/mesh/two_hexes.msh", tests_dir);
  pf_mesh m;
  PF_TEST_OK(read_file(path, NULL, &m));
  PF_TEST_TRUE(m.nnodes == 12 && m.nelem == 2 && m.nblocks == 2);
  for (int n = 0; n < m.nnodes && n < 12; n++) {
    double x[3];
    grid_point(n, x);
    PF_TEST_TRUE(m.X[3 * n] == x[0] && m.X[3 * n + 1] == x[1] && m.X[3 * n + 2] == x[2]);
  }
  static const double unit[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (pf_int e = 0; e < m.nelem && e < 2; e++) {
    double x[8][3];
    element_nodes(&m, e, x);
    for (int a = 0; a < 8; a++)
      PF_TEST_TRUE(x[a][0] == unit[a][0] + e && x[a][1] == unit[a][1] && x[a][2] == unit[a][2]);
  }
  PF_TEST_TRUE(m.nblocks == 2 && !strcmp(m.block_name[0], "left") &&
               !strcmp(m.block_name[1], "right"));
  PF_TEST_TRUE(m.block[0] == 0 && m.block[1] == 1);
  const pf_mesh_set *s = find_set(m.sideset, m.nsidesets, "x0");
  PF_TEST_TRUE(s && s->n == 1 && s->item[0] == 0 && s->face[0] == 3);
  s = find_set(m.sideset, m.nsidesets, "mid"); /* interior: both neighbours */
  PF_TEST_TRUE(s && s->n == 2 && s->item[0] == 0 && s->face[0] == 1 && s->item[1] == 1 &&
               s->face[1] == 3);
  PF_TEST_TRUE(m.nsidesets == 2);
  PF_TEST_TRUE(nodes_on_plane(&m, "x0", 0, 0.0, 4));
  PF_TEST_TRUE(nodes_on_plane(&m, "mid", 0, 1.0, 4));
  s = find_set(m.nodeset, m.nnodesets, "origin");
  PF_TEST_TRUE(s && s->n == 1 && m.X[3 * s->item[0]] == 0 && m.X[3 * s->item[0] + 1] == 0 &&
               m.X[3 * s->item[0] + 2] == 0);
  PF_TEST_TRUE(m.nnodesets == 3);
  pf_mesh_free(&m);
  /* keep only block "right": its 8 nodes, the sides and nodes on it */
  PF_TEST_OK(read_file(path, "  blocks: [right]\n", &m));
  PF_TEST_TRUE(m.nnodes == 8 && m.nelem == 1 && m.nblocks == 1 &&
               !strcmp(m.block_name[0], "right"));
  PF_TEST_CLOSE(mesh_volume(&m), 1.0, 1e-15, 0);
  s = find_set(m.sideset, m.nsidesets, "mid");
  PF_TEST_TRUE(s && s->n == 1 && s->item[0] == 0 && s->face[0] == 3);
  s = find_set(m.sideset, m.nsidesets, "x0");
  PF_TEST_TRUE(s && s->n == 0);
  s = find_set(m.nodeset, m.nnodesets, "origin");
  PF_TEST_TRUE(s && s->n == 0);
  PF_TEST_TRUE(nodes_on_plane(&m, "mid", 0, 1.0, 4));
  pf_mesh_free(&m);
}

/* ---- Exodus ---------------------------------------------------------------------------------- */
static int same_sets(const pf_mesh_set *a, const pf_mesh_set *b, int n) {
  for (int k = 0; k < n; k++) {
    if (strcmp(a[k].name, b[k].name) || a[k].n != b[k].n) return 0;
    if (memcmp(a[k].item, b[k].item, sizeof(pf_int) * (size_t)a[k].n)) return 0;
    if (!a[k].face != !b[k].face) return 0;
    if (a[k].face && memcmp(a[k].face, b[k].face, (size_t)a[k].n)) return 0;
  }
  return 1;
}

static void round_trip(const pf_mesh *m, const char *exo) {
  PF_TEST_OK(pf_mesh_write_exodus(exo, m));
  pf_mesh r;
  PF_TEST_OK(read_file(exo, NULL, &r));
  PF_TEST_TRUE(r.nnodes == m->nnodes && r.nelem == m->nelem && r.nblocks == m->nblocks);
  if (r.nnodes != m->nnodes || r.nelem != m->nelem || r.nblocks != m->nblocks) {
    pf_mesh_free(&r);
    return;
  }
  PF_TEST_TRUE(!memcmp(r.X, m->X, sizeof(double) * 3 * (size_t)m->nnodes));
  PF_TEST_TRUE(!memcmp(r.conn, m->conn, sizeof(pf_int) * 8 * (size_t)m->nelem));
  PF_TEST_TRUE(!memcmp(r.block, m->block, sizeof(int32_t) * (size_t)m->nelem));
  for (int b = 0; b < m->nblocks; b++) PF_TEST_TRUE(!strcmp(r.block_name[b], m->block_name[b]));
  PF_TEST_TRUE(r.nnodesets == m->nnodesets && same_sets(r.nodeset, m->nodeset, m->nnodesets));
  PF_TEST_TRUE(r.nsidesets == m->nsidesets && same_sets(r.sideset, m->sideset, m->nsidesets));
  pf_mesh_free(&r);
}

static void test_exodus_round_trip(void) {
  char path[4096], exo[256];
  snprintf(exo, sizeof exo, "/tmp/pf_test_fem_mesh_%d.e", (int)getpid());
  pf_mesh m;
  snprintf(path, sizeof path, "%s/data/mesh/two_hexes.msh", tests_dir);
  PF_TEST_OK(read_file(path, NULL, &m));
  round_trip(&m, exo);
  /* the side of x0 in the file: Exodus side 4 (x = -1) of element 1, read with the Exodus API */
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  int exoid = ex_open(exo, EX_READ, &cpu_ws, &io_ws, &version);
  PF_TEST_TRUE(exoid >= 0);
  if (exoid >= 0) {
    int ids[2] = {0, 0}, elem[2] = {0, 0}, side[2] = {0, 0},
        nss = (int)ex_inquire_int(exoid, EX_INQ_SIDE_SETS);
    PF_TEST_TRUE(nss == 2 && ex_get_ids(exoid, EX_SIDE_SET, ids) >= 0);
    char name[NC_MAX_NAME + 1] = "";
    PF_TEST_TRUE(ex_get_name(exoid, EX_SIDE_SET, ids[0], name) >= 0 && !strcmp(name, "x0"));
    PF_TEST_TRUE(ex_get_set(exoid, EX_SIDE_SET, ids[0], elem, side) >= 0 && elem[0] == 1 &&
                 side[0] == 4);
    ex_close(exoid);
  }
  pf_mesh_free(&m);
  snprintf(path, sizeof path, "%s/../meshes/bar.geo", tests_dir);
  PF_TEST_OK(read_file(path, "  element_size: 0.5e-3\n", &m));
  round_trip(&m, exo);
  pf_mesh_free(&m);
  remove(exo);
}

/* Write a 2-element HEX8 block (unit cubes side by side along x) with a side set on side 5 of
 * element 1; element `inverted` (1, 2, or 3 for both, 0 for none) has its two faces swapped. */
static int write_exodus_pair(const char *path, int inverted, const char *type) {
  int cpu_ws = 8, io_ws = 8;
  int exoid = ex_create(path, EX_CLOBBER, &cpu_ws, &io_ws);
  if (exoid < 0) return 1;
  double x[12], y[12], z[12];
  for (int n = 0; n < 12; n++) x[n] = n % 3, y[n] = (n / 3) % 2, z[n] = n / 6;
  int conn[16];
  for (int e = 0; e < 2; e++) {
    int base[8] = {0, 1, 4, 3, 6, 7, 10, 9};
    int flip = inverted & (1 << e);
    for (int a = 0; a < 8; a++) conn[8 * e + a] = base[flip ? (a + 4) % 8 : a] + e + 1;
  }
  int elem[1] = {1}, side[1] = {5};
  int st = ex_put_init(exoid, "test", 3, 12, 2, 1, 0, 1);
  if (st >= 0) st = ex_put_coord(exoid, x, y, z);
  if (st >= 0) st = ex_put_block(exoid, EX_ELEM_BLOCK, 10, type, 2, 8, 0, 0, 0);
  if (st >= 0) st = ex_put_conn(exoid, EX_ELEM_BLOCK, 10, conn, NULL, NULL);
  if (st >= 0) st = ex_put_set_param(exoid, EX_SIDE_SET, 7, 1, 0);
  if (st >= 0) st = ex_put_set(exoid, EX_SIDE_SET, 7, elem, side);
  ex_close(exoid);
  return st < 0;
}

static void test_exodus_inverted_block(void) {
  char exo[256];
  snprintf(exo, sizeof exo, "/tmp/pf_test_fem_mesh_inv_%d.e", (int)getpid());
  PF_TEST_OK(write_exodus_pair(exo, 3, "HEX8"));
  pf_mesh m;
  PF_TEST_OK(read_file(exo, NULL, &m));
  PF_TEST_TRUE(m.nelem == 2 && all_corners_positive(&m));
  PF_TEST_CLOSE(mesh_volume(&m), 2.0, 1e-15, 0);
  PF_TEST_TRUE(m.nblocks == 1 && !strcmp(m.block_name[0], "block_10"));
  /* side 5 named nodes 1, 4, 3, 2 of the inside-out element: the face z = 1 */
  PF_TEST_TRUE(sides_on_plane(&m, "sideset_7", 2, 1.0, 1));
  pf_mesh_free(&m);
  remove(exo);
}

/* ---- Pamgen ---------------------------------------------------------------------------------- */
static int read_pamgen(const char *pamgen, pf_mesh *m) {
  char text[8192];
  snprintf(text, sizeof text, "mesh:\n  pamgen: |\n%s", pamgen);
  return read_deck(text, m);
}

static void test_pamgen(void) {
  pf_mesh m;
  /* a brick of 3 x 4 x 5 elements over [0, 0.3] x [0, 0.2] x [0, 0.1] */
  PF_TEST_OK(read_pamgen("    mesh\n"
                         "      rectilinear\n"
                         "        nx = 3\n        ny = 4\n        nz = 5\n"
                         "        bx = 1\n        by = 1\n        bz = 1\n"
                         "        gmin = 0 0 0\n        gmax = 0.3 0.2 0.1\n"
                         "      end\n"
                         "      set assign\n        nodeset, ilo, 1\n        sideset, ihi, 2\n"
                         "        sideset, klo, 3\n      end\n"
                         "    end\n",
                         &m));
  PF_TEST_TRUE(m.nelem == 60 && m.nnodes == 4 * 5 * 6);
  PF_TEST_CLOSE(mesh_volume(&m), 0.3 * 0.2 * 0.1, 1e-12, 0);
  PF_TEST_TRUE(all_corners_positive(&m));
  PF_TEST_TRUE(nodes_on_plane(&m, "nodeset_1", 0, 0.0, 5 * 6));
  PF_TEST_TRUE(sides_on_plane(&m, "sideset_2", 0, 0.3, 4 * 5));
  PF_TEST_TRUE(sides_on_plane(&m, "sideset_3", 2, 0.0, 3 * 4));
  pf_mesh_free(&m);
  /* an annulus sector: r in [1, 2], theta in [0, 90] degrees in 6 intervals, z in [0, 2]: each
   * element's section has corners on two arcs, area sin(dtheta) (r1^2 - r0^2) / 2 */
  PF_TEST_OK(read_pamgen("    mesh\n      radial\n"
                         "        numz 1\n          zblock 1 2.0 interval 3\n"
                         "        numr 1 initial radius 1.0\n          rblock 1 1.0 interval 2\n"
                         "        numa 1\n          ablock 1 90 interval 6\n"
                         "      end\n    end\n",
                         &m));
  PF_TEST_TRUE(m.nelem == 3 * 2 * 6);
  double sector = 0.5 * 6 * sin(PF_PI / 12) * (4 - 1) * 2;
  PF_TEST_CLOSE(mesh_volume(&m), sector, 1e-12, 0);
  PF_TEST_TRUE(mesh_volume(&m) < PF_PI / 4 * (4 - 1) * 2);
  PF_TEST_TRUE(all_corners_positive(&m));
  pf_mesh_free(&m);
  /* the same sector in Pamgen's "cylindrical" form */
  PF_TEST_OK(read_pamgen("    mesh\n      cylindrical\n"
                         "        nr = 2\n        ntheta = 6\n        nz = 3\n"
                         "        br = 1\n        btheta = 1\n        bz = 1\n"
                         "        ri = 1.0\n        ro = 2.0\n        theta = 90\n"
                         "        zmin = 0\n        zmax = 2\n"
                         "      end\n    end\n",
                         &m));
  PF_TEST_TRUE(m.nelem == 3 * 2 * 6);
  PF_TEST_CLOSE(mesh_volume(&m), sector, 1e-12, 0);
  pf_mesh_free(&m);
  /* a solid cylinder, R = 1, L = 2, 16 intervals round: the inscribed 16-gon x L */
  PF_TEST_OK(read_pamgen("    mesh\n      radial trisection\n        trisection blocks, 4\n"
                         "        numz 1\n          zblock 1 2.0 interval 3\n"
                         "        numr 2\n          rblock 1 0.5 interval 2\n"
                         "          rblock 2 0.5 interval 2\n"
                         "        numa 1\n          ablock 1 360 interval 16\n"
                         "      end\n    end\n",
                         &m));
  double V = mesh_volume(&m), polygon = 0.5 * 16 * sin(2 * PF_PI / 16) * 2;
  PF_TEST_CLOSE(V, polygon, 1e-12, 0);
  PF_TEST_TRUE(V < PF_PI * 2);
  PF_TEST_TRUE(all_corners_positive(&m));
  pf_mesh_free(&m);
}

/* ---- bad input ------------------------------------------------------------------------------- */
/* ierr must be PF_ERR_INPUT and the message must hold `want` (and `want2` when given). */
static void expect_input_error(int ierr, const char *want, const char *want2, const char *what) {
  const char *msg = pf_error_message();
  int ok = ierr == PF_ERR_INPUT && strstr(msg, want) && (!want2 || strstr(msg, want2));
  if (!ok)
    fprintf(stderr, "%s: ierr %d, message '%s' (wanted '%s'%s%s)\n", what, ierr, msg, want,
            want2 ? " and " : "", want2 ? want2 : "");
  PF_TEST_TRUE(ok);
  pf_error_clear();
}

static void test_bad_input(void) {
  pf_mesh m;
  char path[4096], text[8192], tmp[256];
  memset(&m, 0, sizeof m);
  pf_error_clear();
  pf_error_set_quiet(1);
  snprintf(path, sizeof path, "%s/data/mesh/no_such_mesh.msh", tests_dir);
  expect_input_error(read_file(path, NULL, &m), "no_such_mesh.msh", "cannot open", "missing file");
  snprintf(path, sizeof path, "%s/data/mesh/tetrahedra.msh", tests_dir);
  expect_input_error(read_file(path, NULL, &m), "tetrahedra.msh", "Tetrahedron", "tetrahedra");
  expect_input_error(read_file("/tmp/shape.stl", NULL, &m), "shape.stl", ".geo .msh", "extension");
  /* one element of two inverted */
  snprintf(tmp, sizeof tmp, "/tmp/pf_test_fem_mesh_bad_%d.e", (int)getpid());
  PF_TEST_OK(write_exodus_pair(tmp, 2, "HEX8"));
  expect_input_error(read_file(tmp, NULL, &m), tmp, "element 2", "inverted element");
  PF_TEST_OK(write_exodus_pair(tmp, 0, "TETRA8"));
  expect_input_error(read_file(tmp, NULL, &m), tmp, "not support", "tetra block");
  remove(tmp);
  /* a .geo with a syntax error */
  snprintf(tmp, sizeof tmp, "/tmp/pf_test_fem_mesh_bad_%d.geo", (int)getpid());
  FILE *fp = fopen(tmp, "w");
  if (fp) fputs("Point(1) = {0, 0, 0};\nLine(1) = {1, 2};\n", fp), fclose(fp);
  expect_input_error(read_file(tmp, NULL, &m), tmp, "gmsh", "bad .geo");
  remove(tmp);
  /* Pamgen: an unknown keyword */
  expect_input_error(
      read_pamgen(
          "    mesh\n      rectilinear\n        nx = 2\n        bogus 3\n      end\n    end\n", &m),
      "pamgen mesh at /tmp/pf_test_fem_mesh", "BOGUS", "bad pamgen");
  snprintf(path, sizeof path, "%s/data/mesh/two_hexes.msh", tests_dir);
  snprintf(text, sizeof text, "mesh:\n  file: %s\n  pamgen: |\n    mesh\n    end\n", path);
  expect_input_error(read_deck(text, &m), "exactly one", NULL, "file and pamgen");
  expect_input_error(read_file(path, "  element_size: 1e-3\n", &m), "element_size", ".geo",
                     "element_size on .msh");
  expect_input_error(read_file(path, "  blocks: [left, centre]\n", &m), "centre", "'left', 'right'",
                     "unknown block");
  pf_error_set_quiet(0);
  PF_TEST_TRUE(m.nnodes == 0 && m.X == NULL); /* failed reads leave the mesh empty */
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  if (!getcwd(tests_dir, sizeof tests_dir)) tests_dir[0] = '.', tests_dir[1] = '\0';
  test_hex_volume();
  test_bar();
  test_panel_plate();
  test_taylor_bar();
  test_expanding_tube_lexan();
  test_sphere();
  test_subdivision();
  test_msh();
  test_exodus_round_trip();
  test_exodus_inverted_block();
  test_pamgen();
  test_bad_input();
  return pf_test_finish();
}
