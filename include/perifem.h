/* perifem.h — the public C API of perifem (libperifem.so.0): build a simulation from a deck, run
 * it step by step, read its fields and history, checkpoint it.
 *
 * Plain C; it includes no MPI header and exposes no internal type. docs/library.md has examples
 * in C and Python.
 *
 * Conventions.
 *  - Every fallible function returns an int status: PERIFEM_OK (0) or one of the PERIFEM_ERR_*
 *    codes; perifem_last_error() then gives the message. Errors in the deck name file:line:column
 *    and the key, as the command line does. The library never ends the process on bad input;
 *    the exceptions, all outside the caller's control of its input, are listed under "Process
 *    ends" below.
 *  - Units are SI throughout (s, m, kg, N, J).
 *  - Ownership: strings and arrays handed in are copied before the call returns, unless said
 *    otherwise; pointers handed out belong to the library and stay valid as long as the function
 *    says.
 *  - MPI. perifem computes on MPI_COMM_WORLD: every rank of it must create the simulation and
 *    make the same collective calls in the same order (marked "Collective" below). A caller may
 *    give a communicator (its Fortran handle, MPI_Comm_c2f(comm), e.g. mpi4py's comm.py2f()); it
 *    must then be congruent to MPI_COMM_WORLD (the same ranks in the same order: MPI_COMM_WORLD,
 *    a duplicate of it), else creation fails with PERIFEM_ERR_INPUT. When MPI is not initialized,
 *    the first creation initializes it (MPI_Init) and perifem_finalize() finalizes it. Each rank
 *    owns part of each body's points (the partition may change at the deck's output steps): the
 *    field functions read this rank's owned points only; the global values (time, step, history,
 *    digest) are the same on every rank.
 *  - Threads: one thread at a time per process may call the library (its error message and log
 *    settings are process-wide).
 *
 * Process ends. MPI errors abort as MPI does; a checkpoint or output file that HDF5 fails to
 * close on one rank ends every rank with MPI_Abort (the other ranks may be waiting inside the
 * close); a gmsh geometry file that calls `Exit;`, or gmsh aborting while it meshes (out of
 * memory), ends the process with status 2 after a message (gmsh offers no way to refuse it).
 */
#ifndef PERIFEM_H
#define PERIFEM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PERIFEM_VERSION_MAJOR 0
#define PERIFEM_VERSION_MINOR 1
#define PERIFEM_VERSION_PATCH 0

/* Status codes (the command line's exit statuses are 0, 1 for PERIFEM_ERR_RUN and the others, 2
 * for PERIFEM_ERR_INPUT). */
enum perifem_status {
  PERIFEM_OK = 0,
  PERIFEM_ERR_RUN = 1,    /* the run failed: instability guard, NaN, a failed write, a signal */
  PERIFEM_ERR_INPUT = 2,  /* bad deck, bad argument, a call out of order */
  PERIFEM_ERR_MEMORY = 3, /* out of memory */
  PERIFEM_ERR_LIB = 4     /* a library perifem calls failed (MPI, HDF5, Exodus, gmsh) */
};

/* The library's version, "MAJOR.MINOR.PATCH", and its numbers (any pointer may be NULL): compare
 * them with the PERIFEM_VERSION_* macros a program was compiled with. */
const char *perifem_version(void);
void perifem_version_numbers(int *major, int *minor, int *patch);

/* The message of the last failed call of this process, "" when none failed (each call that
 * returns a status clears it first). Valid until the next call into the library. */
const char *perifem_last_error(void);

/* How to build a simulation. Zero-initialize it (perifem_options o = {0};): every zero field
 * means the default given. Strings and arrays are copied by perifem_create*. */
