/* The time loop (sim/step.c takes one step): output and history at their intervals, checkpoints
 * and signals, re-partitioning when the work is imbalanced, the progress line, the end-of-run
 * summary and the state digest. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
static void progress(const pf_sim *sim, double wall0, int status) {
  double el = pf_wtime() - wall0, rate = sim->step / fmax(el, 1e-9);
  const int by_time = sim->adaptive && isfinite(sim->final_time);
  const double frac = run_fraction(sim);
  double tend = isfinite(sim->final_time) ? sim->final_time : sim->t / fmax(frac, 1e-300);
  char line[256];
  int n = by_time ? snprintf(line, sizeof line, "step %ld  dt = %.3e s", sim->step, sim->dt)
                  : snprintf(line, sizeof line, "step %ld/%ld", sim->step, sim->nsteps);
  snprintf(line + n, sizeof line - n,
           "  t = %.4e / %.4e s (%.0f %%)  %.1f steps/s  about %.0f s left  energy error %.2e  damage %.4g",
           sim->t, tend, 100 * frac, rate, el * (1 - frac) / fmax(frac, 1e-9), pf_sim_energy_error(sim),
           pf_sim_total(sim, sim->acc.totals.damage_fraction));
  if (status) pf_log_status("%s", line);
  else pf_log("%s\n", line);
}

static void summary(pf_sim *sim, double wall) {
  double nb = 0, bytes = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_family *fam = pf_body_family(&sim->body[b]);
    const double n = fam ? (double)pf_pd_family_nbonds(fam) : 0;
    nb += n;
    bytes += n > 0 ? n * pf_body_bytes_per_bond(&sim->body[b]) : 0;
  }
  nb = pf_sum_all(nb), bytes = pf_sum_all(bytes);
  const pf_sim_totals *T = &sim->acc.totals;
  const double hg = pf_sim_total(sim, T->hourglass), fe = pf_sim_total(sim, T->fe_internal);
  /* wall: from the start of the run (t = 0 forces, first output) to the output files closed;
   * the time loop's steps alone, and its output, history rows and rebalancing, apart. The rate
   * counts every stored directed bond once per step taken in this run (broken ones too: the
   * batched loops pass over them; LPS passes over each twice, dilatation and force); bytes per
   * bond: every per-bond array stored (pf_pd_body_bytes_per_bond). */
  pf_log("perifem: %ld steps of %.4e s to t = %.4e s in %.2f s (time loop %.2f s, output %.2f s)\n",
         sim->loop_steps, sim->dt, sim->t, wall, sim->wall_loop, sim->wall_output);
  pf_log("  ranks %d, threads per rank %d\n", pf_comm_size(), pf_threads_per_rank());
  pf_log("  points %" PF_GID_FMT ", directed bonds %.0f (%.3g bytes each), bond evaluations per second %.4g"
         " (directed bonds x steps / time loop)\n",
         sim->pts->n_global, nb, nb > 0 ? bytes / nb : 0.0,
         sim->wall_loop > 0 ? nb * sim->loop_steps / sim->wall_loop : 0.0);
  double nel = 0;
  for (int b = 0; b < sim->nbodies; b++)
    if (pf_body_mesh(&sim->body[b])) nel += pf_body_mesh(&sim->body[b])->nelem;
  if (nel > 0)
    pf_log("  elements %.0f, element cycles per second %.4g, hourglass energy %.3g J (%.3g times the internal)\n",
           nel, sim->wall_loop > 0 ? nel * sim->loop_steps / sim->wall_loop : 0.0, hg, fe != 0 ? hg / fe : 0.0);
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    const long n = pf_body_eroded_count(body);
    if (n >= 0) pf_log("  body '%s': %ld of %" PF_INT_FMT " elements deleted by erosion\n", sim->body_name[b], n,
                  pf_body_mesh(body)->nelem);
    if (pf_body_as_particles(body))
      pf_log("  body '%s': %ld elements converted into particles, kinetic energy booked at the conversions %.4g J\n",
             sim->body_name[b], pf_fem_particles_count(pf_body_as_particles(body)), pf_sim_total(sim, T->conversion));
  }
  pf_sim_interactions_summary(sim);
  pf_sim_solver_summary(sim);
  /* the set-up's peak resident memory, and the run's: resident at the end of the time loop, or
   * the process's peak when the run raised it above the set-up's */
  const double peak = pf_memory_peak(), setup = pf_max_all(sim->rss_setup), before = pf_max_all(sim->rss0);
  const double run = pf_max_all(peak > sim->rss_setup ? peak : pf_memory_resident());
  pf_log("  memory: set-up peak %.1f MB, run %.1f MB (%.2f x), before the set-up %.1f MB (resident, the largest"
         " over the ranks)\n", setup / 1e6, run / 1e6, run > 0 ? setup / run : 0.0, before / 1e6);
  pf_log("  final damage fraction %.6g, energy balance error %.3g J (relative %.3g; damage dissipated %.3g J)\n",
         pf_sim_total(sim, T->damage_fraction), pf_sim_total(sim, T->error), pf_sim_energy_error(sim),
         pf_sim_total(sim, T->damage));
  if (!sim->opt.no_output)
    pf_log("  output: %s%s, %s\n", sim->exodus_path, pf_sim_spread_output(sim) ? ".<ranks>.<rank>" : "", sim->history_path);
  pf_sim_health_summary(sim);
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

