/* Moving owned points between ranks: every array and registered field of a point
 * and its bond row (with the per-bond state: broken flag, partial-volume fraction, rest length,
 * the materials' per-bond reals) travel together in one packed record, so that a (re)partition
 * keeps the complete state. Records are exchanged with one MPI_Alltoallv. */
#include "core/core.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

enum { NFIXED = 15 }; /* X, u, v, f (3 each), m, vol, cell */

static int field_width(const pf_points *pts) {
  int w = 0;
  for (int k = 0; k < pts->nfields; k++) w += pts->fields[k].ncomp;
  return w;
}

/* Bytes of one bond in a record: gid, broken, vfrac, rest length, nstate reals of state. */
static size_t bond_size(int nstate) { return sizeof(pf_gid) + 1 + 2 * sizeof(float) + sizeof(double) * (size_t)nstate; }

static size_t record_size(int nreal, int nstate, int64_t nbonds) {
  return sizeof(pf_gid) + 2 * sizeof(int32_t) + sizeof(double) * (size_t)nreal + (size_t)nbonds * bond_size(nstate);
}

static char *put(char *p, const void *src, size_t n) {
  if (n) memcpy(p, src, n); /* src may be NULL when n is 0 (a body without bonds) */
  return p + n;
}

static char *pack(const pf_points *pts, const pf_bond_rows *rows, pf_int i, char *p) {
  int32_t nb = (int32_t)(rows->offset[i + 1] - rows->offset[i]);
  int64_t o = rows->offset[i];
  p = put(p, &pts->gid[i], sizeof(pf_gid));
  p = put(p, &pts->body[i], sizeof(int32_t));
  p = put(p, &nb, sizeof(int32_t));
  const double *vec[4] = {pts->X, pts->u, pts->v, pts->f}, *scal[3] = {pts->m, pts->vol, pts->cell};
  for (int k = 0; k < 4; k++) p = put(p, &vec[k][3 * i], 3 * sizeof(double));
  for (int k = 0; k < 3; k++) p = put(p, &scal[k][i], sizeof(double));
  for (int k = 0; k < pts->nfields; k++) {
    const pf_field *fl = &pts->fields[k];
    p = put(p, &fl->data[(size_t)i * fl->ncomp], sizeof(double) * fl->ncomp);
  }
  p = put(p, &rows->gid[o], sizeof(pf_gid) * (size_t)nb);
  p = put(p, &rows->broken[o], (size_t)nb);
  p = put(p, &rows->vfrac[o], sizeof(float) * (size_t)nb);
  p = put(p, &rows->rest[o], sizeof(float) * (size_t)nb);
  return rows->nstate ? put(p, &rows->state[o * rows->nstate], sizeof(double) * (size_t)nb * rows->nstate) : p;
}

/* Aligned copies of one record's parts, reused from record to record. */
typedef struct {
  double *real;
  pf_gid *gid;
  float *vfrac, *rest;
  double *state;
  int32_t cap; /* bonds */
} scratch;

static int scratch_fit(scratch *sc, int32_t nb, int nstate) {
  if (nb <= sc->cap) return 0;
  free(sc->gid), free(sc->vfrac), free(sc->rest), free(sc->state);
  sc->cap = 0;
  PF_MALLOC(sc->gid, nb);
  PF_MALLOC(sc->vfrac, nb);
  PF_MALLOC(sc->rest, nb);
  PF_MALLOC(sc->state, (size_t)nb * nstate);
  sc->cap = nb;
  return 0;
}

