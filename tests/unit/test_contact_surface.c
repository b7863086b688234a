/* Surfaces of FE bodies for contact (contact/surface.c) against hand counts and brute force:
 * the Exodus HEX8 face table is outward for a positive-volume element; the boundary of an
 * nx x ny x nz block of slightly distorted hexahedra has 2 (nx ny + ny nz + nz nx) faces, the
 * same faces as an O(n^2) count of shared faces, each pointing away from the block; a side set
 * returns its sides sorted by (element, face). The closest point of a face: hand values on the
 * unit square (foot, edge, corner, inside, both orientations, triangle-barycentric weights),
 * brute force over 2000 sampled points of the four triangles of a warped face for 1000 random
 * points, and the gradient of a penalty energy 0.5 (r - s)^2 by central differences. */
#include "contact/contact.h"
#include "fem/fem_impl.h"
#include "test_common.h"

#include <math.h>
#include <string.h>

/* ---- meshes ---- */

/* splitmix64: a fixed, portable sequence of uniform numbers in [0, 1). */
static uint64_t rng_state = 12345;
static double uniform(void) {
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

/* An nx x ny x nz block of cells 1.1 x 0.9 x 1.0 m, nodes moved by up to 0.05 m (every element
 * keeps a positive volume), Exodus HEX8 order. */
static void block_mesh(int nx, int ny, int nz, pf_mesh *m) {
  memset(m, 0, sizeof *m);
  m->nnodes = (nx + 1) * (ny + 1) * (nz + 1);
  m->nelem = nx * ny * nz;
  m->X = calloc(3 * (size_t)m->nnodes, sizeof(double));
  m->conn = calloc(8 * (size_t)m->nelem, sizeof(pf_int));
  for (int k = 0; k <= nz; k++)
    for (int j = 0; j <= ny; j++)
      for (int i = 0; i <= nx; i++) {
        double *X = &m->X[3 * (size_t)(i + (nx + 1) * (j + (ny + 1) * k))];
        X[0] = 1.1 * i + 0.05 * sin(1.3 * i + 2.1 * j + 0.7 * k);
        X[1] = 0.9 * j + 0.05 * cos(0.4 * i + 1.7 * j + 2.3 * k);
        X[2] = 1.0 * k + 0.05 * sin(2.9 * i + 0.3 * j + 1.1 * k + 0.5);
      }
  static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        pf_int e = i + nx * (j + ny * k);
        for (int I = 0; I < 8; I++)
          m->conn[8 * (size_t)e + I] = (i + corner[I][0]) +
                                       (nx + 1) * ((j + corner[I][1]) + (ny + 1) * (k + corner[I][2]));
      }
}

static void block_free(pf_mesh *m) {
  free(m->X);
  free(m->conn);
  for (int s = 0; s < m->nsidesets; s++) {
    free(m->sideset[s].item);
    free(m->sideset[s].face);
  }
  free(m->sideset);
}

static void element_coords(const pf_mesh *m, pf_int e, double x[8][3]) {
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) x[I][i] = m->X[3 * (size_t)m->conn[8 * (size_t)e + I] + i];
}

/* Face normal (x2 - x0) x (x3 - x1) (the diagonals: twice the area vector of a flat face) and
 * centre of the face with mesh nodes q[4]. */
static void face_normal(const pf_mesh *m, const pf_int q[4], double nrm[3], double ctr[3]) {
  double d1[3], d2[3];
  for (int i = 0; i < 3; i++) {
    d1[i] = m->X[3 * (size_t)q[2] + i] - m->X[3 * (size_t)q[0] + i];
    d2[i] = m->X[3 * (size_t)q[3] + i] - m->X[3 * (size_t)q[1] + i];
    ctr[i] = 0;
    for (int a = 0; a < 4; a++) ctr[i] += 0.25 * m->X[3 * (size_t)q[a] + i];
  }
  pf_vec3_cross(d1, d2, nrm);
}

static int same_nodes(const pf_int a[4], const pf_int b[4]) {
  int found = 0;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) found += a[i] == b[j];
  return found == 4;
}

