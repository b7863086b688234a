/* The per-point records of the batched bond loops (pd/bond_batch.h). */
#include "pd/bond_batch.h"

#include <stdlib.h>

int pf_batch_records_fill(pf_batch_records *r, const pf_points *pts, const double *aux) {
  const size_t n = (size_t)pts->n_total;
  if (!r->rec || n > r->cap) {
    free(r->rec);
    r->cap = n + n / 8 + 16;
    r->rec = aligned_alloc(64, r->cap * PF_REC * sizeof(double));
    PF_CHECK(r->rec, PF_ERR_MEMORY, "out of memory for the bond-loop records of %zu points", n);
  }
#pragma omp parallel for schedule(static)
  for (size_t j = 0; j < n; j++) {
    double *q = r->rec + PF_REC * j;
    for (int a = 0; a < 3; a++) q[REC_X + a] = pts->X[3 * j + a], q[REC_Y + a] = pts->y[3 * j + a];
    q[REC_V] = pts->vol[j];
    q[REC_AUX] = aux ? aux[j] : 0.0;
  }
  return 0;
}

void pf_batch_records_free(pf_batch_records *r) {
  free(r->rec);
  r->rec = NULL, r->cap = 0;
}
