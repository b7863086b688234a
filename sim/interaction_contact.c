/* Contact between bodies as an interaction (`contact: pairs:`; contact/ holds the methods:
 * node-to-particle, short-range forces between particles, FE <-> FE surfaces). Its books: each
 * pair's force on its first body (<pair>_force), the penalty energy (in contact_energy) and the
 * friction work (in contact_dissipation) of all pairs. At each history row it checks the pairs'
 * interpenetration for the run-health monitor. Under the quasi-static solver the pairs act by their
 * penalties, their friction by a tangential penalty on each point's committed slip (the slips
 * committed, and their work dissipated, at each load step's equilibrium), and bound the
 * fictitious masses. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The run-health thresholds of interpenetration (docs/user_guide.md, "Run health"). */
#define PF_HEALTH_DEPTH 0.5 /* a point behind a contact surface by this much of r_c */
#define PF_HEALTH_CLOSE 0.5 /* two contact points closer than this much of r_c */

typedef struct {
  pf_contact *c;
  pf_sim *sim;    /* the bodies: their views for contact, their broken bonds' rest lengths */
  int energy, dissipation; /* accounts of all pairs */
  int *force;     /* [npairs] accounts */
} contact;

/* The largest cell edge of body b's points over all ranks. Collective. */
static double body_spacing(const pf_sim *sim, int b) {
  double h = 0;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) h = fmax(h, sim->pts->cell[i]);
  return pf_max_all(h);
}

/* What contact needs of each body. Collective (spacings). A body meets others through its mesh's
 * surface when its kind says so (the contact_surface op: an FE body), else by its points, as
 * particles: a coupled body's nodes are the particles that fracture, so an FE projectile meets
 * them node-to-particle (surface to particle) and its fragments meet each other by short-range
 * forces, as a PD body's do. */
static void contact_bodies(const pf_sim *sim, pf_contact_body *cb) {
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    pf_contact_body *c = &cb[b];
    memset(c, 0, sizeof *c);
    c->name = sim->body_name[b];
    c->gid0 = sim->gid0[b];
    c->first = sim->body_start[b];
    c->n = sim->body_start[b + 1] - sim->body_start[b];
    c->spacing = body_spacing(sim, b);
    body->ops->material(body->data, &c->density, &c->bulk_modulus);
    c->fam = pf_body_family(body);
    c->horizon = pf_body_horizon(body);
    c->mesh = pf_body_contact_surface(body);
    c->is_fe = c->mesh != NULL;
    if (c->is_fe) c->eroded = body->ops->eroded, c->eroded_ctx = body->data;
  }
}

static int build(pf_sim *sim) {
  const pf_node *map = pf_node_get(pf_deck_root(sim->deck), "contact");
  if (!map) return 0;
  pf_contact_body cb[PF_MAX_BODIES];
  contact_bodies(sim, cb);
  pf_contact *c = NULL;
  PF_CALL(pf_contact_create(sim->deck, map, sim->nbodies, cb, &c));
  if (!c) return 0;
  contact *x = calloc(1, sizeof *x);
  if (x) x->force = calloc((size_t)pf_contact_npairs(c) + 1, sizeof *x->force);
  if (!x || !x->force) {
    if (x) free(x);
    pf_contact_destroy(&c);
    return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  }
  x->c = c, x->sim = sim;
  sim->contact = c; /* (pf_sim_contact, for tests) */
  return pf_sim_interaction_add(sim, &pf_interaction_kind_contact, x);
}

static int destroy(void **data) {
  contact *x = *data;
  if (x) {
    pf_contact_destroy(&x->c);
    x->sim->contact = NULL;
    free(x->force);
  }
  PF_FREE(*data);
  return 0;
}