/* Every element face of pf_hex8_face order points out of its element (right-hand rule). */
static void check_face_table(const pf_mesh *m) {
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3], ce[3] = {0, 0, 0};
    element_coords(m, e, x);
    PF_TEST_TRUE(pf_mesh_hex_volume((const double(*)[3])x) > 0);
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) ce[i] += x[I][i] / 8;
    for (int f = 0; f < 6; f++) {
      pf_int q[4];
      double nrm[3], cf[3];
      for (int a = 0; a < 4; a++) q[a] = m->conn[8 * (size_t)e + pf_hex8_face[f][a]];
      face_normal(m, q, nrm, cf);
      PF_TEST_TRUE(nrm[0] * (cf[0] - ce[0]) + nrm[1] * (cf[1] - ce[1]) + nrm[2] * (cf[2] - ce[2]) > 0);
    }
  }
}

/* Boundary faces against the brute-force count of faces with the same nodes; their normals
 * point away from the block centre (the block is convex). */
static void check_boundary(int nx, int ny, int nz) {
  pf_mesh m;
  block_mesh(nx, ny, nz, &m);
  check_face_table(&m);
  pf_contact_face *faces = NULL;
  pf_int nf = -1;
  PF_TEST_OK(pf_contact_surface_faces(&m, -1, NULL, &faces, &nf));
  PF_TEST_TRUE(nf == 2 * (nx * ny + ny * nz + nz * nx));
  double cb[3] = {0, 0, 0};
  for (pf_int k = 0; k < m.nnodes; k++)
    for (int i = 0; i < 3; i++) cb[i] += m.X[3 * (size_t)k + i] / m.nnodes;
  pf_int n = 0;
  for (pf_int e = 0; e < m.nelem; e++)
    for (int f = 0; f < 6; f++) {
      pf_int q[4], r[4];
      for (int a = 0; a < 4; a++) q[a] = m.conn[8 * (size_t)e + pf_hex8_face[f][a]];
      int count = 0;
      for (pf_int e2 = 0; e2 < m.nelem; e2++)
        for (int f2 = 0; f2 < 6; f2++) {
          for (int a = 0; a < 4; a++) r[a] = m.conn[8 * (size_t)e2 + pf_hex8_face[f2][a]];
          count += same_nodes(q, r);
        }
      if (count != 1) continue;
      /* the next returned face is this one, nodes in the table's (outward) order */
      PF_TEST_TRUE(n < nf);
      if (n >= nf) continue;
      const pf_contact_face *F = &faces[n++];
      PF_TEST_TRUE(F->elem == e && F->face == f);
      PF_TEST_TRUE(memcmp(F->node, q, sizeof q) == 0);
      double nrm[3], cf[3];
      face_normal(&m, F->node, nrm, cf);
      PF_TEST_TRUE(nrm[0] * (cf[0] - cb[0]) + nrm[1] * (cf[1] - cb[1]) + nrm[2] * (cf[2] - cb[2]) > 0);
    }
  PF_TEST_TRUE(n == nf);
  free(faces);
  block_free(&m);
}

/* Deleted elements (erosion) leave the surface and expose their live neighbours' faces: in a
 * 3 x 3 x 3 block (54 boundary faces) deleting the centre element exposes its 6 neighbours'
 * inner faces (60), deleting a corner too trades its 3 outer faces for its 3 neighbours' (60
 * again); no face belongs to a deleted element, and each exposed face's outward normal points
 * into the hole. */
static void check_eroded(void) {
  pf_mesh m;
  block_mesh(3, 3, 3, &m);
  uint8_t dead[27] = {0};
  pf_contact_face *faces = NULL;
  pf_int nf = -1;
  dead[13] = 1;
  PF_TEST_OK(pf_contact_surface_faces(&m, -1, dead, &faces, &nf));
  PF_TEST_TRUE(nf == 60);
  double c13[3] = {0, 0, 0};
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) c13[i] += m.X[3 * (size_t)m.conn[8 * 13 + I] + i] / 8;
  int inner = 0;
  for (pf_int k = 0; k < nf; k++) {
    PF_TEST_TRUE(faces[k].elem != 13);
    double nrm[3], cf[3], d = 0;
    face_normal(&m, faces[k].node, nrm, cf);
    for (int i = 0; i < 3; i++) d += (cf[i] - c13[i]) * (cf[i] - c13[i]);
    if (d > 0.7 * 0.7) continue; /* a face of the deleted cube (its centre ~0.5 away, the others > 1) */
    inner++;
    PF_TEST_TRUE(nrm[0] * (c13[0] - cf[0]) + nrm[1] * (c13[1] - cf[1]) + nrm[2] * (c13[2] - cf[2]) > 0);
  }
  PF_TEST_TRUE(inner == 6);
  free(faces);
  dead[0] = 1;
  PF_TEST_OK(pf_contact_surface_faces(&m, -1, dead, &faces, &nf));
  PF_TEST_TRUE(nf == 60);
  for (pf_int k = 0; k < nf; k++) PF_TEST_TRUE(faces[k].elem != 13 && faces[k].elem != 0);
  free(faces);
  block_free(&m);
}

