/* Private to core/: the checks a checkpoint's reader (core/checkpoint.c) makes on what it read
 * (core/checkpoint_check.c). Each is collective and agreed: on a failure every rank returns the
 * same PF_ERR_INPUT error naming the checkpoint path and the dataset dset. */
#ifndef PF_CHECKPOINT_IMPL_H
#define PF_CHECKPOINT_IMPL_H

#include "core/bond_rows_impl.h"

/* Every id[n] in [0, total); with unique, no id on two rows of any rank. */
int pf_ckpt_check_ids(const char *path, const char *dset, const pf_gid *id, int64_t n, pf_gid total, int unique);
/* Every x[n] not NaN, finite unless allow_inf, and at least lo (-INFINITY: no bound). */
int pf_ckpt_check_values(const char *path, const char *dset, const double *x, size_t n, double lo, int allow_inf);
/* Every x[n] not NaN. */
int pf_ckpt_check_floats(const char *path, const char *dset, const float *x, size_t n);
/* Every flag x[n] 0 or 1. */
int pf_ckpt_check_flags(const char *path, const char *dset, const uint8_t *x, size_t n);
/* Every body[n] not negative. */
int pf_ckpt_check_bodies(const char *path, const int32_t *body, int64_t n);
/* Every bond count[n] in [0, total]; all ranks' adding up to nbonds. */
int pf_ckpt_check_counts(const char *path, const int32_t *count, int64_t n, pf_gid total, int64_t nbonds);
/* The rows' neighbours in [0, total) and ascending within each row. */
int pf_ckpt_check_rows(const char *path, const pf_bond_rows *rows, pf_gid total);

#endif
