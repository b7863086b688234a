/* Families: O(n) cell-list neighbour search into CSR full neighbour lists, each row sorted by
 * global id (docs/architecture.md §2: owner-computes, partition-independent summation order),
 * with the pre-crack bond filter and Peridigm's partial-volume fractions. */
#include "pd/pd_impl.h"

#include <stdlib.h>
#include <string.h>

/* Fraction of the cube (centre c, edge h) inside the sphere (x, delta): all eight corners in
 * -> 1, all out -> 0, else the 16^3 sub-cell midpoint rule. This is the rule of Peridigm's
 * partial-volume calculator, which produces its published weighted-volume convergence table. */
double pf_pd_partial_volume(const double x[3], const double c[3], double h, double delta) {
  const double d2 = delta * delta;
  int in = 0;
  for (int k = 0; k < 8; k++) {
    double s = 0;
    for (int a = 0; a < 3; a++) {
      double q = c[a] + ((k >> a & 1) ? 0.5 : -0.5) * h - x[a];
      s += q * q;
    }
    in += s <= d2;
  }
  if (in == 8) return 1.0;
  if (in == 0) return 0.0;
  enum { NS = 16 };
  int count = 0;
  for (int k = 0; k < NS; k++) {
    double dz = c[2] + (-0.5 + (k + 0.5) / NS) * h - x[2];
    for (int j = 0; j < NS; j++) {
      double dy = c[1] + (-0.5 + (j + 0.5) / NS) * h - x[1];
      for (int i = 0; i < NS; i++) {
        double dx = c[0] + (-0.5 + (i + 0.5) / NS) * h - x[0];
        count += dx * dx + dy * dy + dz * dz <= d2;
      }
    }
  }
  return (double)count / (NS * NS * NS);
}

/* Does the segment between xi and xj cross the pre-crack? The same answer for (xi, xj) and
 * (xj, xi), to the last bit: the segment is taken from its lexicographically smaller end, so a bond
 * that crosses the plane exactly on the crack's edge is cut in both families or in neither (else
 * the family is one-sided and the pair forces do not balance). */
static int crosses(const pf_precrack *c, const double xa[3], const double xb[3]) {
  const int swap = xb[0] < xa[0] || (xb[0] == xa[0] && (xb[1] < xa[1] || (xb[1] == xa[1] && xb[2] < xa[2])));
  const double *xi = swap ? xb : xa, *xj = swap ? xa : xb;
  double n[3], p[3], d[3];
  if (c->kind == PF_CRACK_RECTANGLE) {
    n[0] = c->a[1] * c->b[2] - c->a[2] * c->b[1];
    n[1] = c->a[2] * c->b[0] - c->a[0] * c->b[2];
    n[2] = c->a[0] * c->b[1] - c->a[1] * c->b[0];
    memcpy(p, c->p0, sizeof p);
  } else {
    memcpy(n, c->normal, sizeof n);
    memcpy(p, c->center, sizeof p);
  }
  double nd = 0, np = 0;
  for (int a = 0; a < 3; a++) {
    d[a] = xj[a] - xi[a];
    nd += n[a] * d[a];
    np += n[a] * (p[a] - xi[a]);
  }
  if (nd == 0) return 0;
  double t = np / nd;
  if (t < 0 || t > 1) return 0;
  double q[3];
  for (int a = 0; a < 3; a++) q[a] = xi[a] + t * d[a] - p[a];
  if (c->kind == PF_CRACK_DISK) return q[0] * q[0] + q[1] * q[1] + q[2] * q[2] <= c->radius * c->radius;
  double qa = 0, qb = 0, aa = 0, bb = 0;
  for (int a = 0; a < 3; a++) {
    qa += q[a] * c->a[a], qb += q[a] * c->b[a];
    aa += c->a[a] * c->a[a], bb += c->b[a] * c->b[a];
  }
  return qa >= 0 && qa <= aa && qb >= 0 && qb <= bb;
}

typedef struct {
  double lo[3], size;
  long dim[3];
  pf_int *start; /* [ncells + 1] */
  pf_int *items; /* cloud indices grouped by cell */
} cell_list;

