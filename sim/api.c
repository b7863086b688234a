/* The public C API (include/perifem.h): a thin layer over pf_sim that copies what it is handed,
 * clears and reports errors as status codes, starts MPI when the caller has not, and reads the
 * point store and the history row for the caller. */
#include "include/perifem.h"

#include <errno.h>
#include <string.h>

#include "sim/sim_impl.h"

/* The field names of the point store's own arrays (the registered fields follow). */
enum { NCORE_FIELDS = 7 };
static const char *const core_field[NCORE_FIELDS] = {"reference_position", "position", "displacement", "velocity",
                                                     "force", "mass", "volume"};

struct perifem_sim {
  pf_sim *sim;
  char *deck_path, *deck_text, *output_dir, *restart_from, *command_line;
  char **overrides;
  int noverrides;
  char field_names[NCORE_FIELDS + PF_MAX_FIELDS][32]; /* refreshed by perifem_field_count/_name */
  int nfield_names;
};

static int started_mpi = 0; /* 1: perifem_create called MPI_Init (perifem_finalize ends it) */

#define RAISE(code, ...) pf_error_raise((code), __FILE__, __LINE__, __func__, __VA_ARGS__)

/* The status of a call: a failure without a message (none should be) gets one. */
static int status(int ierr, const char *what) {
  if (ierr && !pf_error_message()[0]) RAISE(ierr, "%s failed (code %d)", what, ierr);
  return ierr;
}

static int need_sim(const perifem_sim *s, const char *func) {
  pf_error_clear();
  return s && s->sim ? 0 : RAISE(PF_ERR_INPUT, "%s: the simulation is NULL", func);
}

static int need_body(const perifem_sim *s, int b, const char *func) {
  PF_CALL(need_sim(s, func));
  PF_CHECK(b >= 0 && b < s->sim->nbodies, PF_ERR_INPUT, "%s: no body %d (the deck has %d, numbered from 0)", func, b,
           s->sim->nbodies);
  return 0;
}

const char *perifem_version(void) { return PERIFEM_VERSION; }

void perifem_version_numbers(int *major, int *minor, int *patch) {
  if (major) *major = PERIFEM_VERSION_MAJOR;
  if (minor) *minor = PERIFEM_VERSION_MINOR;
  if (patch) *patch = PERIFEM_VERSION_PATCH;
}

const char *perifem_last_error(void) { return pf_error_message(); }

/* ---- creation --------------------------------------------------------------------------------- */

static int start_mpi(void) {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  PF_CHECK(!fin, PF_ERR_LIB, "MPI has been finalized in this process; perifem needs it running");
  if (init) return 0;
  pf_mpi_defaults();
  const int ok = MPI_Init(NULL, NULL) == MPI_SUCCESS;
  pf_mpi_defaults_release();
  PF_CHECK(ok, PF_ERR_LIB, "MPI_Init failed");
  started_mpi = 1;
  return 0;
}

/* perifem computes on MPI_COMM_WORLD (every module reduces and exchanges over it): a communicator
 * given must hold the same ranks in the same order. */
static int check_comm(const perifem_options *o) {
  if (!o->use_comm) return 0;
  MPI_Comm comm = MPI_Comm_f2c(o->comm);
  PF_CHECK(comm != MPI_COMM_NULL, PF_ERR_INPUT, "the communicator given (Fortran handle %d) is MPI_COMM_NULL", o->comm);
  int same = MPI_UNEQUAL, size = 0;
  MPI_Comm_compare(comm, MPI_COMM_WORLD, &same);
  MPI_Comm_size(comm, &size);
  PF_CHECK(same == MPI_IDENT || same == MPI_CONGRUENT, PF_ERR_INPUT,
           "the communicator given (%d ranks) is %s MPI_COMM_WORLD (%d ranks); perifem computes on "
           "MPI_COMM_WORLD: give it or a duplicate of it, with every rank taking part",
           size, same == MPI_SIMILAR ? "MPI_COMM_WORLD's ranks in another order, not" : "not", pf_comm_size());
  return 0;
}

