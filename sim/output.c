/* Running a simulation with its output: Exodus fields at the output interval, the HDF5
 * history of global quantities, the progress line, the end-of-run summary and the digest. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { G_KE, G_EL, G_CONTACT, G_WEXT, G_EERR, G_PX, G_PY, G_PZ, G_DAMAGE,
       G_FEINT, G_HG, G_BV, G_WALL, G_CDISS, G_DDISS, G_FIXED };
static const char *const fixed_names[G_FIXED] = {
    "kinetic_energy", "elastic_energy", "contact_energy", "external_work", "energy_error",
    "momentum_x",     "momentum_y",     "momentum_z",     "damage_fraction",
    "fe_internal_energy", "hourglass_energy", "bulk_viscosity_work", "wall_dissipation", "contact_dissipation",
    "damage_dissipation"};
static const char *const fixed_units[G_FIXED] = {"J", "J", "J", "J", "J", "kg m/s", "kg m/s", "kg m/s", "",
                                                 "J", "J", "J", "J", "J", "J"};

typedef struct {
  int n;
  char **names;
  const char **units;
  double *values;
  double e0; /* initial total energy */
  int body0, probe0; /* the columns (after time and step) where the bodies' and the probes' start */
} globals;

static int globals_init(const pf_sim *sim, globals *g) {
  int npairs = pf_contact_npairs(sim->contact);
  const int body0 = g->body0 = G_FIXED + 3 * (sim->nrigid + sim->nwalls + npairs);
  const int probe0 = g->probe0 = body0 + 6 * sim->nbodies;
  g->n = probe0 + pf_sim_probe_columns(sim);
  PF_MALLOC(g->names, g->n + 2);
  PF_MALLOC(g->units, g->n + 2);
  PF_MALLOC(g->values, g->n + 2);
  /* history columns: time, step, then the globals */
  g->names[0] = strdup("time"), g->units[0] = "s";
  g->names[1] = strdup("step"), g->units[1] = "";
  for (int k = 0; k < G_FIXED; k++) g->names[2 + k] = strdup(fixed_names[k]), g->units[2 + k] = fixed_units[k];
  for (int k = 0; k < sim->nrigid; k++)
    for (int a = 0; a < 3; a++) {
      char buf[128];
      snprintf(buf, sizeof buf, "%s_force_%c", pf_rigid_name(sim->rigid[k]), 'x' + a);
      g->names[2 + G_FIXED + 3 * k + a] = strdup(buf);
      g->units[2 + G_FIXED + 3 * k + a] = "N";
    }
  for (int k = 0; k < sim->nwalls; k++)
    for (int a = 0; a < 3; a++) {
      char buf[128];
      int j = 2 + G_FIXED + 3 * sim->nrigid + 3 * k + a;
      snprintf(buf, sizeof buf, "%s_force_%c", pf_wall_name(sim->walls[k]), 'x' + a);
      g->names[j] = strdup(buf);
      g->units[j] = "N";
    }
  for (int k = 0; k < npairs; k++)
    for (int a = 0; a < 3; a++) {
      char buf[128];
      int j = 2 + G_FIXED + 3 * (sim->nrigid + sim->nwalls + k) + a;
      snprintf(buf, sizeof buf, "%s_force_%c", pf_contact_pair_name(sim->contact, k), 'x' + a);
      g->names[j] = strdup(buf);
      g->units[j] = "N";
    }
  for (int b = 0; b < sim->nbodies; b++)
    for (int q = 0; q < 6; q++) {
      char buf[160];
      int j = 2 + body0 + 6 * b + q;
      snprintf(buf, sizeof buf, "%s_%s_%c", sim->body_name[b], q < 3 ? "position" : "velocity", 'x' + q % 3);
      g->names[j] = strdup(buf);
      g->units[j] = q < 3 ? "m" : "m/s";
    }
  for (int k = 0; k < g->n - probe0; k++) {
    char buf[160];
    pf_sim_probe_column(sim, k, buf, sizeof buf, &g->units[2 + probe0 + k]);
    g->names[2 + probe0 + k] = strdup(buf);
  }
  for (int k = 0; k < g->n + 2; k++) PF_CHECK(g->names[k], PF_ERR_MEMORY, "out of memory");
  return 0;
}