static long cell_of(const cell_list *cl, const double x[3], long idx[3]) {
  for (int a = 0; a < 3; a++) {
    long q = (long)((x[a] - cl->lo[a]) / cl->size);
    idx[a] = q < 0 ? 0 : q >= cl->dim[a] ? cl->dim[a] - 1 : q;
  }
  return (idx[2] * cl->dim[1] + idx[1]) * cl->dim[0] + idx[0];
}

/* A point far from the others (a typo in a points file) makes the grid mostly empty and huge:
 * more than 64 cells a point (and 2^20) is refused before it is allocated, naming the extent and
 * the point farthest from the centroid. Every body's search comes here (a constant horizon is
 * checked earlier against its deck key, sim/body_pd.c; a variable horizon or a coupled body's
 * points only here). */
#define PF_MAX_SEARCH_CELLS_PER_POINT 64.0
static int check_grid(const double *X, pf_int n, double size, const double lo[3], const double hi[3],
                      double ncell) {
  if (ncell <= fmax(PF_MAX_SEARCH_CELLS_PER_POINT * (double)n, 1048576.0)) return 0;
  double c[3] = {0, 0, 0}, dmax = -1;
  for (pf_int i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) c[a] += X[3 * i + a] / (double)n;
  pf_int far = 0;
  for (pf_int i = 0; i < n; i++) {
    const double r = hypot(hypot(X[3 * i] - c[0], X[3 * i + 1] - c[1]), X[3 * i + 2] - c[2]);
    if (r > dmax) dmax = r, far = i;
  }
  const double *x = &X[3 * (size_t)far];
  return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                        "the neighbour search of %" PF_INT_FMT " points spanning %g x %g x %g m takes %.3g cells "
                        "of the largest horizon (%g m), about %.3g GB, %.0f a point: a point far from the others? "
                        "point %" PF_INT_FMT " at (%g, %g, %g) is %g m from the centroid (%g, %g, %g)",
                        n, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], ncell, size, ncell * 8 / 1e9,
                        ncell / (double)n, far + 1, x[0], x[1], x[2], dmax, c[0], c[1], c[2]);
}

static int cell_list_build(const double *X, pf_int n, double size, cell_list *cl) {
  double hi[3];
  for (int a = 0; a < 3; a++) cl->lo[a] = INFINITY, hi[a] = -INFINITY;
  for (pf_int i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) {
      cl->lo[a] = fmin(cl->lo[a], X[3 * i + a]);
      hi[a] = fmax(hi[a], X[3 * i + a]);
    }
  cl->size = size;
  long ncell = 1;
  for (int a = 0; a < 3; a++) {
    cl->dim[a] = (long)((hi[a] - cl->lo[a]) / size) + 1;
    if (cl->dim[a] > 2048) cl->dim[a] = 2048; /* clamp: coarser bins, same neighbours */
    ncell *= cl->dim[a];
  }
  PF_CALL(check_grid(X, n, size, cl->lo, hi, (double)ncell));
  if (cl->dim[0] == 2048 || cl->dim[1] == 2048 || cl->dim[2] == 2048)
    for (int a = 0; a < 3; a++) cl->size = fmax(cl->size, (hi[a] - cl->lo[a]) / 2047.0);
  PF_MALLOC(cl->start, ncell + 1);
  PF_MALLOC(cl->items, n);
  long idx[3];
  for (pf_int i = 0; i < n; i++) cl->start[cell_of(cl, &X[3 * i], idx) + 1]++;
  for (long c = 0; c < ncell; c++) cl->start[c + 1] += cl->start[c];
  pf_int *fill;
  PF_MALLOC(fill, ncell);
  for (pf_int i = 0; i < n; i++) {
    long c = cell_of(cl, &X[3 * i], idx);
    cl->items[cl->start[c] + fill[c]++] = i;
  }
  free(fill);
  return 0;
}

typedef struct {
  pf_gid gid;
  float frac;
} candidate;

static int by_gid(const void *a, const void *b) {
  const candidate *p = a, *q = b;
  return (p->gid > q->gid) - (p->gid < q->gid);
}

typedef struct {
  const pf_pd_cloud *src;
  const double *hz; /* [src->n] each cloud point's own horizon, or NULL: constant */
  double horizon, reach;
  int partial, ncracks;
  const pf_precrack *cracks;
} search_ctx;

