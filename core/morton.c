/* Spatial ordering of points along a Morton (Z-order) curve, so that a point's bond partners
 * sit close to it in memory and the force loop's gathers hit the cache. */
#include "core/core.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  uint64_t key;
  pf_int index;
} keyed;

/* Spread the low 21 bits of v so that two zero bits separate each bit. */
static uint64_t spread3(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

static int by_key(const void *a, const void *b) {
  const keyed *p = a, *q = b;
  if (p->key != q->key) return p->key < q->key ? -1 : 1;
  return p->index < q->index ? -1 : p->index > q->index;
}

int pf_morton_order(pf_int n, const double *X, pf_int *perm) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (pf_int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) {
      lo[c] = fmin(lo[c], X[3 * i + c]);
      hi[c] = fmax(hi[c], X[3 * i + c]);
    }
  double ext = 0;
  for (int c = 0; c < 3; c++) ext = fmax(ext, hi[c] - lo[c]);
  double scale = ext > 0 ? (double)((1 << 21) - 1) / ext : 0;
  keyed *k;
  PF_MALLOC(k, n);
  for (pf_int i = 0; i < n; i++) {
    uint64_t key = 0;
    for (int c = 0; c < 3; c++) key |= spread3((uint64_t)((X[3 * i + c] - lo[c]) * scale)) << c;
    k[i].key = key;
    k[i].index = i;
  }
  qsort(k, (size_t)n, sizeof *k, by_key);
  for (pf_int i = 0; i < n; i++) perm[i] = k[i].index;
  free(k);
  return 0;
}