static char *copy(const char *text) { return text ? strdup(text) : NULL; }

static int copy_options(perifem_sim *s, const char *deck_path, const char *yaml, const perifem_options *o) {
  PF_CHECK(o->noverrides >= 0 && (o->noverrides == 0 || o->overrides), PF_ERR_INPUT,
           "perifem_options: %d overrides and no array of them", o->noverrides);
  s->deck_path = copy(deck_path), s->deck_text = copy(yaml), s->output_dir = copy(o->output_dir);
  s->restart_from = copy(o->restart_from), s->command_line = copy(o->command_line);
  PF_MALLOC(s->overrides, o->noverrides);
  s->noverrides = o->noverrides;
  int ok = s->deck_path && (!yaml || s->deck_text) && (!o->output_dir || s->output_dir) &&
           (!o->restart_from || s->restart_from) && (!o->command_line || s->command_line);
  for (int k = 0; k < o->noverrides; k++) {
    PF_CHECK(o->overrides[k], PF_ERR_INPUT, "perifem_options: override %d is NULL", k);
    ok &= (s->overrides[k] = strdup(o->overrides[k])) != NULL;
  }
  PF_CHECK(ok, PF_ERR_MEMORY, "out of memory copying the options");
  return 0;
}

static void free_copies(perifem_sim *s) {
  for (int k = 0; k < s->noverrides && s->overrides; k++) free(s->overrides[k]);
  free(s->overrides), free(s->deck_path), free(s->deck_text), free(s->output_dir), free(s->restart_from);
  free(s->command_line);
}

static int create(const char *deck_path, const char *yaml, const perifem_options *opt, perifem_sim **out) {
  PF_CHECK(out, PF_ERR_INPUT, "perifem_create: the address of the result is NULL");
  *out = NULL;
  PF_CHECK(deck_path, PF_ERR_INPUT, "perifem_create: the deck's path is NULL");
  const perifem_options none = {0}, *o = opt ? opt : &none;
  PF_CHECK(o->progress >= 0 && o->progress <= 2, PF_ERR_INPUT, "perifem_options: progress must be 0, 1 or 2 (got %d)",
           o->progress);
  PF_CALL(start_mpi());
  PF_CALL(check_comm(o));
  pf_log_set_quiet(o->quiet);
  pf_error_set_quiet(o->silent_errors);
  pf_log_set_status(o->progress == 0 ? -1 : o->progress == 2);
  perifem_sim *s;
  PF_MALLOC(s, 1);
  int ierr = copy_options(s, deck_path, yaml, o);
  const int dir_err = !ierr && s->output_dir && !o->no_output ? pf_sim_dir_creatable(s->output_dir) : 0;
  if (dir_err) /* (before the set-up, which can take minutes) */
    ierr = RAISE(PF_ERR_INPUT, "output folder %s: cannot create the folder: %s", s->output_dir, strerror(dir_err));
  if (!ierr) {
    const pf_sim_options so = {.output_dir = s->output_dir, .no_output = o->no_output, .restart_from = s->restart_from,
                               .sets = (const char *const *)s->overrides, .nsets = s->noverrides,
                               .command_line = s->command_line, .strict = o->strict, .deck_text = s->deck_text,
                               .keep_signals = !o->catch_signals};
    ierr = pf_sim_create(s->deck_path, &so, &s->sim);
  }
  if (ierr) {
    free_copies(s);
    free(s);
    return ierr;
  }
  *out = s;
  return 0;
}

int perifem_create(const char *deck_path, const perifem_options *opt, perifem_sim **sim) {
  pf_error_clear();
  return status(create(deck_path, NULL, opt, sim), "perifem_create");
}

int perifem_create_from_string(const char *yaml, const char *name, const perifem_options *opt, perifem_sim **sim) {
  pf_error_clear();
  if (sim) *sim = NULL;
  if (!yaml) return RAISE(PF_ERR_INPUT, "perifem_create_from_string: the deck's text is NULL");
  return status(create(name ? name : "deck.yaml", yaml, opt, sim), "perifem_create_from_string");
}

