/* Peridigm's Exodus discretization (geometry: {shape: exodus}) of solid elements, on Exodus files
 * written here with the Exodus API, against closed forms:
 *  - a 4 x 2 x 2 box of HEX8 elements whose planes x = 1 and x = 2 lean (x = i + t_i (z - 1)),
 *    so that the elements beside them are trapezoidal prisms: every element's volume and
 *    centroid against the prism's integrals (V = int w dz, V xbar = int (x_r^2 - x_l^2)/2 dz,
 *    V zbar = int z w dz over its height, w = x_r - x_l linear in z: Simpson's rule, exact for
 *    these quadratics), 1e-12 relative; total volume 16; block id; a node set on the face x = 0
 *    gives the 4 elements of the first column and a node set of one inner node the 8 elements
 *    around it (Peridigm: a node brings in every element it is a corner of);
 *  - a unit cube with node 7 raised by h = 0.3 (a warped top face): V = 1 + h/3, the volume of
 *    Peridigm's six tetrahedra about the diagonal 1-7 (worked by hand: the three tetrahedra on
 *    node 7 gain h/6, 0 and h/6), not the trilinear 1 + h/4;
 *  - the unit cube as 2 x 2 x 2 cells of six Kuhn tetrahedra each (TETRA): 48 points, each of
 *    volume (1/2)^3 / 6 at corner + (2 e_a + e_b + (1, 1, 1)) / 8;
 *  - HEX8 + TETRA + SPHERE blocks in one file sharing nodes: counts, volumes, blocks, a node set
 *    on the hexahedra's and the tetrahedra's shared corner and a sphere's node (1 + 6 + 1
 *    points), blocks: taking some of the blocks (the set keeps only their elements);
 *  - refused, naming the file and the block or element, with nothing half-made: a WEDGE block, an
 *    inverted hexahedron.
 * Measured: the largest relative errors of the volumes and of the centroids' coordinates. */
#include "test_common.h"

#include <exodusII.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh/mesh.h"

typedef struct {
  int id, n, npe;
  const char *name, *type;
  const int *conn;    /* [n npe], 1-based */
  const double *attr; /* [n 2] radius, volume (SPHERE) or NULL */
} block;
typedef struct {
  const char *name;
  int n;
  const int *node; /* 1-based */
} node_set;
typedef struct {
  int n;
  double x[200], y[200], z[200];
} nodes;

static int put_block(int exoid, const block *b) {
  int st = ex_put_block(exoid, EX_ELEM_BLOCK, b->id, b->type, b->n, b->npe, 0, 0, b->attr ? 2 : 0);
  if (st >= 0) st = ex_put_conn(exoid, EX_ELEM_BLOCK, b->id, b->conn, NULL, NULL);
  if (st >= 0 && b->attr) st = ex_put_attr(exoid, EX_ELEM_BLOCK, b->id, b->attr);
  char *an[2] = {"radius", "volume"};
  if (st >= 0 && b->attr) st = ex_put_attr_names(exoid, EX_ELEM_BLOCK, b->id, an);
  return st;
}

static const char *write_exodus(const char *tag, const nodes *p, int nb, const block *b, int ns, const node_set *s) {
  static char path[256];
  snprintf(path, sizeof path, "/tmp/pf_test_exodus_points_%s_%d.g", tag, (int)getpid());
  int cpu_ws = 8, io_ws = 8, nelem = 0;
  int exoid = ex_create(path, EX_CLOBBER, &cpu_ws, &io_ws);
  PF_TEST_TRUE(exoid >= 0);
  for (int k = 0; k < nb; k++) nelem += b[k].n;
  int st = ex_put_init(exoid, tag, 3, p->n, nelem, nb, ns, 0);
  if (st >= 0) st = ex_put_coord(exoid, p->x, p->y, p->z);
  char *names[8];
  for (int k = 0; st >= 0 && k < nb; k++) st = put_block(exoid, &b[k]), names[k] = (char *)b[k].name;
  if (st >= 0) st = ex_put_names(exoid, EX_ELEM_BLOCK, names);
  for (int k = 0; st >= 0 && k < ns; k++) {
    st = ex_put_set_param(exoid, EX_NODE_SET, k + 1, s[k].n, 0);
    if (st >= 0) st = ex_put_set(exoid, EX_NODE_SET, k + 1, s[k].node, NULL);
    names[k] = (char *)s[k].name;
  }
  if (st >= 0 && ns) st = ex_put_names(exoid, EX_NODE_SET, names);
  ex_close(exoid);
  PF_TEST_TRUE(st >= 0);
  return path;
}

