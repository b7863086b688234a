/* Sequentially linear failure under the quasi-static solver (`solver.failure: sequential`;
 * docs/theory/quasi_static_failure.md §5.2; Rots & Invernizzi 2004, and Ni et al. 2018 for
 * peridynamics). A body that is linear at its current damage stays at equilibrium when its state
 * and its prescribed displacements are scaled together, and its bonds' failure ratios (stretch over
 * limit, or the square root of energy over limit: sim/body.h) scale with it. So instead of
 * checking the bonds at the load step's target, where bonds are found beyond their limit, the
 * state is scaled back to where the most critical bond meets its limit, that bond fails, the body
 * relaxes at those grips, and so on until the target is reached with no bond over its limit
 * (the loop is sim/solver_relaxation.c's). Here: what the deck must be, the scaling, and the work
 * along the scaled path, segment by segment by the trapezoidal rule (exact on a linear segment). */
#include "sim/sim_impl.h"

#include <math.h>
#include <string.h>

static const pf_node *failure_key(const pf_sim *sim) {
  return pf_node_get(pf_node_get(pf_deck_root(sim->deck), "solver"), "failure");
}

/* A load that the scaling cannot follow: a rigid surface, a wall or contact (not linear in the
 * state), a body force (not a prescribed displacement). */
static int check_loads(const pf_sim *sim, const pf_node *sv) {
  const pf_deck *d = sim->deck;
  const pf_node *root = pf_deck_root(d), *bcs = pf_node_get(root, "boundary_conditions");
  static const char *const sections[] = {"walls", "indenters", "contact"};
  for (int k = 0; k < 3; k++)
    if (pf_node_get(root, sections[k]))
      return pf_deck_error(d, pf_node_get(sv, "failure"), "failure",
                           "sequential failure scales the whole state with the load, which '%s' (not linear in the "
                           "state) does not allow: remove it, or use failure: at_equilibrium", sections[k]);
  for (int j = 0; j < pf_node_count(bcs); j++)
    if (pf_node_get(pf_node_item(bcs, j), "body_force"))
      return pf_deck_error(d, pf_node_get(pf_node_item(bcs, j), "body_force"), "body_force",
                           "solver.failure: sequential takes prescribed displacements and velocities only (the state "
                           "is scaled with them); a body force is not scaled: use failure: at_equilibrium");
  return 0;
}

int pf_sim_solver_sequential_check(const pf_sim *sim, const pf_node *sv) {
  PF_CALL(check_loads(sim, sv));
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    const char *why = pf_body_keeps_history(body, sim->pts)
                          ? "keeps history (plasticity, a rate form or elements), which a scaled state does not follow"
                      : pf_body_softened(body) >= 0 ? "has bonds that soften (law softening), which a scaled state "
                                                      "does not follow"
                      : pf_body_fails_without_ratio(body) ? "has no failure ratio for its bonds"
                                                                              : NULL;
    if (why)
      return pf_deck_error(sim->deck, pf_node_get(sv, "failure"), "failure",
                           "sequential failure needs bodies that are linear at their damage: body '%s' %s; use "
                           "failure: at_equilibrium", sim->body_name[b], why);
  }
  return 0;
}

/* The load step placed its prescribed components at t: each must be its value at the start
 * times t / (t - dt), or the scaled states are not states of the deck's loading. */
int pf_sim_solver_proportional(pf_sim *sim) {
  const pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  const double t0 = sim->t - sim->dt, t1 = sim->t;
  double big = 0, off = 0;
  for (pf_int d = 0; d < 3 * p->n_owned; d++)
    if (s->fixed[d]) big = fmax(big, fabs(p->u[d])), off = fmax(off, fabs(s->u0[d] * t1 - p->u[d] * t0) / t1);
  big = pf_max_all(big), off = pf_max_all(off);
  if (off <= 1e-9 * big) return 0;
  return pf_deck_error(sim->deck, failure_key(sim), "failure",
                       "sequential failure scales the whole load, but the prescribed displacements at t = %g s are "
                       "not in proportion to t: they differ from their values at t = %g s scaled by t by up to "
                       "%.3e m (largest %.3e m); prescribe displacements linear in t, or use failure: at_equilibrium",
                       t1, t0, off, big);
}

double pf_sim_solver_failure_ratio(pf_sim *sim) {
  double local = 0;
  for (int b = 0; b < sim->nbodies; b++) local = fmax(local, pf_body_failure_ratio(&sim->body[b], sim->pts));
  return pf_max_all(local);
}

void pf_sim_solver_path_mark(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  for (pf_int d = 0; d < 3 * p->n_owned; d++) s->um[d] = p->u[d], s->gm[d] = pf_sim_solver_applied(s, p, d);
  memset(s->beyond, 0, sizeof(double) * 3 * (size_t)p->n_owned);
}

void pf_sim_solver_path_segment(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  for (pf_int d = 0; d < 3 * p->n_owned; d++) {
    const double g = pf_sim_solver_applied(s, p, d);
    s->beyond[d] += 0.5 * (s->gm[d] + g) * (p->u[d] - s->um[d]);
    s->um[d] = p->u[d], s->gm[d] = g;
  }
}

int pf_sim_solver_scale(pf_sim *sim, double a) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  for (pf_int d = 0; d < 3 * p->n_owned; d++) p->u[d] *= a, p->y[d] = p->X[d] + p->u[d];
  s->lam *= a;
  if (s->lam > 1 - 1e-12) { /* (back at the target: the prescribed components exactly there) */
    s->lam = 1;
    pf_sim_interactions_place(sim, sim->dt);
  }
  s->scalings++;
  PF_CALL(pf_sim_solver_evaluate(sim));
  pf_sim_solver_path_segment(sim);
  return 0;
}