int perifem_destroy(perifem_sim **sim) {
  pf_error_clear();
  if (!sim || !*sim) return 0;
  perifem_sim *s = *sim;
  int ierr = pf_sim_destroy(&s->sim);
  free_copies(s);
  free(s);
  *sim = NULL;
  return status(ierr, "perifem_destroy");
}

int perifem_finalize(void) {
  pf_error_clear();
  if (pf_io_abandoned())
    return RAISE(PF_ERR_RUN, "a file could not be closed after a failed write: MPI_Finalize would crash inside "
                             "HDF5, so MPI is left running; end the process (MPI_Abort)");
  int fin = 0;
  MPI_Finalized(&fin);
  if (started_mpi && !fin) MPI_Finalize();
  started_mpi = 0;
  return 0;
}

/* ---- running ---------------------------------------------------------------------------------- */

/* Advance n steps (n < 0: to the end); the history row evaluated again at the current step when
 * the last one is older. */
static int advance(perifem_sim *s, long n) {
  pf_sim *sim = s->sim;
  if (!sim->run && s->output_dir && !sim->opt.no_output) {
    const int err = pf_sim_make_dir(s->output_dir);
    PF_CHECK(!err, PF_ERR_INPUT, "output folder %s: cannot create the folder: %s", s->output_dir, strerror(err));
  }
  PF_CHECK(n >= -1, PF_ERR_INPUT, "perifem_step: the number of steps is negative (%ld)", n);
  PF_CALL(pf_sim_run_advance(sim, n));
  pf_sim_history_row *row = pf_sim_history(sim);
  if (row && row->values[1] != (double)sim->step) PF_CALL(pf_sim_globals_eval(sim, row, 0));
  return 0;
}

int perifem_step(perifem_sim *sim, long n) {
  PF_CALL(need_sim(sim, "perifem_step"));
  PF_CHECK(n >= 0, PF_ERR_INPUT, "perifem_step: the number of steps is negative (%ld)", n);
  return status(advance(sim, n), "perifem_step");
}

int perifem_run(perifem_sim *sim) {
  PF_CALL(need_sim(sim, "perifem_run"));
  return status(advance(sim, -1), "perifem_run");
}

int perifem_finished(const perifem_sim *sim) { return sim && sim->sim && pf_sim_finished(sim->sim); }
double perifem_time(const perifem_sim *sim) { return sim && sim->sim ? sim->sim->t : 0.0; }
long perifem_step_count(const perifem_sim *sim) { return sim && sim->sim ? sim->sim->step : 0; }
double perifem_dt(const perifem_sim *sim) { return sim && sim->sim ? sim->sim->dt : 0.0; }
long perifem_total_steps(const perifem_sim *sim) { return sim && sim->sim ? sim->sim->nsteps : 0; }

int perifem_print_check(perifem_sim *sim) {
  PF_CALL(need_sim(sim, "perifem_print_check"));
  return status(pf_sim_check_report(sim->sim), "perifem_print_check");
}

int perifem_catch_signals(int on) {
  pf_error_clear();
  if (on != 0 && on != 1) return RAISE(PF_ERR_INPUT, "perifem_catch_signals: on must be 0 or 1 (got %d)", on);
  pf_sim_catch_run_signals(on);
  return 0;
}

int perifem_signal_caught(void) { return pf_sim_signal_here(); }

/* ---- bodies and fields ------------------------------------------------------------------------ */

int perifem_body_count(const perifem_sim *sim) { return sim && sim->sim ? sim->sim->nbodies : 0; }

const char *perifem_body_name(const perifem_sim *sim, int b) {
  return sim && sim->sim && b >= 0 && b < sim->sim->nbodies ? sim->sim->body_name[b] : NULL;
}

int perifem_body_index(const perifem_sim *sim, const char *name) {
  for (int b = 0; name && b < perifem_body_count(sim); b++)
    if (!strcmp(sim->sim->body_name[b], name)) return b;
  return -1;
}

