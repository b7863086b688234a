/* The distance from a position to the nearest of a fixed set of points: a uniform grid of cells
 * about two points each, searched ring by ring outwards until no closer cell can remain. The
 * result is the minimum of the same distances whatever the query order, so every rank computes
 * bitwise the same value for the same position. */
#include "core/core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct pf_nearest {
  pf_int n;
  double *X;      /* [3n] the points, grouped by cell */
  double lo[3], h;
  long dim[3];
  pf_int *start;  /* [ncells + 1] */
};

static long cell_index(const pf_nearest *q, const double x[3], long c[3]) {
  for (int a = 0; a < 3; a++) {
    long k = (long)floor((x[a] - q->lo[a]) / q->h);
    c[a] = k < 0 ? 0 : (k >= q->dim[a] ? q->dim[a] - 1 : k);
  }
  return (c[2] * q->dim[1] + c[1]) * q->dim[0] + c[0];
}

int pf_nearest_create(const double *X, pf_int n, pf_nearest **out) {
  *out = NULL;
  PF_CHECK(n > 0, PF_ERR_INPUT, "nearest-point search over an empty set");
  pf_nearest *q;
  PF_MALLOC(q, 1);
  double hi[3];
  for (int a = 0; a < 3; a++) q->lo[a] = hi[a] = X[a];
  for (pf_int k = 0; k < n; k++)
    for (int a = 0; a < 3; a++) q->lo[a] = fmin(q->lo[a], X[3 * k + a]), hi[a] = fmax(hi[a], X[3 * k + a]);
  double vol = 1, ext = 0;
  for (int a = 0; a < 3; a++) ext = fmax(ext, hi[a] - q->lo[a]);
  for (int a = 0; a < 3; a++) vol *= fmax(hi[a] - q->lo[a], 1e-3 * ext + 1e-300);
  q->h = fmax(cbrt(2.0 * vol / n), 1e-6 * ext + 1e-300);
  long ncells = 1;
  for (int a = 0; a < 3; a++) q->dim[a] = (long)((hi[a] - q->lo[a]) / q->h) + 1, ncells *= q->dim[a];
  q->n = n;
  PF_MALLOC(q->start, (size_t)ncells + 1);
  PF_MALLOC(q->X, 3 * (size_t)n);
  pf_int *cellof, *fill;
  PF_MALLOC(cellof, n);
  for (pf_int k = 0; k < n; k++) {
    long c[3];
    cellof[k] = (pf_int)cell_index(q, &X[3 * k], c);
    q->start[cellof[k] + 1]++;
  }
  for (long c = 0; c < ncells; c++) q->start[c + 1] += q->start[c];
  PF_MALLOC(fill, ncells + 1);
  memcpy(fill, q->start, sizeof(pf_int) * (size_t)ncells);
  for (pf_int k = 0; k < n; k++) memcpy(&q->X[3 * (size_t)fill[cellof[k]]++], &X[3 * k], 3 * sizeof(double));
  free(cellof), free(fill);
  *out = q;
  return 0;
}

/* The searches keep the squared distance: the square root is correctly rounded and monotone, so
 * the root of the smallest square is bitwise the smallest root. */
static double cell_min(const pf_nearest *q, const double x[3], long i, long j, long k, double best2) {
  const long cell = (k * q->dim[1] + j) * q->dim[0] + i;
  for (pf_int p = q->start[cell]; p < q->start[cell + 1]; p++) {
    const double *y = &q->X[3 * (size_t)p];
    const double d2 = (y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) + (y[2] - x[2]) * (y[2] - x[2]);
    best2 = d2 < best2 ? d2 : best2;
  }
  return best2;
}

/* Ring r of cells about c: every cell of the grid at Chebyshev index distance exactly r. */
static double ring_min(const pf_nearest *q, const double x[3], const long c[3], long r, double best2) {
  const long k0 = c[2] - r < 0 ? 0 : c[2] - r, k1 = c[2] + r >= q->dim[2] ? q->dim[2] - 1 : c[2] + r;
  const long j0 = c[1] - r < 0 ? 0 : c[1] - r, j1 = c[1] + r >= q->dim[1] ? q->dim[1] - 1 : c[1] + r;
  const long i0 = c[0] - r < 0 ? 0 : c[0] - r, i1 = c[0] + r >= q->dim[0] ? q->dim[0] - 1 : c[0] + r;
  for (long k = k0; k <= k1; k++)
    for (long j = j0; j <= j1; j++) {
      if (labs(k - c[2]) == r || labs(j - c[1]) == r) { /* a face of the shell: the whole row */
        for (long i = i0; i <= i1; i++) best2 = cell_min(q, x, i, j, k, best2);
      } else { /* inside the shell's faces: its two ends only */
        if (c[0] - r >= 0) best2 = cell_min(q, x, c[0] - r, j, k, best2);
        if (r > 0 && c[0] + r < q->dim[0]) best2 = cell_min(q, x, c[0] + r, j, k, best2);
      }
    }
  return best2;
}

double pf_nearest_distance(const pf_nearest *q, const double x[3]) {
  long c[3], rmax = 0;
  cell_index(q, x, c);
  for (int a = 0; a < 3; a++) rmax = c[a] > rmax ? c[a] : rmax, rmax = q->dim[a] - 1 - c[a] > rmax ? q->dim[a] - 1 - c[a] : rmax;
  double best = INFINITY, best2 = INFINITY;
  /* cells of ring r are at least (r - 1) h from the query's projection on the grid's box (which
   * lies in cell c), hence from the query itself: the projection on a convex set does not
   * lengthen distances */
  for (long r = 0; r <= rmax && !(best <= (r - 1) * q->h); r++) best2 = ring_min(q, x, c, r, best2), best = sqrt(best2);
  return best;
}

void pf_nearest_destroy(pf_nearest **q) {
  if (!*q) return;
  free((*q)->X), free((*q)->start);
  PF_FREE(*q);
}
