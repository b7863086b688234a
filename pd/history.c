/* A PD body's history for the quasi-static solver (docs/theory/quasi_static_failure.md §6): the point
 * fields its material's force advances (named by the material's setup, pf_pd_body_keep_history)
 * over the body's owned points, and the bonds' material state (fam.state), committed at a load
 * step's start and put back before each force evaluation, so that each evaluation is one
 * increment from the last converged state. Damage is not history: the solver freezes it while it
 * relaxes (pd/damage.c), and bonds failed at a damage check stay failed (a load step abandoned on
 * a signal puts them back: pd/failures_kept.c). */
#include "pd/pd_impl.h"

#include <stdlib.h>
#include <string.h>

int pf_pd_body_keep_history(pf_pd_body *b, int field) {
  for (int k = 0; k < b->history.nfields; k++)
    if (b->history.field[k] == field) return 0;
  PF_CHECK(b->history.nfields < PF_PD_MAX_HISTORY_FIELDS, PF_ERR_RUN,
           "PD body '%s': more than %d history fields", b->name, PF_PD_MAX_HISTORY_FIELDS);
  b->history.field[b->history.nfields++] = field;
  return 0;
}

/* The bonds' state is the material's history, unless it is the softening's damage (pd/softening.c),
 * which like a failure changes at damage checks only and is kept with them (pd/failures_kept.c). */
static int state_is_history(const pf_pd_body *b) { return b->fam.nstate > 0 && b->soft_ratio == 0; }

int pf_pd_body_keeps_history(const pf_pd_body *b) { return b->history.nfields > 0 || state_is_history(b); }

/* The committed copy's length: each field's owned rows of the body, then the bonds' state. */
static size_t history_length(const pf_pd_body *b, const pf_points *pts) {
  size_t n = state_is_history(b) ? (size_t)b->fam.nstate * (size_t)(b->fam.state ? b->fam.offset[b->fam.n] : 0) : 0;
  for (int k = 0; k < b->history.nfields; k++) n += (size_t)pts->fields[b->history.field[k]].ncomp * (size_t)b->n;
  return n;
}

/* Copy between the body's history (out 1: from it into buf) and buf. */
static void history_copy(pf_pd_body *b, pf_points *pts, double *buf, int out) {
  for (int k = 0; k < b->history.nfields; k++) {
    const pf_field *f = &pts->fields[b->history.field[k]];
    double *data = &f->data[(size_t)f->ncomp * (size_t)b->first];
    const size_t len = (size_t)f->ncomp * (size_t)b->n;
    memcpy(out ? buf : data, out ? data : buf, sizeof(double) * len);
    buf += len;
  }
  if (state_is_history(b) && b->fam.state) {
    const size_t len = (size_t)b->fam.nstate * (size_t)b->fam.offset[b->fam.n];
    memcpy(out ? buf : b->fam.state, out ? b->fam.state : buf, sizeof(double) * len);
  }
}

int pf_pd_body_history(pf_pd_body *b, pf_points *pts, int restore) {
  const size_t n = history_length(b, pts);
  if (restore) {
    PF_CHECK(b->history.committed && b->history.n == n, PF_ERR_RUN,
             "PD body '%s': no committed history for its %" PF_INT_FMT " points", b->name, b->n);
    history_copy(b, pts, b->history.committed, 0);
    return 0;
  }
  if (b->history.n != n || !b->history.committed) {
    free(b->history.committed);
    b->history.committed = NULL, b->history.n = 0;
    PF_MALLOC(b->history.committed, n ? n : 1); /* (a rank without the body's points commits too) */
    b->history.n = n;
  }
  history_copy(b, pts, b->history.committed, 1);
  return 0;
}