long perifem_body_points(const perifem_sim *sim, int b) {
  if (!sim || !sim->sim || b < 0 || b >= sim->sim->nbodies) return -1;
  return (long)(sim->sim->body_start[b + 1] - sim->sim->body_start[b]);
}

int64_t perifem_body_points_global(const perifem_sim *sim, int b) {
  const long n = perifem_body_points(sim, b);
  return n < 0 ? -1 : (int64_t)pf_sum_all((double)n);
}

int perifem_body_ids(const perifem_sim *sim, int b, int64_t *ids) {
  PF_CALL(need_body(sim, b, "perifem_body_ids"));
  const pf_int i0 = sim->sim->body_start[b], n = sim->sim->body_start[b + 1] - i0;
  PF_CHECK(ids || n == 0, PF_ERR_INPUT, "perifem_body_ids: the array is NULL");
  for (pf_int i = 0; i < n; i++) ids[i] = sim->sim->pts->gid[i0 + i];
  return 0;
}

/* The field name of the point store (every point) and its components, or NULL. */
static double *store_field(const pf_points *p, const char *name, int *ncomp) {
  double *const core[NCORE_FIELDS] = {p->X, p->y, p->u, p->v, p->f, p->m, p->vol};
  for (int k = 0; k < NCORE_FIELDS; k++)
    if (!strcmp(name, core_field[k])) return *ncomp = k < 5 ? 3 : 1, core[k];
  for (int k = 0; k < p->nfields; k++)
    if (!strcmp(name, p->fields[k].name)) return *ncomp = p->fields[k].ncomp, p->fields[k].data;
  return NULL;
}

static void refresh_field_names(perifem_sim *s) {
  const pf_points *p = s->sim->pts;
  int n = 0;
  for (int k = 0; k < NCORE_FIELDS; k++) snprintf(s->field_names[n++], sizeof s->field_names[0], "%s", core_field[k]);
  for (int k = 0; k < p->nfields; k++) snprintf(s->field_names[n++], sizeof s->field_names[0], "%s", p->fields[k].name);
  s->nfield_names = n;
}

int perifem_field_count(const perifem_sim *sim) {
  if (!sim || !sim->sim) return 0;
  refresh_field_names((perifem_sim *)sim); /* (the names are the handle's cache) */
  return sim->nfield_names;
}

const char *perifem_field_name(const perifem_sim *sim, int k) {
  if (k < 0 || k >= perifem_field_count(sim)) return NULL;
  return sim->field_names[k];
}

int perifem_field_components(const perifem_sim *sim, const char *name) {
  int ncomp = 0;
  if (sim && sim->sim && name && store_field(sim->sim->pts, name, &ncomp)) return ncomp;
  return 0;
}

/* Body b's span of the field name: the first value and the components. */
static int body_field(const perifem_sim *sim, int b, const char *name, const char *func, const double **data,
                      int *ncomp) {
  PF_CALL(need_body(sim, b, func));
  PF_CHECK(name, PF_ERR_INPUT, "%s: the field name is NULL", func);
  const double *all = store_field(sim->sim->pts, name, ncomp);
  if (!all) {
    char known[1024];
    size_t at = 0;
    known[0] = '\0';
    for (int k = 0; k < perifem_field_count(sim) && at < sizeof known; k++)
      at += (size_t)snprintf(known + at, sizeof known - at, "%s%s", k ? ", " : "", sim->field_names[k]);
    return RAISE(PF_ERR_INPUT, "%s: no field '%s' (known: %s)", func, name, known);
  }
  *data = all + (size_t)*ncomp * (size_t)sim->sim->body_start[b];
  return 0;
}

int perifem_field_read(const perifem_sim *sim, int b, const char *name, double *out, long capacity) {
  const double *data;
  int ncomp;
  PF_CALL(body_field(sim, b, name, "perifem_field_read", &data, &ncomp));
  const long n = perifem_body_points(sim, b) * ncomp;
  PF_CHECK(capacity >= n && (out || n == 0), PF_ERR_INPUT,
           "perifem_field_read: field '%s' of body '%s' has %ld values on this rank; the array holds %ld", name,
           sim->sim->body_name[b], n, out ? capacity : 0L);
  if (n) memcpy(out, data, sizeof(double) * (size_t)n);
  return 0;
}

