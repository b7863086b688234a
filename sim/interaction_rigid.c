/* Rigid surfaces with prescribed motion as interactions (`contact: rigid_surfaces:` and the
 * foundation's `indenters:`, the same surfaces; contact/rigid.c has the geometry and the force).
 *
 * Its books (docs/theory/pd.md §8): the force of the points on the surface R (<name>_force), the
 * penalty energy U (<name>_penalty_energy, in contact_energy), the friction work (<name>_friction_work, in
 * contact_dissipation), and over a step in which the surface moves by dx = v(t + dt/2) dt the
 * work on the points -(R^n + R^(n+1))/2 . dx (<name>_work, in external_work) and the impulse
 * -(R^n + R^(n+1)) dt/2 (<name>_impulse): the trapezoidal rule of the ledger, second order in
 * the step, since d(K + W_el + U)/dt = -R . v.
 * Under the quasi-static solver (docs/theory/quasi_static_methods.md §8) the surface is placed at each
 * load step's pseudo-time t (moved by dx = v(t - dt/2) dt) and its work booked at the load step's
 * equilibrium by the same rule, -(R_start + R_end)/2 . dx, with R_start the force of the points
 * at the load step's start; its penalty stiffness bounds the fictitious masses. A surface with
 * friction acts there by a tangential penalty with a stick/slip return mapping from each point's
 * slip (the point field <name>_slip, committed at each load step's equilibrium, when the slip
 * increments' work is booked in <name>_friction_work; pf_rigid_force_static). */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
  pf_rigid *r;
  const pf_node *map; /* its deck entry */
  int force, energy, dissipation, work, impulse; /* accounts */
  double r_old[3]; /* R at the step's start */
  double r_loaded[3]; /* quasi-static: R at the load step's first equilibrium */
  double dx[3];    /* the step's motion */
  double x_start[3]; /* quasi-static: the position at the load step's start */
  char slip[32];     /* quasi-static with friction: the slip's point field ("": none) */
} rigid;

/* A surface that repeats one given before it (the same shape, place and motion, on a body both
 * push) would push twice as hard: refused, naming both. */
static int check_repeat(const pf_sim *sim, const rigid *x) {
  for (int k = 0; k < sim->ninter; k++) {
    if (sim->inter[k].ops != &pf_interaction_kind_rigid) continue;
    const rigid *y = sim->inter[k].data;
    if (!pf_rigid_same_surface(y->r, x->r)) continue;
    char where[256];
    pf_node_where(sim->deck, y->map, where, sizeof where);
    return pf_deck_error(sim->deck, x->map, "shape",
                         "rigid surface '%s' repeats '%s' (%s): the same shape at the same place with the "
                         "same motion, pushing a body both push, would push it twice as hard; give each "
                         "surface once", pf_rigid_name(x->r), pf_rigid_name(y->r), where);
  }
  return 0;
}

static int add(pf_sim *sim, const pf_node *list) {
  for (int k = 0; k < pf_node_count(list); k++) {
    rigid *x;
    PF_MALLOC(x, 1);
    x->map = pf_node_item(list, k);
    int ierr = pf_rigid_create(sim->deck, x->map, sim->nbodies, sim->body_name, &x->r);
    if (!ierr) ierr = check_repeat(sim, x);
    if (!ierr) ierr = pf_sim_interaction_add(sim, &pf_interaction_kind_rigid, x);
    if (ierr) {
      pf_rigid_destroy(&x->r);
      free(x);
      return ierr;
    }
  }
  return 0;
}

static int build(pf_sim *sim) {
  const pf_node *root = pf_deck_root(sim->deck);
  PF_CALL(add(sim, pf_node_get(root, "indenters")));
  return add(sim, pf_node_get(pf_node_get(root, "contact"), "rigid_surfaces"));
}

static int destroy(void **data) {
  rigid *x = *data;
  if (x) pf_rigid_destroy(&x->r);
  PF_FREE(*data);
  return 0;
}

