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

int pf_sim_refresh_fixed_step(pf_sim *sim) {
  stable_step(sim);
  return 0;
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

/* Forces at the current positions; dt is the step just taken (0 for the initial forces: no
 * time has passed, so the element stresses must not advance). */
static int compute_forces(pf_sim *sim, double dt) {
  pf_points *p = sim->pts;
  double *yp;
  PF_CALL(pf_points_exchange_positions(p)); /* the ghosts' u and y */
  PF_CALL(previous_positions(p, &yp));
  int rates = 0; /* element and correspondence rates of deformation need the ghosts' v */
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    rates |= body->ops->uses_velocity && body->ops->uses_velocity(body->data);
  }
  if (rates) PF_CALL(pf_points_exchange(p, p->v, 3));
  memset(p->f, 0, sizeof(double) * 3 * (size_t)p->n_owned);
  for (int b = 0; b < sim->nbodies; b++) /* an inverted element trips the guard: the step's end decides */
    PF_CALL(sim->body[b].ops->force(sim->body[b].data, p, dt, sim->t, sim->step, &sim->guard_tripped));
  memcpy(yp, p->y, sizeof(double) * 3 * (size_t)p->n_total); /* (the ghosts' as exchanged) */
  for (int b = 0; b < sim->nbodies; b++) { /* the stored energy failed bonds took: total, moved part */
    double w[2] = {0, 0};
    if (sim->body[b].ops->take_damage_work) sim->body[b].ops->take_damage_work(sim->body[b].data, w);
    sim->damage_dissipation += w[0], sim->body_damage[b] += w[0];
    sim->damage_redistribution += w[1], sim->body_redistribution[b] += w[1];
  }
  PF_CALL(pf_sim_contact_forces(sim, dt)); /* rigid surfaces, pairs and walls */
  double w[PF_MAX_BODIES] = {0}; /* the body forces of the conditions, and their work */
  for (int k = 0; k < sim->nbcs; k++) pf_bc_apply_force(sim->bcs[k], p, sim->t, dt, w);
  for (int b = 0; b < sim->nbodies && sim->nbcs; b++) sim->bc_work += w[b], sim->body_bc_work[b] += w[b];
  return 0;
}

/* Each prescribed condition's reaction work on this rank's points, per body (body_bc_work) and
 * in all (bc_work); after_mid: the mid-step hook, else the end-of-step one. */
static void apply_bcs(pf_sim *sim, double dt, int after_mid) {
  double w[PF_MAX_BODIES] = {0};
  for (int k = 0; k < sim->nbcs; k++)
    if (after_mid) pf_bc_apply_midstep(sim->bcs[k], sim->pts, sim->t, dt, w);
    else pf_bc_apply_endstep(sim->bcs[k], sim->pts, sim->t, dt, w);
  for (int b = 0; b < sim->nbodies && sim->nbcs; b++) sim->bc_work += w[b], sim->body_bc_work[b] += w[b];
}

/* The walls put the points back on their plane and take their normal velocity (an impulse on
 * this rank's points, booked by the wall on the points it moves); they also take the normal part
 * of the points' force (the reaction: surface_impulses). */
static void enforce_walls(pf_sim *sim) {
  for (int k = 0; k < sim->nwalls; k++) pf_wall_enforce_position(sim->walls[k], sim->pts, &sim->wall_loss, sim->wall_impulse[k]);
}

/* The impulse the rigid surfaces and walls give the points in a half kick of dt/2, -(dt/2) R with
 * R their force on the surface or wall now (the same on every rank: rank 0 books it). */
static void surface_impulses(pf_sim *sim, double dt) {
  if (pf_comm_rank() != 0) return;
  for (int k = 0; k < sim->nrigid; k++)
    for (int a = 0; a < 3; a++) sim->rigid_impulse[k][a] -= 0.5 * dt * sim->reaction[k][a];
  for (int k = 0; k < sim->nwalls; k++)
    for (int a = 0; a < 3; a++) sim->wall_impulse[k][a] -= 0.5 * dt * sim->wall_reaction[k][a];
}

static int one_step(pf_sim *sim) {
  pf_points *p = sim->pts;
  next_dt(sim);
  const double dt = sim->dt;
  PF_CALL(pf_sim_guard_save(sim));
  half_kick(p, dt);
  surface_impulses(sim, dt);
  apply_bcs(sim, dt, 1);
  drift(p, dt);
  pf_sim_guard_motion(sim, dt);
  enforce_walls(sim);
  for (int k = 0; k < sim->nrigid; k++) {
    double w = 0;
    pf_rigid_advance(sim->rigid[k], sim->t, dt, sim->reaction[k], &w);
    sim->external_work += w, sim->rigid_work[k] += w;
  }
  sim->t += dt;
  sim->step++;
  PF_CALL(compute_forces(sim, dt));
  half_kick(p, dt);
  surface_impulses(sim, dt);
  apply_bcs(sim, dt, 0);
  PF_CALL(pf_sim_guard_check(sim)); /* collective: every rank stops, back at the last good state */
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->post_step) PF_CALL(sim->body[b].ops->post_step(sim->body[b].data, p));
  return pf_sim_convert_elements(sim); /* (elements deleted in the step become particles) */
}

int pf_sim_step(pf_sim *sim, long n) {
  if (sim->step == 0 && sim->t == 0) PF_CALL(compute_forces(sim, 0.0));
  for (long s = 0; s < n; s++) PF_CALL(one_step(sim));
  return 0;
}

