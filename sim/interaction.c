/* The dispatchers that call every interaction in list order, each optional op with its default
 * here and nowhere else (sim/interaction.h). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_sim_interaction_add(pf_sim *sim, const pf_interaction_ops *ops, void *data) {
  PF_CHECK(ops->build && ops->destroy, PF_ERR_RUN, "interaction kind '%s' lacks a required op (sim/interaction.h)",
           ops->kind);
  if (sim->ninter == sim->cap_inter) {
    int cap = sim->cap_inter ? 2 * sim->cap_inter : 8;
    pf_interaction *a = realloc(sim->inter, sizeof *a * (size_t)cap);
    PF_CHECK(a, PF_ERR_MEMORY, "out of memory adding an interaction of kind '%s'", ops->kind);
    sim->inter = a, sim->cap_inter = cap;
  }
  sim->inter[sim->ninter++] = (pf_interaction){ops, data};
  return 0;
}


void pf_sim_interactions_destroy(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++) sim->inter[k].ops->destroy(&sim->inter[k].data);
  PF_FREE(sim->inter);
  sim->ninter = sim->cap_inter = 0;
}

int pf_sim_interactions_open_accounts(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->open_accounts) PF_CALL(sim->inter[k].ops->open_accounts(sim->inter[k].data, sim));
  return 0;
}

int pf_sim_interactions_attach(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->attach) PF_CALL(sim->inter[k].ops->attach(sim->inter[k].data, sim));
  return 0;
}

void pf_sim_interactions_work(const pf_sim *sim, int *w) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->work) sim->inter[k].ops->work(sim->inter[k].data, sim->pts, w);
}

void pf_sim_interactions_mark(const pf_sim *sim, uint8_t *fixed) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->mark_prescribed) sim->inter[k].ops->mark_prescribed(sim->inter[k].data, fixed);
}

static pf_interaction_step step_of(pf_sim *sim, double dt) {
  return (pf_interaction_step){sim->pts, &sim->ledger, sim->t, dt, sim->nbodies, sim->acc.body_work};
}

void pf_sim_interactions_midstep(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->midstep) sim->inter[k].ops->midstep(sim->inter[k].data, &s);
}

void pf_sim_interactions_after_drift(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->after_drift) sim->inter[k].ops->after_drift(sim->inter[k].data, &s);
}

void pf_sim_interactions_place(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->place) sim->inter[k].ops->place(sim->inter[k].data, &s);
}

void pf_sim_interactions_loaded(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->loaded) sim->inter[k].ops->loaded(sim->inter[k].data, &s);
}

int pf_sim_interactions_settled(pf_sim *sim, double dt, const double *g0, const double *u0, const double *g1,
                                const double *u1, const double *beyond) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->settled) PF_CALL(sim->inter[k].ops->settled(sim->inter[k].data, &s, g0, u0, g1, u1, beyond));
  return 0;
}

int pf_sim_interactions_prepare(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->prepare) PF_CALL(sim->inter[k].ops->prepare(sim->inter[k].data, &s));
  return 0;
}

static int nsums(const pf_interaction *x) { return x->ops->nsums ? x->ops->nsums(x->data) : 0; }

/* Each interaction's forces and its part of the sums, one reduction for all, then each takes its
 * summed part (reactions, penalty energies). */
void pf_sim_interactions_stiffness_bounds(const pf_sim *sim, double *k) {
  for (int j = 0; j < sim->ninter; j++)
    if (sim->inter[j].ops->stiffness_bounds) sim->inter[j].ops->stiffness_bounds(sim->inter[j].data, sim->pts, k);
}

void pf_sim_interactions_project(const pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->project) sim->inter[k].ops->project(sim->inter[k].data, sim->pts);
}

/* Interaction k's forces (and, with own, their part that books its own work: f after - f before). */
static int force_of(pf_sim *sim, int k, const pf_interaction_step *s, double *sums, double *own) {
  const pf_interaction *x = &sim->inter[k];
  if (!x->ops->force) return 0;
  const pf_int n3 = 3 * sim->pts->n_owned;
  const int mine = own && x->ops->books_own_work;
  if (mine)
    for (pf_int d = 0; d < n3; d++) own[d] -= sim->pts->f[d];
  PF_CALL(x->ops->force(x->data, s, sums));
  if (mine)
    for (pf_int d = 0; d < n3; d++) own[d] += sim->pts->f[d];
  return 0;
}