typedef struct perifem_options {
  const char *const *overrides; /* deck overrides "key.path=value" (a YAML value; list items by
                                   index or by name, e.g. "bodies.sphere.initial_velocity=[0,0,-900]"),
                                   applied in order after include: and before the deck's
                                   parameters are substituted; as the command line's --set */
  int noverrides;
  const char *output_dir;   /* folder of the output files (created when missing); NULL: the current one */
  int no_output;            /* 1: write no Exodus, history or fragments file */
  const char *restart_from; /* a checkpoint to continue from (any number of ranks), or NULL */
  int quiet;                /* 1: print errors only (rank 0 prints the log otherwise) */
  int strict;               /* 1: a run-health warning stops the run as an error */
  int progress;             /* 0: a status line on a terminal, else plain lines; 1: plain lines;
                               2: a status line */
  int silent_errors;        /* 1: errors are not printed to stderr (read perifem_last_error);
                               0: printed as they happen, as the command line does */
  int catch_signals;        /* 1: SIGTERM/SIGINT as the command line: during the set-up the
                               process ends at once, later the run checkpoints and stops at the
                               end of the step; 0: the caller's handlers stay */
  int use_comm;             /* 1: comm below is the communicator; 0: MPI_COMM_WORLD */
  int comm;                 /* the communicator's Fortran handle (MPI_Comm_c2f) */
  const char *command_line; /* recorded in the outputs' provenance, or NULL */
} perifem_options;

/* An opaque simulation. */
typedef struct perifem_sim perifem_sim;

/* Load and check the deck file deck_path, apply opt's overrides, and build the model (points,
 * families, elements, contact, the time step); writes no file. opt may be NULL (defaults). On
 * failure *sim is NULL. Collective. */
int perifem_create(const char *deck_path, const perifem_options *opt, perifem_sim **sim);

/* The same from the deck's YAML text. name is the file the text stands for (it is not read):
 * messages name it, files the deck names are relative to its folder, and the outputs are named
 * after it unless the deck names them; NULL: "deck.yaml" in the current folder. Collective. */
int perifem_create_from_string(const char *yaml, const char *name, const perifem_options *opt,
                               perifem_sim **sim);

/* Free everything; *sim becomes NULL (NULL is accepted). Output files still open are closed.
 * Collective. */
int perifem_destroy(perifem_sim **sim);

/* Finalize MPI if perifem initialized it (call once, after the last perifem_destroy). When a
 * file could not be closed after a failed write, MPI_Finalize would crash inside HDF5: then MPI is
 * left as it is and PERIFEM_ERR_RUN is returned; end the process (MPI_Abort, _exit). */
int perifem_finalize(void);

/* ---- running --------------------------------------------------------------------------------
 * perifem_step(sim, n) takes n more steps with everything a run does at the deck's intervals:
 * Exodus output, history rows, checkpoints, the health checks; the first call (n = 0 allowed)
 * also computes the forces at t = 0 and writes the first output and history row. The run ends at
 * the deck's final time or step count: then the summary is printed and the files are closed;
 * further steps do nothing. Stepping in parts gives bitwise the same state as one run. A run
 * that failed (PERIFEM_ERR_RUN: the instability guard, a failed write, --strict's warning) refuses
 * to go on. Collective. */
int perifem_step(perifem_sim *sim, long n);
/* Run to the end (the command line's run, less the digest line). Collective. */
int perifem_run(perifem_sim *sim);
/* 1 when the run has reached its final time or step count, else 0. */
int perifem_finished(const perifem_sim *sim);
/* Simulated time (s), steps taken, the step size (s; with finite-element or correspondence bodies
 * and no time.dt it follows the deformation), and the number of steps of the whole run (with a
 * varying step: the set-up's estimate). */
double perifem_time(const perifem_sim *sim);
long perifem_step_count(const perifem_sim *sim);
double perifem_dt(const perifem_sim *sim);
long perifem_total_steps(const perifem_sim *sim);
/* SIGINT and SIGTERM from now on (on = 1) as the command line takes them during a run: the run
 * stops at the end of the current step of perifem_step or perifem_run, writes a checkpoint (the
 * deck's restart file), prints where it stopped and closes its files (the ranks agree on the step);
 * the call returns PERIFEM_OK and perifem_signal_caught() gives the signal. Nothing ends the
 * process, during a set-up either; a signal the process ignores stays ignored. on = 0 puts back
 * the handlers there were before. For a caller whose own handler would act only once the call
 * returns (Python's KeyboardInterrupt). A signal caught before is forgotten when catching starts.
 * Process-wide. */
int perifem_catch_signals(int on);
/* The signal caught (SIGINT 2, SIGTERM 15) since perifem_catch_signals(1) or, with
 * perifem_options.catch_signals, since the set-up; 0: none. */
