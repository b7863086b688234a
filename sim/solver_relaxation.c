/* One load step of the quasi-static solver by adaptive dynamic relaxation (Underwood 1983; Kilic &
 * Madenci 2010; docs/theory/quasi_static.md). With the fictitious time step 1 and a diagonal
 * fictitious mass lambda_i >= (1/4) sum_j |K_ij| (Gershgorin, from the bodies' stiffness bounds
 * plus the rigid surfaces' penalty stiffness, docs/theory/quasi_static_methods.md §8):
 *   u-dot^(1/2)   = F^0 / (2 lambda)
 *   u^(n+1)       = u^n + u-dot^(n+1/2)
 *   u-dot^(n+1/2) = ((2 - c^n) u-dot^(n-1/2) + 2 F^n / lambda) / (2 + c^n)
 *   c^n = 2 sqrt(w^T 1K w / w^T w),  1K_ii = -(F_i^n - F_i^(n-1)) / (lambda_i u-dot_i^(n-1/2))
 * with w = u - u^s the displacement since this relaxation started (u^s; Kilic & Madenci's u from a
 * start at rest, u = 0: a load step's predictor or a damage pass starts elsewhere, theory §2)
 * over the free components, c^n each body's own over its components (theory §2); F is the force
 * of the explicit step (bodies, then the loads), the bodies reading an increment as their velocity
 * over a step of 1: a body that keeps history the load step's (its history put back as committed
 * at the load step's start before each evaluation: one backward-Euler increment from the last
 * converged state), the others the iteration's. Every sum is taken by pf_sim_solver_sums, so the
 * iterations are the same on any number of ranks.
 * Damage only at equilibrium: the bodies' damage is frozen while the load step relaxes (no bond
 * fails at the out-of-balance states of the iterations); at the equilibrium reached one force
 * evaluation with the damage thawed fails the bonds whose limit is met, and if any failed the
 * load step relaxes again at the same load, until an equilibrium fails none; or, with
 * solver.failure sequential, the state is scaled to where the most critical bond meets its limit
 * before each check (equilibrate_sequential; sim/solver_sequential.c). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


static int scratch(pf_sim_solver *s, pf_int n) {
  if (s->n == n && s->lambda) return 0;
  free(s->lambda), free(s->vel), free(s->f_old), free(s->u_last), free(s->f_body), free(s->u0), free(s->g0);
  free(s->u1), free(s->g1), free(s->fixed), free(s->terms), free(s->f_own), free(s->um), free(s->u_relax);
  const size_t n3 = 3 * (size_t)n + 1;
  s->lambda = calloc((size_t)n + 1, sizeof(double));
  s->vel = calloc(n3, sizeof(double)), s->f_old = calloc(n3, sizeof(double));
  s->u_last = calloc(n3, sizeof(double)), s->u_relax = calloc(n3, sizeof(double));
  s->f_body = calloc(n3, sizeof(double));
  s->f_own = calloc(n3, sizeof(double));
  s->u0 = calloc(n3, sizeof(double)), s->g0 = calloc(n3, sizeof(double));
  s->u1 = calloc(n3, sizeof(double)), s->g1 = calloc(n3, sizeof(double));
  s->um = calloc(3 * n3, sizeof(double)), s->gm = s->um + n3, s->beyond = s->gm + n3;
  s->terms = calloc(PF_SOLVER_SUMS * n3, sizeof(double));
  s->fixed = calloc(n3, 1);
  s->n = n;
  PF_CHECK(s->lambda && s->vel && s->f_old && s->u_last && s->u_relax && s->f_body && s->f_own && s->u0 && s->g0 &&
               s->u1 && s->g1 && s->terms && s->fixed && s->um,
           PF_ERR_MEMORY, "out of memory for the quasi-static solver's arrays (%" PF_INT_FMT " points)", n);
  return 0;
}

/* The bodies' stiffness bounds k_i into lambda (at the load step's start). */
static int body_bounds(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_int first = sim->body_start[b];
    PF_CALL(pf_body_stiffness_bounds(&sim->body[b], sim->pts, first, sim->body_start[b + 1] - first, &s->lambda[first]));
  }
  return 0;
}

