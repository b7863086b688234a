/* Private to sim/. */
#ifndef PF_SIM_IMPL_H
#define PF_SIM_IMPL_H

#include "contact/contact.h"
#include "sim/body.h"
#include "coupling/coupling.h"
#include "sim/interaction.h"
#include "sim/ledger.h"
#include "sim/sim.h"
#include "sim/solver.h"

#define PF_MAX_BODIES 64
/* The longest output path: the 4096-byte (PATH_MAX) path buffers less room for what a run
 * appends (-restart<step>, .tmp, .lock, .<ranks>.<rank>). */
enum { PF_SIM_PATH_MAX = 4000 };

/* The run's totals in the ledger: the history's first columns, each the sum of its parts (the
 * bodies' and interactions' accounts), in this order. */
typedef struct {
  int kinetic, elastic, contact, work, error, momentum, angular, damage_fraction, fe_internal, hourglass, viscous, wall,
      contact_dissipation, damage, redistribution, conversion, relaxation;
} pf_sim_totals;
/* A body's accounts (sim/accounts.c): its centre of mass and mean velocity, kinetic energy (and
 * the centred one the balance takes), internal energy (PD stored energy and element stress work,
 * also apart), hourglass energy, viscous work, damage dissipation and redistribution, external
 * work (the prescribed motions' and loads' on its points), momentum, angular momentum about the
 * origin, the kinetic energy its
 * conversions removed, its bonds and broken bonds; hidden, its first moment of mass and its mass,
 * summed with the rest and divided into the centre and mean velocity after the reduction. */
typedef struct {
  int position, velocity, kinetic, centred, internal, elastic, fe_internal, hourglass, viscous, damage,
      redistribution, work, momentum, angular, conversion, bonds, broken, moment, mass;
} pf_body_accounts;
typedef struct {
  pf_sim_totals totals;
  pf_body_accounts body[PF_MAX_BODIES];
  int body_work[PF_MAX_BODIES]; /* = body[b].work, for the interactions' step */
  int probe0, nprobe;           /* the probes' accounts: probe0 .. probe0 + nprobe - 1 */
} pf_sim_accounts;

/* Named scalars of a checkpoint (sim/restart.c). */
typedef struct {
  int n;
  char (*name)[96];
  const char **names;
  double *value;
} pf_sim_scalars;

/* A body's geometry as the set-up made it (sim/restart_geometry.c): its points, its elements
 * (0 without a mesh), a hash of the points' reference positions and one of the connectivity. */
typedef struct {
  double points, elements;
  uint64_t hash[2];
} pf_sim_geometry;
enum { PF_GEOMETRY_SCALARS = 6 }; /* a checkpoint's scalars per body: counts, hash halves */

enum { PF_PROBE_MAX_QUANTITIES = 8 };
/* The run-health monitor's state (sim/health.c). */
enum { PF_HEALTH_MAX_WARNINGS = 32 };
typedef struct {
  double e0[PF_MAX_BODIES];     /* each body's energy at the first check, J */
  double damage[PF_MAX_BODIES]; /* each body's damaged fraction at the last check */
  double error;                 /* the relative energy error at the last check */
  double p0[3], i0[3];          /* the momentum and the loads' impulse at the first check, kg m/s */
  double p_scale;               /* the largest momentum in play so far (health.c), kg m/s */
  double p_error;               /* the relative momentum error at the last check */
  long step0;                   /* the step of the first check */
  int started;                  /* the first check is done */
  int n;                        /* warnings given so far */
  char what[PF_HEALTH_MAX_WARNINGS][96]; /* each one's class and body, for the summary */
} pf_sim_health;

typedef struct {
  char name[64];
  int body;         /* -1: every body */
  pf_region region; /* on reference positions */
  int nq, q[PF_PROBE_MAX_QUANTITIES];
} pf_probe;

