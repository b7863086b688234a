/* Exchange plans: which local items each rank sends to which other rank, and where the items it
 * receives go. One plan type serves the point store's halo (ghosts are the off-rank neighbours in
 * the bond rows, core/halo.c) and the contact's view (entities near another rank's box,
 * contact/search.c): items are packed per neighbour in send order, and each neighbour's items
 * arrive as one contiguous block, the blocks in ascending rank order, after a given first slot.
 * Non-blocking point-to-point messages (MPI_Irecv straight into place, MPI_Isend of a packed
 * buffer, MPI_Waitall): only copies, so the received values are bitwise the owner's. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

struct pf_exchange {
  int nnb;          /* ranks we exchange with */
  int *rank;        /* [nnb] ascending */
  pf_int *send_off; /* [nnb + 1] into send_idx */
  pf_int *send_idx; /* the local items to send, per neighbour in its receive order */
  pf_int *recv_off; /* [nnb + 1] received blocks, relative to the first slot */
  double *buf;      /* packing buffer */
  size_t buf_cap;
  MPI_Request *req; /* [2 nnb] */
};

int pf_exchange_create(const pf_int *send_count, const pf_int *send_idx, const pf_int *recv_count, pf_exchange **out) {
  *out = NULL;
  const int size = pf_comm_size();
  pf_exchange *x;
  PF_MALLOC(x, 1);
  pf_int nsend = 0;
  for (int r = 0; r < size; r++) nsend += send_count[r];
  int ierr = 0;
  if (!(x->rank = malloc(sizeof(int) * ((size_t)size + 1))) || !(x->send_off = calloc((size_t)size + 1, sizeof(pf_int))) ||
      !(x->recv_off = calloc((size_t)size + 1, sizeof(pf_int))) || !(x->send_idx = malloc(sizeof(pf_int) * ((size_t)nsend + 1))) ||
      !(x->req = malloc(sizeof(MPI_Request) * (2 * (size_t)size + 1))))
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory for an exchange plan");
  for (int r = 0, at = 0; r < size && !ierr; r++) {
    if (send_count[r] || recv_count[r]) {
      x->rank[x->nnb] = r;
      x->send_off[x->nnb + 1] = x->send_off[x->nnb] + send_count[r];
      x->recv_off[x->nnb + 1] = x->recv_off[x->nnb] + recv_count[r];
      x->nnb++;
    }
    memcpy(&x->send_idx[at], &send_idx[at], sizeof(pf_int) * (size_t)send_count[r]);
    at += send_count[r];
  }
  if (ierr) {
    pf_exchange_destroy(&x);
    return ierr;
  }
  *out = x;
  return 0;
}

pf_int pf_exchange_nrecv(const pf_exchange *x) { return x ? x->recv_off[x->nnb] : 0; }

int pf_exchange_doubles(pf_exchange *x, double *data, int ncomp, pf_int first) {
  if (!x || x->nnb == 0) return 0;
  size_t need = (size_t)ncomp * (size_t)x->send_off[x->nnb];
  if (need > x->buf_cap) {
    free(x->buf);
    x->buf_cap = 0;
    PF_MALLOC(x->buf, need);
    x->buf_cap = need;
  }
  int nreq = 0;
  for (int q = 0; q < x->nnb; q++) {
    int cnt = ncomp * (x->recv_off[q + 1] - x->recv_off[q]);
    if (cnt) MPI_Irecv(data + (size_t)ncomp * (first + x->recv_off[q]), cnt, MPI_DOUBLE, x->rank[q], 17,
                       MPI_COMM_WORLD, &x->req[nreq++]);
  }
  for (int q = 0; q < x->nnb; q++) {
    double *b = x->buf + (size_t)ncomp * x->send_off[q];
    for (pf_int k = x->send_off[q]; k < x->send_off[q + 1]; k++)
      memcpy(b + (size_t)ncomp * (k - x->send_off[q]), data + (size_t)ncomp * x->send_idx[k], sizeof(double) * ncomp);
    int cnt = ncomp * (x->send_off[q + 1] - x->send_off[q]);
    if (cnt) MPI_Isend(b, cnt, MPI_DOUBLE, x->rank[q], 17, MPI_COMM_WORLD, &x->req[nreq++]);
  }
  int st = MPI_Waitall(nreq, x->req, MPI_STATUSES_IGNORE);
  PF_CHECK(st == MPI_SUCCESS, PF_ERR_LIB, "exchange: MPI_Waitall returned %d", st);
  return 0;
}

void pf_exchange_destroy(pf_exchange **x) {
  if (!*x) return;
  free((*x)->rank), free((*x)->send_off), free((*x)->send_idx), free((*x)->recv_off);
  free((*x)->buf), free((*x)->req);
  PF_FREE(*x);
}
