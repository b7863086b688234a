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

static int step_varies(const pf_body *body) {
  return body->ops->step_varies && body->ops->step_varies(body->data);
}

/* The stable step of the bodies whose step changes as they deform (FE elements, correspondence
 * points), now. */
static double varying_step(pf_sim *sim) {
  double dt = INFINITY;
  for (int b = 0; b < sim->nbodies; b++)
    if (step_varies(&sim->body[b])) dt = fmin(dt, sim->body[b].ops->stable_dt(sim->body[b].data, sim->pts));
  return dt;
}

/* The stable step of the set-up: the fixed one of the other bodies and of the contact penalties
 * (kept in pd_stable), and the varying bodies' in their reference shape. Collective. */
static double stable_step(pf_sim *sim) {
  double fixed = INFINITY;
  for (int b = 0; b < sim->nbodies; b++)
    if (!step_varies(&sim->body[b])) fixed = fmin(fixed, sim->body[b].ops->stable_dt(sim->body[b].data, sim->pts));
  sim->pd_stable = fmin(pf_min_all(fixed), pf_sim_contact_stable_dt(sim)); /* with the penalties' */
  return fmin(sim->pd_stable, pf_min_all(varying_step(sim)));
}

int pf_sim_setup_time(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *tm = pf_node_get(pf_deck_root(d), "time");
  double safety = 0.8;
  PF_CALL(pf_deck_real(d, tm, "safety_factor", &safety));
  sim->max_motion = 0.5;
  PF_CALL(pf_deck_real(d, tm, "max_motion", &sim->max_motion));
  if (!(sim->max_motion > 0))
    return pf_deck_error(d, pf_node_get(tm, "max_motion"), "max_motion", "must be positive (got %g)", sim->max_motion);
  if (!(safety > 0 && safety <= 1))
    return pf_deck_error(d, pf_node_get(tm, "safety_factor"), "safety_factor", "must be in (0, 1] (got %g)", safety);
  double stable = stable_step(sim);
  sim->safety = safety;
  sim->dt = safety * stable;
  int varies = 0; /* FE elements and correspondence points change their stable step */
  for (int b = 0; b < sim->nbodies; b++) varies |= step_varies(&sim->body[b]);
  sim->adaptive = varies && !pf_node_get(tm, "dt");
  if (pf_node_get(tm, "dt")) {
    PF_CALL(pf_deck_real(d, tm, "dt", &sim->dt));
    if (!(sim->dt > 0)) return pf_deck_error(d, pf_node_get(tm, "dt"), "dt", "must be positive (got %g)", sim->dt);
    if (sim->dt > stable)
      pf_log("warning: dt = %g s exceeds the stable step %g s\n", sim->dt, stable);
  }
  int hf = pf_node_get(tm, "final_time") != NULL, hs = pf_node_get(tm, "steps") != NULL;
  if (hf == hs) return pf_deck_error(d, tm, "final_time", "give exactly one of 'final_time' and 'steps'");
  if (hs) {
    PF_CALL(pf_deck_int(d, tm, "steps", &sim->nsteps));
    if (sim->nsteps < 0) return pf_deck_error(d, pf_node_get(tm, "steps"), "steps", "must not be negative");
    sim->final_time = sim->nsteps * sim->dt;
  } else {
    PF_CALL(pf_deck_real(d, tm, "final_time", &sim->final_time));
    if (!(sim->final_time >= 0))
      return pf_deck_error(d, pf_node_get(tm, "final_time"), "final_time", "must not be negative");
    sim->nsteps = (long)ceil(sim->final_time / sim->dt - 1e-9);
  }
  if (hs) sim->final_time = INFINITY; /* a step count: adaptive steps end by count */
  return 0;
}

/* The step to take next: with FE or correspondence bodies, the safety factor times the
 * smallest of the fixed PD step, the correspondence points' and the elements' current stable
 * step (bulk viscosity included). The run ends with the first
 * step that reaches final_time (as with a fixed step: the last step is not cut short, which
 * would change the step abruptly). The minimum over ranks keeps every rank on the same step.
 * Collective. */