/* Side sets: 4 sides given out of order come back sorted by (element, face) with the nodes of
 * the face table; an empty side set gives 0 faces; a missing side set is an error. */
static void check_sideset(void) {
  pf_mesh m;
  block_mesh(2, 2, 2, &m);
  m.nsidesets = 2;
  m.sideset = calloc(2, sizeof *m.sideset);
  pf_mesh_set *s = &m.sideset[0];
  snprintf(s->name, sizeof s->name, "xmax");
  s->n = 4;
  s->item = calloc(4, sizeof(pf_int));
  s->face = calloc(4, sizeof(int8_t));
  const pf_int elems[4] = {7, 1, 5, 3}; /* the elements with i = 1; their +x face is side 1 */
  for (int k = 0; k < 4; k++) s->item[k] = elems[k], s->face[k] = 1;
  snprintf(m.sideset[1].name, sizeof m.sideset[1].name, "empty");
  pf_contact_face *faces = NULL;
  pf_int nf = -1;
  PF_TEST_OK(pf_contact_surface_faces(&m, 0, NULL, &faces, &nf));
  PF_TEST_TRUE(nf == 4);
  for (pf_int k = 0; k < nf && k < 4; k++) {
    PF_TEST_TRUE(faces[k].elem == 2 * k + 1 && faces[k].face == 1);
    for (int a = 0; a < 4; a++)
      PF_TEST_TRUE(faces[k].node[a] == m.conn[8 * (size_t)faces[k].elem + pf_hex8_face[1][a]]);
    double nrm[3], cf[3];
    face_normal(&m, faces[k].node, nrm, cf);
    PF_TEST_TRUE(nrm[0] > 0.9 * sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]));
  }
  free(faces);
  PF_TEST_OK(pf_contact_surface_faces(&m, 1, NULL, &faces, &nf));
  PF_TEST_TRUE(nf == 0 && faces != NULL);
  free(faces);
  pf_error_set_quiet(1);
  PF_TEST_TRUE(pf_contact_surface_faces(&m, 2, NULL, &faces, &nf) != 0 && faces == NULL && nf == 0);
  PF_TEST_TRUE(pf_contact_surface_faces(&m, -2, NULL, &faces, &nf) != 0);
  pf_error_clear();
  pf_error_set_quiet(0);
  block_free(&m);
}

/* ---- closest point ---- */

static double worst_hand = 0, worst_brute = 0, worst_wsum = 0, worst_fd = 0;

static void close3(const double got[3], const double want[3], double tol) {
  for (int i = 0; i < 3; i++) {
    PF_TEST_CLOSE(got[i], want[i], 0, tol);
    worst_hand = fmax(worst_hand, fabs(got[i] - want[i]));
  }
}

static void close1(double got, double want, double tol) {
  PF_TEST_CLOSE(got, want, 0, tol);
  worst_hand = fmax(worst_hand, fabs(got - want));
}

/* One hand case on face x: expected s, c, n and (when w_want is not NULL) weights. */
static void hand_case(const double x[4][3], const double p[3], double s_want, const double c_want[3],
                      const double n_want[3], const double w_want[4]) {
  double c[3], w[4], n[3];
  double s = pf_contact_face_closest(x, p, c, w, n);
  close1(s, s_want, 1e-14);
  close3(c, c_want, 1e-14);
  close3(n, n_want, 1e-14);
  double sum = 0;
  for (int k = 0; k < 4; k++) {
    sum += w[k];
    PF_TEST_TRUE(w[k] >= 0);
    if (w_want) close1(w[k], w_want[k], 1e-14);
  }
  close1(sum, 1.0, 1e-14);
}

