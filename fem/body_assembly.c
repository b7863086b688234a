/* An FE body on this rank: its local elements, the node -> element lists of its owned nodes,
 * lumped masses, the force assembly, and the nodal output fields. */
#include "fem/fem_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Store index of every mesh node present on this rank (owned or ghost), -1 elsewhere. */
static int local_index(const pf_fem_body *b, int body, const pf_points *pts, pf_int first, pf_int n, pf_gid gid0,
                       pf_int **loc) {
  PF_MALLOC(*loc, b->mesh.nnodes);
  for (pf_int k = 0; k < b->mesh.nnodes; k++) (*loc)[k] = -1;
  for (pf_int i = first; i < first + n; i++) (*loc)[pts->gid[i] - gid0] = i;
  for (pf_int i = pts->n_owned; i < pts->n_total; i++)
    if (pts->body[i] == body) (*loc)[pts->gid[i] - gid0] = i;
  return 0;
}

/* Blended: is element e of the mesh left to the other operator (beta = 1 at its eight nodes)? */
static int left_to_other(const pf_fem_body *b, pf_int e) {
  if (!b->beta_fn) return 0;
  for (int I = 0; I < 8; I++)
    if (b->beta_fn(b->beta_ctx, &b->mesh.X[3 * (size_t)b->mesh.conn[8 * (size_t)e + I]]) < 1) return 0;
  return 1;
}

/* Elements with at least one owned node, ascending; their connectivity in store indices. */
static int local_elements(pf_fem_body *b, const pf_points *pts, pf_int first, pf_int n, const pf_int *loc) {
  const pf_mesh *m = &b->mesh;
  uint8_t *mark = NULL;
  PF_MALLOC(mark, m->nelem);
  for (pf_int e = 0; e < m->nelem; e++)
    for (int I = 0; I < 8; I++) {
      pf_int i = loc[m->conn[8 * (size_t)e + I]];
      if (i >= first && i < first + n) mark[e] = 1;
    }
  for (pf_int e = 0; e < m->nelem; e++) mark[e] = mark[e] && !left_to_other(b, e);
  b->nel = 0;
  for (pf_int e = 0; e < m->nelem; e++) b->nel += mark[e];
  free(b->eid), free(b->conn), free(b->own);
  b->eid = malloc(sizeof(pf_int) * ((size_t)b->nel + 1));
  b->conn = malloc(sizeof(pf_int) * (8 * (size_t)b->nel + 1));
  b->own = malloc((size_t)b->nel + 1);
  PF_CHECK(b->eid && b->conn && b->own, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " elements", b->nel);
  pf_int k = 0;
  for (pf_int e = 0; e < m->nelem; e++) {
    if (!mark[e]) continue;
    b->eid[k] = e;
    for (int I = 0; I < 8; I++) {
      pf_int i = loc[m->conn[8 * (size_t)e + I]];
      if (i < 0) free(mark);
      PF_CHECK(i >= 0, PF_ERR_RUN, "body '%s': node %" PF_INT_FMT " of element %" PF_INT_FMT " is not on this rank",
               b->name, m->conn[8 * (size_t)e + I] + 1, e + 1);
      b->conn[8 * (size_t)k + I] = i;
    }
    b->own[k] = b->conn[8 * (size_t)k] < pts->n_owned;
    k++;
  }
  free(mark);
  return 0;
}

/* For each owned node, its (element, corner) pairs in ascending element order. */
static int node_lists(pf_fem_body *b) {
  free(b->node_off), free(b->node_item);
  PF_MALLOC(b->node_off, b->n + 1);
  PF_MALLOC(b->node_item, 8 * (size_t)b->nel);
  for (pf_int e = 0; e < b->nel; e++)
    for (int I = 0; I < 8; I++) {
      pf_int i = b->conn[8 * (size_t)e + I] - b->first;
      if (i >= 0 && i < b->n) b->node_off[i + 1]++;
    }
  for (pf_int i = 0; i < b->n; i++) b->node_off[i + 1] += b->node_off[i];
  int64_t *fill = malloc(sizeof(int64_t) * ((size_t)b->n + 1));
  PF_CHECK(fill, PF_ERR_MEMORY, "out of memory");
  memcpy(fill, b->node_off, sizeof(int64_t) * ((size_t)b->n + 1));
  for (pf_int e = 0; e < b->nel; e++)
    for (int I = 0; I < 8; I++) {
      pf_int i = b->conn[8 * (size_t)e + I] - b->first;
      if (i >= 0 && i < b->n) b->node_item[fill[i]++] = 8 * e + I;
    }
  free(fill);
  return 0;
}

static void element_reference(const pf_fem_body *b, const pf_points *p, pf_int e, double x[8][3]) {
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) x[I][i] = p->X[3 * (size_t)b->conn[8 * (size_t)e + I] + i];
}