/* The fictitious masses lambda_i = (k_i + k^c_i) / (4 safety^2): the bodies' bound k_i and the
 * interactions' k^c_i (a rigid surface's penalty; Gershgorin: the row sums of a sum of
 * stiffnesses are at most the sums of theirs), with the load step placed. */
static void masses(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_sim_interactions_stiffness_bounds(sim, s->lambda);
  for (pf_int i = 0; i < sim->pts->n_owned; i++) s->lambda[i] /= 4 * sim->safety * sim->safety;
}

/* The damping coefficient c[b] of each body's components: 2 sqrt(w^T 1K w / w^T w) over them
 * (pf_sim_solver_quotient_terms), 0 where the quotient is not positive, at most 2. With one body
 * the iteration's sums q are its own. Collective. */
static int damping(pf_sim *sim, const double *q, double *c) {
  pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  for (int b = 0; b < sim->nbodies; b++) {
    double r[2] = {q[S_UKU], q[S_UU]};
    if (sim->nbodies > 1) {
      const pf_int d0 = 3 * sim->body_start[b], n = 3 * sim->body_start[b + 1] - d0;
      double *t = s->terms;
      for (pf_int k = 0; k < n; k++) pf_sim_solver_quotient_terms(s, p, d0 + k, &t[k], &t[n + k]);
      PF_CALL(pf_sim_solver_sums(t, n, 2, r));
    }
    const double ratio = r[1] > 0 ? r[0] / r[1] : 0;
    c[b] = ratio > 0 ? fmin(2 * sqrt(ratio), 2.0) : 0;
  }
  return 0;
}

/* The next relaxation velocity of the free components (first: u-dot^(1/2)), each body's damped by
 * its own coefficient, then u moves by it. */
static int advance(pf_sim *sim, const double *q, int first) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  double c[PF_MAX_BODIES] = {0};
  if (!first) PF_CALL(damping(sim, q, c));
  for (int b = 0; b < sim->nbodies; b++)
    for (pf_int d = 3 * sim->body_start[b]; d < 3 * sim->body_start[b + 1]; d++) {
      if (!pf_sim_solver_is_free(s, d)) continue;
      const double a = p->f[d] / s->lambda[d / 3];
      s->vel[d] = first ? 0.5 * a : ((2 - c[b]) * s->vel[d] + 2 * a) / (2 + c[b]);
      s->f_old[d] = p->f[d];
      p->u[d] += s->vel[d];
      p->y[d] = p->X[d] + p->u[d];
    }
  return 0;
}

/* Points that went through a constraint (a wall) go back onto it, their inward relaxation
 * velocity dropped (pts->v carries it to the interactions). */
static void project(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  const pf_int n3 = 3 * p->n_owned;
  for (pf_int d = 0; d < n3; d++) p->v[d] = pf_sim_solver_is_free(s, d) ? s->vel[d] : 0;
  pf_sim_interactions_project(sim);
  for (pf_int d = 0; d < n3; d++)
    if (pf_sim_solver_is_free(s, d)) s->vel[d] = p->v[d];
}

static int not_converged(const pf_sim *sim, long it, double res) {
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                        "quasi-static load step %ld of %ld (t = %g s) did not converge: the residual is %.3e of the "
                        "reference force after %ld iterations (solver.tolerance %g, solver.max_iterations %ld)",
                        sim->step, sim->solver.load_steps, sim->t, res, it, sim->solver.tolerance,
                        sim->solver.max_iterations);
}