/* Read the file as a body's geometry (extra: more keys of the mapping); returns the error. */
static int read_points(const char *path, const char *extra, pf_point_cloud *pc) {
  char text[1024];
  snprintf(text, sizeof text, "geometry: {shape: exodus, file: %s%s}\n", path, extra ? extra : "");
  pf_deck *d = NULL;
  int ierr = pf_test_deck_text("exodus_points", text, NULL, NULL, &d);
  memset(pc, 0, sizeof *pc);
  if (!ierr) ierr = pf_mesh_exodus_points_from_deck(d, pf_node_get(pf_deck_root(d), "geometry"), pc);
  pf_deck_destroy(&d);
  return ierr;
}

static double worst_volume, worst_centroid; /* largest relative errors against the closed forms */

/* got against the closed form want (1e-12 relative), keeping the largest error in *worst. */
static void closed_form(double got, double want, double *worst) {
  PF_TEST_CLOSE(got, want, 1e-12, 0);
  *worst = fmax(*worst, fabs(got - want) / fabs(want));
}

static const pf_point_set *find_set(const pf_point_cloud *pc, const char *name) {
  for (int k = 0; k < pc->nsets; k++)
    if (!strcmp(pc->sets[k].name, name)) return &pc->sets[k];
  PF_TEST_TRUE(!"the node set is in the cloud");
  return NULL;
}

/* The set holds exactly the n points want (ascending). */
static void set_is(const pf_point_cloud *pc, const char *name, int n, const pf_gid *want) {
  const pf_point_set *s = find_set(pc, name);
  int same = s && s->n == n;
  for (int k = 0; same && k < n; k++) same = s->gid[k] == want[k];
  if (!same) fprintf(stderr, "node set '%s': %d points, want %d\n", name, s ? (int)s->n : -1, n);
  PF_TEST_TRUE(same);
}

static double total_volume(const pf_point_cloud *pc) {
  double V = 0;
  for (pf_int i = 0; i < pc->n; i++) V += pc->vol[i];
  return V;
}

/* Node (i, j, k) of an (nx + 1) x (ny + 1) x (nz + 1) grid, 1-based. */
static int grid_node(int i, int j, int k, int nx, int ny) { return 1 + i + (nx + 1) * (j + (ny + 1) * k); }

/* The 8 nodes of cell (i, j, k) in Exodus HEX8 order. */
static void hex_conn(int i, int j, int k, int nx, int ny, int *c) {
  const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
  for (int a = 0; a < 8; a++) c[a] = grid_node(i + di[a % 4], j + dj[a % 4], k + a / 4, nx, ny);
}

/* ---- the leaning box ----------------------------------------------------------------------- */
enum { NX = 4, NY = 2, NZ = 2 };
static const double lean[NX + 1] = {0, 0.25, -0.125, 0, 0}; /* plane x = i leans by t_i (z - 1) */

static double plane_x(int i, double z) { return i + lean[i] * (z - 1); }

/* Simpson's rule over [k, k + 1] (exact for polynomials of degree 3). */
static double simpson(double f0, double fm, double f1) { return (f0 + 4 * fm + f1) / 6; }

/* Volume and centroid of cell (i, j, k) of the leaning box (the prism's integrals). */
static void prism(int i, int j, int k, double c[3], double *V) {
  double zs[3] = {k, k + 0.5, k + 1}, w[3], xm[3], zw[3];
  for (int q = 0; q < 3; q++) {
    const double xl = plane_x(i, zs[q]), xr = plane_x(i + 1, zs[q]);
    w[q] = xr - xl, xm[q] = (xr * xr - xl * xl) / 2, zw[q] = zs[q] * w[q];
  }
  *V = simpson(w[0], w[1], w[2]);
  c[0] = simpson(xm[0], xm[1], xm[2]) / *V;
  c[1] = j + 0.5;
  c[2] = simpson(zw[0], zw[1], zw[2]) / *V;
}

