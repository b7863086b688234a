/* Rigid, fixed planar walls as interactions (`walls:`; contact/wall.c enforces them). Its books:
 * the force of the points on the wall (<name>_force), the kinetic energy it removes from points
 * it puts back on its plane (<name>_energy_loss, in wall_dissipation), and its impulse on the
 * points (<name>_impulse): the momentum it removes then, and over each step the ledger's rule
 * -(R^n + R^(n+1)) dt/2 for the normal force it takes off the points on it.
 * Under the quasi-static solver a point that a relaxation iteration moved through the plane goes
 * back onto it, its inward relaxation velocity dropped (no energy booked: that velocity is
 * fictitious); the wall does no work (it is fixed) and its force is a reaction. */
#include "sim/sim_impl.h"

#include <stdlib.h>

typedef struct {
  pf_wall *w;
  int force, impulse, dissipation; /* accounts */
  double r_old[3];
} wall;

static int build(pf_sim *sim) {
  const pf_node *list = pf_node_get(pf_deck_root(sim->deck), "walls");
  for (int k = 0; k < pf_node_count(list); k++) {
    wall *x;
    PF_MALLOC(x, 1);
    int ierr = pf_wall_create(sim->deck, pf_node_item(list, k), sim->nbodies, sim->body_name, &x->w);
    if (!ierr) ierr = pf_sim_interaction_add(sim, &pf_interaction_kind_wall, x);
    if (ierr) {
      pf_wall_destroy(&x->w);
      free(x);
      return ierr;
    }
  }
  return 0;
}

static int destroy(void **data) {
  wall *x = *data;
  if (x) pf_wall_destroy(&x->w);
  PF_FREE(*data);
  return 0;
}

static int open_accounts(void *data, pf_sim *sim) {
  wall *x = data;
  char name[160];
  const char *n = pf_wall_name(x->w);
  snprintf(name, sizeof name, "%s_force", n);
  PF_CALL(pf_ledger_open(&sim->ledger, name, "N", 3, 0, PF_BOOK_LAST, PF_BOOK_SHARED, -1, &x->force));
  snprintf(name, sizeof name, "%s_impulse", n);
  PF_CALL(pf_ledger_open(&sim->ledger, name, "N s", 3, 0, PF_BOOK_RUNNING, 0, -1, &x->impulse));
  snprintf(name, sizeof name, "%s_energy_loss", n);
  return pf_ledger_open(&sim->ledger, name, "J", 1, 1, PF_BOOK_RUNNING, 0, sim->acc.totals.wall, &x->dissipation);
}

static void midstep(void *data, const pf_interaction_step *s) {
  wall *x = data;
  pf_ledger_get(s->ledger, x->force, x->r_old);
}

/* Points behind the plane go back onto it (an impulse on this rank's points). */
static void after_drift(void *data, const pf_interaction_step *s) {
  wall *x = data;
  double loss = 0, impulse[3] = {0, 0, 0};
  pf_wall_enforce_position(x->w, s->pts, &loss, impulse);
  pf_ledger_add(s->ledger, x->dissipation, loss);
  pf_ledger_book(s->ledger, x->impulse, impulse);
}

static int nsums(const void *data) {
  (void)data;
  return 3;
}

static int force(void *data, const pf_interaction_step *s, double *sums) {
  pf_wall_enforce_force_local(((wall *)data)->w, s->pts, sums);
  return 0;
}

static void take_sums(void *data, const pf_interaction_step *s, const double *sums) {
  pf_ledger_set(s->ledger, ((wall *)data)->force, sums);
}

/* The step's impulse of the normal force taken off the points (the same on every rank: rank 0
 * books it). */
static void endstep(void *data, const pf_interaction_step *s) {
  wall *x = data;
  if (pf_comm_rank() != 0) return;
  double r_new[3];
  pf_ledger_get(s->ledger, x->force, r_new);
  pf_ledger_book_impulse(s->ledger, x->impulse, x->r_old, r_new, s->dt);
}

static void project(const void *data, pf_points *pts) {
  double loss = 0, impulse[3] = {0, 0, 0};
  pf_wall_enforce_position(((const wall *)data)->w, pts, &loss, impulse);
}

static const char *name(const void *data) { return pf_wall_name(((const wall *)data)->w); }

const pf_interaction_ops pf_interaction_kind_wall = {
    .kind = "wall",
    .build = build,
    .destroy = destroy,
    .open_accounts = open_accounts,
    .midstep = midstep,
    .after_drift = after_drift,
    .nsums = nsums,
    .force = force,
    .take_sums = take_sums,
    .endstep = endstep,
    .project = project,
    .books_own_work = 1,
    .name = name,
};