struct pf_sim {
  pf_deck *deck;
  pf_sim_options opt;
  pf_points *pts;
  int nbodies;
  pf_body body[PF_MAX_BODIES];     /* each body's kind (its ops) and data (sim/body.h) */
  pf_sim_geometry geometry[PF_MAX_BODIES]; /* recorded in checkpoints, compared on restart */
  int nmeshed;                     /* bodies with a mesh (written joined: no spread output) */
  pf_gid gid0[PF_MAX_BODIES + 1];  /* global ids of body b: [gid0[b], gid0[b+1]) */
  const char *body_name[PF_MAX_BODIES];
  pf_int body_start[PF_MAX_BODIES + 1];
  pf_contact *contact; /* the contact pairs' (borrowed from their interaction; NULL: none): pf_sim_contact */
  pf_point_sets sets; /* the bodies' node and side sets, for regions (sim/sets.c) */
  pf_interaction *inter; /* rigid surfaces, contact, walls, conditions (sim/interaction.h), list order */
  int ninter, cap_inter;
  pf_ledger ledger;      /* the run's books (sim/ledger.h) */
  pf_sim_accounts acc;   /* the run's and the bodies' accounts in it (sim/accounts.c) */
  /* parallel */
  pf_partition_method decomposition;
  double rebalance_threshold; /* re-partition when max/mean work exceeds this (0: never) */
  int *row_work;              /* each owned point's bonds + 1 when last partitioned, */
  pf_gid *row_work_gid;       /* with its global id (the re-partition check's weights) */
  pf_int row_work_n;
  int spread_output;          /* one Exodus file per rank */
  /* time */
  double t, dt, final_time;
  long step, nsteps;
  int adaptive;         /* dt follows the FE stable step each step */
  double safety;        /* fraction of the stable step */
  double max_motion;    /* guard: largest step motion, as a fraction of horizon (PD) or cell (FE) */
  double pd_stable;     /* the PD bodies' stable step (fixed) */
  int restart_format;  /* the format of the checkpoint restarted from */
  int restart_nfields; /* the point fields it held (registered first) */
  /* checkpoints */
  char restart_path[4096];
  long restart_interval;
  int stopped; /* a signal stopped the run after a checkpoint */
  int signal;  /* the largest signal any rank received by the last step's end (0: none) */
  pf_sim_scalars restart_scalars; /* read from the checkpoint we restart from */
  /* output */
  long output_interval, history_interval; /* steps between frames / rows (0 frames: first and last only) */
  double output_period, history_period;    /* or seconds between them (0: by steps; sim/output.c) */
  char exodus_path[4096], history_path[4096];
  char *lock_path[3];  /* the lock files this run holds (rank 0; sim/output_lock.c) */
  int nlocks;
  pf_provenance prov; /* written into the outputs (sim/provenance.c) */
  pf_exodus_options exo_opt; /* output.fields, precision, compression (sim/output.c) */
  const char **exo_fields;
  char **prov_lines, title[256];
  int fragments;                /* output.fragments: label the fragments at every Exodus step */
  char fragments_path[4128];    /* <Exodus file less .e>.fragments.csv */
  long fragments_rows;          /* rows written to it so far */
  pf_probe *probes;             /* output.probes: history columns of region averages */
  int nprobes;
  pf_exodus *exo;
  pf_points *joined; /* rank 0: every point in global-id order, for the joined Exodus file */
  pf_history *hist;
  double wall_loop;   /* seconds of the time loop's steps (output excluded) */
  double wall_output; /* seconds of the time loop's output, history and rebalancing */
  long loop_steps;    /* steps this run took (after a restart: since the checkpoint) */
  double rss0; /* the process's peak resident memory before the set-up, bytes (--check) */
  double rss_setup; /* the same at the end of the set-up (the run summary) */
  int calibrated;   /* --check took calibration steps: the model is spent (sim/check_calibrate.c) */
  /* instability guards (sim/guard.c) */
  int guard_tripped;    /* this rank found a NaN, a runaway point or an inverted element */
  int last_good;        /* the run stopped and the points hold the last good state */
  double *good_u, *good_v; /* [3 n_owned] state at the start of the step */
  pf_int good_n;
  double good_t;
  long good_step;
  pf_sim_health health; /* run-health monitor (sim/health.c) */
  struct pf_sim_run *run; /* the time loop between calls (sim/run.c); NULL until it starts */
  pf_sim_solver solver;   /* explicit dynamics or quasi-static loading (sim/solver.h) */
};

/* sim/convert.c: link each particles body to the FE body it names (before the clouds); at a
 * step's end, the elements deleted in the step become particles (*converted of them, collective:
 * the caller then recomputes the fixed stable step). */
int pf_sim_link_particles(pf_sim *sim);
int pf_sim_convert_elements(pf_sim *sim, long *converted);
/* 1 when some body's particles come from another's elements. */
int pf_sim_converts(const pf_sim *sim);
/* sim/step.c: recompute the fixed part of the stable step (PD bodies, contact penalties) from the
 * current masses, after conversions changed them or a restart restored them. Collective. */
int pf_sim_refresh_fixed_step(pf_sim *sim);
/* sim/step.c: the bodies' forces at the current positions into f (the ghosts exchanged, the failed
 * bonds' energy booked; the interactions' come after, pf_sim_interactions_force); ahead: the
 * interactions' prepare after the ghosts' exchange (explicit steps). Collective. */