static int open_accounts(void *data, pf_sim *sim) {
  rigid *x = data;
  pf_ledger *l = &sim->ledger;
  const pf_sim_totals *T = &sim->acc.totals;
  char name[160];
  const char *n = pf_rigid_name(x->r);
  snprintf(name, sizeof name, "%s_force", n);
  PF_CALL(pf_ledger_open(l, name, "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &x->force));
  snprintf(name, sizeof name, "%s_penalty_energy", n);
  PF_CALL(pf_ledger_open(l, name, "J", 1, 1, PF_BOOK_LAST, PF_BOOK_SHARED, T->contact, &x->energy));
  snprintf(name, sizeof name, "%s_friction_work", n);
  PF_CALL(pf_ledger_open(l, name, "J", 1, 1, PF_BOOK_RUNNING, 0, T->contact_dissipation, &x->dissipation));
  snprintf(name, sizeof name, "%s_work", n);
  PF_CALL(pf_ledger_open(l, name, "J", 1, -1, PF_BOOK_RUNNING, PF_BOOK_SHARED, T->work, &x->work));
  snprintf(name, sizeof name, "%s_impulse", n);
  PF_CALL(pf_ledger_open(l, name, "N s", 3, 0, PF_BOOK_RUNNING, PF_BOOK_SHARED, -1, &x->impulse));
  if (sim->solver.type != PF_SOLVER_QUASI_STATIC || !(pf_rigid_friction(x->r) > 0)) return 0;
  if (!(pf_rigid_tangential_stiffness(x->r) > 0))
    return pf_deck_error(sim->deck, x->map, "tangential_stiffness",
                         "rigid surface '%s': friction with the quasi_static solver needs 'tangential_stiffness' "
                         "(k_t, N/m) with the quadratic law", n);
  int idx;
  snprintf(x->slip, sizeof x->slip, "%.26s_slip", n); /* (a point field's name: 31 characters) */
  return pf_points_field_register(sim->pts, x->slip, 3, PF_FIELD_RESTART, &idx);
}

static void midstep(void *data, const pf_interaction_step *s) {
  rigid *x = data;
  pf_ledger_get(s->ledger, x->force, x->r_old);
}

static void after_drift(void *data, const pf_interaction_step *s) {
  rigid *x = data;
  pf_rigid_advance(x->r, s->t, s->dt, x->dx);
}

static int nsums(const void *data) {
  (void)data;
  return 4;
}

static int force(void *data, const pf_interaction_step *s, double *sums) {
  rigid *x = data;
  if (x->slip[0]) return pf_rigid_force_static(x->r, s->pts, pf_points_field_get(s->pts, x->slip), NULL, sums);
  double diss = 0;
  PF_CALL(pf_rigid_force_local(x->r, s->pts, s->dt, sums, &diss));
  pf_ledger_add(s->ledger, x->dissipation, diss);
  return 0;
}

static void take_sums(void *data, const pf_interaction_step *s, const double *sums) {
  rigid *x = data;
  pf_ledger_set(s->ledger, x->force, sums);
  pf_ledger_set(s->ledger, x->energy, &sums[3]);
}

static void endstep(void *data, const pf_interaction_step *s) {
  rigid *x = data;
  double r_new[3];
  pf_ledger_get(s->ledger, x->force, r_new);
  pf_ledger_book_centred(s->ledger, x->work, x->r_old, r_new, x->dx);
  pf_ledger_book_impulse(s->ledger, x->impulse, x->r_old, r_new, s->dt);
}

/* Quasi-static: to the load step's end s->t (dt < 0: back to its start, the load step abandoned). */
static void place(void *data, const pf_interaction_step *s) {
  rigid *x = data;
  if (s->dt < 0) {
    pf_rigid_set_position(x->r, x->x_start);
    return;
  }
  pf_ledger_get(s->ledger, x->force, x->r_old);
  pf_rigid_position(x->r, x->x_start);
  pf_rigid_advance(x->r, s->t - s->dt, s->dt, x->dx);
}

/* Quasi-static: the force at the load step's first equilibrium, where the surface has moved (past
 * it the surface stays while bonds fail). */
static void loaded(void *data, const pf_interaction_step *s) {
  rigid *x = data;
  pf_ledger_get(s->ledger, x->force, x->r_loaded);
}

/* Quasi-static: the load step's work at its equilibrium, the surface's force taken at the first
 * (g1: after bonds failed); with friction, each point's slip committed and the work of the slip
 * increments (summed by pf_sim_solver_sums: the same bits on any number of ranks) dissipated. */
static int settled(void *data, const pf_interaction_step *s, const double *g0, const double *u0, const double *g1,
                   const double *u1, const double *beyond) {
  (void)g0, (void)u0, (void)u1, (void)beyond; /* (sequential failure refuses rigid surfaces) */
  rigid *x = data;
  double r_new[3];
  pf_ledger_get(s->ledger, x->force, r_new);
  pf_ledger_book_centred(s->ledger, x->work, x->r_old, g1 ? x->r_loaded : r_new, x->dx);
  if (!x->slip[0]) return 0;
  double *terms, unused[4], W;
  PF_MALLOC(terms, s->pts->n_owned);
  int ierr = pf_rigid_force_static(x->r, s->pts, pf_points_field_get(s->pts, x->slip), terms, unused);
  if (!ierr) ierr = pf_sim_solver_sums(terms, s->pts->n_owned, 1, &W);
  free(terms);
  if (!ierr) pf_ledger_add(s->ledger, x->dissipation, (pf_comm_rank() == 0) * W);
  return ierr;
}

static void stiffness_bounds(const void *data, const pf_points *pts, double *k) {
  pf_rigid_stiffness_bounds(((const rigid *)data)->r, pts, k);
}

static double stable_dt(const void *data, const pf_points *pts) {
  return pf_rigid_stable_dt(((const rigid *)data)->r, pts);
}

static int nstate(const void *data) {
  (void)data;
  return 3;
}

static void state_names(const void *data, char (*names)[96]) {
  for (int a = 0; a < 3; a++) snprintf(names[a], 96, "rigid:%.70s_position_%c", pf_rigid_name(((const rigid *)data)->r), 'x' + a);
}

static void state_get(const void *data, double *v) { pf_rigid_position(((const rigid *)data)->r, v); }
static void state_set(void *data, const double *v) { pf_rigid_set_position(((rigid *)data)->r, v); }
static int check_finite(void *data, pf_sim *sim, double t_end, int nt) {
  (void)sim;
  return pf_rigid_check_finite(((rigid *)data)->r, t_end, nt);
}

static const char *name(const void *data) { return pf_rigid_name(((const rigid *)data)->r); }

const pf_interaction_ops pf_interaction_kind_rigid = {
    .kind = "rigid",
    .build = build,
    .destroy = destroy,
    .open_accounts = open_accounts,
    .midstep = midstep,
    .after_drift = after_drift,
    .nsums = nsums,
    .force = force,
    .take_sums = take_sums,
    .endstep = endstep,
    .place = place,
    .loaded = loaded,
    .settled = settled,
    .stiffness_bounds = stiffness_bounds,
    .books_own_work = 1,
    .stable_dt = stable_dt,
    .nstate = nstate,
    .state_names = state_names,
    .state_get = state_get,
    .state_set = state_set,
    .check_finite = check_finite,
    .name = name,
};