/* The sums of pf_sim_globals_get, this rank's then all ranks': the global ones (S_*), then
 * PF_BODY_SUMS per body, 6 per prescribed condition (its last step's impulse, its impulse since
 * the start), 3 per rigid surface and 3 per wall (their impulses). One reduction for all. */
enum { S_KE, S_KC, S_EL, S_FEINT, S_HG, S_BV, S_WALL, S_CDISS, S_DAMAGE, S_REDIST, S_BCW, S_PX, S_PY, S_PZ,
       S_BONDS, S_BROKEN, S_CONV, S_N };

int pf_sim_sums_count(const pf_sim *sim) {
  return S_N + PF_BODY_SUMS * sim->nbodies + 6 * sim->nbcs + 3 * (sim->nrigid + sim->nwalls);
}

/* Body b's kinetic energy and momentum into x[PF_BODY_KE] and x[PF_BODY_PX ..], and its part of
 * the centred kinetic energy into *kc (a prescribed component's force, marked in fixed, is a
 * reaction, not an acceleration: it does not enter the centred kinetic energy). */
static void body_motion_sums(const pf_sim *sim, int b, const uint8_t *fixed, double *x, double *kc) {
  const pf_points *p = sim->pts;
  const double h = 0.5 * sim->dt;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++)
    for (int a = 0; a < 3; a++) {
      double v = p->v[3 * i + a], acc = fixed[3 * i + a] || !(p->m[i] > 0) ? 0 : p->f[3 * i + a] / p->m[i];
      x[PF_BODY_KE] += 0.5 * p->m[i] * v * v;
      *kc += 0.5 * p->m[i] * (v * v - h * h * acc * acc);
      x[PF_BODY_PX + a] += p->m[i] * v;
    }
}

int pf_sim_globals_get(pf_sim *sim, pf_sim_globals *g) {
  memset(g, 0, sizeof *g);
  const pf_points *p = sim->pts;
  const int n = pf_sim_sums_count(sim);
  double *s;
  PF_MALLOC(s, n);
  uint8_t *fixed = calloc(3 * (size_t)p->n_owned + 1, 1);
  if (!fixed) free(s);
  PF_CHECK(fixed, PF_ERR_MEMORY, "out of memory");
  for (int k = 0; k < sim->nbcs; k++) pf_bc_mark(sim->bcs[k], fixed);
  for (int b = 0; b < sim->nbodies; b++) {
    double *x = &s[S_N + PF_BODY_SUMS * b];
    pf_body_energies e;
    sim->body[b].ops->energies(sim->body[b].data, sim->pts, &e);
    sim->health.local[b] = e; /* the run-health monitor's per-body figures */
    body_motion_sums(sim, b, fixed, x, &s[S_KC]);
    x[PF_BODY_INTERNAL] = e.elastic + e.fe[0], x[PF_BODY_HG] = e.fe[1], x[PF_BODY_VISCOUS] = e.fe[2];
    x[PF_BODY_DAMAGE] = sim->body_damage[b] - sim->body_redistribution[b];
    x[PF_BODY_REDIST] = sim->body_redistribution[b];
    x[PF_BODY_WEXT] = sim->body_bc_work[b];
    s[S_KE] += x[PF_BODY_KE], s[S_EL] += e.elastic, s[S_FEINT] += e.fe[0], s[S_HG] += e.fe[1], s[S_BV] += e.fe[2];
    for (int a = 0; a < 3; a++) s[S_PX + a] += x[PF_BODY_PX + a];
    s[S_BONDS] += e.bonds, s[S_BROKEN] += e.broken, s[S_CONV] += e.converted;
  }
  free(fixed);
  s[S_WALL] = sim->wall_loss, s[S_CDISS] = sim->contact_dissipation;
  s[S_DAMAGE] = sim->damage_dissipation - sim->damage_redistribution, s[S_REDIST] = sim->damage_redistribution;
  s[S_BCW] = sim->bc_work;
  double *x = &s[S_N + PF_BODY_SUMS * sim->nbodies];
  for (int k = 0; k < sim->nbcs; k++, x += 6) pf_bc_impulse(sim->bcs[k], x, x + 3);
  for (int k = 0; k < sim->nrigid; k++, x += 3) memcpy(x, sim->rigid_impulse[k], sizeof(double[3]));
  for (int k = 0; k < sim->nwalls; k++, x += 3) memcpy(x, sim->wall_impulse[k], sizeof(double[3]));
  free(sim->row_sums);
  sim->row_sums = s;
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, s, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed summing the history's quantities");
  g->time = sim->t;
  g->kinetic = s[S_KE];
  g->kinetic_centred = s[S_KC];
  g->elastic = s[S_EL];
  g->fe_internal = s[S_FEINT];
  g->hourglass = s[S_HG];
  g->bulk_viscosity = s[S_BV];
  g->wall_loss = s[S_WALL];
  g->contact = sim->contact_energy;
  g->contact_dissipation = s[S_CDISS];
  g->damage_dissipation = s[S_DAMAGE];
  g->damage_redistribution = s[S_REDIST];
  g->conversion_loss = s[S_CONV];
  g->external_work = sim->external_work + s[S_BCW];
  for (int a = 0; a < 3; a++) g->momentum[a] = s[S_PX + a];
  g->damage_fraction = s[S_BONDS] > 0 ? s[S_BROKEN] / s[S_BONDS] : 0;
  return 0;
}

const double *pf_sim_row_sums(const pf_sim *sim) { return sim->row_sums ? sim->row_sums + S_N : NULL; }

uint64_t pf_sim_digest(pf_sim *sim) {
  uint64_t h = 0;
  if (pf_state_digest(sim->pts, &h)) return 0;
  return h;
}