int perifem_field_view(const perifem_sim *sim, int b, const char *name, const double **data, int *ncomp) {
  PF_CHECK(data && ncomp, PF_ERR_INPUT, "perifem_field_view: data or ncomp is NULL");
  *data = NULL, *ncomp = 0;
  return body_field(sim, b, name, "perifem_field_view", data, ncomp);
}

/* ---- history ---------------------------------------------------------------------------------- */

static const pf_sim_history_row *history(const perifem_sim *sim) {
  return sim && sim->sim ? pf_sim_history(sim->sim) : NULL;
}

int perifem_history_count(const perifem_sim *sim) {
  const pf_sim_history_row *row = history(sim);
  return row ? row->n + 2 : 0;
}

const char *perifem_history_name(const perifem_sim *sim, int k) {
  return k >= 0 && k < perifem_history_count(sim) ? history(sim)->names[k] : NULL;
}

const char *perifem_history_unit(const perifem_sim *sim, int k) {
  return k >= 0 && k < perifem_history_count(sim) ? history(sim)->units[k] : NULL;
}

static int need_history(const perifem_sim *sim, const char *func) {
  PF_CALL(need_sim(sim, func));
  PF_CHECK(history(sim), PF_ERR_INPUT, "%s: no history row: the run %s", func,
           sim->sim->run ? "stopped on an error" : "has not started (perifem_step or perifem_run starts it)");
  return 0;
}

int perifem_history_row(const perifem_sim *sim, double *values, int capacity) {
  PF_CALL(need_history(sim, "perifem_history_row"));
  const pf_sim_history_row *row = history(sim);
  PF_CHECK(values && capacity >= row->n + 2, PF_ERR_INPUT, "perifem_history_row: the row has %d values; the array holds %d",
           row->n + 2, values ? capacity : 0);
  memcpy(values, row->values, sizeof(double) * (size_t)(row->n + 2));
  return 0;
}

int perifem_history_value(const perifem_sim *sim, const char *name, double *value) {
  PF_CALL(need_history(sim, "perifem_history_value"));
  PF_CHECK(name && value, PF_ERR_INPUT, "perifem_history_value: name or value is NULL");
  const pf_sim_history_row *row = history(sim);
  for (int k = 0; k < row->n + 2; k++)
    if (!strcmp(row->names[k], name)) return *value = row->values[k], 0;
  return RAISE(PF_ERR_INPUT, "perifem_history_value: no history column '%s' (perifem_history_name lists them)", name);
}

/* ---- checkpoint and digest -------------------------------------------------------------------- */

int perifem_checkpoint(perifem_sim *sim, const char *path) {
  PF_CALL(need_sim(sim, "perifem_checkpoint"));
  PF_CHECK(path && path[0], PF_ERR_INPUT, "perifem_checkpoint: no path given");
  pf_sim *s = sim->sim;
  if (!s->run) PF_CALL(status(advance(sim, 0), "perifem_checkpoint")); /* the forces at t = 0 */
  char target[sizeof s->restart_path], deck_path[sizeof s->restart_path];
  PF_CALL(status(pf_sim_check_checkpoint_path(s, path, target, sizeof target), "perifem_checkpoint"));
  memcpy(deck_path, s->restart_path, sizeof deck_path);
  memcpy(s->restart_path, target, sizeof target);
  const int ierr = pf_sim_checkpoint(s);
  memcpy(s->restart_path, deck_path, sizeof deck_path);
  return status(ierr, "perifem_checkpoint");
}

int perifem_digest(perifem_sim *sim, uint64_t *digest) {
  PF_CALL(need_sim(sim, "perifem_digest"));
  PF_CHECK(digest, PF_ERR_INPUT, "perifem_digest: the result's address is NULL");
  return status(pf_state_digest(sim->sim->pts, digest), "perifem_digest");
}