/* Each body's centre of mass (current positions) and mass-averaged velocity into v[6 b ..]:
 * a projectile's path and its residual velocity. Collective. */
static void body_motion(const pf_sim *sim, double *v) {
  const pf_points *p = sim->pts;
  double s[7 * PF_MAX_BODIES] = {0}; /* per body: m y (3), m v (3), m; one reduction for all */
  for (int b = 0; b < sim->nbodies; b++)
    for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) {
      for (int a = 0; a < 3; a++) s[7 * b + a] += p->m[i] * p->y[3 * i + a], s[7 * b + 3 + a] += p->m[i] * p->v[3 * i + a];
      s[7 * b + 6] += p->m[i];
    }
  MPI_Allreduce(MPI_IN_PLACE, s, 7 * sim->nbodies, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (int b = 0; b < sim->nbodies; b++)
    for (int q = 0; q < 6; q++) v[6 * b + q] = s[7 * b + 6] > 0 ? s[7 * b + q] / s[7 * b + 6] : 0.0;
}

static void globals_free(globals *g) {
  for (int k = 0; g->names && k < g->n + 2; k++) free(g->names[k]);
  PF_FREE(g->names);
  PF_FREE(g->units);
  PF_FREE(g->values);
}

/* Fill values[0..n+1]: time, step, globals. */
static int globals_eval(pf_sim *sim, globals *g, int first) {
  pf_sim_globals s;
  PF_CALL(pf_sim_globals_get(sim, &s));
  double total = s.kinetic_centred + s.elastic + s.contact - s.external_work + s.fe_internal + s.hourglass +
                 s.bulk_viscosity + s.wall_loss + s.contact_dissipation + s.damage_dissipation;
  if (first && !sim->have_e0) sim->e0 = total, sim->have_e0 = 1;
  g->e0 = sim->e0;
  double *v = g->values + 2;
  g->values[0] = sim->t;
  g->values[1] = (double)sim->step;
  v[G_KE] = s.kinetic, v[G_EL] = s.elastic, v[G_CONTACT] = s.contact, v[G_WEXT] = s.external_work;
  v[G_EERR] = total - g->e0;
  for (int a = 0; a < 3; a++) v[G_PX + a] = s.momentum[a];
  v[G_DAMAGE] = s.damage_fraction;
  v[G_FEINT] = s.fe_internal, v[G_HG] = s.hourglass, v[G_BV] = s.bulk_viscosity, v[G_WALL] = s.wall_loss;
  v[G_CDISS] = s.contact_dissipation, v[G_DDISS] = s.damage_dissipation;
  for (int k = 0; k < sim->nrigid; k++)
    for (int a = 0; a < 3; a++) v[G_FIXED + 3 * k + a] = sim->reaction[k][a];
  for (int k = 0; k < sim->nwalls; k++)
    for (int a = 0; a < 3; a++) v[G_FIXED + 3 * sim->nrigid + 3 * k + a] = sim->wall_reaction[k][a];
  for (int k = 0; k < pf_contact_npairs(sim->contact); k++)
    pf_contact_pair_force(sim->contact, k, &v[G_FIXED + 3 * (sim->nrigid + sim->nwalls + k)]);
  body_motion(sim, &v[g->body0]);
  return pf_sim_probes_eval(sim, &v[g->probe0]);
}

static int spread(const pf_sim *sim) { return sim->spread_output && pf_comm_size() > 1; }

/* The spread form <file>.<ranks>.<rank>, the rank zero-padded to the width of <ranks> (the
 * Nemesis convention by which ParaView's Exodus reader opens the set as one data set). */