static void test_leaning_box(void) {
  nodes p = {0};
  for (int k = 0; k <= NZ; k++)
    for (int j = 0; j <= NY; j++)
      for (int i = 0; i <= NX; i++, p.n++) p.x[p.n] = plane_x(i, k), p.y[p.n] = j, p.z[p.n] = k;
  int conn[NX * NY * NZ * 8], e = 0;
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++, e++) hex_conn(i, j, k, NX, NY, conn + 8 * e);
  int face[(NY + 1) * (NZ + 1)], nf = 0, inner[1] = {grid_node(2, 1, 1, NX, NY)};
  for (int k = 0; k <= NZ; k++)
    for (int j = 0; j <= NY; j++) face[nf++] = grid_node(0, j, k, NX, NY);
  const block b = {7, e, 8, "box", "HEX8", conn, NULL};
  const node_set s[2] = {{"x0", nf, face}, {"inner", 1, inner}};
  const char *path = write_exodus("box", &p, 1, &b, 2, s);
  pf_point_cloud pc;
  PF_TEST_OK(read_points(path, NULL, &pc));
  PF_TEST_TRUE(pc.n == NX * NY * NZ);
  for (int k = 0, q = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX && q < pc.n; i++, q++) {
        double c[3], V;
        prism(i, j, k, c, &V);
        closed_form(pc.vol[q], V, &worst_volume);
        for (int a = 0; a < 3; a++) closed_form(pc.X[3 * q + a], c[a], &worst_centroid);
        PF_TEST_TRUE(pc.block[q] == 7);
      }
  PF_TEST_CLOSE(total_volume(&pc), NX * NY * NZ, 1e-12, 0);
  const pf_gid first_column[4] = {0, 4, 8, 12}, around[8] = {1, 2, 5, 6, 9, 10, 13, 14};
  set_is(&pc, "x0", 4, first_column);
  set_is(&pc, "inner", 8, around);
  pf_point_cloud_free(&pc);
  remove(path);
}

/* ---- a warped hexahedron ------------------------------------------------------------------- */
static void test_warped_hex(void) {
  const double h = 0.3;
  nodes p = {8, {0, 1, 1, 0, 0, 1, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1}, {0, 0, 0, 0, 1, 1, 1 + h, 1}};
  const int conn[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const block b = {1, 1, 8, "warped", "HEX", conn, NULL};
  const char *path = write_exodus("warped", &p, 1, &b, 0, NULL);
  pf_point_cloud pc;
  PF_TEST_OK(read_points(path, NULL, &pc));
  PF_TEST_TRUE(pc.n == 1);
  if (pc.n == 1) closed_form(pc.vol[0], 1 + h / 3, &worst_volume);
  double x[8][3];
  for (int a = 0; a < 8; a++) x[a][0] = p.x[a], x[a][1] = p.y[a], x[a][2] = p.z[a];
  PF_TEST_CLOSE(pf_mesh_hex_volume((const double(*)[3])x), 1 + h / 4, 1e-12, 0); /* not Peridigm's */
  pf_point_cloud_free(&pc);
  remove(path);
}

/* ---- tetrahedra ---------------------------------------------------------------------------- */
static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
static const int perm_sign[6] = {1, -1, -1, 1, 1, -1};

/* The 6 Kuhn tetrahedra of cell (i, j, k) of an n^3 grid (positively oriented), 1-based. */
static void kuhn_conn(int i, int j, int k, int n, int *c) {
  for (int t = 0; t < 6; t++) {
    int o[3] = {0, 0, 0}, v[4];
    v[0] = grid_node(i, j, k, n, n);
    for (int s = 0; s < 3; s++) {
      o[perms[t][s]] = 1;
      v[s + 1] = grid_node(i + o[0], j + o[1], k + o[2], n, n);
    }
    const int swap = perm_sign[t] < 0;
    c[4 * t] = v[0], c[4 * t + 1] = v[swap ? 2 : 1], c[4 * t + 2] = v[swap ? 1 : 2], c[4 * t + 3] = v[3];
  }
}

/* Centroid of Kuhn tetrahedron t of the cell at corner (edge hc): corner + hc (2 e_a + e_b + 1)/4. */
static void kuhn_centroid(const double corner[3], double hc, int t, double c[3]) {
  for (int a = 0; a < 3; a++) c[a] = corner[a] + hc * (1 + 2 * (perms[t][0] == a) + (perms[t][1] == a)) / 4;
}

static void test_tetrahedra(void) {
  enum { N = 2 };
  const double hc = 1.0 / N;
  nodes p = {0};
  for (int k = 0; k <= N; k++)
    for (int j = 0; j <= N; j++)
      for (int i = 0; i <= N; i++, p.n++) p.x[p.n] = i * hc, p.y[p.n] = j * hc, p.z[p.n] = k * hc;
  int conn[N * N * N * 24], e = 0;
  for (int k = 0; k < N; k++)
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++, e += 6) kuhn_conn(i, j, k, N, conn + 4 * e);
  const block b = {3, e, 4, "tets", "TETRA", conn, NULL};
  const char *path = write_exodus("tets", &p, 1, &b, 0, NULL);
  pf_point_cloud pc;
  PF_TEST_OK(read_points(path, NULL, &pc));
  PF_TEST_TRUE(pc.n == 6 * N * N * N);
  for (int q = 0; q < pc.n; q++) {
    const int cell = q / 6, i = cell % N, j = (cell / N) % N, k = cell / (N * N);
    const double corner[3] = {i * hc, j * hc, k * hc};
    double c[3];
    kuhn_centroid(corner, hc, q % 6, c);
    closed_form(pc.vol[q], hc * hc * hc / 6, &worst_volume);
    for (int a = 0; a < 3; a++) closed_form(pc.X[3 * q + a], c[a], &worst_centroid);
  }
  PF_TEST_CLOSE(total_volume(&pc), 1.0, 1e-12, 0);
  pf_point_cloud_free(&pc);
  remove(path);
}

