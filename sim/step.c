/* The time loop (docs/architecture.md §3): explicit velocity Verlet,
 *   v(t+dt/2) = v(t) + dt/2 a(t);  u(t+dt) = u(t) + dt v(t+dt/2);
 *   f(t+dt) from PD bodies, FE bodies, contact and walls;  v(t+dt) = v(t+dt/2) + dt/2 a(t+dt),
 * with prescribed motions applied to the mid-step velocity, walls to the new positions, a step
 * that follows the FE elements' and correspondence points' stable step, and the instability guards
 * (sim/guard.c). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The stable step of the bodies whose step changes as they deform (FE elements, correspondence
 * points), now. */
static double varying_step(pf_sim *sim) {
  double dt = INFINITY;
  for (int b = 0; b < sim->nbodies; b++)
    if (pf_body_step_varies(&sim->body[b])) dt = fmin(dt, sim->body[b].ops->stable_dt(sim->body[b].data, sim->pts));
  return dt;
}

/* The stable step of the set-up: the fixed one of the other bodies and of the contact penalties
 * (kept in pd_stable), and the varying bodies' in their reference shape. Collective. */
static double stable_step(pf_sim *sim) {
  double fixed = INFINITY;
  for (int b = 0; b < sim->nbodies; b++)
    if (!pf_body_step_varies(&sim->body[b])) fixed = fmin(fixed, sim->body[b].ops->stable_dt(sim->body[b].data, sim->pts));
  sim->pd_stable = fmin(pf_min_all(fixed), pf_sim_interactions_stable_dt(sim)); /* with the penalties' */
  return fmin(sim->pd_stable, pf_min_all(varying_step(sim)));
}

int pf_sim_refresh_fixed_step(pf_sim *sim) {
  stable_step(sim);
  return 0;
}

/* The most steps a run may take: far beyond any run that ends, and well inside a long and a
 * double's exact integers, so that the step count and step * dt neither overflow nor round. */
#define PF_MAX_STEPS 1e12

int pf_sim_check_time_keys(const pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *tm = pf_node_get(pf_deck_root(d), "time");
  double safety = 0.8, motion = 0.5, dt = 1, final_time = 0;
  PF_CALL(pf_deck_real(d, tm, "safety_factor", &safety));
  PF_CALL(pf_deck_real(d, tm, "max_motion", &motion));
  if (!(motion > 0)) return pf_deck_error(d, pf_node_get(tm, "max_motion"), "max_motion", "must be positive (got %g)", motion);
  if (!(safety > 0 && safety <= 1))
    return pf_deck_error(d, pf_node_get(tm, "safety_factor"), "safety_factor", "must be in (0, 1] (got %g)", safety);
  if (pf_node_get(tm, "dt")) {
    PF_CALL(pf_deck_real(d, tm, "dt", &dt));
    if (!(dt > 0)) return pf_deck_error(d, pf_node_get(tm, "dt"), "dt", "must be positive (got %g)", dt);
  }
  const int hf = pf_node_get(tm, "final_time") != NULL, hs = pf_node_get(tm, "steps") != NULL;
  if (hf == hs) return pf_deck_error(d, tm, "final_time", "give exactly one of 'final_time' and 'steps'");
  if (hs) {
    long steps;
    PF_CALL(pf_deck_int(d, tm, "steps", &steps));
    if (steps < 0) return pf_deck_error(d, pf_node_get(tm, "steps"), "steps", "must not be negative");
    if (steps > PF_MAX_STEPS)
      return pf_deck_error(d, pf_node_get(tm, "steps"), "steps", "%ld steps: at most %.0e are allowed", steps,
                           PF_MAX_STEPS);
    return 0;
  }
  PF_CALL(pf_deck_real(d, tm, "final_time", &final_time));
  if (!(final_time >= 0 && isfinite(final_time)))
    return pf_deck_error(d, pf_node_get(tm, "final_time"), "final_time", "must be finite and not negative (got %g)",
                         final_time);
  return 0;
}