int pf_sim_interactions_force(pf_sim *sim, double dt, double *own) {
  const pf_interaction_step s = step_of(sim, dt);
  int n = 0;
  for (int k = 0; k < sim->ninter; k++) n += nsums(&sim->inter[k]);
  double *local = NULL;
  PF_MALLOC(local, 2 * (size_t)n + 1);
  double *sum = local + n;
  int ierr = 0;
  if (own) memset(own, 0, sizeof(double) * 3 * (size_t)sim->pts->n_owned);
  for (int k = 0, at = 0; k < sim->ninter && !ierr; at += nsums(&sim->inter[k]), k++)
    ierr = force_of(sim, k, &s, &local[at], own);
  if (!ierr && n > 0 && MPI_Allreduce(local, sum, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS)
    ierr = pf_error_raise(PF_ERR_LIB, __FILE__, __LINE__, __func__, "MPI_Allreduce failed summing the interactions' forces");
  for (int k = 0, at = 0; k < sim->ninter && !ierr; at += nsums(&sim->inter[k]), k++)
    if (sim->inter[k].ops->take_sums) sim->inter[k].ops->take_sums(sim->inter[k].data, &s, &sum[at]);
  free(local);
  return ierr;
}

void pf_sim_interactions_endstep(pf_sim *sim, double dt) {
  const pf_interaction_step s = step_of(sim, dt);
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->endstep) sim->inter[k].ops->endstep(sim->inter[k].data, &s);
}

double pf_sim_interaction_stable_dt(const pf_sim *sim, int k) {
  const pf_interaction *x = &sim->inter[k];
  return x->ops->stable_dt ? x->ops->stable_dt(x->data, sim->pts) : INFINITY;
}

double pf_sim_interactions_stable_dt(const pf_sim *sim) {
  double dt = INFINITY;
  for (int k = 0; k < sim->ninter; k++) dt = fmin(dt, pf_sim_interaction_stable_dt(sim, k));
  return dt;
}

int pf_sim_interactions_fit_step(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->fit_step) PF_CALL(sim->inter[k].ops->fit_step(sim->inter[k].data, sim));
  return 0;
}

static int nstate(const pf_interaction *x) { return x->ops->nstate ? x->ops->nstate(x->data) : 0; }

int pf_sim_interactions_nstate(const pf_sim *sim) {
  int n = 0;
  for (int k = 0; k < sim->ninter; k++) n += nstate(&sim->inter[k]);
  return n;
}

void pf_sim_interactions_state_names(const pf_sim *sim, char (*names)[96]) {
  for (int k = 0; k < sim->ninter; names += nstate(&sim->inter[k]), k++)
    if (nstate(&sim->inter[k])) sim->inter[k].ops->state_names(sim->inter[k].data, names);
}

void pf_sim_interactions_state_get(const pf_sim *sim, double *v) {
  for (int k = 0; k < sim->ninter; v += nstate(&sim->inter[k]), k++)
    if (nstate(&sim->inter[k])) sim->inter[k].ops->state_get(sim->inter[k].data, v);
}

void pf_sim_interactions_state_set(pf_sim *sim, const double *v) {
  for (int k = 0; k < sim->ninter; v += nstate(&sim->inter[k]), k++)
    if (nstate(&sim->inter[k])) sim->inter[k].ops->state_set(sim->inter[k].data, v);
}

int pf_sim_interactions_restored(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->restored) PF_CALL(sim->inter[k].ops->restored(sim->inter[k].data));
  return 0;
}

int pf_sim_interactions_check_finite(pf_sim *sim, double t_end, int nt) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->check_finite)
      PF_CALL(sim->inter[k].ops->check_finite(sim->inter[k].data, sim, t_end, nt));
  return 0;
}

int pf_sim_interactions_health(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->health) PF_CALL(sim->inter[k].ops->health(sim->inter[k].data, sim));
  return 0;
}

void pf_sim_interactions_summary(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->summary) sim->inter[k].ops->summary(sim->inter[k].data, sim);
}

void pf_sim_interactions_masses_changed(pf_sim *sim) {
  for (int k = 0; k < sim->ninter; k++)
    if (sim->inter[k].ops->masses_changed) sim->inter[k].ops->masses_changed(sim->inter[k].data);
}

const char *pf_sim_interaction_name(const pf_sim *sim, int k) {
  const pf_interaction *x = &sim->inter[k];
  return x->ops->name ? x->ops->name(x->data) : x->ops->kind;
}
