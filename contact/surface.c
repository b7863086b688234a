/* Geometry of the surfaces of FE bodies for contact: the boundary faces of a hexahedral mesh
 * and the closest point of a face to a point.
 *
 * Boundary faces: a face of the mesh is on the boundary when exactly one element has it. The
 * 6 nelem element faces are keyed by their 4 node ids, sorted; sorting the keys brings equal
 * faces together (O(n log n)), and a key that occurs once is a boundary face. The faces keep the
 * node order of pf_hex8_face (Exodus HEX8 sides), whose right-hand rule gives the outward
 * normal of a positive-volume element.
 *
 * Closest point: the bilinear quadrilateral x(xi, eta) = sum_a N_a x_a is replaced by the four
 * triangles T_a = (x_a, x_a+1, m), a = 0..3 (x_4 = x_0), about its centre
 * m = (x_0 + x_1 + x_2 + x_3) / 4; the four triangles cover the quadrilateral exactly when it
 * is flat and interpolate it (same nodes, edges and centre) when it is warped. The closest point
 * of each triangle comes from its Voronoi regions (vertex, edge, interior) as in Ericson,
 * Real-Time Collision Detection (2005), sec. 5.1.5, "Closest point on triangle to point"; the
 * closest of the four wins (ties: the lowest triangle). With c = l0 x_a + l1 x_a+1 + l2 m the
 * node weights are w_a += l0, w_a+1 += l1, w_k += l2 / 4 (k = 0..3): they sum to 1, are >= 0,
 * and sum_k w_k x_k = c, so a force at c spreads to the nodes with the same resultant and
 * moment. The signed distance s = sign((p - c) . t) |p - c|, t the unit normal of the closest
 * triangle (right-hand rule, outward), is the distance function whose gradient ds/dp is the
 * returned normal n = sign (p - c) / |p - c|. */
#include "contact/contact.h"
#include "mesh/mesh.h"

#include <math.h>
#include <stdlib.h>

/* ---- boundary faces ------------------------------------------------------------------------ */

typedef struct {
  pf_int key[4]; /* the face's node ids, ascending */
  pf_gid id;     /* 6 elem + face */
} face_key;

static void sort4(pf_int k[4]) {
  for (int i = 1; i < 4; i++)
    for (int j = i; j > 0 && k[j] < k[j - 1]; j--) {
      pf_int t = k[j];
      k[j] = k[j - 1];
      k[j - 1] = t;
    }
}

static int same_key(const face_key *a, const face_key *b) {
  return a->key[0] == b->key[0] && a->key[1] == b->key[1] && a->key[2] == b->key[2] &&
         a->key[3] == b->key[3];
}

static int by_key(const void *pa, const void *pb) {
  const face_key *a = pa, *b = pb;
  for (int i = 0; i < 4; i++)
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  return (a->id > b->id) - (a->id < b->id);
}

static int by_elem_face(const void *pa, const void *pb) {
  const pf_contact_face *a = pa, *b = pb;
  if (a->elem != b->elem) return a->elem < b->elem ? -1 : 1;
  return (a->face > b->face) - (a->face < b->face);
}

/* Face f of element e, in pf_hex8_face order (outward). */
static void make_face(const pf_mesh *m, pf_int e, int f, pf_contact_face *out) {
  for (int i = 0; i < 4; i++) out->node[i] = m->conn[8 * (size_t)e + pf_hex8_face[f][i]];
  out->elem = e;
  out->face = f;
}

/* Mark the element faces (6 e + f) of live elements that no other live element has. */
static int mark_boundary(const pf_mesh *m, const uint8_t *dead, unsigned char *boundary) {
  size_t nf = 0;
  face_key *k;
  PF_MALLOC(k, 6 * (size_t)m->nelem);
  for (pf_int e = 0; e < m->nelem; e++)
    for (int f = 0; f < 6 && !(dead && dead[e]); f++) {
      face_key *q = &k[nf++];
      for (int i = 0; i < 4; i++) q->key[i] = m->conn[8 * (size_t)e + pf_hex8_face[f][i]];
      sort4(q->key);
      q->id = 6 * (pf_gid)e + f;
    }
  qsort(k, nf, sizeof *k, by_key);
  for (size_t i = 0; i < nf;) {
    size_t j = i + 1;
    while (j < nf && same_key(&k[i], &k[j])) j++;
    if (j == i + 1) boundary[k[i].id] = 1;
    i = j;
  }
  free(k);
  return 0;
}

