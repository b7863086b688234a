/* The per-bond field registry of bond rows (docs/parallel.md, "Per-bond fields"): a quantity
 * kept per bond (a broken flag, a rest length, a material's per-bond reals) is registered once
 * by name, type and number of components, and the rows keep it as its own array; migration
 * (core/migrate.c), checkpoints (core/checkpoint.c) and the row operations (core/bond_rows.c)
 * carry every registered field without naming any. Fields are kept ascending by name, so that
 * ranks with the same names have them in the same order (pf_bond_rows_fields_agree makes the
 * names the same). */
#include "core/bond_rows_impl.h"

#include <string.h>

size_t pf_bond_type_size(pf_bond_type type) {
  return type == PF_BOND_UINT8 ? 1 : type == PF_BOND_FLOAT ? sizeof(float) : sizeof(double);
}

static void store(pf_bond_field *f, int64_t at, double v) {
  if (f->type == PF_BOND_UINT8) ((uint8_t *)f->data)[at] = (uint8_t)v;
  else if (f->type == PF_BOND_FLOAT) ((float *)f->data)[at] = (float)v;
  else ((double *)f->data)[at] = v;
}

void pf_bond_field_fill(pf_bond_field *f, int64_t first, int64_t count, int c0) {
  for (int64_t k = first; k < first + count; k++)
    for (int c = c0; c < f->ncomp; c++) store(f, k * f->ncomp + c, f->init);
}

static int field_index(const pf_bond_rows *r, const char *name) {
  for (int k = 0; k < r->nfields; k++)
    if (!strcmp(r->field[k].name, name)) return k;
  return -1;
}

const pf_bond_field *pf_bond_rows_field(const pf_bond_rows *r, const char *name) {
  int k = field_index(r, name);
  return k < 0 ? NULL : &r->field[k];
}

void *pf_bond_rows_field_data(const pf_bond_rows *r, const char *name, pf_bond_type type) {
  const pf_bond_field *f = pf_bond_rows_field(r, name);
  return f && f->type == type ? f->data : NULL;
}

/* f's data for room of cap bonds of ncomp components: the bonds' first components copied from
 * f, the others init. */
static int reshape(pf_bond_field *f, const pf_bond_rows *r, int ncomp) {
  const size_t sz = pf_bond_type_size(f->type);
  const int64_t nb = pf_bond_rows_nbonds(r);
  char *old = f->data, *data = calloc((size_t)(r->cap > 0 ? r->cap : 1) * (size_t)ncomp, sz);
  PF_CHECK(data, PF_ERR_MEMORY, "out of memory for the bond field '%s' of %" PRId64 " bonds", f->name, r->cap);
  for (int64_t k = 0; old && k < nb; k++)
    memcpy(data + (size_t)(k * ncomp) * sz, old + (size_t)(k * f->ncomp) * sz, (size_t)f->ncomp * sz);
  const int c0 = old ? f->ncomp : 0;
  free(old);
  f->data = data, f->ncomp = ncomp;
  pf_bond_field_fill(f, 0, nb, c0);
  return 0;
}

/* Checks of a registration of name with type, ncomp, init against the registered field f
 * (NULL: a new one). */
static int check_register(const pf_bond_rows *r, const pf_bond_field *f, const char *name, pf_bond_type type,
                          int ncomp, double init) {
  PF_CHECK(name && name[0] && strlen(name) < sizeof r->field[0].name, PF_ERR_RUN,
           "bond field name '%s': 1 to %zu characters", name ? name : "", sizeof r->field[0].name - 1);
  PF_CHECK(strcmp(name, "count") && strcmp(name, "gid"), PF_ERR_RUN,
           "'%s' is not a bond field name (the checkpoints keep the rows under it)", name);
  PF_CHECK(type == PF_BOND_UINT8 || type == PF_BOND_FLOAT || type == PF_BOND_DOUBLE, PF_ERR_RUN,
           "bond field '%s': unknown type %d", name, (int)type);
  PF_CHECK(ncomp >= 1, PF_ERR_RUN, "bond field '%s' with %d components", name, ncomp);
  PF_CHECK(type != PF_BOND_UINT8 || (init >= 0 && init <= 255 && init == (double)(uint8_t)init), PF_ERR_RUN,
           "bond field '%s': %g is not a uint8 value", name, init);
  if (!f) return 0;
  PF_CHECK(f->type == type && f->init == init, PF_ERR_RUN,
           "bond field '%s' registered again with another type or initial value", name);
  return 0;
}