/* ---- HEX8 + TETRA + SPHERE ----------------------------------------------------------------- */
/* Two unit hexahedra over [0, 2] x [0, 1]^2 (block 'bar', id 1), the cube [2, 3] x [0, 1]^2 as
 * six Kuhn tetrahedra on the same nodes (block 'tets', id 2), and two spheres at (5, .5, .5) and
 * (6, .5, .5) of volume 0.7 (block 'balls', id 3). */
static const char *write_mixed(const char *tag, const char *sphere_type, int sphere_npe) {
  nodes p = {0};
  for (int k = 0; k <= 1; k++)
    for (int j = 0; j <= 1; j++)
      for (int i = 0; i <= 3; i++, p.n++) p.x[p.n] = i, p.y[p.n] = j, p.z[p.n] = k;
  const int ball[2] = {p.n + 1, p.n + 2};
  for (int s = 0; s < 2; s++, p.n++) p.x[p.n] = 5 + s, p.y[p.n] = p.z[p.n] = 0.5;
  int hexes[16], tets[24], conn6[12];
  for (int e = 0; e < 2; e++) hex_conn(e, 0, 0, 3, 1, hexes + 8 * e);
  int unit[24];
  kuhn_conn(0, 0, 0, 1, unit); /* on a grid of 2 x 2 x 2 nodes: renumbered into the 4 x 2 x 2 one */
  for (int a = 0; a < 24; a++) {
    const int q = unit[a] - 1, i = q % 2, j = (q / 2) % 2, k = q / 4;
    tets[a] = grid_node(2 + i, j, k, 3, 1);
  }
  for (int a = 0; a < 12; a++) conn6[a] = ball[a % 2];
  const double attr[4] = {0.55, 0.7, 0.55, 0.7};
  const block b[3] = {{1, 2, 8, "bar", "HEX8", hexes, NULL},
                      {2, 6, 4, "tets", "TETRA", tets, NULL},
                      {3, sphere_npe == 1 ? 2 : 1, sphere_npe, "balls", sphere_type, sphere_npe == 1 ? ball : conn6,
                       sphere_npe == 1 ? attr : NULL}};
  const int corner[2] = {grid_node(2, 0, 0, 3, 1), ball[0]};
  const int face[4] = {grid_node(0, 0, 0, 3, 1), grid_node(0, 1, 0, 3, 1), grid_node(0, 0, 1, 3, 1),
                       grid_node(0, 1, 1, 3, 1)};
  const node_set s[2] = {{"corner", 2, corner}, {"x0", 4, face}};
  return write_exodus(tag, &p, 3, b, 2, s);
}

