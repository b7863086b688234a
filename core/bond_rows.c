/* Bond lists in transit: rows of neighbour global ids with the registered
 * per-bond fields (core/bond_fields.c), the form in which families move between ranks when
 * points are (re)partitioned and in which checkpoints store them. Appending a row sets every
 * field: from the values given, from another rows' bonds, or to the field's init. */
#include "core/bond_rows_impl.h"

#include <stdlib.h>
#include <string.h>

int pf_bond_rows_init(pf_bond_rows *r) {
  memset(r, 0, sizeof *r);
  PF_MALLOC(r->offset, 1);
  PF_MALLOC(r->gid, 1); /* never NULL: an HDF5 transfer of no bonds still names a buffer */
  return 0;
}

int pf_bond_rows_free(pf_bond_rows *r) {
  PF_FREE(r->offset);
  PF_FREE(r->gid);
  for (int k = 0; k < r->nfields; k++) PF_FREE(r->field[k].data);
  memset(r, 0, sizeof *r);
  return 0;
}

void pf_bond_rows_clear(pf_bond_rows *r) {
  r->n = 0;
  if (r->offset) r->offset[0] = 0;
}

/* Room for exactly cap bonds in gid and every field (when there is less). */
static int grow_exact(pf_bond_rows *r, int64_t cap) {
  if (cap <= r->cap) return 0;
  pf_gid *g = realloc(r->gid, sizeof(pf_gid) * (size_t)cap);
  PF_CHECK(g, PF_ERR_MEMORY, "out of memory for %" PRId64 " bonds", cap);
  r->gid = g;
  pf_memory_huge_pages(g, sizeof(pf_gid) * (size_t)cap);
  for (int k = 0; k < r->nfields; k++) {
    pf_bond_field *f = &r->field[k];
    const size_t bytes = pf_bond_type_size(f->type) * (size_t)f->ncomp * (size_t)cap;
    void *d = realloc(f->data, bytes);
    PF_CHECK(d, PF_ERR_MEMORY, "out of memory for the bond field '%s' of %" PRId64 " bonds", f->name, cap);
    f->data = d;
    pf_memory_huge_pages(d, bytes);
  }
  r->cap = cap;
  return 0;
}

/* Room for need bonds, with room to spare for the next rows. */
static int grow(pf_bond_rows *r, int64_t need) {
  return need <= r->cap ? 0 : grow_exact(r, need + need / 2 + 1024);
}

int pf_bond_rows_reserve(pf_bond_rows *r, pf_int nrows, int64_t nbonds) {
  if (nrows >= r->row_cap) {
    int64_t *o = realloc(r->offset, sizeof(int64_t) * ((size_t)nrows + 2));
    PF_CHECK(o, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " bond rows", nrows);
    r->offset = o;
    r->row_cap = nrows + 1;
  }
  return grow_exact(r, r->offset[r->n] + nbonds);
}

int pf_bond_rows_release(pf_bond_rows *r) {
  pf_bond_rows_clear(r);
  PF_FREE(r->gid);
  r->cap = 0;
  PF_MALLOC(r->gid, 1); /* never NULL (pf_bond_rows_init) */
  for (int k = 0; k < r->nfields; k++) {
    pf_bond_field *f = &r->field[k];
    free(f->data);
    f->data = calloc((size_t)f->ncomp, pf_bond_type_size(f->type)); /* room for one bond, as registered */
    PF_CHECK(f->data, PF_ERR_MEMORY, "out of memory for the bond field '%s'", f->name);
  }
  return 0;
}

int pf_bond_rows_append_unset(pf_bond_rows *r, pf_int count, int64_t *at) {
  PF_CHECK(count >= 0, PF_ERR_RUN, "a bond row of %" PF_INT_FMT " bonds", count);
  if (r->n + 1 >= r->row_cap) {
    pf_int cap = r->row_cap + r->row_cap / 2 + 1024;
    int64_t *o = realloc(r->offset, sizeof(int64_t) * ((size_t)cap + 1));
    PF_CHECK(o, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " bond rows", cap);
    r->offset = o;
    r->row_cap = cap;
  }
  *at = r->offset[r->n];
  PF_CALL(grow(r, *at + count));
  r->offset[r->n + 1] = *at + count;
  r->n++;
  return 0;
}

/* A new row of count bonds with neighbours gid (NULL: zeros); its first bond is *at. The
 * fields' values are for the caller to set. */
static int add_row(pf_bond_rows *r, pf_int count, const pf_gid *gid, int64_t *at) {
  PF_CALL(pf_bond_rows_append_unset(r, count, at));
  if (gid && count > 0) memcpy(r->gid + *at, gid, sizeof(pf_gid) * (size_t)count);
  else if (count > 0) memset(r->gid + *at, 0, sizeof(pf_gid) * (size_t)count);
  return 0;
}