static void spread_name(const char *path, char *out, size_t len) {
  int size = pf_comm_size(), width = snprintf(NULL, 0, "%d", size);
  snprintf(out, len, "%s.%d.%0*d", path, size, width, pf_comm_rank());
}

static int open_exodus(pf_sim *sim, globals *g) {
  const char *const *names = (const char *const *)g->names + 2;
  if (spread(sim)) {
    char path[sizeof sim->exodus_path + 32];
    spread_name(sim->exodus_path, path, sizeof path);
    return pf_exodus_create(path, sim->pts, sim->nbodies, sim->body_name, sim->body_start, g->n, names, &sim->exo);
  }
  PF_CALL(pf_points_gather(sim->pts, &sim->joined));
  if (!sim->joined) return 0; /* rank 0 writes */
  pf_int start[PF_MAX_BODIES + 1] = {0};
  for (pf_int i = 0; i < sim->joined->n_owned; i++) start[sim->joined->body[i] + 1]++;
  for (int b = 0; b < sim->nbodies; b++) start[b + 1] += start[b];
  /* FE bodies: HEX8 blocks; the joined view is in global-id order, so node k of body b's mesh
   * is point gid0[b] + k of the file */
  pf_exodus_hexes hex[PF_MAX_BODIES];
  pf_int *conn[PF_MAX_BODIES] = {NULL};
  int64_t next_id = sim->pts->n_global;
  int ierr = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    hex[b] = (pf_exodus_hexes){0, NULL, 0};
    const pf_body *body = &sim->body[b];
    if (!body->ops->mesh || ierr) continue;
    const pf_mesh *m = body->ops->mesh(body->data);
    if (!(conn[b] = malloc(sizeof(pf_int) * 8 * ((size_t)m->nelem + 1)))) {
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
      break;
    }
    for (size_t k = 0; k < 8 * (size_t)m->nelem; k++) conn[b][k] = (pf_int)(sim->gid0[b] + m->conn[k]);
    hex[b] = (pf_exodus_hexes){m->nelem, conn[b], next_id};
    next_id += m->nelem;
  }
  if (!ierr)
    ierr = pf_exodus_create_mixed(sim->exodus_path, sim->joined, sim->nbodies, sim->body_name, start, hex, g->n,
                                  names, &sim->exo);
  for (int b = 0; b < sim->nbodies; b++) free(conn[b]);
  return ierr;
}

static int open_output(pf_sim *sim, globals *g) {
  if (sim->opt.no_output) return 0;
  PF_CALL(open_exodus(sim, g));
  PF_CALL(pf_history_create(sim->history_path, g->n + 2, (const char *const *)g->names, g->units, &sim->hist));
  return 0;
}

static int write_exodus(pf_sim *sim, const double *values) {
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->output_fields) PF_CALL(sim->body[b].ops->output_fields(sim->body[b].data, sim->pts));
  if (spread(sim)) return pf_exodus_write(sim->exo, sim->t, sim->pts, values);
  PF_CALL(pf_points_gather(sim->pts, &sim->joined));
  return sim->joined ? pf_exodus_write(sim->exo, sim->t, sim->joined, values) : 0;
}

static int write_output(pf_sim *sim, globals *g, int exodus, int history, int last) {
  if (exodus) PF_CALL(pf_sim_fragments(sim, last));
  if (sim->opt.no_output) return 0;
  if (exodus) PF_CALL(write_exodus(sim, g->values + 2));
  if (history) PF_CALL(pf_history_append(sim->hist, g->values));
  return 0;
}

/* The guards stopped the run with every rank back at the start of the failed step: write that
 * state as a last Exodus step (the global variables are those of the last history row; FE
 * stresses are those of the failed step), then fail with the guard's error. Collective. */
static int write_last_good(pf_sim *sim, globals *g, int ierr) {
  if (sim->opt.no_output || write_exodus(sim, g->values + 2)) return ierr;
  pf_log("perifem: the last good state (step %ld, t = %.6e s) is the last step of %s\n", sim->step, sim->t,
         sim->exodus_path);
  return ierr;
}

