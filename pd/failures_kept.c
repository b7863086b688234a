/* The bonds' failures kept at a quasi-static load step's start and put back when the load step is
 * abandoned (a signal: sim/solver_relaxation.c), so that the checkpoint then written is the last
 * equilibrium's, bonds included: the broken flags, and the rest lengths the contact records at a
 * break with their record bits (a family has all three: pd/family.c), and where the bonds soften
 * their state (s_max, d: pd/softening.c). What a failing bond changes
 * besides is put back elsewhere: its booked energy with the ledger, the point fields with the
 * solver's copy of them; the correspondence's shape cache follows the intact count
 * (pd/material_correspondence.c). */
#include "pd/pd_impl.h"

#include <stdlib.h>
#include <string.h>

/* The softening's state (s_max, d) of each bond, kept or put back with the failures; either way
 * the first pass of a load step follows (pd/softening.c). */
static int soft_state(pf_pd_body *b, int restore) {
  const int64_t n = 2 * pf_pd_family_nbonds(&b->fam);
  if (restore) {
    PF_CHECK(b->soft_qs.kept && b->soft_qs.n == n, PF_ERR_RUN, "PD body '%s': no bond state kept", b->name);
  } else if (b->soft_qs.n != n || b->soft_qs.npoints != b->n || !b->soft_qs.kept) {
    free(b->soft_qs.kept), free(b->soft_qs.base), free(b->soft_qs.theta);
    b->soft_qs.n = 0;
    PF_MALLOC(b->soft_qs.kept, n + 1);
    PF_MALLOC(b->soft_qs.base, n + 1);
    PF_MALLOC(b->soft_qs.theta, (size_t)b->n + 1);
    b->soft_qs.n = n, b->soft_qs.npoints = b->n;
  }
  memcpy(restore ? b->fam.state : b->soft_qs.kept, restore ? b->soft_qs.kept : b->fam.state, sizeof(double) * (size_t)n);
  memcpy(b->soft_qs.base, b->fam.state, sizeof(double) * (size_t)n);
  b->soft_qs.pass = 1, b->soft_qs.theta_stale = 1;
  return 0;
}

int pf_pd_body_failures(pf_pd_body *b, int restore) {
  pf_family *fam = &b->fam;
  if (!fam->broken) return 0;
  const int64_t nb = pf_pd_family_nbonds(fam), nwords = nb / 64 + 1;
  if (restore) {
    PF_CHECK(b->kept.broken && b->kept.nbonds == nb, PF_ERR_RUN,
             "PD body '%s': no failures kept for its %" PF_INT_FMT " points", b->name, b->n);
  } else if (b->kept.nbonds != nb || !b->kept.broken) {
    pf_pd_body_failures_free(b);
    PF_MALLOC(b->kept.broken, nb + 1);
    PF_MALLOC(b->kept.rest, nb + 1);
    PF_MALLOC(b->kept.recorded, nwords);
    b->kept.nbonds = nb;
  }
  if (b->soft_ratio > 0) PF_CALL(soft_state(b, restore));
  if (restore) {
    memcpy(fam->broken, b->kept.broken, (size_t)nb);
    memcpy(fam->rest, b->kept.rest, sizeof(float) * (size_t)nb);
    memcpy(fam->recorded, b->kept.recorded, sizeof(uint64_t) * (size_t)nwords);
  } else {
    memcpy(b->kept.broken, fam->broken, (size_t)nb);
    memcpy(b->kept.rest, fam->rest, sizeof(float) * (size_t)nb);
    memcpy(b->kept.recorded, fam->recorded, sizeof(uint64_t) * (size_t)nwords);
  }
  return 0;
}

void pf_pd_body_failures_free(pf_pd_body *b) {
  PF_FREE(b->soft_qs.kept);
  PF_FREE(b->soft_qs.base);
  PF_FREE(b->soft_qs.theta);
  b->soft_qs.n = 0;
  PF_FREE(b->kept.broken);
  PF_FREE(b->kept.rest);
  PF_FREE(b->kept.recorded);
  b->kept.nbonds = 0;
}
