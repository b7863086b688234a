/* The driver: a simulation built from a deck, and its time loop. Used by main() and by tests
 * that run whole decks. */
#ifndef PF_SIM_H
#define PF_SIM_H

#include "core/core.h"

#ifndef PF_USES_SIM
#error "sim/sim.h is included by a module below sim/ (docs/architecture.md: the module layers)"
#endif
#include "pd/pd.h"

typedef struct pf_sim pf_sim;

typedef struct {
  const char *output_dir; /* NULL: the current directory */
  int no_output;          /* 1: write no Exodus or history file (tests) */
  const char *restart_from; /* a checkpoint to continue from, or NULL */
  const char *const *sets;  /* deck overrides "a.b.c=value" (--set), applied in order */
  int nsets;
  const char *command_line; /* recorded in the outputs, or NULL */
  int strict;             /* 1: a run-health warning stops the run as an error (--strict) */
  const char *deck_text;  /* the deck's YAML text, read instead of the file deck_path (which still
                             names the deck: files in it are relative to its folder, outputs are
                             named after it), or NULL */
  int keep_signals;       /* 1: leave SIGTERM/SIGINT to the caller (the library; see sim/restart.c) */
} pf_sim_options;

/* Load and validate the deck and build everything; writes no file. */
int pf_sim_create(const char *deck_path, const pf_sim_options *opt, pf_sim **sim);
/* Run to the final time; writes output, prints the summary and the state digest. */
int pf_sim_run(pf_sim *sim);
/* The same run in parts: _begin computes the forces at t = 0 and writes the first output and
 * history row (once; later calls do nothing); _advance takes up to n more steps (n < 0: to the
 * end) with output, history, checkpoints and health checks at their intervals, and at the end
 * prints the summary and closes the outputs (it prints no digest). A run that failed refuses to
 * go on. Collective. */
int pf_sim_run_begin(pf_sim *sim);
int pf_sim_run_advance(pf_sim *sim, long n);
int pf_sim_destroy(pf_sim **sim);

pf_points *pf_sim_points(pf_sim *sim);
int pf_sim_nbodies(const pf_sim *sim);
/* Body b's PD operator (a peridynamic body; NULL for the other kinds) and FE body (finite_element
 * bodies, coupled ones included; NULL for the other kinds): for tests and tools. */
pf_pd_body *pf_sim_body(pf_sim *sim, int b);
struct pf_fem_body *pf_sim_fem_body(pf_sim *sim, int b);
/* The contact between bodies (NULL: the deck has no pair): for tests. */
struct pf_contact *pf_sim_contact(pf_sim *sim);
/* Add body b's internal forces at the current positions to the points' f (dt: the step they
 * advance the material over); an element failure is an error. For tests. */
int pf_sim_body_force(pf_sim *sim, int b, double dt);
double pf_sim_dt(const pf_sim *sim);
long pf_sim_nsteps(const pf_sim *sim);
/* 1 when the step follows the deformation (FE or correspondence bodies, no time.dt): then dt and
 * nsteps are those of the set-up, estimates of the run's. */
int pf_sim_adaptive(const pf_sim *sim);
/* perifem --check (sim/check_report.c): print on rank 0 what the run will be: per body its kind,
 * points, directed bonds, elements, horizon/spacing and material; the step and the number of
 * steps; the memory per rank (the estimate and the measured peak); the output and checkpoint
 * sizes; the run time from a few steps it takes and times (sim/check_calibrate.c), after
 * which the run refuses to begin. Collective. */
int pf_sim_check_report(pf_sim *sim);
/* Global quantities of the current state. */
typedef struct {
  double time, kinetic, elastic, contact, external_work, momentum[3];
  /* sum m (|v|^2 - (dt/2)^2 |a|^2) / 2 = sum m v(t-dt/2).v(t+dt/2) / 2: the kinetic part of
   * the energy that velocity Verlet conserves exactly for linear forces (docs/theory/pd.md) */
  double kinetic_centred;
  double damage_fraction;
  /* finite elements: stress work (internal energy), hourglass energy, bulk-viscosity work; and
   * the kinetic energy rigid walls removed, J */
  double fe_internal, hourglass, bulk_viscosity, wall_loss;
  double contact_dissipation; /* friction work of contacts and rigid surfaces, J */
  double damage_dissipation;  /* energy released by failed bonds (PMB, LPS, elastic_plastic), J, >= 0 */
  /* the stored energy failed bonds moved rather than released (LPS: the dilatation's cross term
   * where negative; docs/theory/pd.md §5.1), J, <= 0; the balance books both */
  double damage_redistribution;
  /* the kinetic energy converting elements into particles removed (the shares' velocities
   * averaged; docs/theory/fem.md §9b), J, >= 0 */
  double conversion_loss;
} pf_sim_globals;
int pf_sim_globals_get(pf_sim *sim, pf_sim_globals *g);
/* 1 when the run has reached its final time (or step count). */
int pf_sim_finished(const pf_sim *sim);
/* Advance n steps (no output). */
int pf_sim_step(pf_sim *sim, long n);
uint64_t pf_sim_digest(pf_sim *sim);

/* The top-level deck keys (for validation and docs). */
extern const pf_key pf_deck_keys[];
/* Every key table the loader checks, as Markdown (perifem --deck-keys; docs/deck_keys.md). */
int pf_deck_reference(FILE *out);
/* mkdir -p dir on rank 0 (an output folder, before a run opens its files): 0 or an errno, the
 * same on every rank. Collective (sim/paths.c). */
int pf_sim_make_dir(const char *dir);
/* Whether pf_sim_make_dir(dir) can succeed, before the set-up, making nothing: 0 when dir is a
 * folder or its deepest existing ancestor is one this process may write in, else an errno
 * (ENOTDIR: a file where a folder must be; EACCES). Collective (sim/paths.c). */
int pf_sim_dir_creatable(const char *dir);
/* The command line, before MPI_Init: a SIGTERM or SIGINT from then on ends the process with the
 * set-up's message (sim/signals.c), on the rank the launcher calls 0. */
void pf_sim_catch_signals_early(void);

#endif
