/* Moving owned points between ranks (DESIGN.md 6): every array and registered field of a point
 * and its bond row travel together in one packed record, so that a (re)partition keeps the
 * complete state. Records are exchanged with one MPI_Alltoallv. */
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

static size_t record_size(int nreal, int64_t nbonds) {
  return sizeof(pf_gid) + 2 * sizeof(int32_t) + sizeof(double) * (size_t)nreal +
         (size_t)nbonds * (sizeof(pf_gid) + 1 + sizeof(float));
}

static char *put(char *p, const void *src, size_t n) {
  memcpy(p, src, n);
  return p + n;
}

static char *pack(const pf_points *pts, const pf_bond_rows *rows, pf_int i, int nreal, char *p) {
  int32_t nb = (int32_t)(rows->offset[i + 1] - rows->offset[i]);
  double *real = malloc(sizeof(double) * (size_t)nreal), *r = real;
  if (!real) return NULL;
  for (int a = 0; a < 3; a++) r[a] = pts->X[3 * i + a], r[3 + a] = pts->u[3 * i + a],
                              r[6 + a] = pts->v[3 * i + a], r[9 + a] = pts->f[3 * i + a];
  r[12] = pts->m[i], r[13] = pts->vol[i], r[14] = pts->cell[i];
  r += NFIXED;
  for (int k = 0; k < pts->nfields; k++) {
    const pf_field *fl = &pts->fields[k];
    memcpy(r, &fl->data[(size_t)i * fl->ncomp], sizeof(double) * fl->ncomp);
    r += fl->ncomp;
  }
  int64_t o = rows->offset[i];
  p = put(p, &pts->gid[i], sizeof(pf_gid));
  p = put(p, &pts->body[i], sizeof(int32_t));
  p = put(p, &nb, sizeof(int32_t));
  p = put(p, real, sizeof(double) * (size_t)nreal);
  p = put(p, &rows->gid[o], sizeof(pf_gid) * (size_t)nb);
  p = put(p, &rows->broken[o], (size_t)nb);
  p = put(p, &rows->vfrac[o], sizeof(float) * (size_t)nb);
  free(real);
  return p;
}

/* Unpack one record into point k of pts and append its row; returns the next record. */
static const char *unpack(const char *p, pf_points *pts, pf_bond_rows *rows, pf_int k, int nreal,
                          double *real, int *ierr) {
  int32_t nb;
  memcpy(&pts->gid[k], p, sizeof(pf_gid)), p += sizeof(pf_gid);
  memcpy(&pts->body[k], p, sizeof(int32_t)), p += sizeof(int32_t);
  memcpy(&nb, p, sizeof(int32_t)), p += sizeof(int32_t);
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
  const pf_gid *g = (const pf_gid *)(const void *)p;
  const uint8_t *b = (const uint8_t *)(p + sizeof(pf_gid) * (size_t)nb);
  const float *vf = (const float *)(const void *)(p + (sizeof(pf_gid) + 1) * (size_t)nb);
  /* the record may be unaligned for gid/float: copy through aligned buffers */
  pf_gid *ga = malloc(sizeof(pf_gid) * ((size_t)nb + 1));
  float *fa = malloc(sizeof(float) * ((size_t)nb + 1));
  if (!ga || !fa) *ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  else {
    memcpy(ga, g, sizeof(pf_gid) * (size_t)nb);
    memcpy(fa, vf, sizeof(float) * (size_t)nb);
    *ierr = pf_bond_rows_append(rows, nb, ga, b, fa);
  }
  free(ga), free(fa);
  return p + (sizeof(pf_gid) + 1 + sizeof(float)) * (size_t)nb;
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
    bytes[dest[i]] += record_size(nreal, rows->offset[i + 1] - rows->offset[i]);
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
  int ok = 1;
  for (pf_int i = 0; i < pts->n_owned && ok; i++) {
    char *end = pack(pts, rows, i, nreal, *buf + at[dest[i]]);
    ok = end != NULL;
    if (ok) at[dest[i]] = (size_t)(end - *buf);
  }
  free(bytes), free(at);
  PF_CHECK(ok, PF_ERR_MEMORY, "out of memory packing points");
  return 0;
}

/* Count the records in a received buffer. */
static pf_int count_records(const char *p, size_t len, int nreal) {
  pf_int n = 0;
  for (size_t at = 0; at < len; n++) {
    int32_t nb;
    memcpy(&nb, p + at + sizeof(pf_gid) + sizeof(int32_t), sizeof nb);
    at += record_size(nreal, nb);
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
  for (pf_int k = 0; k < rows->n; k++) {
    int64_t o = rows->offset[perm[k]];
    PF_CALL(pf_bond_rows_append(&out, (pf_int)(rows->offset[perm[k] + 1] - o), &rows->gid[o],
                                &rows->broken[o], &rows->vfrac[o]));
  }
  pf_bond_rows_free(rows);
  *rows = out;
  return 0;
}

int pf_points_migrate(pf_points *pts, pf_bond_rows *rows, const int *dest, int nbodies, pf_int *body_start) {
  int size = pf_comm_size(), nreal = NFIXED + field_width(pts);
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
  pf_halo_destroy(&pts->halo);
  pf_int n = count_records(rbuf, (size_t)rdispl[size], nreal);
  PF_CALL(pf_points_resize(pts, n, 0));
  pf_bond_rows_free(rows);
  PF_CALL(pf_bond_rows_init(rows));
  double *real;
  PF_MALLOC(real, nreal);
  const char *p = rbuf;
  int ierr = 0;
  for (pf_int k = 0; k < n && !ierr; k++) p = unpack(p, pts, rows, k, nreal, real, &ierr);
  free(real), free(rbuf), free(rdispl);
  if (ierr) return ierr;
  pf_int *perm;
  PF_MALLOC(perm, n);
  ierr = order_by_body(pts, nbodies, body_start, perm);
  if (!ierr) ierr = pf_points_permute(pts, perm);
  if (!ierr) ierr = permute_rows(rows, perm);
  free(perm);
  return ierr;
}