int pf_sim_body_forces(pf_sim *sim, double dt, int ahead);
extern const pf_key pf_parallel_keys[];
int pf_sim_setup_parallel(pf_sim *sim);
/* sim/output.c: output.fields, precision and compression, checked against the output fields. */
int pf_sim_setup_exodus_format(pf_sim *sim, const pf_node *out);
/* sim/provenance.c: the outputs' title and provenance lines (sim->prov), and their release. */
int pf_sim_provenance(pf_sim *sim);
void pf_sim_provenance_free(pf_sim *sim);
/* Partition the bodies' points (clouds generated on every rank), keep this rank's points with
 * their families and ghosts, and attach them to the bodies. Collective. */
int pf_sim_distribute(pf_sim *sim, const pf_point_cloud *pc);
/* sim/sets.c: the bodies' node and side sets into sim->sets, from their meshes and clouds. */
int pf_sim_sets_build(pf_sim *sim, const pf_point_cloud *pc);
/* The bodies' global ids, consecutive in deck order: gid0[b + 1] = gid0[b] + count[b]. */
void pf_sim_number_bodies(pf_sim *sim, const pf_gid *count);
/* Re-partition when the work imbalance exceeds the deck's threshold (at output steps): the work
 * of a point is its intact bonds + 1 and the work of its interactions (pf_sim_interactions_work),
 * the weights the partition balances. */
int pf_sim_rebalance(pf_sim *sim);
/* The time section's keys that need no model (max_motion, safety_factor, dt, exactly one of
 * final_time and steps, each in range): checked before the bodies are built, so that a slip there
 * is reported at once rather than after the set-up. */
int pf_sim_check_time_keys(const pf_sim *sim);
/* The step and the run's length from the time keys and the bodies' stable step. */
int pf_sim_setup_time(pf_sim *sim);
/* Partition, migrate, add ghosts and attach the bodies; fresh: initial state (set-up). extra: NULL
 * or each owned point's interaction work (pf_partition_weight); imbalance: NULL, or the work
 * imbalance of the new partition by its weights. The rows' bonds are given back at the end (the
 * bodies hold them then); the caller frees the rows. */
int pf_sim_settle(pf_sim *sim, pf_bond_rows *rows, const int *extra, int fresh, double *imbalance);
/* An output's path: given (or <deck name less its extension><ext>), under --output-dir unless
 * absolute. A path longer than PF_SIM_PATH_MAX is an error naming key (node: where the deck
 * gives it). */
int pf_sim_output_name(const pf_sim *sim, const pf_node *node, const char *key, const char *given, const char *ext,
                       char *out, size_t len);
extern const pf_key pf_restart_keys[];
int pf_sim_setup_restart(pf_sim *sim);
int pf_sim_checkpoint(pf_sim *sim);
int pf_sim_restore_points(pf_sim *sim, const pf_point_cloud *pc);
int pf_sim_restore_state(pf_sim *sim);
void pf_sim_restart_free(pf_sim *sim);
/* A checkpoint's content checked against the deck (sim/restart_check.c): bodies (collective),
 * global ids within their body's range (collective, after pf_sim_number_bodies), the scalars
 * time v[0], step v[1], dt v[2] and the bodies' stable steps, and (after the set-up) time,
 * step and dt against each other and the run's end. */
int pf_sim_check_restart_bodies(const pf_sim *sim);
int pf_sim_check_restart_gids(const pf_sim *sim);
int pf_sim_check_restart_scalars(const pf_sim *sim, const double *v, const double *stable);
int pf_sim_check_restart_time(const pf_sim *sim, const double *v);
/* Each owned point's reference position, volume and cell equal to its set-up's in the clouds
 * pc[nbodies] (bitwise: the set-up copies them), after the ids are checked. Collective. */
int pf_sim_check_restart_reference(const pf_sim *sim, const pf_point_cloud *pc);
/* After the set-up: every point field the run's models keep in checkpoints was in the file
 * (one registered by the set-up alone would start from nothing). */
int pf_sim_check_restart_fields(const pf_sim *sim);

/* The timed calibration of --check (sim/check_calibrate.c): CPU seconds per rank (per thread of
 * a rank), each the largest over the ranks; steps 0 when none was taken (the run began, or a
 * quasi-static solver's load step). Collective; the model is spent afterwards. */
