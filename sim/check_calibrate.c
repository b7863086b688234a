/* The timed calibration of `perifem --check`: the built model takes a few real steps (the whole
 * step: every body's forces, coupling, contact, walls, the guards and the ledger's booking), with
 * no output written, and the median of their CPU times (the largest over the ranks, each step)
 * is the step cost the run time is extrapolated from. Two steps warm up first; then up to
 * PF_CALIBRATION_STEPS steps are timed, fewer once PF_CALIBRATION_SECONDS have gone (at least
 * one). A history row and a frame's output fields are timed once each. Every decision is taken
 * on values reduced over the ranks, so all of them take the same steps. Collective. The model
 * is spent afterwards: pf_sim_run_begin refuses it. */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <time.h>

#define PF_CALIBRATION_WARMUP 2
#define PF_CALIBRATION_STEPS 9
#define PF_CALIBRATION_SECONDS 2.0

double pf_sim_cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The CPU time since c0 on this rank, per thread of a rank, the largest over the ranks. */
static double since(double c0) { return pf_max_all((pf_sim_cpu_seconds() - c0) / pf_threads_per_rank()); }

/* The CPU time of f(sim), as since(); an error on any rank is every rank's. */
static int timed(pf_sim *sim, int (*f)(pf_sim *), double *seconds) {
  const double c0 = pf_sim_cpu_seconds();
  const int ierr = pf_agree(f(sim), "a calibration step of --check");
  *seconds = since(c0);
  return ierr;
}

static int forces_at_zero(pf_sim *sim) { return pf_sim_step(sim, 0); }
static int one_step(pf_sim *sim) { return pf_sim_step(sim, 1); }

/* A history row (the ledger's totals), its columns made before the clock starts. */
static int time_row(pf_sim *sim, double *seconds) {
  pf_sim_history_row g = {0};
  int ierr = pf_sim_globals_init(sim, &g);
  const double c0 = pf_sim_cpu_seconds();
  if (!ierr) ierr = pf_sim_globals_eval(sim, &g, 0);
  *seconds = since(c0);
  pf_sim_globals_free(&g);
  return pf_agree(ierr, "a history row of --check");
}

/* A frame's work short of the file: the bodies' output fields and the fragments' labels. */
static int frame_fields(pf_sim *sim) {
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_output_fields(&sim->body[b], sim->pts));
  return pf_sim_fragments(sim, 0);
}

static int by_value(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The steps: warm-up, then timed until the count or the time budget is reached. */
static int time_steps(pf_sim *sim, pf_sim_calibration *c) {
  double t[PF_CALIBRATION_STEPS], spent = 0, s;
  const long left = sim->nsteps - sim->step;
  for (; c->warmup < PF_CALIBRATION_WARMUP && c->warmup < left - 1; c->warmup++) PF_CALL(timed(sim, one_step, &s));
  int n = 0;
  while (n < PF_CALIBRATION_STEPS && (n == 0 || spent < PF_CALIBRATION_SECONDS) && !pf_sim_finished(sim)) {
    PF_CALL(timed(sim, one_step, &t[n]));
    spent += t[n++];
  }
  qsort(t, (size_t)n, sizeof t[0], by_value);
  c->steps = n;
  c->step = n ? (n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2])) : 0;
  return 0;
}

int pf_sim_check_calibrate(pf_sim *sim, pf_sim_calibration *c) {
  *c = (pf_sim_calibration){.from = sim->step};
  c->setup = pf_max_all(pf_sim_cpu_seconds() / pf_threads_per_rank());
  if (sim->run || sim->solver.load_step) return 0; /* (the run began; a load step is a whole relaxation) */
  const int no_output = sim->opt.no_output;
  sim->opt.no_output = 1; /* (the fragments' file) */
  sim->calibrated = 1;
  int ierr = sim->step == 0 && sim->t == 0 ? timed(sim, forces_at_zero, &c->first) : 0;
  if (!ierr) ierr = time_steps(sim, c);
  if (!ierr) ierr = time_row(sim, &c->row);
  if (!ierr) ierr = timed(sim, frame_fields, &c->frame);
  sim->opt.no_output = no_output;
  return ierr;
}