/* Relax the load step's state to equilibrium: *it iterations, *res the relative residual; *stop
 * set (on every rank) to STOP_GUARD when a body tripped the guard or the residual is not finite,
 * to STOP_SIGNAL when a rank received SIGTERM or SIGINT. */
static int relax(pf_sim *sim, long *it, double *res, int *stop) {
  pf_sim_solver *s = &sim->solver;
  double q[PF_SOLVER_SUMS];
  memset(s->vel, 0, sizeof(double) * 3 * (size_t)sim->pts->n_owned);
  memcpy(s->u_relax, sim->pts->u, sizeof(double) * 3 * (size_t)sim->pts->n_owned);
  PF_CALL(pf_sim_solver_evaluate(sim));
  PF_CALL(pf_sim_solver_measure(sim, q));
  for (*it = 0;; ++*it) {
    *res = pf_sim_solver_residual(q);
    *stop = q[S_TRIPPED] > 0 || !isfinite(*res) ? STOP_GUARD : q[S_SIGNAL] > 0 ? STOP_SIGNAL : 0;
    if (*stop || *res <= s->tolerance) return 0;
    if (*it == s->max_iterations) return not_converged(sim, *it, *res);
    PF_CALL(advance(sim, q, *it == 0));
    project(sim);
    PF_CALL(pf_sim_solver_evaluate(sim));
    PF_CALL(pf_sim_solver_measure(sim, q));
  }
}

/* Equilibrium by the deck's method: Newton-Krylov, falling back to relaxation from the state it
 * reached when it does not converge (sim/solver_newton.c); or relaxation. */
static int solve(pf_sim *sim, long *it, double *res, int *stop) {
  long n = 0;
  *it = 0;
  if (sim->solver.method != PF_SOLVER_RELAXATION) {
    int converged = 0;
    if (sim->solver.method == PF_SOLVER_SNES) PF_CALL(pf_sim_solver_snes(sim, &n, res, stop, &converged));
    else PF_CALL(pf_sim_solver_newton(sim, &n, res, stop, &converged));
    *it = n;
    if (converged || *stop) return 0;
    sim->solver.fallbacks++;
  }
  PF_CALL(relax(sim, &n, res, stop));
  *it += n;
  return 0;
}

/* Freeze (1) or thaw (0) every body's damage (sim/body.h). */
static int freeze_damage(pf_sim *sim, int frozen) {
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_freeze_damage(&sim->body[b], sim->pts, frozen));
  return 0;
}

/* The failed directed bonds of every body over every rank (an integer: the sum is exact). */
static double broken_bonds(const pf_sim *sim) {
  int64_t n = 0;
  for (int b = 0; b < sim->nbodies; b++) n += pf_body_broken_bonds(&sim->body[b]);
  for (int b = 0; b < sim->nbodies; b++) n += pf_body_softened(&sim->body[b]) > 0 ? pf_body_softened(&sim->body[b]) : 0;
  return pf_sum_all((double)n);
}

/* The damage check at an equilibrium: one force evaluation with the damage thawed (the bodies fail
 * the bonds whose limit the state meets, their energy booked; bonds that soften take the damage of
 * their stretch); *failed the bonds it failed, and those whose damage grew by more than the law's
 * tolerance. */
static int check_damage(pf_sim *sim, double *failed) {
  const double before = broken_bonds(sim);
  PF_CALL(freeze_damage(sim, 0));
  PF_CALL(pf_sim_solver_evaluate(sim));
  PF_CALL(freeze_damage(sim, 1));
  *failed = broken_bonds(sim) - before;
  return 0;
}

static int too_many_passes(const pf_sim *sim, double failed) {
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                        "quasi-static load step %ld of %ld (t = %g s): bonds still fail at equilibrium after %ld "
                        "damage passes (%.0f directed bonds in the last check; solver.max_damage_passes %ld)",
                        sim->step, sim->solver.load_steps, sim->t, sim->solver.max_damage_passes, failed,
                        sim->solver.max_damage_passes);
}

