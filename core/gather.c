/* The joined view for output: rank 0 holds a copy of every owned point in
 * global-id order (positions, displacement, velocity, force, body and the output fields), so
 * one Exodus file is the same whatever the number of ranks. Positions and bodies, which a
 * point keeps for good, are gathered once, when the view is created. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

static int create_joined(const pf_points *pts, pf_points **all) {
  PF_CALL(pf_points_create((pf_int)pts->n_global, all));
  for (int k = 0; k < pts->nfields; k++) {
    const pf_field *fl = &pts->fields[k];
    int idx;
    if (fl->flags & PF_FIELD_OUTPUT) PF_CALL(pf_points_field_register(*all, fl->name, fl->ncomp, fl->flags, &idx));
  }
  return 0;
}

/* Gather ncomp values per owned point into all_data (rank 0) by global id. */
static int gather_array(const pf_points *pts, const double *data, int ncomp, const pf_gid *gid,
                        const int *cnt, const int *dsp, double *tmp, double *all_data) {
  int size = pf_comm_size(), *c, *d;
  PF_MALLOC(c, size);
  PF_MALLOC(d, size);
  for (int r = 0; r < size; r++) c[r] = cnt[r] * ncomp, d[r] = dsp[r] * ncomp;
  MPI_Gatherv(data, pts->n_owned * ncomp, MPI_DOUBLE, tmp, c, d, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (all_data)
    for (pf_gid k = 0; k < pts->n_global; k++)
      memcpy(&all_data[(size_t)ncomp * gid[k]], &tmp[(size_t)ncomp * k], sizeof(double) * ncomp);
  free(c), free(d);
  return 0;
}

int pf_points_gather(const pf_points *pts, pf_points **all) {
  int rank = pf_comm_rank(), size = pf_comm_size(), n = pts->n_owned, *cnt, *dsp;
  int first = rank == 0 && !*all; /* create the view (ids 0..n-1 in order) and fill X, body */
  MPI_Bcast(&first, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank == 0 && first) PF_CALL(create_joined(pts, all));
  pf_points *a = rank == 0 ? *all : NULL;
  PF_MALLOC(cnt, size);
  PF_MALLOC(dsp, size + 1);
  MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  double *tmp = NULL, *body = NULL, *mybody = NULL;
  int maxc = 3;
  for (int k = 0; k < pts->nfields; k++)
    if ((pts->fields[k].flags & PF_FIELD_OUTPUT) && pts->fields[k].ncomp > maxc) maxc = pts->fields[k].ncomp;
  PF_MALLOC(mybody, n);
  for (pf_int i = 0; i < n; i++) mybody[i] = pts->body[i];
  if (a) {
    PF_MALLOC(tmp, (size_t)maxc * (size_t)pts->n_global);
    PF_MALLOC(body, pts->n_global);
  }
  pf_gid *gid = NULL; /* gathered ids, in rank order */
  if (a) PF_MALLOC(gid, pts->n_global);
  MPI_Gatherv(pts->gid, n, PF_GID_MPI, gid, cnt, dsp, PF_GID_MPI, 0, MPI_COMM_WORLD);
  if (first) {
    PF_CALL(gather_array(pts, pts->X, 3, gid, cnt, dsp, tmp, a ? a->X : NULL));
    PF_CALL(gather_array(pts, mybody, 1, gid, cnt, dsp, tmp, body));
    if (a)
      for (pf_gid k = 0; k < pts->n_global; k++) a->body[k] = (int32_t)body[k];
  }
  PF_CALL(gather_array(pts, pts->u, 3, gid, cnt, dsp, tmp, a ? a->u : NULL));
  PF_CALL(gather_array(pts, pts->v, 3, gid, cnt, dsp, tmp, a ? a->v : NULL));
  PF_CALL(gather_array(pts, pts->f, 3, gid, cnt, dsp, tmp, a ? a->f : NULL));
  for (int k = 0; k < pts->nfields; k++) {
    const pf_field *fl = &pts->fields[k];
    if (fl->flags & PF_FIELD_OUTPUT)
      PF_CALL(gather_array(pts, fl->data, fl->ncomp, gid, cnt, dsp, tmp, a ? pf_points_field_get(a, fl->name) : NULL));
  }
  free(cnt), free(dsp), free(tmp), free(body), free(mybody), free(gid);
  return 0;
}
