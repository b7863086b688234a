/* Ghost points and the halo exchange. Ghosts are exactly the neighbours of owned
 * points that another rank owns (taken from the bond rows, not from a geometric guess). They sit
 * after the owned points, grouped by owner rank and ascending in global id, so that each
 * owner's values arrive in one contiguous block; the owner sends them in the same order (an exchange
 * plan, core/exchange.c). */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
  int owner;
  pf_gid gid;
} ghost_key;

static int by_owner_gid(const void *a, const void *b) {
  const ghost_key *p = a, *q = b;
  if (p->owner != q->owner) return p->owner < q->owner ? -1 : 1;
  return (p->gid > q->gid) - (p->gid < q->gid);
}

/* The ghosts of this rank, sorted by (owner, gid); loc[] marks owned points and ghosts. */
static int find_ghosts(const pf_points *pts, const pf_bond_rows *rows, const int *owner_of,
                       pf_int *loc, ghost_key **out, pf_int *nout) {
  int rank = pf_comm_rank();
  pf_int n = 0, cap = 1024;
  ghost_key *g;
  PF_MALLOC(g, cap);
  for (int64_t e = 0; e < rows->offset[rows->n]; e++) {
    pf_gid q = rows->gid[e];
    PF_CHECK(q >= 0 && q < pts->n_global, PF_ERR_RUN, "bond to global id %" PF_GID_FMT " of %" PF_GID_FMT, q, pts->n_global);
    if (loc[q] != -1) continue;
    PF_CHECK(owner_of[q] != rank, PF_ERR_RUN, "point %" PF_GID_FMT " is owned here but not in the store", q);
    loc[q] = -2; /* seen */
    if (n == cap) {
      ghost_key *ng = realloc(g, sizeof *g * (size_t)(cap *= 2));
      if (!ng) free(g);
      PF_CHECK(ng, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " ghosts", cap);
      g = ng;
    }
    g[n++] = (ghost_key){owner_of[q], q};
  }
  qsort(g, (size_t)n, sizeof *g, by_owner_gid);
  *out = g;
  *nout = n;
  return 0;
}

/* Tell each owner which of its points we hold as ghosts; build the send lists from the
 * requests we receive. */
static int build_halo(pf_points *pts, const ghost_key *g, pf_int ng, const pf_int *loc) {
  int size = pf_comm_size();
  int *rc, *sc, *rd, *sd;
  PF_MALLOC(rc, size);
  PF_MALLOC(sc, size);
  PF_MALLOC(rd, size + 1);
  PF_MALLOC(sd, size + 1);
  for (pf_int k = 0; k < ng; k++) rc[g[k].owner]++;
  MPI_Alltoall(rc, 1, MPI_INT, sc, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) rd[r + 1] = rd[r] + rc[r], sd[r + 1] = sd[r] + sc[r];
  pf_gid *want, *give;
  PF_MALLOC(want, ng);
  PF_MALLOC(give, sd[size]);
  for (pf_int k = 0; k < ng; k++) want[k] = g[k].gid;
  MPI_Alltoallv(want, rc, rd, PF_GID_MPI, give, sc, sd, PF_GID_MPI, MPI_COMM_WORLD);
  pf_int *send_idx = malloc(sizeof(pf_int) * ((size_t)sd[size] + 1)), *scount = malloc(sizeof(pf_int) * (size_t)size),
         *rcount = malloc(sizeof(pf_int) * (size_t)size);
  int ierr = send_idx && scount && rcount ? 0 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (int r = 0; r < size && !ierr; r++) {
    scount[r] = sc[r], rcount[r] = rc[r];
    for (int k = 0; k < sc[r] && !ierr; k++) {
      pf_int i = loc[give[sd[r] + k]];
      if (!(i >= 0 && i < pts->n_owned))
        ierr = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__, "rank %d asks for point %" PF_GID_FMT ", not owned here",
                              r, give[sd[r] + k]);
      else send_idx[sd[r] + k] = i;
    }
  }
  if (!ierr) ierr = pf_exchange_create(scount, send_idx, rcount, &pts->halo);
  free(send_idx), free(scount), free(rcount);
  free(rc), free(sc), free(rd), free(sd), free(want), free(give);
  return ierr;
}

/* Ghost copies of the owners' arrays: X, vol, cell, m, body, u (and y), and ghosted fields. */
static int fill_ghosts(pf_points *pts) {
  PF_CALL(pf_points_exchange(pts, pts->X, 3));
  PF_CALL(pf_points_exchange(pts, pts->vol, 1));
  PF_CALL(pf_points_exchange(pts, pts->cell, 1));
  PF_CALL(pf_points_exchange(pts, pts->m, 1));
  double *body;
  PF_MALLOC(body, pts->n_total);
  for (pf_int i = 0; i < pts->n_owned; i++) body[i] = pts->body[i];
  int ierr = pf_points_exchange(pts, body, 1);
  for (pf_int i = pts->n_owned; i < pts->n_total; i++) pts->body[i] = (int32_t)body[i];
  free(body);
  if (ierr) return ierr;
  PF_CALL(pf_points_exchange_positions(pts));
  for (int k = 0; k < pts->nfields; k++)
    if (pts->fields[k].flags & PF_FIELD_GHOST) PF_CALL(pf_points_exchange(pts, pts->fields[k].data, pts->fields[k].ncomp));
  return 0;
}

int pf_points_add_ghosts(pf_points *pts, const pf_bond_rows *rows, const int *owner_of, pf_int *local) {
  pf_int *loc;
  PF_MALLOC(loc, pts->n_global);
  for (pf_gid q = 0; q < pts->n_global; q++) loc[q] = -1;
  for (pf_int i = 0; i < pts->n_owned; i++) loc[pts->gid[i]] = i;
  ghost_key *g = NULL;
  pf_int ng = 0;
  int ierr = find_ghosts(pts, rows, owner_of, loc, &g, &ng);
  if (!ierr) ierr = pf_points_resize(pts, pts->n_owned, ng);
  for (pf_int k = 0; k < ng && !ierr; k++) {
    pts->gid[pts->n_owned + k] = g[k].gid;
    loc[g[k].gid] = pts->n_owned + k;
  }
  for (int64_t e = 0; e < rows->offset[rows->n] && !ierr; e++) local[e] = loc[rows->gid[e]];
  pf_exchange_destroy(&pts->halo);
  if (!ierr) ierr = build_halo(pts, g, ng, loc);
  free(loc), free(g);
  if (!ierr) ierr = fill_ghosts(pts);
  return ierr;
}

int pf_points_exchange(pf_points *pts, double *data, int ncomp) {
  return pf_exchange_doubles(pts->halo, data, ncomp, pts->n_owned);
}

int pf_points_exchange_positions(pf_points *pts) {
  PF_CALL(pf_points_exchange(pts, pts->u, 3));
  for (size_t i = 3 * (size_t)pts->n_owned; i < 3 * (size_t)pts->n_total; i++) pts->y[i] = pts->X[i] + pts->u[i];
  return 0;
}