/* Lumped masses m_I = sum_e rho_e int N_I dV (rho_e the element's material's): each element's 8 contributions once (kept in wmass,
 * the shares a converted element takes with it), then each node sums its elements in order,
 * leaving out the elements converted into particles (fem/particles.c): the same sum on any rank
 * and after any history of conversions, restarts and re-partitions. */
static int element_shares(pf_fem_body *b, const pf_points *p) {
  free(b->wmass);
  PF_MALLOC(b->wmass, 8 * (size_t)b->nel);
  for (pf_int e = 0; e < b->nel; e++) {
    double x[8][3];
    element_reference(b, p, e, x);
    pf_hex8_lumped_mass(x, pf_fem_element_material(b, e)->rho, &b->wmass[8 * (size_t)e]);
  }
  return 0;
}

void pf_fem_lumped_masses(const pf_fem_body *b, pf_points *p) {
  for (pf_int i = 0; i < b->n; i++) {
    double m = 0;
    for (int64_t q = b->node_off[i]; q < b->node_off[i + 1]; q++) {
      const pf_int k = b->node_item[q];
      if (!b->mesh_converted || !b->mesh_converted[b->eid[k / 8]]) m += b->wmass[k];
    }
    p->m[b->first + i] = m;
  }
}

/* The reference elements' step l / c, c = sqrt((K + 4G/3) / rho) of each element's material. */
static double reference_stable_dt(const pf_fem_body *b, const pf_points *p) {
  double dt = INFINITY;
  for (pf_int e = 0; e < b->nel; e++) {
    double x[8][3], B[8][3];
    const pf_fem_material *fm = pf_fem_element_material(b, e);
    const double c = sqrt((fm->K + 4.0 * fm->G / 3.0) / fm->rho);
    element_reference(b, p, e, x);
    dt = fmin(dt, pf_hex8_char_length(x, pf_hex8_mean_gradient(x, B)) / c);
  }
  return dt;
}

static int register_fields(const pf_fem_body *b, pf_points *pts) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "stress", 6, PF_FIELD_OUTPUT, &idx));
  for (int k = 0; k < b->nnames; k++) PF_CALL(pf_points_field_register(pts, b->names[k], 1, PF_FIELD_OUTPUT, &idx));
  return 0;
}

int pf_fem_body_attach(pf_fem_body *b, int body, pf_points *pts, pf_int first, pf_int n, pf_gid gid0) {
  pf_int *loc = NULL;
  b->first = first, b->n = n, b->gid0 = gid0;
  PF_CALL(local_index(b, body, pts, first, n, gid0, &loc));
  int ierr = local_elements(b, pts, first, n, loc);
  free(loc);
  if (ierr) return ierr;
  PF_CALL(node_lists(b));
  PF_CALL(element_shares(b, pts));
  pf_fem_lumped_masses(b, pts);
  b->pts = pts;
  size_t nq = (size_t)b->nqp * b->nel;
  free(b->sigma), free(b->state), free(b->hgq), free(b->bvq), free(b->fe), free(b->energy), free(b->buf), free(b->ref);
  PF_MALLOC(b->ref, 25 * (size_t)b->nel);
  for (pf_int e = 0; e < b->nel; e++) {
    double x[8][3];
    element_reference(b, pts, e, x);
    b->ref[25 * (size_t)e + 24] = pf_hex8_mean_gradient(x, (double(*)[3]) & b->ref[25 * (size_t)e]);
  }
  PF_MALLOC(b->sigma, 6 * nq);
  PF_MALLOC(b->state, (size_t)b->nstate * nq);
  PF_MALLOC(b->hgq, 12 * (size_t)b->nel);
  PF_MALLOC(b->bvq, b->nel);
  PF_MALLOC(b->fe, 24 * (size_t)b->nel);
  PF_MALLOC(b->energy, 3 * (size_t)b->nel);
  b->buf = NULL, b->nbuf = 0; /* (grown to the thread count at the first evaluation) */
  free(b->due);
  b->due = NULL, b->n_due = 0;
  if (b->erosion) PF_MALLOC(b->due, b->nel);
  PF_CALL(pf_fem_materials_init(b));
  b->stable_dt = reference_stable_dt(b, pts);
  return b->beta_fn ? 0 : register_fields(b, pts); /* (a blended body's stress is the other operator's) */
}

void pf_fem_body_node_force(const pf_fem_body *b, pf_int i, int weighted, double f[3]) {
  const double *share = weighted ? b->share : NULL;
  f[0] = f[1] = f[2] = 0;
  for (int64_t q = b->node_off[i]; q < b->node_off[i + 1]; q++) {
    const pf_int k = b->node_item[q];
    const double *fe = &b->fe[3 * (size_t)k], w = share ? share[k / 8] : 1.0; /* (1.0 * x is x) */
    f[0] += w * fe[0], f[1] += w * fe[1], f[2] += w * fe[2];
  }
}