int perifem_signal_caught(void);
/* Print the set-up report of `perifem --check` (rank 0, standard output): bodies, points, bonds,
 * elements, the step, memory, output sizes, and the run time from a few steps it times (no
 * output written). Before the run has begun those steps spend the model: perifem_step and
 * perifem_run then fail; create it again to run. Collective. */
int perifem_print_check(perifem_sim *sim);

/* ---- bodies and fields ----------------------------------------------------------------------
 * Bodies are numbered 0 .. perifem_body_count() - 1 in deck order. A field is named:
 * "reference_position", "position" (current), "displacement", "velocity", "force" (N), each with
 * 3 components; "mass" (kg), "volume" (m^3); and any registered point field (e.g. "damage"; list
 * them with perifem_field_name). Values are point-major: value c of point i is data[i * ncomp + c].
 * Points are this rank's owned points of the body, in the library's order: perifem_body_ids gives
 * their global ids (0-based, consecutive per body in deck order). */
int perifem_body_count(const perifem_sim *sim);
/* Body b's name (valid until perifem_destroy), or NULL for a bad index. */
const char *perifem_body_name(const perifem_sim *sim, int b);
/* The index of the body named name, or -1. */
int perifem_body_index(const perifem_sim *sim, const char *name);
/* Body b's points on this rank (owned), and over all ranks (collective); -1 for a bad index. */
long perifem_body_points(const perifem_sim *sim, int b);
int64_t perifem_body_points_global(const perifem_sim *sim, int b);
/* The global ids of body b's points on this rank into ids[perifem_body_points()]. */
int perifem_body_ids(const perifem_sim *sim, int b, int64_t *ids);

/* The number of field names, and the k-th (valid until perifem_destroy; NULL past the end). */
int perifem_field_count(const perifem_sim *sim);
const char *perifem_field_name(const perifem_sim *sim, int k);
/* The components of the field name (0: no such field). */
int perifem_field_components(const perifem_sim *sim, const char *name);
/* Copy field name of body b's points on this rank into out, which holds capacity doubles (at
 * least perifem_body_points() * components). */
int perifem_field_read(const perifem_sim *sim, int b, const char *name, double *out, long capacity);
/* The field's values of body b's points on this rank in place, without a copy: *data points to
 * perifem_body_points() * *ncomp doubles. Read only, and valid until the next perifem_step,
 * perifem_run or perifem_destroy (a step may re-partition the points). */
int perifem_field_view(const perifem_sim *sim, int b, const char *name, const double **data, int *ncomp);

/* ---- history --------------------------------------------------------------------------------
 * The history columns: "time", "step", the energies, momentum, damage fraction, forces on rigid
 * surfaces, walls and contact pairs, each body's centre and mean velocity, probes (the columns
 * of the history file, docs/user_guide.md). Available once the run has started (after the first
 * perifem_step or perifem_run); the values are those at the current step, the same on every
 * rank. Column names and units are valid until perifem_destroy. */
int perifem_history_count(const perifem_sim *sim);
const char *perifem_history_name(const perifem_sim *sim, int k);
const char *perifem_history_unit(const perifem_sim *sim, int k);
/* The current row into values[capacity] (capacity >= perifem_history_count()). */
int perifem_history_row(const perifem_sim *sim, double *values, int capacity);
/* The value of the column name at the current step into *value. */
int perifem_history_value(const perifem_sim *sim, const char *name, double *value);

/* ---- checkpoint and digest ------------------------------------------------------------------- */
/* Write a checkpoint of the current state to path (HDF5; written to path.tmp and renamed, so a
 * failed write keeps the file there before); perifem_options.restart_from continues from it on
 * any number of ranks. path follows the rule for every file a run writes (docs/user_guide.md,
 * "What a run may write"): the deck, another input or output, a device, a FIFO or an unwritable
 * folder gives PERIFEM_ERR_INPUT and writes nothing; a symbolic link is written through.
 * Collective. */
int perifem_checkpoint(perifem_sim *sim, const char *path);
/* The state digest (a hash of every point's state in global-id order, independent of the number
 * of ranks): the value `perifem` prints as "state digest: %016llx". Collective. */
int perifem_digest(perifem_sim *sim, uint64_t *digest);

#ifdef __cplusplus
}
#endif

#endif