int pf_contact_surface_faces(const pf_mesh *m, int sideset, const uint8_t *dead, pf_contact_face **faces,
                             pf_int *nfaces) {
  *faces = NULL;
  *nfaces = 0;
  PF_CHECK(sideset >= -1 && sideset < m->nsidesets, PF_ERR_INPUT,
           "side set %d does not exist (the mesh has %d)", sideset, m->nsidesets);
  pf_contact_face *out;
  if (sideset >= 0) {
    const pf_mesh_set *s = &m->sideset[sideset];
    for (pf_int k = 0; k < s->n; k++)
      PF_CHECK(s->item[k] >= 0 && s->item[k] < m->nelem && s->face[k] >= 0 && s->face[k] < 6,
               PF_ERR_INPUT, "side %" PF_INT_FMT " of side set '%s' is element %" PF_INT_FMT
               " face %d (the mesh has %" PF_INT_FMT " elements, faces 0..5)",
               k, s->name, s->item[k], (int)s->face[k], m->nelem);
    PF_MALLOC(out, s->n);
    pf_int n = 0;
    for (pf_int k = 0; k < s->n; k++)
      if (!(dead && dead[s->item[k]])) make_face(m, s->item[k], s->face[k], &out[n++]);
    qsort(out, (size_t)n, sizeof *out, by_elem_face);
    *faces = out;
    *nfaces = n;
    return 0;
  }
  size_t nf = 6 * (size_t)m->nelem, n = 0;
  unsigned char *boundary;
  PF_MALLOC(boundary, nf);
  int ierr = mark_boundary(m, dead, boundary);
  if (ierr) {
    free(boundary);
    return ierr;
  }
  for (size_t i = 0; i < nf; i++) n += boundary[i];
  out = calloc(n ? n : 1, sizeof *out);
  if (!out) free(boundary);
  PF_CHECK(out, PF_ERR_MEMORY, "out of memory allocating %zu boundary faces", n);
  n = 0;
  for (size_t i = 0; i < nf; i++) /* ascending 6 e + f: sorted by (elem, face) */
    if (boundary[i]) make_face(m, (pf_int)(i / 6), (int)(i % 6), &out[n++]);
  free(boundary);
  *faces = out;
  *nfaces = (pf_int)n;
  return 0;
}

/* ---- closest point of a face --------------------------------------------------------------- */

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double ratio(double num, double den) { return den > 0 ? num / den : 0; }

/* Barycentric coordinates l[3] (of a, b, c) of the point of triangle (a, b, c) closest to p:
 * Ericson (2005) sec. 5.1.5, the Voronoi regions tested in turn, with
 *   d1 = ab.ap, d2 = ac.ap, d3 = ab.bp, d4 = ac.bp, d5 = ab.cp, d6 = ac.cp,
 *   vc = d1 d4 - d3 d2, vb = d5 d2 - d1 d6, va = d3 d6 - d5 d4
 * (va, vb, vc: the unnormalized barycentrics of the projection of p onto the plane). A
 * degenerate edge (zero length) gives the weight 0 instead of 0/0. */