/* The energy the ledger holds now, less the kinetic part (mid load step the points' velocities
 * are the bodies' increments, not a motion): the stored energies, the dissipations and the work
 * booked so far. Collective. */
static int held(pf_sim *sim, double *e) {
  PF_CALL(pf_sim_accounts_evaluate(sim, 0));
  *e = pf_ledger_balance(&sim->ledger);
  for (int b = 0; b < sim->nbodies; b++) *e -= pf_ledger_value(&sim->ledger, sim->acc.body[b].centred, 0);
  return 0;
}

/* The load step's first equilibrium, before its damage check: u1, the applied forces g1, the
 * energy held, and what the interactions keep of it (the load step's work is done here: past it
 * the load stays while bonds fail; docs/theory/quasi_static_failure.md §5.1). Collective. */
static int loaded(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  for (pf_int d = 0; d < 3 * p->n_owned; d++) s->u1[d] = p->u[d], s->g1[d] = pf_sim_solver_applied(s, p, d);
  pf_sim_interactions_loaded(sim, sim->dt);
  if (s->sequential) pf_sim_solver_path_mark(sim);
  return held(sim, &s->held1);
}

static int nothing_failed(const pf_sim *sim, double r) {
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                        "quasi-static load step %ld of %ld (t = %g s): the state was scaled to put its most critical "
                        "bond at its limit (failure ratio %.6g before the scaling), but the damage check failed no "
                        "bond: the bodies' failure ratio and their damage test disagree",
                        sim->step, sim->solver.load_steps, sim->t, r);
}

/* Sequentially linear failure (sim/solver_sequential.c): relax at the grips' place lam (a fraction
 * of the load step's target); at the equilibrium the largest failure ratio r says whether the
 * target keeps every bond within its limit (r / lam <= 1): then the state goes to the target,
 * relaxes there, and a check that fails nothing ends the load step; else the state is scaled by
 * (1 + margin) / r, which puts the most critical bonds just past their limit (the bonds within
 * 0.1 % of it with them), the check fails them, and the state relaxes at those grips. Arguments
 * as equilibrate's. */
static int equilibrate_sequential(pf_sim *sim, long *it, double *res, long *passes, int *stop) {
  pf_sim_solver *s = &sim->solver;
  const double margin = 1e-3;
  *it = 0;
  s->lam = 1;
  for (*passes = 0;; ++*passes) {
    long n = 0;
    double failed = 0;
    PF_CALL(solve(sim, &n, res, stop));
    *it += n;
    if (*stop) return 0;
    if (*passes == 0) PF_CALL(loaded(sim));
    else pf_sim_solver_path_segment(sim);
    const double r = pf_sim_solver_failure_ratio(sim);
    if (r <= s->lam && s->lam < 1) {
      PF_CALL(pf_sim_solver_scale(sim, 1 / s->lam));
    } else if (r <= s->lam) {
      PF_CALL(check_damage(sim, &failed));
      if (failed == 0) return 0;
    } else {
      PF_CALL(pf_sim_solver_scale(sim, (1 + margin) / r));
      PF_CALL(check_damage(sim, &failed));
      if (failed == 0) return nothing_failed(sim, r);
    }
    if (*passes == sim->solver.max_damage_passes) return too_many_passes(sim, failed);
  }
}

/* Relax, check the damage at the equilibrium, relax again at the same load while bonds fail:
 * *it iterations in all, *res the last relative residual, *passes the relaxations after the first;
 * *stop as relax leaves it. */
static int equilibrate(pf_sim *sim, long *it, double *res, long *passes, int *stop) {
  if (sim->solver.sequential) return equilibrate_sequential(sim, it, res, passes, stop);
  *it = 0;
  for (*passes = 0;; ++*passes) {
    long n = 0;
    double failed = 0;
    PF_CALL(solve(sim, &n, res, stop));
    *it += n;
    if (*stop) return 0; /* (the guard check names a guard's stop; a signal abandons the load step) */
    if (*passes == 0) PF_CALL(loaded(sim));
    PF_CALL(check_damage(sim, &failed));
    if (failed == 0) return 0;
    if (*passes == sim->solver.max_damage_passes) return too_many_passes(sim, failed);
  }
}