typedef struct {
  int steps;    /* steps timed (after the warm-up) */
  int warmup;   /* steps taken before them */
  long from;    /* the step the calibration started from */
  double setup; /* the process so far: start, deck, mesh, points, bonds */
  double first; /* the forces at t = 0 */
  double step;  /* the median of the timed steps */
  double row;   /* a history row (the energy ledger's totals) */
  double frame; /* a frame's output fields and fragments, short of the file */
} pf_sim_calibration;
int pf_sim_check_calibrate(pf_sim *sim, pf_sim_calibration *c);
double pf_sim_cpu_seconds(void);
/* sim/restart_geometry.c: each body's geometry from its set-up cloud pc[nbodies] (and mesh);
 * as checkpoint scalars v[PF_GEOMETRY_SCALARS nbodies] (points, elements, hash halves); a
 * checkpoint's saved[PF_GEOMETRY_SCALARS nbodies] against this set-up's, refused naming the body, its mesh or point file and what
 * differs. */
void pf_sim_geometry_take(pf_sim *sim, const pf_point_cloud *pc);
void pf_sim_geometry_scalars(const pf_sim *sim, double *v);
int pf_sim_check_restart_geometry(const pf_sim *sim, const double *saved);
/* sim/signals.c: SIGTERM / SIGINT, caught from the start of the set-up. During the set-up (meshing, lattices,
 * neighbour search: nothing is written then) a signal ends the process at once with a message
 * and exit status 128 + signal; after pf_sim_setup_done it stops the run at the end of the
 * current step with a checkpoint. */
void pf_sim_catch_signals(void);
void pf_sim_setup_done(void);
/* The signal this rank received (0: none); the step's guard reduction (pf_sim_guard_check) makes
 * it the largest over the ranks, in sim->signal. */
int pf_sim_signal_here(void);
/* on = 1: SIGTERM / SIGINT stop the run at the end of the current step with a checkpoint (the
 * set-up's exit is not armed), the signal caught so far forgotten; on = 0: the handlers there were
 * before put back (perifem_catch_signals). */
void pf_sim_catch_run_signals(int on);
int pf_sim_setup_output(pf_sim *sim);
/* The output section's schedules (interval, time_interval, frames and their history twins: at
 * most one of each three, each in range), checked before the bodies are built. */
int pf_sim_check_output_keys(const pf_deck *d);
/* Whether a step (from t_before to t) writes a frame or a history row: by time (period > 0) when
 * t reaches the next multiple of the period, else every `every` steps (0: never). Depends on
 * the step's times only, so a restarted run keeps the schedule. */
int pf_sim_output_due(long every, double period, long step, double t_before, double t);
/* sim/output.c: the history's columns (time, step, then the ledger's columns: the run's totals,
 * each body's, each interaction's, the probes') and one row of them; the Exodus file; output at a
 * step; the last good state. Collective. */
typedef struct {
  int n;             /* the ledger's columns (time and step come before them) */
  char **names;
  const char **units;
  double *values;    /* [n + 2] */
} pf_sim_history_row;
int pf_sim_globals_init(const pf_sim *sim, pf_sim_history_row *g);
/* Fill values[0..n+1]: time, step, the columns; first: the balance now is the initial one. */
int pf_sim_globals_eval(pf_sim *sim, pf_sim_history_row *g, int first);
void pf_sim_globals_free(pf_sim_history_row *g);
/* sim/accounts.c: open the run's totals, each body's accounts, the interactions' and the
 * probes' (at set-up, after the interactions are built); evaluate them (the bodies' energies and
 * motion, the probes, one reduction; first: the initial balance); book the energy the bodies'
 * failed bonds released since the last call (after each force evaluation). Collective but the
 * last. */
int pf_sim_accounts_open(pf_sim *sim);
int pf_sim_accounts_evaluate(pf_sim *sim, int first);
void pf_sim_accounts_book_damage(pf_sim *sim);
/* The run's totals after the last evaluation: its account's value. */
double pf_sim_total(const pf_sim *sim, int id);
/* The largest energy in play, max(|E0|, |W_ext|, KE + W_el + U_contact + |U_FE|), J, and the
 * energy balance error relative to it, after the last evaluation. */
double pf_sim_energy_scale(const pf_sim *sim);
double pf_sim_energy_error(const pf_sim *sim);
/* sim/run.c: the history columns as last evaluated (at the start of the run and at each history
 * row; sim/api.c evaluates them again at the end of each call), or NULL before the run starts or
 * after it failed. */
pf_sim_history_row *pf_sim_history(pf_sim *sim);
void pf_sim_run_free(pf_sim *sim);
int pf_sim_open_output(pf_sim *sim, pf_sim_history_row *g);
int pf_sim_write_output(pf_sim *sim, pf_sim_history_row *g, int exodus, int history, int last);
int pf_sim_write_last_good(pf_sim *sim, pf_sim_history_row *g, int ierr);
/* 1 when the Exodus output is one file per rank (output.layout: spread, on several ranks). */
int pf_sim_spread_output(const pf_sim *sim);

