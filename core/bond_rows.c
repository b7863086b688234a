/* Bond lists in transit (DESIGN.md 6): rows of neighbour global ids with their per-bond state,
 * the form in which families move between ranks when points are (re)partitioned. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

int pf_bond_rows_init(pf_bond_rows *r) {
  memset(r, 0, sizeof *r);
  PF_MALLOC(r->offset, 1);
  return 0;
}

static int grow(pf_bond_rows *r, int64_t need) {
  if (need <= r->cap) return 0;
  int64_t cap = need + need / 2 + 1024;
  pf_gid *g = realloc(r->gid, sizeof(pf_gid) * (size_t)cap);
  if (g) r->gid = g;
  uint8_t *b = realloc(r->broken, (size_t)cap);
  if (b) r->broken = b;
  float *v = realloc(r->vfrac, sizeof(float) * (size_t)cap);
  if (v) r->vfrac = v;
  PF_CHECK(g && b && v, PF_ERR_MEMORY, "out of memory for %" PRId64 " bonds", cap);
  r->cap = cap;
  return 0;
}

int pf_bond_rows_append(pf_bond_rows *r, pf_int count, const pf_gid *gid, const uint8_t *broken,
                        const float *vfrac) {
  if (r->n + 1 >= r->row_cap) {
    pf_int cap = r->row_cap + r->row_cap / 2 + 1024;
    int64_t *o = realloc(r->offset, sizeof(int64_t) * ((size_t)cap + 1));
    PF_CHECK(o, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " bond rows", cap);
    r->offset = o;
    r->row_cap = cap;
  }
  int64_t at = r->offset[r->n];
  PF_CALL(grow(r, at + count));
  if (count > 0) memcpy(r->gid + at, gid, sizeof(pf_gid) * (size_t)count); /* gid may be NULL then */
  for (pf_int k = 0; k < count; k++) {
    r->broken[at + k] = broken ? broken[k] : 0;
    r->vfrac[at + k] = vfrac ? vfrac[k] : 1.0f;
  }
  r->offset[++r->n] = at + count;
  return 0;
}

int pf_bond_rows_free(pf_bond_rows *r) {
  PF_FREE(r->offset);
  PF_FREE(r->gid);
  PF_FREE(r->broken);
  PF_FREE(r->vfrac);
  r->n = 0;
  r->cap = 0;
  return 0;
}
