/* Bond lists in transit: rows of neighbour global ids with their per-bond state
 * (broken flag, partial-volume fraction, rest length, and the reals a material keeps per bond,
 * e.g. the plastic extensions of elastic_plastic), the form in which families move between ranks
 * when points are (re)partitioned and in which checkpoints store them. */
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
  float *l = realloc(r->rest, sizeof(float) * (size_t)cap);
  if (l) r->rest = l;
  int ok = g && b && v && l;
  if (r->nstate > 0) {
    double *s = realloc(r->state, sizeof(double) * (size_t)cap * (size_t)r->nstate);
    if (s) r->state = s;
    ok = ok && s;
  }
  PF_CHECK(ok, PF_ERR_MEMORY, "out of memory for %" PRId64 " bonds", cap);
  r->cap = cap;
  return 0;
}

int pf_bond_rows_widen(pf_bond_rows *r, int nstate) {
  if (nstate <= r->nstate) return 0;
  double *s = calloc((size_t)(r->cap > 0 ? r->cap : 1) * (size_t)nstate, sizeof(double));
  PF_CHECK(s, PF_ERR_MEMORY, "out of memory for the state of %" PRId64 " bonds", r->cap);
  int64_t nb = r->offset[r->n];
  for (int64_t k = 0; k < nb; k++)
    for (int c = 0; c < r->nstate; c++) s[k * nstate + c] = r->state[k * r->nstate + c];
  free(r->state);
  r->state = s;
  r->nstate = nstate;
  return 0;
}

int pf_bond_rows_append_state(pf_bond_rows *r, pf_int count, const pf_gid *gid,
                              const uint8_t *broken, const float *vfrac, const float *rest, int nstate,
                              const double *state) {
  PF_CHECK(nstate >= 0, PF_ERR_RUN, "%d reals of bond state", nstate);
  PF_CALL(pf_bond_rows_widen(r, nstate));
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
    r->rest[at + k] = rest ? rest[k] : 0.0f;
    for (int c = 0; c < r->nstate; c++)
      r->state[(at + k) * r->nstate + c] = state && c < nstate ? state[(int64_t)k * nstate + c] : 0.0;
  }
  r->offset[++r->n] = at + count;
  return 0;
}

int pf_bond_rows_append(pf_bond_rows *r, pf_int count, const pf_gid *gid, const uint8_t *broken,
                        const float *vfrac) {
  return pf_bond_rows_append_state(r, count, gid, broken, vfrac, NULL, 0, NULL);
}

int pf_bond_rows_free(pf_bond_rows *r) {
  PF_FREE(r->offset);
  PF_FREE(r->gid);
  PF_FREE(r->broken);
  PF_FREE(r->vfrac);
  PF_FREE(r->rest);
  PF_FREE(r->state);
  r->n = 0;
  r->nstate = 0;
  r->cap = 0;
  return 0;
}