/* The energy balance error relative to the largest energy in play. */
static double relative_error(const globals *g) {
  const double *v = g->values + 2;
  double scale = fmax(fabs(g->e0), fmax(fabs(v[G_WEXT]), v[G_KE] + v[G_EL] + v[G_CONTACT] + fabs(v[G_FEINT])));
  return scale > 0 ? fabs(v[G_EERR]) / scale : 0.0;
}

/* How far the run is, 0..1: by time when the step follows the deformation (the step count is
 * not known ahead), else by steps. */
static double run_fraction(const pf_sim *sim) {
  if (sim->adaptive && isfinite(sim->final_time)) return sim->t / sim->final_time;
  return (double)sim->step / fmax((double)sim->nsteps, 1.0);
}

/* Progress (rank 0): the step (of the total when the step is fixed, else with the step size),
 * simulated time of the final time, steps per second of wall time, the time left at that rate,
 * and the energy balance error and damage fraction of the last history row (no collective:
 * ranks need not agree on when). */
static void progress(const pf_sim *sim, const globals *g, double wall0, int status) {
  double el = pf_wtime() - wall0, rate = sim->step / fmax(el, 1e-9);
  const int by_time = sim->adaptive && isfinite(sim->final_time);
  const double frac = run_fraction(sim);
  double tend = isfinite(sim->final_time) ? sim->final_time : sim->t / fmax(frac, 1e-300);
  char line[256];
  int n = by_time ? snprintf(line, sizeof line, "step %ld  dt = %.3e s", sim->step, sim->dt)
                  : snprintf(line, sizeof line, "step %ld/%ld", sim->step, sim->nsteps);
  snprintf(line + n, sizeof line - n,
           "  t = %.4e / %.4e s (%.0f %%)  %.1f steps/s  about %.0f s left  energy error %.2e  damage %.4g",
           sim->t, tend, 100 * frac, rate, el * (1 - frac) / fmax(frac, 1e-9), relative_error(g),
           g->values[2 + G_DAMAGE]);
  if (status) pf_log_status("%s", line);
  else pf_log("%s\n", line);
}

static void summary(const pf_sim *sim, const globals *g, double wall) {
  double nb = 0, bytes = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    if (!body->ops->family) continue;
    const double n = (double)pf_pd_family_nbonds(body->ops->family(body->data));
    nb += n;
    bytes += n * body->ops->bytes_per_bond(body->data);
  }
  nb = pf_sum_all(nb), bytes = pf_sum_all(bytes);
  const double *v = g->values + 2;
  pf_log("perifem: %ld steps of %.4e s to t = %.4e s in %.2f s (time loop %.2f s)\n", sim->step,
         sim->dt, sim->t, wall, sim->wall_loop);
  pf_log("  points %" PF_GID_FMT ", directed bonds %.0f (%.3g bytes each), bond evaluations per second %.4g\n",
         sim->pts->n_global, nb, nb > 0 ? bytes / nb : 0.0,
         sim->wall_loop > 0 ? nb * sim->step / sim->wall_loop : 0.0);
  double nel = 0;
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->mesh) nel += sim->body[b].ops->mesh(sim->body[b].data)->nelem;
  if (nel > 0)
    pf_log("  elements %.0f, element cycles per second %.4g, hourglass energy %.3g J (%.3g times the internal)\n",
           nel, sim->wall_loop > 0 ? nel * sim->step / sim->wall_loop : 0.0, v[G_HG],
           v[G_FEINT] != 0 ? v[G_HG] / v[G_FEINT] : 0.0);
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    long n = 0;
    if (body->ops->eroded && body->ops->eroded(body->data, &n))
      pf_log("  body '%s': %ld of %" PF_INT_FMT " elements deleted by erosion\n", sim->body_name[b], n,
             body->ops->mesh(body->data)->nelem);
  }
  if (sim->contact) {
    long rebuilds;
    double sec;
    pf_contact_stats(sim->contact, &rebuilds, &sec);
    sec = pf_max_all(sec);
    pf_log("  contact: %ld search rebuilds, %.3g s (%.1f %% of the time loop), dissipation %.3g J\n", rebuilds, sec,
           sim->wall_loop > 0 ? 100 * sec / sim->wall_loop : 0.0, v[G_CDISS]);
  }
  pf_log("  final damage fraction %.6g, energy balance error %.3g J (relative %.3g; damage dissipated %.3g J)\n",
         v[G_DAMAGE], v[G_EERR], relative_error(g), v[G_DDISS]);
  if (!sim->opt.no_output)
    pf_log("  output: %s%s, %s\n", sim->exodus_path, spread(sim) ? ".<ranks>.<rank>" : "", sim->history_path);
}