static void next_dt(pf_sim *sim) {
  if (!sim->adaptive) return;
  sim->dt = sim->safety * fmin(sim->pd_stable, pf_min_all(varying_step(sim)));
}

int pf_sim_finished(const pf_sim *sim) {
  if (sim->adaptive && isfinite(sim->final_time)) return sim->t >= sim->final_time * (1 - 1e-12);
  return sim->step >= sim->nsteps;
}

void pf_sim_output_name(const pf_sim *sim, const char *given, const char *ext, char *out, size_t len) {
  char base[2048];
  if (given) snprintf(base, sizeof base, "%s", given);
  else {
    const char *p = pf_deck_path(sim->deck), *slash = strrchr(p, '/'), *name = slash ? slash + 1 : p;
    const char *dot = strrchr(name, '.');
    snprintf(base, sizeof base, "%.*s%s", (int)(dot ? dot - name : (long)strlen(name)), name, ext);
  }
  if (sim->opt.output_dir && base[0] != '/') snprintf(out, len, "%s/%s", sim->opt.output_dir, base);
  else snprintf(out, len, "%s", base);
}

int pf_sim_setup_output(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *out = pf_node_get(pf_deck_root(d), "output");
  const char *file = NULL, *hfile = NULL;
  sim->output_interval = 100;
  sim->history_interval = 10;
  PF_CALL(pf_deck_string(d, out, "file", &file));
  PF_CALL(pf_deck_string(d, out, "history_file", &hfile));
  PF_CALL(pf_deck_int(d, out, "interval", &sim->output_interval));
  PF_CALL(pf_deck_int(d, out, "history_interval", &sim->history_interval));
  PF_CALL(pf_deck_bool(d, out, "fragments", &sim->fragments));
  PF_CALL(pf_sim_fragments_setup(sim));
  PF_CALL(pf_sim_setup_probes(sim));
  if (sim->output_interval < 0)
    return pf_deck_error(d, pf_node_get(out, "interval"), "interval", "must not be negative");
  if (sim->history_interval < 1)
    return pf_deck_error(d, pf_node_get(out, "history_interval"), "history_interval", "must be at least 1");
  pf_sim_output_name(sim, file, ".e", sim->exodus_path, sizeof sim->exodus_path);
  pf_sim_output_name(sim, hfile, ".h5", sim->history_path, sizeof sim->history_path);
  return pf_sim_setup_exodus_format(sim, out);
}

static void half_kick(pf_points *p, double dt) {
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double s = 0.5 * dt / p->m[i];
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

/* Forces at the current positions; dt is the step just taken (0 for the initial forces: no
 * time has passed, so the element stresses must not advance). */
static int compute_forces(pf_sim *sim, double dt) {
  pf_points *p = sim->pts;
  PF_CALL(pf_points_exchange_positions(p)); /* the ghosts' u and y */
  int rates = 0; /* element and correspondence rates of deformation need the ghosts' v */
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    rates |= body->ops->uses_velocity && body->ops->uses_velocity(body->data);
  }
  if (rates) PF_CALL(pf_points_exchange(p, p->v, 3));
  memset(p->f, 0, sizeof(double) * 3 * (size_t)p->n_owned);
  for (int b = 0; b < sim->nbodies; b++) /* an inverted element trips the guard: the step's end decides */
    PF_CALL(sim->body[b].ops->force(sim->body[b].data, p, dt, sim->t, sim->step, &sim->guard_tripped));
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->take_damage_work) sim->damage_dissipation += sim->body[b].ops->take_damage_work(sim->body[b].data);
  PF_CALL(pf_sim_contact_forces(sim, dt)); /* rigid surfaces, pairs and walls */
  return 0;
}

