/* The point store (docs/architecture.md §2): one structure of arrays for every kinematic point,
 * with per-module fields registered by name (as PETSc's DMSwarm and LAMMPS' atom_vec_peri do), so
 * that halo exchange, restart and output are written once. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

int pf_points_create(pf_int n, pf_points **pts) {
  PF_CHECK(n >= 0, PF_ERR_INPUT, "negative number of points %" PF_INT_FMT, n);
  pf_points *p;
  PF_MALLOC(p, 1);
  p->n_owned = p->n_total = n;
  p->n_global = n;
  PF_MALLOC(p->X, 3 * (size_t)n);
  PF_MALLOC(p->u, 3 * (size_t)n);
  PF_MALLOC(p->v, 3 * (size_t)n);
  PF_MALLOC(p->f, 3 * (size_t)n);
  PF_MALLOC(p->y, 3 * (size_t)n);
  PF_MALLOC(p->m, n);
  PF_MALLOC(p->vol, n);
  PF_MALLOC(p->cell, n);
  PF_MALLOC(p->gid, n);
  PF_MALLOC(p->body, n);
  for (pf_int i = 0; i < n; i++) p->gid[i] = i;
  *pts = p;
  return 0;
}

int pf_points_destroy(pf_points **pts) {
  pf_points *p = *pts;
  if (!p) return 0;
  free(p->X);
  free(p->u);
  free(p->v);
  free(p->f);
  free(p->y);
  free(p->m);
  free(p->vol);
  free(p->cell);
  free(p->gid);
  free(p->body);
  for (int i = 0; i < p->nfields; i++) free(p->fields[i].data);
  pf_exchange_destroy(&p->halo);
  PF_FREE(*pts);
  return 0;
}

int pf_points_field_register(pf_points *pts, const char *name, int ncomp, int flags, int *idx) {
  for (int i = 0; i < pts->nfields; i++) {
    if (strcmp(pts->fields[i].name, name)) continue;
    PF_CHECK(pts->fields[i].ncomp == ncomp, PF_ERR_RUN,
             "field '%s' registered with %d components and again with %d", name,
             pts->fields[i].ncomp, ncomp);
    pts->fields[i].flags |= flags;
    *idx = i;
    return 0;
  }
  PF_CHECK(pts->nfields < PF_MAX_FIELDS, PF_ERR_RUN, "more than %d point fields", PF_MAX_FIELDS);
  PF_CHECK(strlen(name) < sizeof pts->fields[0].name, PF_ERR_RUN, "field name '%s' too long",
           name);
  pf_field *fl = &pts->fields[pts->nfields];
  strcpy(fl->name, name);
  fl->ncomp = ncomp;
  fl->flags = flags;
  PF_MALLOC(fl->data, (size_t)pts->n_total * ncomp);
  *idx = pts->nfields++;
  return 0;
}

double *pf_points_field_get(const pf_points *pts, const char *name) {
  for (int i = 0; i < pts->nfields; i++)
    if (!strcmp(pts->fields[i].name, name)) return pts->fields[i].data;
  return NULL;
}

/* Reallocate *a from `keep` to `total` entries of `width` bytes, zeroing the new ones. */
static int resize_array(void **a, size_t width, pf_int keep, pf_int total) {
  char *p = realloc(*a, width * (size_t)(total > 0 ? total : 1));
  PF_CHECK(p, PF_ERR_MEMORY, "out of memory resizing a point array to %" PF_INT_FMT " entries", total);
  if (total > keep) memset(p + width * (size_t)keep, 0, width * (size_t)(total - keep));
  *a = p;
  return 0;
}

int pf_points_resize(pf_points *pts, pf_int n_owned, pf_int n_ghost) {
  PF_CHECK(n_owned >= 0 && n_ghost >= 0, PF_ERR_RUN, "negative point count");
  pf_int keep = n_owned < pts->n_owned ? n_owned : pts->n_owned, total = n_owned + n_ghost;
  void **vec[] = {(void **)&pts->X, (void **)&pts->u, (void **)&pts->v, (void **)&pts->f, (void **)&pts->y};
  for (int k = 0; k < 5; k++) PF_CALL(resize_array(vec[k], 3 * sizeof(double), keep, total));
  PF_CALL(resize_array((void **)&pts->m, sizeof(double), keep, total));
  PF_CALL(resize_array((void **)&pts->vol, sizeof(double), keep, total));
  PF_CALL(resize_array((void **)&pts->cell, sizeof(double), keep, total));
  PF_CALL(resize_array((void **)&pts->gid, sizeof(pf_gid), keep, total));
  PF_CALL(resize_array((void **)&pts->body, sizeof(int32_t), keep, total));
  for (int i = 0; i < pts->nfields; i++)
    PF_CALL(resize_array((void **)&pts->fields[i].data, pts->fields[i].ncomp * sizeof(double), keep, total));
  pts->n_owned = n_owned;
  pts->n_total = total;
  return 0;
}

/* Gather array a (count entries of width bytes per point) through perm. */
static int permute_array(void *a, size_t width, pf_int n, const pf_int *perm) {
  char *src = a, *tmp;
  PF_MALLOC(tmp, width * (size_t)n);
  for (pf_int k = 0; k < n; k++) memcpy(tmp + width * k, src + width * perm[k], width);
  memcpy(src, tmp, width * (size_t)n);
  free(tmp);
  return 0;
}

int pf_points_permute(pf_points *pts, const pf_int *perm) {
  pf_int n = pts->n_owned;
  PF_CALL(permute_array(pts->X, 3 * sizeof(double), n, perm));
  PF_CALL(permute_array(pts->u, 3 * sizeof(double), n, perm));
  PF_CALL(permute_array(pts->v, 3 * sizeof(double), n, perm));
  PF_CALL(permute_array(pts->f, 3 * sizeof(double), n, perm));
  PF_CALL(permute_array(pts->y, 3 * sizeof(double), n, perm));
  PF_CALL(permute_array(pts->m, sizeof(double), n, perm));
  PF_CALL(permute_array(pts->vol, sizeof(double), n, perm));
  PF_CALL(permute_array(pts->cell, sizeof(double), n, perm));
  PF_CALL(permute_array(pts->gid, sizeof(pf_gid), n, perm));
  PF_CALL(permute_array(pts->body, sizeof(int32_t), n, perm));
  for (int i = 0; i < pts->nfields; i++)
    PF_CALL(permute_array(pts->fields[i].data, pts->fields[i].ncomp * sizeof(double), n, perm));
  return 0;
}