/* Bonds [at, at + count) of f from data [count * nc] of its type; components beyond nc init. */
static void put_values(pf_bond_field *f, int64_t at, int64_t count, const void *data, int nc) {
  const size_t sz = pf_bond_type_size(f->type);
  char *dst = (char *)f->data + (size_t)(at * f->ncomp) * sz;
  if (nc == f->ncomp) {
    memcpy(dst, data, (size_t)(count * nc) * sz);
    return;
  }
  for (int64_t k = 0; k < count; k++)
    memcpy(dst + (size_t)(k * f->ncomp) * sz, (const char *)data + (size_t)(k * nc) * sz, (size_t)nc * sz);
  pf_bond_field_fill(f, at, count, nc);
}

int pf_bond_rows_append(pf_bond_rows *r, pf_int count, const pf_gid *gid, int nvalues,
                        const pf_bond_values *values) {
  for (int v = 0; v < nvalues; v++) {
    const pf_bond_field *f = pf_bond_rows_field(r, values[v].name);
    PF_CHECK(f, PF_ERR_RUN, "no bond field '%s' is registered", values[v].name);
    PF_CHECK(values[v].ncomp >= 0 && values[v].ncomp <= f->ncomp, PF_ERR_RUN,
             "%d components for the bond field '%s' of %d", values[v].ncomp, f->name, f->ncomp);
  }
  int64_t at;
  PF_CALL(add_row(r, count, gid, &at));
  for (int k = 0; k < r->nfields; k++) {
    pf_bond_field *f = &r->field[k];
    const pf_bond_values *v = NULL;
    for (int q = 0; q < nvalues && !v; q++)
      if (!strcmp(values[q].name, f->name)) v = &values[q];
    if (v && v->data && count > 0) put_values(f, at, count, v->data, v->ncomp);
    else pf_bond_field_fill(f, at, count, 0);
  }
  return 0;
}

/* Bond k of f from bond q of s (the same type; q < 0: init). */
static void copy_bond(pf_bond_field *f, int64_t k, const pf_bond_field *s, int64_t q) {
  const size_t sz = pf_bond_type_size(f->type);
  const int nc = q < 0 ? 0 : f->ncomp < s->ncomp ? f->ncomp : s->ncomp;
  if (nc) memcpy((char *)f->data + (size_t)(k * f->ncomp) * sz, (const char *)s->data + (size_t)(q * s->ncomp) * sz,
                 (size_t)nc * sz);
  if (nc < f->ncomp) pf_bond_field_fill(f, k, 1, nc);
}

/* The field of src that f takes its values from, or NULL (then f takes init). */
static int source_field(const pf_bond_field *f, const pf_bond_rows *src, const pf_bond_field **s) {
  *s = pf_bond_rows_field(src, f->name);
  PF_CHECK(!*s || (*s)->type == f->type, PF_ERR_RUN, "bond field '%s' of two types", f->name);
  return 0;
}

int pf_bond_rows_append_from(pf_bond_rows *r, pf_int count, const pf_gid *gid, const pf_bond_rows *src,
                             const int64_t *from) {
  for (pf_int k = 0; k < count; k++)
    PF_CHECK(from[k] < pf_bond_rows_nbonds(src), PF_ERR_RUN, "bond %" PRId64 " of %" PRId64, from[k],
             pf_bond_rows_nbonds(src));
  int64_t at;
  PF_CALL(add_row(r, count, gid, &at));
  for (int f = 0; f < r->nfields; f++) {
    const pf_bond_field *s;
    PF_CALL(source_field(&r->field[f], src, &s));
    for (pf_int k = 0; k < count; k++) copy_bond(&r->field[f], at + k, s, s ? from[k] : -1);
  }
  return 0;
}

int pf_bond_rows_append_row(pf_bond_rows *r, const pf_bond_rows *src, pf_int row) {
  PF_CHECK(row >= 0 && row < src->n, PF_ERR_RUN, "bond row %" PF_INT_FMT " of %" PF_INT_FMT, row, src->n);
  const int64_t o = src->offset[row];
  const pf_int count = (pf_int)(src->offset[row + 1] - o);
  int64_t at;
  PF_CALL(add_row(r, count, &src->gid[o], &at));
  for (int f = 0; f < r->nfields; f++) {
    const pf_bond_field *s;
    PF_CALL(source_field(&r->field[f], src, &s));
    if (!s) pf_bond_field_fill(&r->field[f], at, count, 0);
    else if (count > 0 && s->ncomp == r->field[f].ncomp)
      put_values(&r->field[f], at, count, (const char *)s->data + (size_t)(o * s->ncomp) * pf_bond_type_size(s->type),
                 s->ncomp);
    else
      for (pf_int k = 0; k < count; k++) copy_bond(&r->field[f], at + k, s, o + k);
  }
  return 0;
}