static int one_step(pf_sim *sim) {
  pf_points *p = sim->pts;
  next_dt(sim);
  const double dt = sim->dt;
  PF_CALL(pf_sim_guard_save(sim));
  half_kick(p, dt);
  for (int k = 0; k < sim->nbcs; k++) pf_bc_apply_midstep(sim->bcs[k], p, sim->t, dt, &sim->bc_work);
  drift(p, dt);
  pf_sim_guard_motion(sim, dt);
  for (int k = 0; k < sim->nwalls; k++) pf_wall_enforce_position(sim->walls[k], p, &sim->wall_loss);
  for (int k = 0; k < sim->nrigid; k++)
    pf_rigid_advance(sim->rigid[k], sim->t, dt, sim->reaction[k], &sim->external_work);
  sim->t += dt;
  sim->step++;
  PF_CALL(compute_forces(sim, dt));
  half_kick(p, dt);
  for (int k = 0; k < sim->nbcs; k++) pf_bc_apply_endstep(sim->bcs[k], p, sim->t, dt, &sim->bc_work);
  PF_CALL(pf_sim_guard_check(sim)); /* collective: every rank stops, back at the last good state */
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->post_step) PF_CALL(sim->body[b].ops->post_step(sim->body[b].data, p));
  return 0;
}

int pf_sim_step(pf_sim *sim, long n) {
  if (sim->step == 0 && sim->t == 0) PF_CALL(compute_forces(sim, 0.0));
  for (long s = 0; s < n; s++) PF_CALL(one_step(sim));
  return 0;
}

int pf_sim_globals_get(pf_sim *sim, pf_sim_globals *g) {
  memset(g, 0, sizeof *g);
  const pf_points *p = sim->pts;
  /* a prescribed component's force is a reaction, not an acceleration: it does not enter the
   * centred kinetic energy */
  uint8_t *fixed = calloc(3 * (size_t)p->n_owned + 1, 1);
  PF_CHECK(fixed, PF_ERR_MEMORY, "out of memory");
  for (int k = 0; k < sim->nbcs; k++) pf_bc_mark(sim->bcs[k], fixed);
  double ke = 0, kc = 0, mom[3] = {0, 0, 0}, h = 0.5 * sim->dt;
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int a = 0; a < 3; a++) {
      double v = p->v[3 * i + a], acc = fixed[3 * i + a] ? 0 : p->f[3 * i + a] / p->m[i];
      ke += 0.5 * p->m[i] * v * v;
      kc += 0.5 * p->m[i] * (v * v - h * h * acc * acc);
      mom[a] += p->m[i] * v;
    }
  free(fixed);
  double el = 0, nb = 0, nbroken = 0, fe[3] = {0, 0, 0};
  for (int b = 0; b < sim->nbodies; b++) {
    pf_body_energies e;
    sim->body[b].ops->energies(sim->body[b].data, sim->pts, &e);
    sim->health.local[b] = e; /* the run-health monitor's per-body figures */
    el += e.elastic, nb += e.bonds, nbroken += e.broken;
    for (int c = 0; c < 3; c++) fe[c] += e.fe[c];
  }
  g->time = sim->t;
  g->kinetic = pf_sum_all(ke);
  g->kinetic_centred = pf_sum_all(kc);
  g->elastic = pf_sum_all(el);
  g->fe_internal = pf_sum_all(fe[0]);
  g->hourglass = pf_sum_all(fe[1]);
  g->bulk_viscosity = pf_sum_all(fe[2]);
  g->wall_loss = pf_sum_all(sim->wall_loss);
  g->contact = sim->contact_energy;
  g->contact_dissipation = pf_sum_all(sim->contact_dissipation);
  g->damage_dissipation = pf_sum_all(sim->damage_dissipation);
  g->external_work = sim->external_work + pf_sum_all(sim->bc_work);
  for (int a = 0; a < 3; a++) g->momentum[a] = pf_sum_all(mom[a]);
  nb = pf_sum_all(nb);
  g->damage_fraction = nb > 0 ? pf_sum_all(nbroken) / nb : 0;
  return 0;
}

uint64_t pf_sim_digest(pf_sim *sim) {
  uint64_t h = 0;
  if (pf_state_digest(sim->pts, &h)) return 0;
  return h;
}