/* Unpack one record into point k of pts and append its row; returns the next record. */
static const char *unpack(const char *p, pf_points *pts, pf_bond_rows *rows, pf_int k, int nreal,
                          int nstate, scratch *sc, int *ierr) {
  int32_t nb;
  memcpy(&pts->gid[k], p, sizeof(pf_gid)), p += sizeof(pf_gid);
  memcpy(&pts->body[k], p, sizeof(int32_t)), p += sizeof(int32_t);
  memcpy(&nb, p, sizeof(int32_t)), p += sizeof(int32_t);
  memcpy(sc->real, p, sizeof(double) * (size_t)nreal), p += sizeof(double) * (size_t)nreal;
  const double *r = sc->real;
  for (int a = 0; a < 3; a++) {
    pts->X[3 * k + a] = r[a], pts->u[3 * k + a] = r[3 + a];
    pts->v[3 * k + a] = r[6 + a], pts->f[3 * k + a] = r[9 + a];
    pts->y[3 * k + a] = r[a] + r[3 + a];
  }
  pts->m[k] = r[12], pts->vol[k] = r[13], pts->cell[k] = r[14];
  r += NFIXED;
  for (int f = 0; f < pts->nfields; f++) {
    pf_field *fl = &pts->fields[f];
    memcpy(&fl->data[(size_t)k * fl->ncomp], r, sizeof(double) * fl->ncomp);
    r += fl->ncomp;
  }
  *ierr = scratch_fit(sc, nb, nstate);
  if (*ierr) return p;
  const uint8_t *broken = (const uint8_t *)(p + sizeof(pf_gid) * (size_t)nb);
  if (nb > 0) { /* the scratch is not allocated before the first bond */
    memcpy(sc->gid, p, sizeof(pf_gid) * (size_t)nb);
    memcpy(sc->vfrac, p + (sizeof(pf_gid) + 1) * (size_t)nb, sizeof(float) * (size_t)nb);
    memcpy(sc->rest, p + (sizeof(pf_gid) + 1 + sizeof(float)) * (size_t)nb, sizeof(float) * (size_t)nb);
    if (nstate)
      memcpy(sc->state, p + (sizeof(pf_gid) + 1 + 2 * sizeof(float)) * (size_t)nb,
             sizeof(double) * (size_t)nb * nstate);
  }
  *ierr = pf_bond_rows_append_state(rows, nb, sc->gid, broken, sc->vfrac, sc->rest, nstate, sc->state);
  return p + bond_size(nstate) * (size_t)nb;
}

/* Pack the owned points by destination rank: buffer, byte counts and displacements. */
static int pack_all(const pf_points *pts, const pf_bond_rows *rows, const int *dest, int nreal,
                    char **buf, int *count, int *displ) {
  int size = pf_comm_size();
  size_t *bytes, total = 0;
  PF_MALLOC(bytes, size);
  for (pf_int i = 0; i < pts->n_owned; i++) {
    PF_CHECK(dest[i] >= 0 && dest[i] < size, PF_ERR_RUN, "point %" PF_GID_FMT " sent to rank %d of %d",
             pts->gid[i], dest[i], size);
    bytes[dest[i]] += record_size(nreal, rows->nstate, rows->offset[i + 1] - rows->offset[i]);
  }
  size_t *at;
  PF_MALLOC(at, size);
  for (int r = 0; r < size; r++) {
    PF_CHECK(bytes[r] < INT_MAX && total + bytes[r] < INT_MAX, PF_ERR_RUN,
             "migration of more than 2 GB from one rank; use more ranks");
    count[r] = (int)bytes[r], displ[r] = (int)total, at[r] = total;
    total += bytes[r];
  }
  PF_MALLOC(*buf, total);
  for (pf_int i = 0; i < pts->n_owned; i++) at[dest[i]] = (size_t)(pack(pts, rows, i, *buf + at[dest[i]]) - *buf);
  free(bytes), free(at);
  return 0;
}

/* Count the records in a received buffer. */
static pf_int count_records(const char *p, size_t len, int nreal, int nstate) {
  pf_int n = 0;
  for (size_t at = 0; at < len; n++) {
    int32_t nb;
    memcpy(&nb, p + at + sizeof(pf_gid) + sizeof(int32_t), sizeof nb);
    at += record_size(nreal, nstate, nb);
  }
  return n;
}