void pf_fem_body_node_blend_vector(const pf_fem_body *b, pf_int i, double beta_i, double g[3]) {
  g[0] = g[1] = g[2] = 0;
  for (int64_t q = b->node_off[i]; q < b->node_off[i + 1] && b->share; q++) {
    const pf_int k = b->node_item[q], e = k / 8;
    const double *ref = &b->ref[25 * (size_t)e], w = (b->share[e] - (1.0 - beta_i)) * ref[24];
    for (int a = 0; a < 3; a++) g[a] += w * ref[3 * (k % 8) + a];
  }
}

int pf_fem_body_evaluate(pf_fem_body *b, pf_points *pts, double dt, double t, long step) {
  b->t = t, b->step = step;
  return pf_fem_elements_evaluate(b, pts, dt);
}

int pf_fem_body_force(pf_fem_body *b, pf_points *pts, double dt, double t, long step) {
  int ierr = pf_fem_body_evaluate(b, pts, dt, t, step);
  PF_CALL(pf_fem_erosion_sync(b)); /* (collective: also after a failed evaluation) */
  if (ierr) return ierr;
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < b->n; i++) {
    double f[3];
    pf_fem_body_node_force(b, i, 0, f);
    for (int a = 0; a < 3; a++) pts->f[3 * (size_t)(b->first + i) + a] += f[a];
  }
  return 0;
}

double pf_fem_body_stable_dt(const pf_fem_body *b) { return b->stable_dt; }

void pf_fem_body_energies(const pf_fem_body *b, double e[3]) {
  e[0] = e[1] = e[2] = 0;
  for (pf_int k = 0; k < b->nel; k++) {
    if (!b->own[k]) continue;
    const double w = b->share ? b->share[k] : 1.0; /* blended: the element's share */
    for (int c = 0; c < 3; c++) e[c] += w * b->energy[3 * (size_t)k + c];
  }
}

const pf_mesh *pf_fem_body_mesh(const pf_fem_body *b) { return &b->mesh; }
const pf_material *pf_fem_body_material(const pf_fem_body *b) { return b->mats[0].mat; }

int pf_fem_body_output_fields(pf_fem_body *b, pf_points *pts) {
  if (b->beta_fn) return 0; /* blended: the nodes' stress and history are the other operator's */
  double *stress = pf_points_field_get(pts, "stress");
  PF_CHECK(stress, PF_ERR_RUN, "body '%s': no stress field", b->name);
  double *st[PF_FEM_MAX_STATE_NAMES], *vq = NULL;
  for (int k = 0; k < b->nnames; k++) st[k] = pf_points_field_get(pts, b->names[k]);
  const int nq = b->nqp;
  PF_MALLOC(vq, b->nel); /* each element's current volume per quadrature point, once */
#pragma omp parallel for schedule(static)
  for (pf_int e0 = 0; e0 < b->nel; e0 += PF_HEX8_LANES) { /* (8 elements at a time: the lanes) */
    _Alignas(64) double x[8][3][PF_HEX8_LANES], B[8][3][PF_HEX8_LANES], V[PF_HEX8_LANES];
    for (int l = 0; l < PF_HEX8_LANES; l++) {
      const pf_int e = e0 + l < b->nel ? e0 + l : e0; /* (lanes past the end repeat the first) */
      for (int I = 0; I < 8; I++)
        for (int a = 0; a < 3; a++) x[I][a][l] = pts->y[3 * (size_t)b->conn[8 * (size_t)e + I] + a];
    }
    pf_hex8_mean_gradient_lanes(x, B, V);
    for (int l = 0; l < PF_HEX8_LANES && e0 + l < b->nel; l++) vq[e0 + l] = V[l] / nq;
  }
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < b->n; i++) { /* (each node its own sums, in its element order) */
    double w = 0, s[6] = {0}, h[PF_FEM_MAX_STATE_NAMES] = {0};
    for (int64_t q = b->node_off[i]; q < b->node_off[i + 1]; q++) {
      pf_int e = b->node_item[q] / 8;
      const int8_t *slot = b->slot[pf_fem_mesh_material(b, b->eid[e])]; /* (-1: none, counts 0) */
      for (int g = 0; g < nq && !pf_fem_element_eroded(b, e); g++) {
        for (int c = 0; c < 6; c++) s[c] += vq[e] * b->sigma[6 * ((size_t)nq * e + g) + c];
        for (int k = 0; k < b->nnames; k++)
          if (slot[k] >= 0) h[k] += vq[e] * b->state[(size_t)b->nstate * (nq * (size_t)e + g) + slot[k]];
        w += vq[e];
      }
    }
    pf_int p = b->first + i;
    for (int c = 0; c < 6; c++) stress[6 * (size_t)p + c] = w > 0 ? s[c] / w : 0;
    for (int k = 0; k < b->nnames; k++) st[k][p] = w > 0 ? h[k] / w : 0;
  }
  free(vq);
  return 0;
}