/* sim/fragments.c: the "fragment" field (registered by _setup when the deck asks)
 * and <file>.fragments.csv at an Exodus step; final: also the summary lines. Collective. */
int pf_sim_fragments_setup(pf_sim *sim);
/* The fragments table's name, <Exodus file less .e>.fragments.csv (after the output names). */
void pf_sim_fragments_name(pf_sim *sim);
/* sim/paths.c: the rule for every file a run writes (an input error naming the key): no output
 * is an input (deck, meshes, point files, the checkpoint restarted from) or another output or
 * temporary file, compared through the file system; each is absent or a regular file in a
 * writable folder; a symbolic link is replaced by its target in the sim's paths (and logged). */
int pf_sim_check_paths(pf_sim *sim);
/* The same rule for perifem_checkpoint's path: target (len bytes) gets the file to write. */
int pf_sim_check_checkpoint_path(pf_sim *sim, const char *path, char *target, size_t len);
/* sim/output_lock.c: <file>.lock for each output (rank 0 creates them; collective): a second run
 * writing the same files is refused, naming the first; a lock of a process gone from this host
 * is taken over with a warning. Unlock removes them (pf_sim_destroy). */
int pf_sim_lock_outputs(pf_sim *sim);
void pf_sim_unlock_outputs(pf_sim *sim);
/* sim/unit_slips.c: warn (rank 0, with file:line:key) about material values that look like a
 * unit slip: a density outside [100, 1e5] kg/m^3, a modulus outside [1e6, 1e13] Pa. */
void pf_sim_warn_unit_slips(const pf_deck *d, const pf_node *materials);
int pf_sim_fragments(pf_sim *sim, int final);
/* sim/probes.c: output.probes, mass-averaged quantities over regions. The columns'
 * count and names; _eval fills values[count] (collective; a probe whose region holds no point
 * is an input error). */
extern const pf_key pf_sim_probe_keys[];
int pf_sim_setup_probes(pf_sim *sim);
int pf_sim_probe_columns(const pf_sim *sim);
void pf_sim_probe_column(const pf_sim *sim, int column, char *name, size_t len, const char **units);
int pf_sim_probes_eval(const pf_sim *sim, double *values);
/* Instability guards: keep the state at the start of each step; flag a point moving more than
 * time.max_motion of its horizon (PD) or cell (FE node) in one step; at the step's end check
 * forces and velocities for NaN/Inf and, on every rank together, go back to the last good
 * state and fail. */
int pf_sim_guard_save(pf_sim *sim);
void pf_sim_guard_motion(pf_sim *sim, double dt);
int pf_sim_guard_check(pf_sim *sim);
void pf_sim_guard_free(pf_sim *sim);
/* sim/health.c, the run-health monitor: at each history row (g just evaluated), warn on rank 0
 * once per class and body when the energy error passes 1 % and 5 %, a body's hourglass energy
 * passes 10 % of its internal energy, a body's damaged fraction rises by more than 0.1 between
 * two rows, or a contact pair's bodies interpenetrate; with --strict the first warning is a run
 * failure on every rank. Two small reductions. Collective. */
int pf_sim_health_check(pf_sim *sim);
/* A warning of the monitor, unless `what` (its class and owner) was given before; with --strict
 * an error on every rank (each holds the same reduced figures). */
int pf_sim_health_warn(pf_sim *sim, const char *what, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The summary's last line: "health: ok" or "health: N warnings (…)". */
void pf_sim_health_summary(const pf_sim *sim);
/* sim/body_state.c: body b's span of the store; the bond rows of every owned point (PD
 * families, FE node adjacency); the bodies' per-element state as tables (name fem_<body>, the
 * kinds with table ops); a re-partition that keeps that state. */
pf_body_span pf_sim_span(const pf_sim *sim, int b);
int pf_sim_bond_rows(const pf_sim *sim, pf_bond_rows *rows);
/* The bond fields the bodies' rows carry, registered alone (before a checkpoint is read into
 * rows). */
int pf_sim_bond_fields(const pf_sim *sim, pf_bond_rows *rows);
/* 1 when body b keeps a state table: t gets its name, total and ncomp, *nlocal its local rows. */
int pf_sim_table_shape(const pf_sim *sim, int b, pf_table *t, pf_int *nlocal);
int pf_sim_body_tables(const pf_sim *sim, pf_table *t, int *n);
void pf_sim_body_tables_free(pf_table *t, int n);
#endif
