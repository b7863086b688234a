/* Prescribed motions and loads as interactions (`boundary_conditions:`; core/bc.c applies
 * them): a prescribed velocity or displacement sets the points' velocity at the velocity-Verlet
 * hooks, a body force adds to their force. Its books: the work of its reaction (or load) on the
 * points of each body, into that body's external work (core/bc.c gives the trapezoidal rule), and
 * the same work as a figure of its own (<name>_work), its impulse on the points (<name>_impulse),
 * its mean reaction over the last step, the step's impulse over dt (<name>_reaction), and the
 * mean displacement of its points at the step's end (<name>_displacement: the grip's).
 * Under the quasi-static solver the reaction, work and displacement are booked at each load
 * step's equilibrium instead (settled; docs/theory/quasi_static.md §4.1), summed over the ranks by
 * pf_sim_solver_sums: the same bits on any number of ranks. */
#include "sim/sim_impl.h"

#include <stdlib.h>

typedef struct {
  pf_bc *bc;
  double npoints;                             /* over the ranks */
  int reaction, impulse, displacement, work; /* accounts */
} condition;

static int build(pf_sim *sim) {
  const pf_node *list = pf_node_get(pf_deck_root(sim->deck), "boundary_conditions");
  for (int k = 0; k < pf_node_count(list); k++) {
    condition *x;
    PF_MALLOC(x, 1);
    int ierr = pf_bc_create(sim->deck, pf_node_item(list, k), sim->pts, sim->nbodies, sim->body_name, &sim->sets, k,
                            &x->bc);
    if (!ierr) ierr = pf_sim_interaction_add(sim, &pf_interaction_kind_condition, x);
    if (ierr) {
      pf_bc_destroy(&x->bc);
      free(x);
      return ierr;
    }
    char where[512];
    pf_node_where(sim->deck, pf_node_item(list, k), where, sizeof where);
    x->npoints = pf_sum_all(pf_bc_npoints(x->bc));
    pf_log("boundary condition '%s' (%s): %" PF_GID_FMT " points\n", pf_bc_name(x->bc), where, (pf_gid)x->npoints);
  }
  return 0;
}

static int destroy(void **data) {
  condition *x = *data;
  if (x) pf_bc_destroy(&x->bc);
  PF_FREE(*data);
  return 0;
}

static int open_accounts(void *data, pf_sim *sim) {
  condition *x = data;
  char name[160];
  snprintf(name, sizeof name, "%s_reaction", pf_bc_name(x->bc));
  PF_CALL(pf_ledger_open(&sim->ledger, name, "N", 3, 0, PF_BOOK_LAST, 0, -1, &x->reaction));
  snprintf(name, sizeof name, "%s_impulse", pf_bc_name(x->bc));
  PF_CALL(pf_ledger_open(&sim->ledger, name, "N s", 3, 0, PF_BOOK_RUNNING, 0, -1, &x->impulse));
  snprintf(name, sizeof name, "%s_displacement", pf_bc_name(x->bc));
  PF_CALL(pf_ledger_open(&sim->ledger, name, "m", 3, 0, PF_BOOK_LAST, 0, -1, &x->displacement));
  /* (a figure: the same work is in the bodies' external work, which the balance counts) */
  snprintf(name, sizeof name, "%s_work", pf_bc_name(x->bc));
  return pf_ledger_open(&sim->ledger, name, "J", 1, 0, PF_BOOK_RUNNING, 0, -1, &x->work);
}

static int attach(void *data, pf_sim *sim) { return pf_bc_select(((condition *)data)->bc, sim->pts); }

static void mark_prescribed(const void *data, uint8_t *fixed) { pf_bc_mark(((const condition *)data)->bc, fixed); }

typedef void (*bc_hook)(pf_bc *bc, pf_points *pts, double t, double dt, double *work);

/* Run a hook of core/bc.c and book what it did: the work per body, the impulse. */
static void apply(condition *x, const pf_interaction_step *s, bc_hook hook) {
  double w[PF_MAX_BODIES] = {0}, step[3], d[3];
  hook(x->bc, s->pts, s->t, s->dt, w);
  pf_bc_impulse(x->bc, step, d);
  pf_ledger_book(s->ledger, x->impulse, d);
  double all = 0;
  for (int b = 0; b < s->nbodies; b++) pf_ledger_add(s->ledger, s->body_work[b], w[b]), all += w[b];
  pf_ledger_add(s->ledger, x->work, all);
}

static void midstep(void *data, const pf_interaction_step *s) { apply(data, s, pf_bc_apply_midstep); }

static int force(void *data, const pf_interaction_step *s, double *sums) {
  (void)sums;
  apply(data, s, pf_bc_apply_force);
  return 0;
}

static void endstep(void *data, const pf_interaction_step *s) {
  condition *x = data;
  apply(x, s, pf_bc_apply_endstep);
  double step[3], hook[3];
  pf_bc_impulse(x->bc, step, hook);
  for (int a = 0; a < 3; a++) step[a] /= s->dt;
  pf_ledger_set(s->ledger, x->reaction, step);
  double u[3]; /* this rank's part of the mean */
  pf_bc_displacement_sum(x->bc, s->pts, u);
  for (int a = 0; a < 3; a++) u[a] /= x->npoints;
  pf_ledger_set(s->ledger, x->displacement, u);
}

static void place(void *data, const pf_interaction_step *s) {
  pf_bc_apply_static(((condition *)data)->bc, s->pts, s->t, s->dt);
}

/* The load step's equilibrium: the reaction (or load), its work over the load step and the mean
 * displacement, each summed over the ranks by pf_sim_solver_sums and booked on rank 0 (0 on the
 * others: the ledger's sum over the ranks keeps the bits). */
static int settled(void *data, const pf_interaction_step *s, const double *g0, const double *u0, const double *g1,
                   const double *u1, const double *beyond) {
  condition *x = data;
  const pf_int n = pf_bc_npoints(x->bc);
  double sums[7], *terms = malloc(sizeof(double) * (7 * (size_t)n + 1));
  PF_CHECK(terms, PF_ERR_MEMORY, "out of memory for the books of boundary condition '%s'", pf_bc_name(x->bc));
  pf_bc_static_terms(x->bc, s->pts, s->t, s->dt, g0, u0, g1, u1, beyond, terms);
  int ierr = pf_sim_solver_sums(terms, n, 4, sums); /* reaction, work */
  if (!ierr) ierr = pf_sim_solver_sums(terms + 4 * (size_t)n, n, 3, sums + 4); /* displacement */
  free(terms);
  if (ierr) return ierr;
  const double root = pf_comm_rank() == 0;
  double r[3], u[3];
  for (int a = 0; a < 3; a++) r[a] = root * sums[a], u[a] = root * sums[4 + a] / x->npoints;
  pf_ledger_set(s->ledger, x->reaction, r);
  pf_ledger_set(s->ledger, x->displacement, u);
  pf_ledger_add(s->ledger, x->work, root * sums[3]);
  return 0;
}

static int check_finite(void *data, pf_sim *sim, double t_end, int nt) {
  return pf_bc_check_finite(((condition *)data)->bc, sim->pts, t_end, nt);
}

static const char *name(const void *data) { return pf_bc_name(((const condition *)data)->bc); }

const pf_interaction_ops pf_interaction_kind_condition = {
    .kind = "condition",
    .build = build,
    .destroy = destroy,
    .open_accounts = open_accounts,
    .attach = attach,
    .mark_prescribed = mark_prescribed,
    .midstep = midstep,
    .force = force,
    .endstep = endstep,
    .place = place,
    .settled = settled,
    .check_finite = check_finite,
    .name = name,
};