static void check_closest_hand(void) {
  const double sq[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}; /* normal +z */
  const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  /* above the interior at (0.35, 0.6): triangle 3 (x3, x0, m) with l = (0.25, 0.05, 0.7), so
   * w3 = 0.25 + 0.175, w0 = 0.05 + 0.175, w1 = w2 = 0.175 (not the bilinear N_a) */
  const double foot[3] = {0.35, 0.6, 0}, wfoot[4] = {0.225, 0.175, 0.175, 0.425};
  hand_case(sq, (double[3]){0.35, 0.6, 0.3}, 0.3, foot, up, wfoot);
  hand_case(sq, (double[3]){0.35, 0.6, -0.2}, -0.2, foot, up, wfoot); /* inside */
  /* centre: every triangle ties, the weights are 1/4 */
  hand_case(sq, (double[3]){0.5, 0.5, 0.7}, 0.7, (double[3]){0.5, 0.5, 0},
            up, (double[4]){0.25, 0.25, 0.25, 0.25});
  /* above the midpoint of edge x0-x1 */
  hand_case(sq, (double[3]){0.5, 0, 0.2}, 0.2, (double[3]){0.5, 0, 0}, up,
            (double[4]){0.5, 0.5, 0, 0});
  /* beyond edge x0-x1, above and below the plane: c on the edge, |s| = 0.5 */
  hand_case(sq, (double[3]){0.4, -0.3, 0.4}, 0.5, (double[3]){0.4, 0, 0},
            (double[3]){0, -0.6, 0.8}, (double[4]){0.6, 0.4, 0, 0});
  hand_case(sq, (double[3]){0.4, -0.3, -0.4}, -0.5, (double[3]){0.4, 0, 0},
            (double[3]){0, 0.6, 0.8}, (double[4]){0.6, 0.4, 0, 0});
  /* beyond corner x2: c = x2, w = e_2 */
  double d = sqrt(0.2 * 0.2 + 0.5 * 0.5 + 0.1 * 0.1);
  hand_case(sq, (double[3]){1.2, 1.5, 0.1}, d, sq[2], (double[3]){0.2 / d, 0.5 / d, 0.1 / d},
            (double[4]){0, 0, 1, 0});
  /* on the face: s = 0, n the face normal */
  hand_case(sq, (double[3]){0.3, 0.2, 0}, 0, (double[3]){0.3, 0.2, 0}, up, NULL);
  /* the other orientation: the outward normal is -z, the same points change sides */
  const double rv[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  hand_case(rv, (double[3]){0.35, 0.6, 0.3}, -0.3, foot, down, NULL);
  hand_case(rv, (double[3]){0.35, 0.6, -0.2}, 0.2, foot, down, NULL);
  hand_case(rv, (double[3]){0.5, 0.5, -0.7}, 0.7, (double[3]){0.5, 0.5, 0}, down,
            (double[4]){0.25, 0.25, 0.25, 0.25});
  /* a collapsed face (x3 = x2: a triangle, triangle 2 of zero area): finite values; above the
   * midpoint of x0-x2 the foot is on the edge of triangles 0-1 and 3 */
  const double tri[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}};
  hand_case(tri, (double[3]){0.9, 0.1, 0.4}, 0.4, (double[3]){0.9, 0.1, 0}, up, NULL);
  /* beyond the collapsed corner, below the plane: c = x2, s < 0, n from p towards c */
  hand_case(tri, (double[3]){1, 1.5, -0.1}, -sqrt(0.26), tri[2],
            (double[3]){0, -0.5 / sqrt(0.26), 0.1 / sqrt(0.26)}, (double[4]){0, 0, 1, 0});
}

/* A face of size ~1 with corners moved by up to 0.3 in every direction (warped), shifted. */
static void warped_face(double x[4][3]) {
  const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int a = 0; a < 4; a++) {
    x[a][0] = 3 + sq[a][0] + 0.6 * (uniform() - 0.5);
    x[a][1] = -2 + sq[a][1] + 0.6 * (uniform() - 0.5);
    x[a][2] = 1 + 0.6 * (uniform() - 0.5);
  }
}

/* Random points around random warped faces: c is no farther from p than 2000 sampled points of
 * the four triangles; |p - c| = |s|; n is a unit vector with n . (p - c) = s; the weights are
 * >= 0, sum to 1 and reproduce c. */