int pf_sim_setup_time(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *tm = pf_node_get(pf_deck_root(d), "time");
  double safety = 0.8;
  PF_CALL(pf_deck_real(d, tm, "safety_factor", &safety));
  sim->max_motion = 0.5;
  PF_CALL(pf_deck_real(d, tm, "max_motion", &sim->max_motion));
  PF_CALL(pf_sim_interactions_fit_step(sim)); /* (soft contact pairs: from the bodies' steps) */
  double stable = stable_step(sim);
  sim->safety = safety;
  sim->dt = safety * stable;
  int varies = 0; /* FE elements and correspondence points change their stable step */
  for (int b = 0; b < sim->nbodies; b++) varies |= pf_body_step_varies(&sim->body[b]);
  sim->adaptive = varies && !pf_node_get(tm, "dt");
  if (pf_node_get(tm, "dt")) {
    PF_CALL(pf_deck_real(d, tm, "dt", &sim->dt));
    if (sim->dt > stable)
      pf_log("warning: dt = %g s exceeds the stable step %g s\n", sim->dt, stable);
  }
  if (!(sim->dt > 0 && isfinite(sim->dt))) {
    const char *key = pf_node_get(tm, "dt") ? "dt" : "safety_factor";
    return pf_deck_error(d, pf_node_get(tm, key) ? pf_node_get(tm, key) : tm, key,
                         "the time step is %g s (the stable step %g s): it must be a positive finite number; check the "
                         "materials' moduli and densities, or give time.dt",
                         sim->dt, stable);
  }
  const int hs = pf_node_get(tm, "steps") != NULL; /* (one of the two: pf_sim_check_time_keys) */
  if (hs) {
    PF_CALL(pf_deck_int(d, tm, "steps", &sim->nsteps));
    sim->final_time = sim->nsteps * sim->dt;
  } else {
    PF_CALL(pf_deck_real(d, tm, "final_time", &sim->final_time));
    const double n = ceil(sim->final_time / sim->dt - 1e-9);
    /* (a quasi-static run takes solver.load_steps steps over its pseudo-time, whatever the stable step) */
    const char *solver = "explicit";
    PF_CALL(pf_deck_string(d, pf_node_get(pf_deck_root(d), "solver"), "type", &solver));
    if (!(n <= PF_MAX_STEPS) && strcmp(solver, "quasi_static")) {
      /* blame the key that made the count large: a tiny step given or chosen, else the end time */
      const char *key = pf_node_get(tm, "dt") ? "dt" : (safety < 1e-6 ? "safety_factor" : "final_time");
      return pf_deck_error(d, pf_node_get(tm, key), key,
                           "the run would take %.3g steps (final_time / dt = %g s / %g s): at most %.0e are allowed",
                           n, sim->final_time, sim->dt, PF_MAX_STEPS);
    }
    sim->nsteps = n <= PF_MAX_STEPS ? (long)n : 0; /* (quasi-static: set from load_steps later) */
  }
  if (hs) sim->final_time = INFINITY; /* a step count: adaptive steps end by count */
  return 0;
}

/* The step to take next: with FE or correspondence bodies, the safety factor times the
 * smallest of the fixed PD step, the correspondence points' and the elements' current stable
 * step (bulk viscosity included). The run ends with the first
 * step that reaches final_time (as with a fixed step: the last step is not cut short, which
 * would change the step abruptly). When no body bounds the step any more (each of its points
 * detached), the last one stays. The minimum over ranks keeps every rank on the same step.
 * Collective. */
static void next_dt(pf_sim *sim) {
  if (!sim->adaptive) return;
  const double stable = fmin(sim->pd_stable, pf_min_all(varying_step(sim)));
  if (isfinite(stable)) sim->dt = sim->safety * stable; /* (else nothing left bounds it: every point
                                                           detached, say; the step stays) */
}

int pf_sim_finished(const pf_sim *sim) {
  if (sim->adaptive && isfinite(sim->final_time)) return sim->t >= sim->final_time * (1 - 1e-12);
  return sim->step >= sim->nsteps;
}

static void half_kick(pf_points *p, double dt) {
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double s = p->m[i] > 0 ? 0.5 * dt / p->m[i] : 0; /* (mass 0: a dormant particle, a node all of whose elements converted) */
    for (int a = 0; a < 3; a++) p->v[3 * i + a] += s * p->f[3 * i + a];
  }
}

static void drift(pf_points *p, double dt) {
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < 3 * p->n_owned; i++) {
    p->u[i] += dt * p->v[i];
    p->y[i] = p->X[i] + p->u[i];
  }
}

/* The positions of the last force evaluation (PF_PREVIOUS_POSITIONS), for the PD kernels' booking
 * of failing bonds: registered at the first evaluation of a run, or read from its checkpoint
 * (one written before they were kept restarts with the current positions: the end-of-step
 * booking for its first step). */
static int previous_positions(pf_points *p, double **yp) {
  *yp = pf_points_field_get(p, PF_PREVIOUS_POSITIONS);
  if (*yp) return 0;
  int idx;
  PF_CALL(pf_points_field_register(p, PF_PREVIOUS_POSITIONS, 3, PF_FIELD_GHOST | PF_FIELD_RESTART, &idx));
  *yp = p->fields[idx].data;
  memcpy(*yp, p->y, sizeof(double) * 3 * (size_t)p->n_total);
  return 0;
}

/* The bodies' forces at the current positions (f set to them); dt is the step just taken (0 for
 * the initial forces: no time has passed, so the element stresses must not advance); ahead: the
 * interactions' prepare once the ghosts have their positions. */