/* The load step's start: scratch, prescribed components, masses, the bodies' history committed,
 * the forces at the state reached (their applied part g0 and u0 for the work). */
static int begin(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  PF_CALL(scratch(s, p->n_owned));
  memset(s->fixed, 0, 3 * (size_t)p->n_owned);
  pf_sim_interactions_mark(sim, s->fixed);
  PF_CALL(body_bounds(sim));
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_history(&sim->body[b], sim->pts, PF_HISTORY_COMMIT));
  memcpy(s->u_last, p->u, sizeof(double) * 3 * (size_t)p->n_owned);
  memcpy(s->u0, p->u, sizeof(double) * 3 * (size_t)p->n_owned);
  PF_CALL(pf_sim_solver_evaluate(sim));
  for (pf_int d = 0; d < 3 * p->n_owned; d++) s->g0[d] = pf_sim_solver_applied(s, p, d);
  return 0;
}

/* The predictor: the free components move by the last load step's increment (exact for a linear
 * response to a load proportional to t; nothing at the first load step). */
static void predict(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  const double *inc = pf_points_field_get(p, PF_SOLVER_INCREMENT);
  for (pf_int d = 0; d < 3 * p->n_owned; d++)
    if (pf_sim_solver_is_free(s, d)) p->u[d] += inc[d], p->y[d] = p->X[d] + p->u[d];
}

/* The load step's end: the work of the reactions and loads over it into each body's external
 * work by the trapezoidal rule along its path, (g0 + g1) / 2 . (u1 - u0) to the first
 * equilibrium and (g1 + g) / 2 . (u - u1) past it (sequential failure: the legs of the scaled
 * path past it, s->beyond); after damage passes, what the relaxation's
 * damping took at the fixed load into relaxation_dissipation: the loads' work past the first
 * equilibrium less what the ledger holds more than there (docs/theory/quasi_static_failure.md §5.1); the
 * interactions' books at the equilibrium (the conditions' reactions, work and grip
 * displacements); the increment kept; the points at rest. Collective. */
static int finish(pf_sim *sim, long passes) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  double w[PF_MAX_BODIES] = {0}, *inc = pf_points_field_get(p, PF_SOLVER_INCREMENT), past = 0, now = 0;
  const pf_int n3 = 3 * p->n_owned;
  if (passes == 0) /* (the equilibrium is the first: the same bits as one segment) */
    for (pf_int d = 0; d < n3; d++) s->u1[d] = p->u[d], s->g1[d] = pf_sim_solver_applied(s, p, d);
  else PF_CALL(held(sim, &now));
  const double *path = s->sequential && passes ? s->beyond : NULL;
  if (path) pf_sim_solver_path_segment(sim);
  PF_CALL(pf_sim_interactions_settled(sim, sim->dt, s->g0, s->u0, passes ? s->g1 : NULL, passes ? s->u1 : NULL, path));
  for (pf_int d = 0; d < n3; d++) {
    const double g = pf_sim_solver_applied(s, p, d), to_first = 0.5 * (s->g0[d] + s->g1[d]) * (s->u1[d] - s->u0[d]);
    const double beyond = path ? path[d] : 0.5 * (s->g1[d] + g) * (p->u[d] - s->u1[d]);
    w[p->body[d / 3]] += to_first + beyond;
    past += beyond;
    inc[d] = p->u[d] - s->u0[d];
    p->v[d] = 0;
  }
  for (int b = 0; b < sim->nbodies; b++) pf_ledger_add(&sim->ledger, sim->acc.body_work[b], w[b]);
  if (passes > 0)
    pf_ledger_add(&sim->ledger, sim->acc.totals.relaxation, past - (pf_comm_rank() == 0) * (now - s->held1));
  return 0;
}

