/* Tables of global rows spread over the ranks (element state of FE bodies): gathering the
 * whole table on every rank, for checkpoints and re-partitioning. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

int pf_table_allgather(const pf_table *t, double *full) {
  int size = pf_comm_size();
  int *cnt = NULL, *off = NULL, *dcnt = NULL, *doff = NULL;
  PF_MALLOC(cnt, size);
  PF_MALLOC(off, size);
  PF_MALLOC(dcnt, size);
  PF_MALLOC(doff, size);
  int mine = (int)t->n, total = 0;
  MPI_Allgather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) {
    off[r] = total, total += cnt[r];
    dcnt[r] = cnt[r] * t->ncomp, doff[r] = off[r] * t->ncomp;
  }
  pf_gid *id = malloc(sizeof(pf_gid) * ((size_t)total + 1));
  double *data = malloc(sizeof(double) * ((size_t)total * t->ncomp + 1));
  int ierr = id && data ? 0 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  if (!ierr) {
    MPI_Allgatherv(t->id, mine, PF_GID_MPI, id, cnt, off, PF_GID_MPI, MPI_COMM_WORLD);
    MPI_Allgatherv(t->data, mine * t->ncomp, MPI_DOUBLE, data, dcnt, doff, MPI_DOUBLE, MPI_COMM_WORLD);
    memset(full, 0, sizeof(double) * (size_t)t->total * t->ncomp);
    for (int k = 0; k < total && !ierr; k++) {
      if (id[k] < 0 || id[k] >= t->total)
        ierr = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__, "table %s: row %" PF_GID_FMT " of %" PF_GID_FMT,
                              t->name, id[k], t->total);
      else memcpy(&full[(size_t)id[k] * t->ncomp], &data[(size_t)k * t->ncomp], sizeof(double) * t->ncomp);
    }
  }
  free(id), free(data), free(cnt), free(off), free(dcnt), free(doff);
  return ierr;
}