static void check_closest_brute(void) {
  enum { NSAMPLE = 2000, NPOINT = 1000 };
  static double samp[NSAMPLE][3];
  double x[4][3];
  for (int ip = 0; ip < NPOINT; ip++) {
    if (ip % 100 == 0) { /* a new face (and its samples) every 100 points */
      warped_face(x);
      double m[3];
      for (int i = 0; i < 3; i++) m[i] = 0.25 * (x[0][i] + x[1][i] + x[2][i] + x[3][i]);
      for (int k = 0; k < NSAMPLE; k++) {
        int a = k % 4, b = (a + 1) % 4;
        double u = uniform(), v = uniform();
        if (u + v > 1) u = 1 - u, v = 1 - v;
        if (k < 12) u = (k / 4) == 0, v = (k / 4) == 1; /* the vertices too */
        for (int i = 0; i < 3; i++) samp[k][i] = x[a][i] + u * (x[b][i] - x[a][i]) + v * (m[i] - x[a][i]);
      }
    }
    double p[3] = {3.5 + 2.4 * (uniform() - 0.5), -1.5 + 2.4 * (uniform() - 0.5), 1 + 2 * (uniform() - 0.5)};
    double c[3], w[4], n[3];
    double s = pf_contact_face_closest((const double(*)[3])x, p, c, w, n);
    double r[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]}, d = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    PF_TEST_CLOSE(fabs(s), d, 1e-14, 1e-15);
    PF_TEST_CLOSE(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-14, 0);
    PF_TEST_CLOSE(n[0] * r[0] + n[1] * r[1] + n[2] * r[2], s, 1e-13, 1e-15);
    double best = INFINITY;
    for (int k = 0; k < NSAMPLE; k++) {
      double e[3] = {p[0] - samp[k][0], p[1] - samp[k][1], p[2] - samp[k][2]};
      best = fmin(best, sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]));
    }
    PF_TEST_TRUE(d <= best + 1e-13);
    worst_brute = fmax(worst_brute, d - best);
    double sum = 0, cw[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++) {
      PF_TEST_TRUE(w[k] >= 0);
      sum += w[k];
      for (int i = 0; i < 3; i++) cw[i] += w[k] * x[k][i];
    }
    PF_TEST_CLOSE(sum, 1.0, 0, 1e-14);
    worst_wsum = fmax(worst_wsum, fabs(sum - 1));
    for (int i = 0; i < 3; i++) {
      PF_TEST_CLOSE(cw[i], c[i], 0, 1e-13);
      worst_wsum = fmax(worst_wsum, fabs(cw[i] - c[i]));
    }
  }
}

/* U(p) = 0.5 (r - s(p))^2 for s < r: -dU/dp = (r - s) ds/dp = (r - s) n, by central
 * differences (step 1e-5: truncation ~1e-10, round-off ~1e-11 relative). */
static double energy(const double x[4][3], const double p[3], double r) {
  double c[3], w[4], n[3], s = pf_contact_face_closest(x, p, c, w, n);
  return 0.5 * (r - s) * (r - s);
}

static void check_gradient(void) {
  const double x[4][3] = {{0, 0, 0.05}, {1.1, 0.1, -0.04}, {1.0, 0.9, 0.06}, {-0.1, 1.0, -0.03}};
  const double pts[6][3] = {{0.4, 0.3, 0.2},  {0.7, 0.6, -0.15}, {0.2, 0.7, 0.05},
                            {0.5, -0.3, 0.3}, {1.4, 1.3, 0.2},   {0.8, 0.2, -0.3}};
  const double r = 1.0, h = 1e-5;
  for (int k = 0; k < 6; k++) {
    double c[3], w[4], n[3], s = pf_contact_face_closest(x, pts[k], c, w, n), f[3], fd[3];
    PF_TEST_TRUE(s < r);
    for (int i = 0; i < 3; i++) {
      double pp[3] = {pts[k][0], pts[k][1], pts[k][2]}, pm[3] = {pts[k][0], pts[k][1], pts[k][2]};
      pp[i] += h;
      pm[i] -= h;
      fd[i] = -(energy(x, pp, r) - energy(x, pm, r)) / (2 * h);
      f[i] = (r - s) * n[i];
    }
    double fn = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) {
      PF_TEST_CLOSE(fd[i], f[i], 0, 1e-6 * fn);
      worst_fd = fmax(worst_fd, fabs(fd[i] - f[i]) / fn);
    }
  }
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  check_boundary(2, 2, 2);
  check_boundary(3, 1, 1);
  check_boundary(5, 4, 3);
  check_eroded();
  check_sideset();
  check_closest_hand();
  check_closest_brute();
  check_gradient();
  pf_test_measure("closest_point_hand", worst_hand, "m");
  pf_test_measure("closest_point_brute", worst_brute, "m");
  pf_test_measure("weights", worst_wsum, "1");
  pf_test_measure("gradient", worst_fd, "1");
  if (getenv("PF_TEST_VERBOSE"))
    printf("worst errors: hand %.3g, brute (|p-c| - min sample) %.3g, weights %.3g, gradient %.3g\n",
           worst_hand, worst_brute, worst_wsum, worst_fd);
  return pf_test_finish();
}
