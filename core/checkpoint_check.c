/* What a checkpoint's reader checks before it uses what it read (core/checkpoint.c): ids in
 * range and unique, bond counts that add up, finite values. The data's bytes are guarded by
 * HDF5's Fletcher32 checksums and the metadata's by HDF5's own; these checks catch a file whose
 * checksums hold but whose content cannot be a perifem state (written by another tool, or by a
 * bug). Every check is collective and agreed: on a failure every rank returns the same
 * PF_ERR_INPUT error naming the file and the dataset or attribute. */
#include "core/checkpoint_impl.h"

#include <math.h>
#include <string.h>

/* Every global id in [0, total); with unique, no id twice among all ranks' (the union of the
 * ranks' sets has total members exactly when the total ids are distinct). */
int pf_ckpt_check_ids(const char *path, const char *dset, const pf_gid *id, int64_t n, pf_gid total, int unique) {
  char msg[512] = "";
  int ok = 1;
  for (int64_t i = 0; i < n && ok; i++)
    if (id[i] < 0 || id[i] >= total) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: id %" PF_GID_FMT " at row %" PRId64
               " of this rank's slice is outside [0, %" PF_GID_FMT "): the file is damaged", path, dset, id[i], i, total);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  if (!unique) return 0;
  size_t nbytes = (size_t)(total + 7) / 8;
  unsigned char *seen;
  PF_MALLOC(seen, nbytes);
  for (int64_t i = 0; i < n; i++) {
    if (seen[id[i] / 8] & (1u << (id[i] % 8))) ok = 0; /* twice on this rank */
    seen[id[i] / 8] |= (unsigned char)(1u << (id[i] % 8));
  }
  MPI_Allreduce(MPI_IN_PLACE, seen, (int)nbytes, MPI_UNSIGNED_CHAR, MPI_BOR, MPI_COMM_WORLD);
  int64_t members = 0;
  for (size_t k = 0; k < nbytes; k++) members += __builtin_popcount(seen[k]);
  free(seen);
  ok = ok && members == total;
  if (!ok)
    snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: the %" PF_GID_FMT " ids are not distinct (%" PRId64
             " different ones): the file is damaged", path, dset, total, members);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

/* Every value not NaN, finite unless allow_inf, and at least lo (-INFINITY: no bound). */
int pf_ckpt_check_values(const char *path, const char *dset, const double *x, size_t n, double lo, int allow_inf) {
  char msg[512] = "";
  int ok = 1;
  for (size_t i = 0; i < n && ok; i++)
    if (isnan(x[i]) || (!allow_inf && isinf(x[i])) || x[i] < lo) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: value %g at entry %zu of this rank's slice is %s: the file "
               "is damaged", path, dset, x[i], i, isnan(x[i]) || isinf(x[i]) ? "not finite" : "out of range");
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

int pf_ckpt_check_floats(const char *path, const char *dset, const float *x, size_t n) {
  char msg[512] = "";
  int ok = 1;
  for (size_t i = 0; i < n && ok; i++)
    if (isnan(x[i])) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: entry %zu of this rank's slice is NaN: the file is damaged",
               path, dset, i);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

int pf_ckpt_check_flags(const char *path, const char *dset, const uint8_t *x, size_t n) {
  char msg[512] = "";
  int ok = 1;
  for (size_t i = 0; i < n && ok; i++)
    if (x[i] > 1) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: entry %zu of this rank's slice is %d, not a flag (0 or 1): "
               "the file is damaged", path, dset, i, x[i]);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

/* Body indices not negative (the caller, who knows the bodies, bounds them above). */
int pf_ckpt_check_bodies(const char *path, const int32_t *body, int64_t n) {
  char msg[512] = "";
  int ok = 1;
  for (int64_t i = 0; i < n && ok; i++)
    if (body[i] < 0) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset /points/body: body index %" PRId32 " at row %" PRId64
               " of this rank's slice: the file is damaged", path, body[i], i);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

/* Each row's bond count in [0, total], and all ranks' counts adding up to the nbonds rows of
 * /bonds/gid. */
int pf_ckpt_check_counts(const char *path, const int32_t *count, int64_t n, pf_gid total, int64_t nbonds) {
  char msg[512] = "";
  int ok = 1;
  long long sum = 0;
  for (int64_t i = 0; i < n; i++) {
    if (ok && (count[i] < 0 || count[i] > total)) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset /bonds/count: %" PRId32 " bonds at row %" PRId64
               " of this rank's slice (outside [0, %" PF_GID_FMT "]): the file is damaged", path, count[i], i, total);
    }
    sum += count[i];
  }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (sum != nbonds)
    snprintf(msg, sizeof msg, "checkpoint %s: dataset /bonds/count adds up to %lld bonds, /bonds/gid holds %" PRId64
             ": the file is damaged", path, sum, nbonds);
  PF_AGREE(sum == nbonds, PF_ERR_INPUT, msg);
  return 0;
}

/* Each row's neighbours: in [0, total) and ascending (the rows' invariant, core/core.h). */
int pf_ckpt_check_rows(const char *path, const pf_bond_rows *rows, pf_gid total) {
  PF_CALL(pf_ckpt_check_ids(path, "/bonds/gid", rows->gid, rows->offset[rows->n], total, 0));
  char msg[512] = "";
  int ok = 1;
  for (pf_int i = 0; i < rows->n && ok; i++)
    for (int64_t k = rows->offset[i] + 1; k < rows->offset[i + 1] && ok; k++)
      if (rows->gid[k] <= rows->gid[k - 1]) {
        ok = 0;
        snprintf(msg, sizeof msg, "checkpoint %s: dataset /bonds/gid: the neighbours of row %" PF_INT_FMT
                 " of this rank's slice are not ascending: the file is damaged", path, i);
      }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}