/* Checkpoint at the deck's interval; on SIGTERM/SIGINT checkpoint and stop (*stop = 1). */
static int checkpoints(pf_sim *sim, int *stop) {
  int sig = sim->signal; /* (reduced with the step's guard) */
  if (sig || (sim->restart_interval > 0 && sim->step % sim->restart_interval == 0)) PF_CALL(pf_sim_checkpoint(sim));
  if (sig) {
    pf_log("perifem: signal %d: stopped at step %ld, t = %.6e s; continue with --restart %s\n", sig, sim->step,
           sim->t, sim->restart_path);
    *stop = 1;
  }
  return 0;
}

static int run_loop(pf_sim *sim, globals *g, double wall0) {
  const int status = pf_log_terminal();
  int twentieths = 0; /* plain lines: one at each twentieth of the run */
  double loop0 = pf_wtime(), shown = loop0;
  while (!pf_sim_finished(sim) && !sim->stopped) {
    int ierr = pf_sim_step(sim, 1);
    if (ierr && sim->last_good) return write_last_good(sim, g, ierr);
    if (ierr) return ierr;
    PF_CALL(checkpoints(sim, &sim->stopped));
    int last = pf_sim_finished(sim) || sim->stopped;
    int exo = last || (sim->output_interval > 0 && sim->step % sim->output_interval == 0);
    int his = last || sim->step % sim->history_interval == 0;
    if (exo || his) {
      double t0 = pf_wtime();
      if (exo) PF_CALL(pf_sim_rebalance(sim));
      PF_CALL(globals_eval(sim, g, 0));
      PF_CALL(write_output(sim, g, exo, his, last));
      loop0 += pf_wtime() - t0; /* output is not part of the step rate */
    }
    if (last) continue;
    if (status && pf_wtime() - shown > 0.25) progress(sim, g, wall0, 1), shown = pf_wtime();
    else if (!status && (int)(20 * run_fraction(sim)) > twentieths)
      twentieths = (int)(20 * run_fraction(sim)), progress(sim, g, wall0, 0);
  }
  sim->wall_loop = pf_wtime() - loop0;
  return 0;
}

int pf_sim_run(pf_sim *sim) {
  double wall0 = pf_wtime();
  globals g = {0};
  int ierr = globals_init(sim, &g);
  if (!ierr) ierr = pf_sim_step(sim, 0); /* forces at t = 0 */
  if (!ierr) ierr = globals_eval(sim, &g, 1);
  if (!ierr) ierr = open_output(sim, &g);
  if (!ierr) ierr = write_output(sim, &g, 1, 1, 0);
  if (!ierr) ierr = run_loop(sim, &g, wall0);
  if (!ierr) summary(sim, &g, pf_wtime() - wall0);
  globals_free(&g);
  pf_exodus_destroy(&sim->exo);
  pf_history_destroy(&sim->hist);
  if (ierr || sim->stopped) return ierr;
  uint64_t h;
  PF_CALL(pf_state_digest(sim->pts, &h));
  if (pf_comm_rank() == 0) printf("state digest: %016" PRIx64 "\n", h); /* even with --quiet */
  return 0;
}