static int order_by_body(const pf_points *pts, int nbodies, pf_int *body_start, pf_int *perm) {
  memset(body_start, 0, sizeof(pf_int) * (size_t)(nbodies + 1));
  for (pf_int i = 0; i < pts->n_owned; i++) {
    PF_CHECK(pts->body[i] >= 0 && pts->body[i] < nbodies, PF_ERR_RUN, "point with body %d", pts->body[i]);
    body_start[pts->body[i] + 1]++;
  }
  for (int b = 0; b < nbodies; b++) body_start[b + 1] += body_start[b];
  pf_int *idx, *sub;
  double *X;
  PF_MALLOC(idx, pts->n_owned);
  PF_MALLOC(sub, pts->n_owned);
  PF_MALLOC(X, 3 * (size_t)pts->n_owned);
  pf_int *fill;
  PF_MALLOC(fill, nbodies);
  for (pf_int i = 0; i < pts->n_owned; i++) idx[body_start[pts->body[i]] + fill[pts->body[i]]++] = i;
  for (int b = 0; b < nbodies; b++) {
    pf_int first = body_start[b], n = body_start[b + 1] - first;
    for (pf_int k = 0; k < n; k++) memcpy(&X[3 * k], &pts->X[3 * idx[first + k]], 3 * sizeof(double));
    PF_CALL(pf_morton_order(n, X, sub));
    for (pf_int k = 0; k < n; k++) perm[first + k] = idx[first + sub[k]];
  }
  free(idx), free(sub), free(X), free(fill);
  return 0;
}

static int permute_rows(pf_bond_rows *rows, const pf_int *perm) {
  pf_bond_rows out;
  PF_CALL(pf_bond_rows_init(&out));
  PF_CALL(pf_bond_rows_widen(&out, rows->nstate));
  for (pf_int k = 0; k < rows->n; k++) {
    int64_t o = rows->offset[perm[k]];
    PF_CALL(pf_bond_rows_append_state(&out, (pf_int)(rows->offset[perm[k] + 1] - o), &rows->gid[o],
                                      &rows->broken[o], &rows->vfrac[o], &rows->rest[o], rows->nstate,
                                      rows->state ? &rows->state[o * rows->nstate] : NULL));
  }
  pf_bond_rows_free(rows);
  *rows = out;
  return 0;
}

int pf_points_migrate(pf_points *pts, pf_bond_rows *rows, const int *dest, int nbodies, pf_int *body_start) {
  int size = pf_comm_size(), nreal = NFIXED + field_width(pts), nstate = rows->nstate;
  /* every record carries the same number of state reals per bond: the widest rank's */
  MPI_Allreduce(MPI_IN_PLACE, &nstate, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  PF_CALL(pf_bond_rows_widen(rows, nstate));
  int *scount, *sdispl, *rcount, *rdispl;
  PF_MALLOC(scount, size);
  PF_MALLOC(sdispl, size);
  PF_MALLOC(rcount, size);
  PF_MALLOC(rdispl, size + 1);
  char *sbuf = NULL, *rbuf = NULL;
  PF_CALL(pack_all(pts, rows, dest, nreal, &sbuf, scount, sdispl));
  MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) {
    PF_CHECK((size_t)rdispl[r] + (size_t)rcount[r] < INT_MAX, PF_ERR_RUN,
             "migration of more than 2 GB into one rank; use more ranks");
    rdispl[r + 1] = rdispl[r] + rcount[r];
  }
  PF_MALLOC(rbuf, rdispl[size]);
  MPI_Alltoallv(sbuf, scount, sdispl, MPI_BYTE, rbuf, rcount, rdispl, MPI_BYTE, MPI_COMM_WORLD);
  free(sbuf), free(scount), free(sdispl), free(rcount);
  pf_exchange_destroy(&pts->halo);
  pf_int n = count_records(rbuf, (size_t)rdispl[size], nreal, nstate);
  PF_CALL(pf_points_resize(pts, n, 0));
  pf_bond_rows_free(rows);
  PF_CALL(pf_bond_rows_init(rows));
  PF_CALL(pf_bond_rows_widen(rows, nstate));
  scratch sc = {0};
  PF_MALLOC(sc.real, nreal);
  const char *p = rbuf;
  int ierr = 0;
  for (pf_int k = 0; k < n && !ierr; k++) p = unpack(p, pts, rows, k, nreal, nstate, &sc, &ierr);
  free(sc.real), free(sc.gid), free(sc.vfrac), free(sc.rest), free(sc.state), free(rbuf), free(rdispl);
  if (ierr) return ierr;
  pf_int *perm;
  PF_MALLOC(perm, n);
  ierr = order_by_body(pts, nbodies, body_start, perm);
  if (!ierr) ierr = pf_points_permute(pts, perm);
  if (!ierr) ierr = permute_rows(rows, perm);
  free(perm);
  return ierr;
}
