/* The state digest printed at the end of a run: FNV-1a (64-bit) over the bytes of the final
 * displacement of every point, taken in global-id order, so two runs (any rank count, any
 * point order) can be compared bitwise. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

uint64_t pf_fnv1a(uint64_t h, const void *data, size_t len) {
  const unsigned char *p = data;
  for (size_t i = 0; i < len; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

int pf_state_digest(const pf_points *pts, uint64_t *digest) {
  int size = pf_comm_size(), rank = pf_comm_rank(), n = pts->n_owned, *cnt, *dsp;
  PF_MALLOC(cnt, size);
  PF_MALLOC(dsp, size + 1);
  MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  pf_gid *gid = NULL;
  double *u = NULL, *byid = NULL;
  if (rank == 0) {
    PF_CHECK(dsp[size] == pts->n_global, PF_ERR_RUN, "the ranks own %d points, expected %" PF_GID_FMT,
             dsp[size], pts->n_global);
    PF_MALLOC(gid, pts->n_global);
    PF_MALLOC(u, 3 * (size_t)pts->n_global);
    PF_MALLOC(byid, 3 * (size_t)pts->n_global);
  }
  MPI_Gatherv(pts->gid, n, PF_GID_MPI, gid, cnt, dsp, PF_GID_MPI, 0, MPI_COMM_WORLD);
  for (int r = 0; r <= size; r++) dsp[r] *= 3;
  for (int r = 0; r < size; r++) cnt[r] *= 3;
  MPI_Gatherv(pts->u, 3 * n, MPI_DOUBLE, u, cnt, dsp, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  uint64_t h = 0;
  if (rank == 0) {
    for (pf_gid k = 0; k < pts->n_global; k++) {
      PF_CHECK(gid[k] >= 0 && gid[k] < pts->n_global, PF_ERR_RUN,
               "global id %" PF_GID_FMT " outside [0, %" PF_GID_FMT ")", gid[k], pts->n_global);
      memcpy(&byid[3 * gid[k]], &u[3 * k], 3 * sizeof(double));
    }
    h = pf_fnv1a(PF_FNV1A_SEED, byid, 3 * (size_t)pts->n_global * sizeof(double));
  }
  MPI_Bcast(&h, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  *digest = h;
  free(cnt), free(dsp), free(gid), free(u), free(byid);
  return 0;
}