int pf_sim_body_forces(pf_sim *sim, double dt, int ahead) {
  pf_points *p = sim->pts;
  double *yp;
  PF_CALL(pf_points_exchange_positions(p)); /* the ghosts' u and y */
  if (ahead) PF_CALL(pf_sim_interactions_prepare(sim, dt));
  PF_CALL(previous_positions(p, &yp));
  int rates = 0; /* element and correspondence rates of deformation need the ghosts' v */
  for (int b = 0; b < sim->nbodies; b++) rates |= pf_body_uses_velocity(&sim->body[b]);
  if (rates) PF_CALL(pf_points_exchange(p, p->v, 3));
  memset(p->f, 0, sizeof(double) * 3 * (size_t)p->n_owned);
  for (int b = 0; b < sim->nbodies; b++) /* an inverted element trips the guard: the step's end decides */
    PF_CALL(sim->body[b].ops->force(sim->body[b].data, p, dt, sim->t, sim->step, &sim->guard_tripped));
  memcpy(yp, p->y, sizeof(double) * 3 * (size_t)p->n_total); /* (the ghosts' as exchanged) */
  pf_sim_accounts_book_damage(sim); /* the stored energy failed bonds took */
  return 0;
}

/* Forces at the current positions: the bodies', then the interactions' (their search ahead of the
 * bodies', so that its exchanges do not wait for the rank whose bodies take longest). */
static int compute_forces(pf_sim *sim, double dt) {
  PF_CALL(pf_sim_body_forces(sim, dt, 1));
  return pf_sim_interactions_force(sim, dt, NULL);
}

/* One velocity-Verlet step; the interactions' hooks in their places (sim/interaction.h). */
static int one_step(pf_sim *sim) {
  pf_points *p = sim->pts;
  next_dt(sim);
  const double dt = sim->dt;
  PF_CALL(pf_sim_guard_save(sim));
  half_kick(p, dt);
  pf_sim_interactions_midstep(sim, dt);
  drift(p, dt);
  pf_sim_guard_motion(sim, dt);
  pf_sim_interactions_after_drift(sim, dt);
  sim->t += dt;
  sim->step++;
  PF_CALL(compute_forces(sim, dt));
  half_kick(p, dt);
  pf_sim_interactions_endstep(sim, dt);
  PF_CALL(pf_sim_guard_check(sim)); /* collective: every rank stops, back at the last good state */
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_post_step(&sim->body[b], p));
  long converted; /* (elements deleted in the step become particles) */
  PF_CALL(pf_sim_convert_elements(sim, &converted));
  return converted ? pf_sim_refresh_fixed_step(sim) : 0; /* (the nodes are lighter, the new particles in contact) */
}

int pf_sim_step(pf_sim *sim, long n) {
  if (sim->step == 0 && sim->t == 0) PF_CALL(compute_forces(sim, 0.0));
  for (long s = 0; s < n; s++) PF_CALL(sim->solver.load_step ? sim->solver.load_step(sim) : one_step(sim));
  return 0;
}

int pf_sim_globals_get(pf_sim *sim, pf_sim_globals *g) {
  memset(g, 0, sizeof *g);
  PF_CALL(pf_sim_accounts_evaluate(sim, 0));
  const pf_sim_totals *T = &sim->acc.totals;
  double kc = 0; /* the centred kinetic energy, the bodies' parts */
  for (int b = 0; b < sim->nbodies; b++) kc += pf_ledger_value(&sim->ledger, sim->acc.body[b].centred, 0);
  g->time = sim->t;
  g->kinetic = pf_sim_total(sim, T->kinetic);
  g->kinetic_centred = kc;
  g->elastic = pf_sim_total(sim, T->elastic);
  g->fe_internal = pf_sim_total(sim, T->fe_internal);
  g->hourglass = pf_sim_total(sim, T->hourglass);
  g->bulk_viscosity = pf_sim_total(sim, T->viscous);
  g->wall_loss = pf_sim_total(sim, T->wall);
  g->contact = pf_sim_total(sim, T->contact);
  g->contact_dissipation = pf_sim_total(sim, T->contact_dissipation);
  g->damage_dissipation = pf_sim_total(sim, T->damage);
  g->damage_redistribution = pf_sim_total(sim, T->redistribution);
  g->conversion_loss = pf_sim_total(sim, T->conversion);
  g->external_work = pf_sim_total(sim, T->work);
  for (int a = 0; a < 3; a++) g->momentum[a] = pf_ledger_value(&sim->ledger, T->momentum, a);
  g->damage_fraction = pf_sim_total(sim, T->damage_fraction);
  return 0;
}

uint64_t pf_sim_digest(pf_sim *sim) {
  uint64_t h = 0;
  if (pf_state_digest(sim->pts, &h)) return 0;
  return h;
}