/* Every checkpointed point field over the owned points (the bodies' history, and what failing
 * bonds change besides their flags: an LPS point's lost weighted volume, for one) into v, or
 * back from it (restore 1); the doubles it takes. */
static size_t fields_kept(pf_points *p, double *v, int restore) {
  size_t m = 0;
  for (int k = 0; k < p->nfields; k++) {
    const pf_field *f = &p->fields[k];
    if (!(f->flags & PF_FIELD_RESTART)) continue;
    const size_t len = (size_t)f->ncomp * (size_t)p->n_owned;
    if (v && restore) memcpy(f->data, &v[m], sizeof(double) * len);
    else if (v) memcpy(&v[m], f->data, sizeof(double) * len);
    m += len;
  }
  return m;
}

/* The state a load step starts from besides the displacements (restore 0: kept), or put back
 * (restore 1): the bonds' failures, the checkpointed point fields and the ledger's bookings. */
static int start_state(pf_sim *sim, int restore) {
  pf_sim_solver *s = &sim->solver;
  const size_t nf = fields_kept(sim->pts, NULL, 0), n = nf + 3 * (size_t)sim->ledger.n;
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_failures(&sim->body[b], restore));
  if (restore) {
    PF_CHECK(s->kept && s->kept_n == n, PF_ERR_RUN, "quasi-static load step %ld: its start was not kept", sim->step);
  } else if (s->kept_n != n) {
    free(s->kept);
    s->kept_n = 0;
    PF_MALLOC(s->kept, n + 1);
    s->kept_n = n;
  }
  fields_kept(sim->pts, s->kept, restore);
  if (restore) pf_ledger_put_back(&sim->ledger, &s->kept[nf]);
  else pf_ledger_keep(&sim->ledger, &s->kept[nf]);
  return 0;
}

/* SIGTERM or SIGINT during a load step: back to the last equilibrium (the load step's start:
 * displacements, the bonds its damage passes failed, the point fields, the ledger's bookings, and
 * the forces, the bodies' history and fields evaluated there with the damage still frozen; step
 * and time), so that the checkpoint the time loop then writes, and the history row, are those of
 * the last load step; the restart takes this load step again, to the uninterrupted run's bits.
 * Collective (every rank stops at the same iteration: the signal is one of the iteration's sums). */
static int abandon(pf_sim *sim, long it, long passes) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  PF_CALL(start_state(sim, 1));
  pf_sim_interactions_place(sim, -sim->dt); /* (dt < 0: the surfaces go back) */
  for (pf_int d = 0; d < 3 * p->n_owned; d++) p->u[d] = s->u0[d], p->y[d] = p->X[d] + p->u[d];
  PF_CALL(pf_sim_solver_evaluate(sim));
  /* the history as committed at the load step's start, bit for bit: the evaluation just made
   * returned it through the model once more (a zero increment, round-off apart), and a restart
   * commits what the checkpoint holds */
  for (int b = 0; b < sim->nbodies; b++)
    if (pf_body_keeps_history(&sim->body[b], p)) PF_CALL(pf_body_history(&sim->body[b], p, PF_HISTORY_RESTORE));
  PF_CALL(freeze_damage(sim, 0));
  memset(p->v, 0, sizeof(double) * 3 * (size_t)p->n_owned);
  sim->step--;
  sim->t = (double)sim->step / (double)s->load_steps * sim->final_time;
  s->iterations += it;
  pf_log("load step %ld/%ld abandoned after %ld iterations and %ld damage passes: signal %d\n", sim->step + 1,
         s->load_steps, it, passes, pf_sim_signal_here());
  return pf_sim_guard_check(sim); /* (collective: sets sim->signal for the time loop's checkpoint) */
}