static void triangle_closest(const double a[3], const double b[3], const double c[3],
                             const double p[3], double l[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; i++) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
    bp[i] = p[i] - b[i];
    cp[i] = p[i] - c[i];
  }
  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  l[0] = l[1] = l[2] = 0;
  if (d1 <= 0 && d2 <= 0) { /* vertex region a */
    l[0] = 1;
    return;
  }
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) { /* vertex region b */
    l[1] = 1;
    return;
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { /* edge region ab: a + v ab, v = d1 / (d1 - d3) */
    double v = ratio(d1, d1 - d3);
    l[0] = 1 - v;
    l[1] = v;
    return;
  }
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) { /* vertex region c */
    l[2] = 1;
    return;
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { /* edge region ac: a + w ac, w = d2 / (d2 - d6) */
    double w = ratio(d2, d2 - d6);
    l[0] = 1 - w;
    l[2] = w;
    return;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) { /* edge region bc: b + w (c - b) */
    double w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
    l[1] = 1 - w;
    l[2] = w;
    return;
  }
  /* interior: va, vb, vc > 0 here, so the weights are positive */
  double r = 1 / (va + vb + vc);
  l[0] = va * r;
  l[1] = vb * r;
  l[2] = vc * r;
}

/* Unit normal of triangle (a, b, c) by the right-hand rule, (b - a) x (c - a) / |...|; 0 when the
 * triangle is degenerate. */
static void triangle_normal(const double a[3], const double b[3], const double c[3],
                            double t[3]) {
  double u[3], v[3];
  for (int i = 0; i < 3; i++) u[i] = b[i] - a[i], v[i] = c[i] - a[i];
  pf_vec3_cross(u, v, t);
  double len = sqrt(dot3(t, t));
  for (int i = 0; i < 3; i++) t[i] = len > 0 ? t[i] / len : 0;
}

double pf_contact_face_closest(const double x[4][3], const double p[3], double c[3], double w[4],
                               double n[3]) {
  double m[3], h2 = 0;
  for (int i = 0; i < 3; i++) m[i] = 0.25 * (x[0][i] + x[1][i] + x[2][i] + x[3][i]);
  for (int k = 0; k < 4; k++) {
    double r[3] = {x[k][0] - m[0], x[k][1] - m[1], x[k][2] - m[2]};
    h2 = fmax(h2, dot3(r, r)); /* face size: the largest node distance from the centre */
  }
  int best = 0;
  double bestd2 = INFINITY, bl[3] = {1, 0, 0};
  for (int a = 0; a < 4; a++) {
    const double *xa = x[a], *xb = x[(a + 1) % 4];
    double l[3], q[3], r[3];
    triangle_closest(xa, xb, m, p, l);
    for (int i = 0; i < 3; i++) q[i] = l[0] * xa[i] + l[1] * xb[i] + l[2] * m[i], r[i] = p[i] - q[i];
    double d2 = dot3(r, r);
    if (d2 < bestd2) { /* strict: ties keep the lowest triangle */
      bestd2 = d2;
      best = a;
      for (int i = 0; i < 3; i++) bl[i] = l[i];
    }
  }
  int a = best, b = (best + 1) % 4;
  for (int k = 0; k < 4; k++) w[k] = 0.25 * bl[2];
  w[a] += bl[0];
  w[b] += bl[1];
  double t[3], r[3];
  for (int i = 0; i < 3; i++) {
    c[i] = bl[0] * x[a][i] + bl[1] * x[b][i] + bl[2] * m[i];
    r[i] = p[i] - c[i];
  }
  triangle_normal(x[a], x[b], m, t);
  if (dot3(t, t) == 0) { /* degenerate triangle: the face normal, diagonals' cross product */
    double d1[3], d2[3];
    for (int i = 0; i < 3; i++) d1[i] = x[2][i] - x[0][i], d2[i] = x[3][i] - x[1][i];
    pf_vec3_cross(d1, d2, t);
    double len = sqrt(dot3(t, t));
    for (int i = 0; i < 3; i++) t[i] = len > 0 ? t[i] / len : 0;
  }
  double d = sqrt(dot3(r, r)), sign = dot3(r, t) >= 0 ? 1 : -1;
  if (d > 1e-12 * sqrt(h2)) {
    for (int i = 0; i < 3; i++) n[i] = sign * r[i] / d;
  } else { /* p on the face: the triangle's normal */
    for (int i = 0; i < 3; i++) n[i] = t[i];
  }
  return sign * d;
}