static int open_accounts(void *data, pf_sim *sim) {
  contact *x = data;
  pf_ledger *l = &sim->ledger;
  const pf_sim_totals *T = &sim->acc.totals;
  for (int k = 0; k < pf_contact_npairs(x->c); k++) {
    char name[160];
    snprintf(name, sizeof name, "%s_force", pf_contact_pair_name(x->c, k));
    PF_CALL(pf_ledger_open(l, name, "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &x->force[k]));
  }
  PF_CALL(pf_ledger_open(l, "contact:pairs_energy", "J", 1, 1, PF_BOOK_LAST, PF_BOOK_SHARED | PF_BOOK_HIDDEN,
                         T->contact, &x->energy));
  PF_CALL(pf_ledger_open(l, "contact:pairs_dissipation", "J", 1, 1, PF_BOOK_RUNNING, PF_BOOK_HIDDEN,
                         T->contact_dissipation, &x->dissipation));
  if (sim->solver.type != PF_SOLVER_QUASI_STATIC) return 0;
  return pf_contact_quasi_static(x->c, sim->deck, pf_node_get(pf_deck_root(sim->deck), "contact"), sim->pts);
}

static int attach(void *data, pf_sim *sim) {
  pf_contact_body cb[PF_MAX_BODIES];
  contact_bodies(sim, cb);
  return pf_contact_attach(((contact *)data)->c, cb);
}

static int nsums(const void *data) { return pf_contact_nsums(((const contact *)data)->c); }

static int prepare(void *data, const pf_interaction_step *s) {
  return pf_contact_prepare(((contact *)data)->c, s->pts);
}

/* The bodies in short-range contact with themselves first give their bonds broken since the last
 * evaluation their rest lengths; then the pairs' forces. */
static int force(void *data, const pf_interaction_step *s, double *sums) {
  contact *x = data;
  const pf_sim *sim = x->sim;
  for (int b = 0; b < sim->nbodies; b++)
    if (pf_contact_self_pair(x->c, b)) pf_body_record_breaks(&sim->body[b], s->pts);
  double diss = 0;
  PF_CALL(pf_contact_force(x->c, s->pts, s->dt, sums, &diss));
  pf_ledger_add(s->ledger, x->dissipation, diss);
  return 0;
}

/* Quasi-static: at the load step's equilibrium the points' slips are committed and the work of
 * their increments (summed by pf_sim_solver_sums: the same bits on any number of ranks)
 * dissipated. The pairs' work is their penalty energy's change (books_own_work). */
static int settled(void *data, const pf_interaction_step *s, const double *g0, const double *u0, const double *g1,
                   const double *u1, const double *beyond) {
  (void)g0, (void)u0, (void)g1, (void)u1, (void)beyond;
  contact *x = data;
  double *terms, W;
  PF_MALLOC(terms, s->pts->n_owned + 1);
  int ierr = pf_contact_commit_slips(x->c, s->pts, terms);
  if (!ierr) ierr = pf_sim_solver_sums(terms, s->pts->n_owned, 1, &W);
  free(terms);
  if (!ierr) pf_ledger_add(s->ledger, x->dissipation, (pf_comm_rank() == 0) * W);
  return ierr;
}

static void take_sums(void *data, const pf_interaction_step *s, const double *sums) {
  contact *x = data;
  double U;
  pf_contact_sums_take(x->c, sums, &U);
  pf_ledger_set(s->ledger, x->energy, &U);
  for (int k = 0; k < pf_contact_npairs(x->c); k++) {
    double f[3];
    pf_contact_pair_force(x->c, k, f);
    pf_ledger_set(s->ledger, x->force[k], f);
  }
}

static double stable_dt(const void *data, const pf_points *pts) {
  return pf_contact_stable_dt(((const contact *)data)->c, pts);
}

/* Soft pairs: each body's stable step at the set-up (over all ranks) sets their stiffness. */
static int fit_step(void *data, pf_sim *sim) {
  contact *x = data;
  if (!pf_contact_nsoft(x->c)) return 0;
  double dt[PF_MAX_BODIES];
  for (int b = 0; b < sim->nbodies; b++) dt[b] = pf_body_stable_dt_all(&sim->body[b], sim->pts);
  return pf_contact_soften(x->c, sim->pts, dt, (const char *const *)sim->body_name);
}

/* The soft pairs' stiffnesses go in the checkpoint: a restart keeps the run's, whatever the
 * restored bodies' steps (a correspondence body's are its points' last). */
static int nstate(const void *data) { return pf_contact_nsoft(((const contact *)data)->c); }
static void state_names(const void *data, char (*names)[96]) {
  const pf_contact *c = ((const contact *)data)->c;
  for (int k = 0, q = 0; k < pf_contact_npairs(c); k++)
    if (pf_contact_pair_soft(c, k)) snprintf(names[q++], 96, "contact:%.60s_soft_stiffness", pf_contact_pair_name(c, k));
}
static void state_get(const void *data, double *v) { pf_contact_soft_stiffness_get(((const contact *)data)->c, v); }
static void state_set(void *data, const double *v) { pf_contact_soft_stiffness_set(((contact *)data)->c, v); }

static void stiffness_bounds(const void *data, const pf_points *pts, double *k) {
  pf_contact_stiffness_bounds(((const contact *)data)->c, pts, k);
}

static void work(const void *data, const pf_points *pts, int *w) {
  (void)pts;
  pf_contact_work(((const contact *)data)->c, w);
}

static int restored(void *data) { return pf_contact_restored(((contact *)data)->c); }
static void masses_changed(void *data) { pf_contact_rebuild(((contact *)data)->c); }

/* Each pair's smallest gap over the ranks (one reduction), against the thresholds. */
static int health(void *data, pf_sim *sim) {
  contact *x = data;
  const int np = pf_contact_npairs(x->c);
  double *gap;
  PF_MALLOC(gap, np);
  pf_contact_gap *info;
  PF_MALLOC(info, np);
  for (int k = 0; k < np; k++) gap[k] = pf_contact_pair_gap(x->c, k, &info[k]);
  int ierr = MPI_Allreduce(MPI_IN_PLACE, gap, np, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD) != MPI_SUCCESS;
  for (int k = 0; k < np && !ierr; k++) {
    const pf_contact_gap *c = &info[k];
    const char *a = sim->body_name[c->a], *b = sim->body_name[c->b];
    char what[96], pair[200];
    snprintf(what, sizeof what, "interpenetration '%.34s'/'%.34s'", a, b);
    if (c->a == c->b) snprintf(pair, sizeof pair, "body '%s' (with itself)", a);
    else snprintf(pair, sizeof pair, "bodies '%s' and '%s'", a, b);
    const char *start = sim->step == sim->health.step0 ? " (they start inside each other)" : "";
    if (c->surface && gap[k] < -PF_HEALTH_DEPTH)
      ierr = pf_sim_health_warn(sim, what,
                                "%s interpenetrate at t = %.4e s (step %ld)%s: a point is %.3g m behind the surface of "
                                "'%s', %.3g contact radii (r_c = %.3g m; more than %g)",
                                pair, sim->t, sim->step, start, -gap[k] * c->length, a, -gap[k], c->length,
                                PF_HEALTH_DEPTH);
    else if (!c->surface && gap[k] < PF_HEALTH_CLOSE)
      ierr = pf_sim_health_warn(sim, what,
                                "%s interpenetrate at t = %.4e s (step %ld)%s: two points are %.3g of their contact "
                                "radius apart (less than %g; r_c = %.3g m)",
                                pair, sim->t, sim->step, start, gap[k], PF_HEALTH_CLOSE, c->length);
  }
  free(gap), free(info);
  return ierr;
}

static void summary(const void *data, pf_sim *sim) {
  const contact *x = data;
  long rebuilds;
  double sec;
  pf_contact_stats(x->c, &rebuilds, &sec);
  sec = pf_max_all(sec);
  pf_log("  contact: %ld search rebuilds, %.3g s (%.1f %% of the time loop), dissipation %.3g J\n", rebuilds, sec,
         sim->wall_loop > 0 ? 100 * sec / sim->wall_loop : 0.0, pf_ledger_value(&sim->ledger, x->dissipation, 0));
}

static const char *name(const void *data) {
  (void)data;
  return "contact pairs";
}

const pf_interaction_ops pf_interaction_kind_contact = {
    .kind = "contact",
    .build = build,
    .destroy = destroy,
    .open_accounts = open_accounts,
    .attach = attach,
    .nsums = nsums,
    .prepare = prepare,
    .force = force,
    .take_sums = take_sums,
    .settled = settled,
    .stiffness_bounds = stiffness_bounds,
    /* (quasi-static: the pairs' forces are internal, their work is the change of their penalty
     * energy, booked in contact_energy; none of it is a load's) */
    .books_own_work = 1,
    .work = work,
    .stable_dt = stable_dt,
    .fit_step = fit_step,
    .nstate = nstate,
    .state_names = state_names,
    .state_get = state_get,
    .state_set = state_set,
    .restored = restored,
    .masses_changed = masses_changed,
    .health = health,
    .summary = summary,
    .name = name,
};