/* A load step stopped by the guard: a body tripped it (its rank's message is out), or the
 * out-of-balance force is no longer finite, the relaxation having diverged (the fictitious masses
 * do not bound the stiffness somewhere). Then the rank holding the point of the largest
 * out-of-balance force names it and trips the guard too. The guard's check puts back the load
 * step's start on every rank and stops the run. Collective. */
static int stopped(pf_sim *sim, long it) {
  const pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  struct { double f; int rank; } mine = {-1.0, pf_comm_rank()}, top;
  pf_int at = -1;
  for (pf_int i = 0; i < p->n_owned; i++) {
    double f2 = 0;
    for (int a = 0; a < 3; a++)
      if (pf_sim_solver_is_free(s, 3 * i + a)) f2 += p->f[3 * i + a] * p->f[3 * i + a];
    if (!(f2 <= mine.f)) mine.f = isfinite(f2) ? f2 : INFINITY, at = i; /* (NaN too) */
  }
  PF_CHECK(MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed naming the quasi-static solver's largest force");
  const int tripped = pf_max_all(sim->guard_tripped) > 0; /* (a body's guard: its message is out) */
  if (!tripped && top.rank == mine.rank && at >= 0) {
    sim->guard_tripped = 1;
    pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                   "quasi-static load step %ld of %ld (t = %g s): the out-of-balance force is not finite after %ld "
                   "iterations; the largest, %g N, is on point %" PF_GID_FMT " (body '%s') at (%g, %g, %g) m: the "
                   "relaxation diverged there (the fictitious masses do not bound its stiffness: lower "
                   "time.safety_factor; docs/theory/quasi_static.md section 2), or a prescribed motion or load is "
                   "too large",
                   sim->step, s->load_steps, sim->t, it, sqrt(mine.f), p->gid[at], sim->body_name[p->body[at]],
                   p->X[3 * at], p->X[3 * at + 1], p->X[3 * at + 2]);
  }
  return pf_sim_guard_check(sim);
}

static int progress(pf_sim *sim, long it, double res, long passes) {
  PF_CALL(pf_sim_accounts_evaluate(sim, 0)); /* (collective) the damage fraction */
  pf_log("load step %ld/%ld  t = %.4e s  iterations %ld  residual %.3e  damage passes %ld  damage %.4g\n",
         sim->step, sim->solver.load_steps, sim->t, it, res, passes,
         pf_sim_total(sim, sim->acc.totals.damage_fraction));
  return 0;
}

int pf_sim_solver_load_step(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  const double wall0 = pf_wtime();
  PF_CALL(pf_sim_guard_save(sim));
  PF_CALL(start_state(sim, 0));
  PF_CALL(freeze_damage(sim, 1)); /* (thawed at the load step's end: nothing re-attaches bodies within it) */
  PF_CALL(begin(sim));
  sim->step++;
  sim->t = (double)sim->step / (double)s->load_steps * sim->final_time;
  pf_sim_interactions_place(sim, sim->dt);
  if (s->sequential) PF_CALL(pf_sim_solver_proportional(sim));
  masses(sim);
  predict(sim);
  project(sim);
  long it = 0, passes = 0;
  double res = 0;
  int stop = 0;
  PF_CALL(equilibrate(sim, &it, &res, &passes, &stop));
  if (stop == STOP_SIGNAL) return abandon(sim, it, passes);
  if (stop == STOP_GUARD) PF_CALL(stopped(sim, it));
  PF_CALL(freeze_damage(sim, 0));
  s->iterations += it, s->damage_passes += passes;
  PF_CALL(finish(sim, passes));
  PF_CALL(pf_sim_guard_check(sim)); /* collective: a body that tripped, a non-finite force */
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_post_step(&sim->body[b], sim->pts));
  s->wall += pf_wtime() - wall0;
  return progress(sim, it, res, passes);
}
