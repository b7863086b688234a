/* Moving owned points between ranks: every array and registered field of a point
 * and its bond row (with every registered bond field: broken flags, partial-volume fractions,
 * rest lengths, the materials' per-bond reals, whatever a model registered) travel together in
 * one packed record, so that a (re)partition keeps the complete state. Records are exchanged
 * with one MPI_Alltoallv. */
#include "core/bond_rows_impl.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

enum { NFIXED = 15 }; /* X, u, v, f (3 each), m, vol, cell */

static int field_width(const pf_points *pts) {
  int w = 0;
  for (int k = 0; k < pts->nfields; k++) w += pts->fields[k].ncomp;
  return w;
}

/* Bytes of one bond in a record: its neighbour's gid and every bond field. */
static size_t bond_size(const pf_bond_rows *rows) {
  size_t s = sizeof(pf_gid);
  for (int k = 0; k < rows->nfields; k++) s += pf_bond_type_size(rows->field[k].type) * (size_t)rows->field[k].ncomp;
  return s;
}

static size_t record_size(int nreal, size_t bond_bytes, int64_t nbonds) {
  return sizeof(pf_gid) + 2 * sizeof(int32_t) + sizeof(double) * (size_t)nreal + (size_t)nbonds * bond_bytes;
}

static char *put(char *p, const void *src, size_t n) {
  if (n) memcpy(p, src, n); /* src may be NULL when n is 0 (a body without bonds) */
  return p + n;
}

/* Bytes of bonds [o, o + nb) of field f. */
static size_t field_bytes(const pf_bond_field *f, int64_t nb) {
  return pf_bond_type_size(f->type) * (size_t)f->ncomp * (size_t)nb;
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
  for (int k = 0; k < rows->nfields; k++)
    p = put(p, (const char *)rows->field[k].data + field_bytes(&rows->field[k], o), field_bytes(&rows->field[k], nb));
  return p;
}

/* Unpack the point of one record into point k of pts; *nb gets its bond count. Returns the
 * record's bonds. */
static const char *unpack_point(const char *p, pf_points *pts, pf_int k, int nreal, double *real, int32_t *nb) {
  memcpy(&pts->gid[k], p, sizeof(pf_gid)), p += sizeof(pf_gid);
  memcpy(&pts->body[k], p, sizeof(int32_t)), p += sizeof(int32_t);
  memcpy(nb, p, sizeof(int32_t)), p += sizeof(int32_t);
  memcpy(real, p, sizeof(double) * (size_t)nreal), p += sizeof(double) * (size_t)nreal;
  const double *r = real;
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
  return p;
}

/* Append the row of nb bonds packed at p (neighbours, then each field). */
static int unpack_row(const char *p, int32_t nb, pf_bond_rows *rows) {
  int64_t at;
  PF_CALL(pf_bond_rows_append_unset(rows, nb, &at)); /* (every byte of it from the record) */
  memcpy(rows->gid + at, p, sizeof(pf_gid) * (size_t)nb), p += sizeof(pf_gid) * (size_t)nb;
  for (int q = 0; q < rows->nfields; q++) {
    const pf_bond_field *f = &rows->field[q];
    memcpy((char *)f->data + field_bytes(f, at), p, field_bytes(f, nb)), p += field_bytes(f, nb);
  }
  return 0;
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
    bytes[dest[i]] += record_size(nreal, bond_size(rows), rows->offset[i + 1] - rows->offset[i]);
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
static pf_int count_records(const char *p, size_t len, int nreal, size_t bond_bytes) {
  pf_int n = 0;
  for (size_t at = 0; at < len; n++) {
    int32_t nb;
    memcpy(&nb, p + at + sizeof(pf_gid) + sizeof(int32_t), sizeof nb);
    at += record_size(nreal, bond_bytes, nb);
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

/* The records are packed, the rows' own copy of the bonds is given back before the exchange
 * (on one rank the packed buffer is the received one), and the rows are rebuilt from the
 * received records directly in the points' final order: at most two copies of this rank's
 * bonds exist at any time (the rows and the packed buffer, or the send and receive buffers). */
int pf_points_migrate(pf_points *pts, pf_bond_rows *rows, const int *dest, int nbodies, pf_int *body_start) {
  int size = pf_comm_size(), nreal = NFIXED + field_width(pts);
  PF_CALL(pf_bond_rows_fields_agree(rows)); /* every record carries the same bond fields */
  int *scount, *sdispl, *rcount, *rdispl;
  PF_MALLOC(scount, size);
  PF_MALLOC(sdispl, size);
  PF_MALLOC(rcount, size);
  PF_MALLOC(rdispl, size + 1);
  char *sbuf = NULL, *rbuf = NULL;
  PF_CALL(pack_all(pts, rows, dest, nreal, &sbuf, scount, sdispl));
  PF_CALL(pf_bond_rows_release(rows)); /* (its bonds are in sbuf) */
  MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) {
    PF_CHECK((size_t)rdispl[r] + (size_t)rcount[r] < INT_MAX, PF_ERR_RUN,
             "migration of more than 2 GB into one rank; use more ranks");
    rdispl[r + 1] = rdispl[r] + rcount[r];
  }
  if (size == 1) rbuf = sbuf, sbuf = NULL; /* (everything stays) */
  else {
    PF_MALLOC(rbuf, rdispl[size]);
    MPI_Alltoallv(sbuf, scount, sdispl, MPI_BYTE, rbuf, rcount, rdispl, MPI_BYTE, MPI_COMM_WORLD);
  }
  free(sbuf), free(scount), free(sdispl), free(rcount);
  pf_exchange_destroy(&pts->halo);
  const size_t bond_bytes = bond_size(rows);
  pf_int n = count_records(rbuf, (size_t)rdispl[size], nreal, bond_bytes);
  PF_CALL(pf_points_resize(pts, n, 0));
  double *real;
  const char **bonds; /* [n] each record's bonds */
  int32_t *nb;
  pf_int *perm;
  PF_MALLOC(real, nreal);
  PF_MALLOC(bonds, n);
  PF_MALLOC(nb, n);
  PF_MALLOC(perm, n);
  const char *p = rbuf;
  for (pf_int k = 0; k < n; k++) {
    bonds[k] = unpack_point(p, pts, k, nreal, real, &nb[k]);
    p = bonds[k] + (size_t)nb[k] * bond_bytes;
  }
  int64_t nbonds = 0;
  for (pf_int k = 0; k < n; k++) nbonds += nb[k];
  int ierr = pf_bond_rows_reserve(rows, n, nbonds);
  if (!ierr) ierr = order_by_body(pts, nbodies, body_start, perm);
  if (!ierr) ierr = pf_points_permute(pts, perm);
  for (pf_int k = 0; k < n && !ierr; k++) ierr = unpack_row(bonds[perm[k]], nb[perm[k]], rows);
  free(real), free(bonds), free(nb), free(perm), free(rbuf), free(rdispl);
  pf_memory_trim();
  return ierr;
}