/* Neighbours of the point at xi (cloud index self) into row[]; returns their count. */
static pf_int find_row(const search_ctx *s, const cell_list *cl, const double *xi, pf_int self,
                       candidate *row) {
  const double *X = s->src->X;
  long idx[3];
  cell_of(cl, xi, idx);
  pf_int count = 0;
  for (long cz = idx[2] - 1; cz <= idx[2] + 1; cz++)
    for (long cy = idx[1] - 1; cy <= idx[1] + 1; cy++)
      for (long cx = idx[0] - 1; cx <= idx[0] + 1; cx++) {
        if (cx < 0 || cy < 0 || cz < 0 || cx >= cl->dim[0] || cy >= cl->dim[1] || cz >= cl->dim[2])
          continue;
        long c = (cz * cl->dim[1] + cy) * cl->dim[0] + cx;
        for (pf_int k = cl->start[c]; k < cl->start[c + 1]; k++) {
          pf_int j = cl->items[k];
          const double *xj = &X[3 * j];
          double dx = xj[0] - xi[0], dy = xj[1] - xi[1], dz = xj[2] - xi[2];
          double r2 = dx * dx + dy * dy + dz * dz;
          if (j == self || r2 > s->reach * s->reach) continue;
          double frac = 1.0, h = s->hz ? fmax(s->hz[self], s->hz[j]) : s->horizon;
          if (s->partial) frac = pf_pd_partial_volume(xi, xj, s->src->cell[j], h);
          else if (r2 > h * h) continue;
          if (frac <= 0) continue;
          int cut = 0;
          for (int q = 0; q < s->ncracks && !cut; q++) cut = crosses(&s->cracks[q], xi, xj);
          if (cut) continue;
          row[count++] = (candidate){s->src->gid0 + j, (float)frac};
        }
      }
  qsort(row, (size_t)count, sizeof *row, by_gid);
  return count;
}

static int append_row(pf_bond_rows *rows, const candidate *row, pf_int count, int partial, pf_gid *gid, float *frac) {
  for (pf_int k = 0; k < count; k++) gid[k] = row[k].gid, frac[k] = row[k].frac;
  const pf_bond_values v = {"vfrac", frac, 1};
  return pf_bond_rows_append(rows, count, gid, partial, &v);
}

int pf_pd_family_register_fields(pf_bond_rows *rows, int partial_volumes, int nstate) {
  PF_CALL(pf_bond_rows_field_register(rows, "broken", PF_BOND_UINT8, 1, PF_FIELD_RESTART, 0.0));
  PF_CALL(pf_bond_rows_field_register(rows, "rest", PF_BOND_FLOAT, 1, PF_FIELD_RESTART, 0.0));
  if (partial_volumes) PF_CALL(pf_bond_rows_field_register(rows, "vfrac", PF_BOND_FLOAT, 1, PF_FIELD_RESTART, 1.0));
  if (nstate > 0) PF_CALL(pf_bond_rows_field_register(rows, "state", PF_BOND_DOUBLE, nstate, PF_FIELD_RESTART, 0.0));
  return 0;
}

int pf_pd_family_build(const pf_pd_cloud *src, const pf_points *pts, pf_int first, pf_int n,
                       double horizon, const double *hz, int partial_volumes, int ncracks,
                       const pf_precrack *cracks, pf_bond_rows *rows) {
  PF_CHECK(horizon > 0, PF_ERR_INPUT, "horizon must be positive (got %g)", horizon);
  PF_CALL(pf_pd_family_register_fields(rows, partial_volumes, 0));
  double hmax = 0;
  for (pf_int j = 0; j < src->n; j++) hmax = fmax(hmax, src->cell[j]);
  search_ctx s = {src, hz, horizon, horizon + (partial_volumes ? 0.8660254037844387 * hmax : 0),
                  partial_volumes, ncracks, cracks};
  cell_list cl = {0};
  PF_CALL(cell_list_build(src->X, src->n, s.reach, &cl));
  pf_int maxocc = 0; /* a row never holds more than the points of 27 cells */
  for (long c = 0; c < cl.dim[0] * cl.dim[1] * cl.dim[2]; c++)
    if (cl.start[c + 1] - cl.start[c] > maxocc) maxocc = cl.start[c + 1] - cl.start[c];
  candidate *row;
  pf_gid *gid;
  float *frac;
  PF_MALLOC(row, 27 * (size_t)maxocc);
  PF_MALLOC(gid, 27 * (size_t)maxocc);
  PF_MALLOC(frac, 27 * (size_t)maxocc);
  int ierr = 0;
  for (pf_int i = first; i < first + n && !ierr; i++) {
    pf_int self = (pf_int)(pts->gid[i] - src->gid0);
    ierr = append_row(rows, row, find_row(&s, &cl, &pts->X[3 * i], self, row), partial_volumes, gid, frac);
  }
  free(row), free(gid), free(frac);
  free(cl.start);
  free(cl.items);
  return ierr;
}