/* The time loop between calls: its state, the history columns, the wall clock at the start,
 * and the progress lines shown so far. */
enum { RUN_GOING, RUN_ENDED, RUN_FAILED };
typedef struct pf_sim_run {
  int state;
  pf_sim_history_row row;
  double wall0, shown; /* the run's start; the last status line */
  int twentieths;      /* plain lines: one at each twentieth of the run */
  long step0;          /* the step the run started from (a restart's) */
} pf_sim_run_state;

static int run_failed(void) {
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__, "the run stopped on an error; it cannot go on");
}

/* Up to n steps of the time loop (n < 0: to the end), with output, history, checkpoints and the
 * health check at their intervals; the progress lines and the loop's wall time carry over from
 * one call to the next. */
static int run_loop(pf_sim *sim, long n) {
  pf_sim_history_row *g = &sim->run->row;
  const int status = pf_log_terminal();
  double loop0 = pf_wtime();
  for (long s = 0; (n < 0 || s < n) && !pf_sim_finished(sim) && !sim->stopped; s++) {
    const double t_before = sim->t;
    int ierr = pf_sim_step(sim, 1);
    if (ierr && sim->last_good) ierr = pf_sim_write_last_good(sim, g, ierr);
    if (ierr) return sim->wall_loop += pf_wtime() - loop0, ierr;
    PF_CALL(checkpoints(sim, &sim->stopped));
    int last = pf_sim_finished(sim) || sim->stopped;
    int exo = last || pf_sim_output_due(sim->output_interval, sim->output_period, sim->step, t_before, sim->t);
    int his = last || pf_sim_output_due(sim->history_interval, sim->history_period, sim->step, t_before, sim->t);
    if (exo || his) {
      double t0 = pf_wtime();
      if (exo && !last) PF_CALL(pf_sim_rebalance(sim)); /* (not for the steps no run will take) */
      PF_CALL(pf_sim_globals_eval(sim, g, 0));
      PF_CALL(pf_sim_write_output(sim, g, exo, his, last));
      if (his) PF_CALL(pf_sim_health_check(sim));
      sim->wall_output += pf_wtime() - t0;
      loop0 += pf_wtime() - t0; /* output is not part of the step rate */
    }
    if (last) continue;
    if (status && pf_wtime() - sim->run->shown > 0.25) progress(sim, sim->run->wall0, 1), sim->run->shown = pf_wtime();
    else if (!status && (int)(20 * run_fraction(sim)) > sim->run->twentieths)
      sim->run->twentieths = (int)(20 * run_fraction(sim)), progress(sim, sim->run->wall0, 0);
  }
  sim->wall_loop += pf_wtime() - loop0;
  sim->loop_steps = sim->step - sim->run->step0;
  return 0;
}

/* The outputs closed: the run is over (RUN_ENDED) or failed (the history columns stay, with
 * their last values, until pf_sim_destroy). */
static void run_close(pf_sim *sim, int state) {
  pf_exodus_destroy(&sim->exo);
  pf_history_destroy(&sim->hist);
  sim->run->state = state;
}

int pf_sim_run_begin(pf_sim *sim) {
  if (sim->run) return sim->run->state == RUN_FAILED ? run_failed() : 0;
  if (sim->calibrated)
    return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                          "the --check report (perifem_print_check) took calibration steps: this model is spent; create "
                          "it again to run");
  PF_MALLOC(sim->run, 1);
  pf_sim_run_state *r = sim->run;
  r->wall0 = pf_wtime();
  r->step0 = sim->step;
  sim->wall_output = 0;
  int ierr = pf_sim_globals_init(sim, &r->row);
  if (!ierr) ierr = pf_sim_step(sim, 0); /* forces at t = 0 */
  if (!ierr) ierr = pf_sim_globals_eval(sim, &r->row, 1);
  if (!ierr) ierr = pf_sim_open_output(sim, &r->row);
  if (!ierr) ierr = pf_sim_write_output(sim, &r->row, 1, 1, 0);
  if (!ierr) ierr = pf_sim_health_check(sim);
  if (ierr) run_close(sim, RUN_FAILED);
  r->shown = pf_wtime();
  return ierr;
}

int pf_sim_run_advance(pf_sim *sim, long n) {
  PF_CALL(pf_sim_run_begin(sim));
  if (sim->run->state == RUN_ENDED) return 0;
  int ierr = run_loop(sim, n);
  if (ierr) run_close(sim, RUN_FAILED);
  else if (pf_sim_finished(sim) || sim->stopped) {
    run_close(sim, RUN_ENDED); /* (closing the files is part of the run's wall time) */
    summary(sim, pf_wtime() - sim->run->wall0);
  }
  return ierr;
}

pf_sim_history_row *pf_sim_history(pf_sim *sim) {
  return sim->run && sim->run->state != RUN_FAILED ? &sim->run->row : NULL;
}

void pf_sim_run_free(pf_sim *sim) {
  if (!sim->run) return;
  pf_sim_globals_free(&sim->run->row);
  PF_FREE(sim->run);
}

int pf_sim_run(pf_sim *sim) {
  int ierr = pf_sim_run_advance(sim, -1);
  if (ierr || sim->stopped) return ierr;
  uint64_t h;
  PF_CALL(pf_state_digest(sim->pts, &h));
  if (pf_comm_rank() == 0) printf("state digest: %016" PRIx64 "\n", h); /* even with --quiet */
  return 0;
}