static void test_mixed(void) {
  const char *path = write_mixed("mixed", "SPHERE", 1);
  pf_point_cloud pc;
  PF_TEST_OK(read_points(path, NULL, &pc));
  PF_TEST_TRUE(pc.n == 2 + 6 + 2);
  const int32_t blk[10] = {1, 1, 2, 2, 2, 2, 2, 2, 3, 3};
  const double vol[10] = {1, 1, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 0.7, 0.7};
  for (pf_int q = 0; q < pc.n && q < 10; q++) {
    PF_TEST_TRUE(pc.block[q] == blk[q]);
    PF_TEST_CLOSE(pc.vol[q], vol[q], 1e-12, 0);
  }
  /* the blocks taken, by id and name (material_regions names them) */
  PF_TEST_TRUE(pc.nnamed == 3 && pc.named_id[0] == 1 && pc.named_id[2] == 3);
  PF_TEST_TRUE(pc.nnamed == 3 && !strcmp(pc.named[0], "bar") && !strcmp(pc.named[1], "tets") &&
               !strcmp(pc.named[2], "balls"));
  PF_TEST_CLOSE(pc.X[0], 0.5, 1e-12, 0);
  PF_TEST_CLOSE(pc.X[3 * 9], 6.0, 0, 0);
  PF_TEST_CLOSE(total_volume(&pc), 2 + 1 + 1.4, 1e-12, 0);
  const pf_gid corner[8] = {1, 2, 3, 4, 5, 6, 7, 8}, x0[1] = {0};
  set_is(&pc, "corner", 8, corner);
  set_is(&pc, "x0", 1, x0);
  pf_point_cloud_free(&pc);
  /* the tetrahedra and the spheres alone: the set keeps their points, renumbered */
  PF_TEST_OK(read_points(path, ", blocks: [tets, '3']", &pc));
  PF_TEST_TRUE(pc.n == 6 + 2);
  const pf_gid corner2[7] = {0, 1, 2, 3, 4, 5, 6};
  set_is(&pc, "corner", 7, corner2);
  set_is(&pc, "x0", 0, NULL);
  pf_point_cloud_free(&pc);
  remove(path);
}

/* ---- refusals ------------------------------------------------------------------------------ */
static void refused(const char *path, const char *must_mention) {
  pf_point_cloud pc;
  pf_error_clear();
  pf_error_set_quiet(1);
  const int ierr = read_points(path, NULL, &pc);
  pf_error_set_quiet(0);
  pf_test_refused(ierr, pc.n != 0 || pc.X != NULL || pc.sets != NULL, path, must_mention);
  PF_TEST_TRUE(strstr(pf_error_message(), path) != NULL);
  pf_point_cloud_free(&pc);
}

static void test_refusals(void) {
  const char *path = write_mixed("wedge", "WEDGE", 6);
  refused(path, "block 'balls' (id 3) holds WEDGE elements of 6 nodes; a Peridigm discretization is read from "
                "SPHERE (1 node), HEX8 (HEX, HEX8, HEXAHEDRON: 8 nodes) and TET4 (TET, TET4, TETRA, TETRA4: 4 nodes)");
  remove(path);
  nodes p = {8, {0, 1, 1, 0, 0, 1, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1}, {1, 1, 1, 1, 0, 0, 0, 0}};
  const int conn[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const block b = {5, 1, 8, "upside_down", "HEX8", conn, NULL};
  path = write_exodus("inverted", &p, 1, &b, 0, NULL);
  refused(path, "element 1 (block 'upside_down', HEX8) has volume -1 with a tetrahedron of volume");
  remove(path);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  test_leaning_box();
  test_warped_hex();
  test_tetrahedra();
  test_mixed();
  test_refusals();
  pf_test_measure("volume_error", worst_volume, NULL);
  pf_test_measure("centroid_error", worst_centroid, NULL);
  return pf_test_finish();
}