int pf_bond_rows_field_register(pf_bond_rows *r, const char *name, pf_bond_type type, int ncomp, int flags,
                                double init) {
  int k = field_index(r, name);
  PF_CALL(check_register(r, k < 0 ? NULL : &r->field[k], name, type, ncomp, init));
  if (k >= 0) {
    r->field[k].flags |= flags;
    return ncomp > r->field[k].ncomp ? reshape(&r->field[k], r, ncomp) : 0;
  }
  PF_CHECK(r->nfields < PF_MAX_BOND_FIELDS, PF_ERR_RUN, "more than %d bond fields (registering '%s')",
           PF_MAX_BOND_FIELDS, name);
  pf_bond_field f = {.type = type, .ncomp = ncomp, .flags = flags, .init = init};
  snprintf(f.name, sizeof f.name, "%s", name);
  PF_CALL(reshape(&f, r, ncomp));
  for (k = r->nfields; k > 0 && strcmp(r->field[k - 1].name, name) > 0; k--) r->field[k] = r->field[k - 1];
  r->field[k] = f;
  r->nfields++;
  return 0;
}

int pf_bond_rows_field_copy(const pf_bond_rows *r, const char *name, pf_bond_type type, int64_t first,
                            int64_t count, int ncomp, void *out) {
  const pf_bond_field *f = pf_bond_rows_field(r, name);
  if (!f || count == 0) return 0;
  PF_CHECK(f->type == type, PF_ERR_RUN, "bond field '%s' is of another type", name);
  PF_CHECK(first >= 0 && count > 0 && first + count <= pf_bond_rows_nbonds(r) && ncomp >= 1, PF_ERR_RUN,
           "bonds [%" PRId64 ", %" PRId64 ") of field '%s' (%" PRId64 " bonds)", first, first + count, name,
           pf_bond_rows_nbonds(r));
  const size_t sz = pf_bond_type_size(type), nc = (size_t)(ncomp < f->ncomp ? ncomp : f->ncomp);
  const char *src = f->data;
  char *dst = out;
  if ((int)nc == ncomp && ncomp == f->ncomp) {
    memcpy(dst, src + (size_t)(first * ncomp) * sz, (size_t)(count * ncomp) * sz);
    return 0;
  }
  for (int64_t k = 0; k < count; k++)
    memcpy(dst + (size_t)(k * ncomp) * sz, src + (size_t)((first + k) * f->ncomp) * sz, nc * sz);
  return 0;
}

int pf_bond_rows_fields_copy(pf_bond_rows *dst, const pf_bond_rows *src) {
  for (int k = 0; k < src->nfields; k++) {
    const pf_bond_field *f = &src->field[k];
    PF_CALL(pf_bond_rows_field_register(dst, f->name, f->type, f->ncomp, f->flags, f->init));
  }
  return 0;
}

/* A field's registration as it travels between ranks. */
typedef struct {
  char name[32];
  int32_t type, ncomp, flags;
  double init;
} descriptor;

int pf_bond_rows_fields_agree(pf_bond_rows *r) {
  const int size = pf_comm_size(), n = r->nfields;
  int *count, *displ;
  descriptor mine[PF_MAX_BOND_FIELDS], *all;
  PF_MALLOC(count, size);
  PF_MALLOC(displ, size + 1);
  for (int k = 0; k < n; k++) {
    const pf_bond_field *f = &r->field[k];
    mine[k] = (descriptor){.type = f->type, .ncomp = f->ncomp, .flags = f->flags, .init = f->init};
    memcpy(mine[k].name, f->name, sizeof mine[k].name);
  }
  int bytes = n * (int)sizeof(descriptor);
  MPI_Allgather(&bytes, 1, MPI_INT, count, 1, MPI_INT, MPI_COMM_WORLD);
  for (int q = 0; q < size; q++) displ[q + 1] = displ[q] + count[q];
  PF_MALLOC(all, displ[size] / (int)sizeof(descriptor) + 1);
  MPI_Allgatherv(mine, bytes, MPI_BYTE, all, count, displ, MPI_BYTE, MPI_COMM_WORLD);
  int ierr = 0;
  for (int k = 0; k < displ[size] / (int)sizeof(descriptor) && !ierr; k++)
    ierr = pf_bond_rows_field_register(r, all[k].name, (pf_bond_type)all[k].type, all[k].ncomp, all[k].flags,
                                       all[k].init);
  free(count), free(displ), free(all);
  return ierr;
}
