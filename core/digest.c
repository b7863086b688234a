/* The state digest printed at the end of a run: FNV-1a (64-bit) over the bytes of the final
 * displacement of every point, taken in global-id order, so two runs (any rank count, any
 * point order) can be compared bitwise. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

static uint64_t fnv1a(uint64_t h, const void *data, size_t len) {
  const unsigned char *p = data;
  for (size_t i = 0; i < len; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

int pf_state_digest(const pf_points *pts, uint64_t *digest) {
  PF_CHECK(pf_comm_size() == 1, PF_ERR_RUN, "the state digest is serial for now");
  pf_gid n = pts->n_owned;
  double *byid;
  PF_MALLOC(byid, 3 * (size_t)n);
  for (pf_int i = 0; i < pts->n_owned; i++) {
    pf_gid g = pts->gid[i];
    PF_CHECK(g >= 0 && g < n, PF_ERR_RUN, "global id %" PF_GID_FMT " outside [0, %" PF_GID_FMT ")",
             g, n);
    memcpy(&byid[3 * g], &pts->u[3 * i], 3 * sizeof(double));
  }
  *digest = fnv1a(1469598103934665603ULL, byid, 3 * (size_t)n * sizeof(double));
  free(byid);
  return 0;
}