int pf_pd_family_from_rows(const pf_bond_rows *rows, const pf_int *local, pf_int first, pf_int n,
                           int partial_volumes, pf_family *fam) {
  const int ns = fam->nstate; /* set by the material, kept */
  pf_pd_family_free(fam);
  PF_FREE(fam->state);
  fam->nstate = ns;
  fam->first = first;
  fam->n = n;
  int64_t o0 = rows->offset[first], nb = rows->offset[first + n] - o0;
  PF_MALLOC(fam->offset, n + 1);
  /* PF_FAMILY_SLACK zeroed entries past the end: the batched bond loops read a whole batch */
  PF_MALLOC(fam->neighbor, nb + PF_FAMILY_SLACK);
  PF_MALLOC(fam->broken, nb + PF_FAMILY_SLACK);
  if (partial_volumes) PF_MALLOC(fam->vfrac, nb + PF_FAMILY_SLACK);
  PF_MALLOC(fam->rest, nb + PF_FAMILY_SLACK);
  PF_MALLOC(fam->recorded, nb / 64 + 1);
  if (ns > 0) PF_MALLOC(fam->state, nb * ns);
  for (pf_int i = 0; i <= n; i++) fam->offset[i] = rows->offset[first + i] - o0;
  for (int64_t k = 0; k < nb; k++) fam->neighbor[k] = local[o0 + k];
  for (int64_t k = 0; k < nb && partial_volumes; k++) fam->vfrac[k] = 1.0f; /* (rows without fractions) */
  /* each array from the bond field of its name (left zero, or 1, where the rows lack it) */
  PF_CALL(pf_bond_rows_field_copy(rows, "broken", PF_BOND_UINT8, o0, nb, 1, fam->broken));
  PF_CALL(pf_bond_rows_field_copy(rows, "rest", PF_BOND_FLOAT, o0, nb, 1, fam->rest));
  for (int64_t k = 0; k < nb; k++) fam->recorded[k / 64] |= (uint64_t)(fam->rest[k] > 0) << (k % 64);
  if (partial_volumes) PF_CALL(pf_bond_rows_field_copy(rows, "vfrac", PF_BOND_FLOAT, o0, nb, 1, fam->vfrac));
  if (ns > 0) PF_CALL(pf_bond_rows_field_copy(rows, "state", PF_BOND_DOUBLE, o0, nb, ns, fam->state));
  return 0;
}

int pf_pd_family_to_rows(const pf_family *fam, const pf_points *pts, pf_bond_rows *rows) {
  PF_CALL(pf_pd_family_register_fields(rows, fam->vfrac != NULL, fam->nstate));
  pf_gid *gid;
  int64_t maxrow = 0;
  for (pf_int i = 0; i < fam->n; i++)
    if (fam->offset[i + 1] - fam->offset[i] > maxrow) maxrow = fam->offset[i + 1] - fam->offset[i];
  PF_MALLOC(gid, maxrow);
  int ierr = 0;
  for (pf_int i = 0; i < fam->n && !ierr; i++) {
    int64_t o = fam->offset[i];
    pf_int cnt = (pf_int)(fam->offset[i + 1] - o), nv = 2;
    for (pf_int k = 0; k < cnt; k++) gid[k] = pts->gid[fam->neighbor[o + k]];
    pf_bond_values v[4] = {{"broken", &fam->broken[o], 1}, {"rest", &fam->rest[o], 1}};
    if (fam->vfrac) v[nv++] = (pf_bond_values){"vfrac", &fam->vfrac[o], 1};
    if (fam->nstate > 0 && fam->state) v[nv++] = (pf_bond_values){"state", &fam->state[o * fam->nstate], fam->nstate};
    ierr = pf_bond_rows_append(rows, cnt, gid, nv, v);
  }
  free(gid);
  return ierr;
}
