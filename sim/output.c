/* A simulation's output: the history's columns and rows (global quantities), the Exodus file
 * (joined or spread) with its fields, and the last good state when a guard stops the run. The
 * time loop that writes them at their intervals is sim/run.c. */
#include "sim/sim_impl.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_sim_output_name(const pf_sim *sim, const pf_node *node, const char *key, const char *given, const char *ext,
                       char *out, size_t len) {
  const char *p = pf_deck_path(sim->deck), *slash = strrchr(p, '/'), *name = slash ? slash + 1 : p;
  const char *dot = strrchr(name, '.');
  const int stem = (int)(dot ? dot - name : (long)strlen(name));
  const char *dir = sim->opt.output_dir && (!given || given[0] != '/') ? sim->opt.output_dir : NULL;
  const size_t n = given ? (size_t)snprintf(out, len, "%s%s%s", dir ? dir : "", dir ? "/" : "", given)
                         : (size_t)snprintf(out, len, "%s%s%.*s%s", dir ? dir : "", dir ? "/" : "", stem, name, ext);
  if (n <= PF_SIM_PATH_MAX) return 0;
  out[0] = '\0';
  return pf_deck_error(sim->deck, node, key, "the path is %zu bytes long; at most %d (the system's PATH_MAX, %d, less "
                       "room for the suffixes a run adds: -restart<step>, .tmp, .lock)", n, PF_SIM_PATH_MAX, PATH_MAX);
}

/* The run's end for output.frames: time.final_time, or for a run given by steps, the steps
 * times the first step (the step of a quasi-static run is final_time / load steps). */
static double frames_span(const pf_sim *sim) {
  return isfinite(sim->final_time) ? sim->final_time : (double)sim->nsteps * sim->dt;
}

/* One schedule of the output: keys[0] steps between writes (at least `least`), keys[1] seconds
 * between them, keys[2] a count over the run; at most one given, each in its range. Needs no
 * model. */
static int check_schedule(const pf_deck *d, const pf_node *out, const char *const keys[3], long least) {
  const char *first = NULL;
  for (int k = 0; k < 3; k++) {
    if (!pf_node_get(out, keys[k])) continue;
    if (first)
      return pf_deck_error(d, pf_node_get(out, keys[k]), keys[k], "give at most one of '%s', '%s' and '%s' (also "
                           "given: '%s')", keys[0], keys[1], keys[2], first);
    first = keys[k];
  }
  double period = 1;
  long n = least;
  if (pf_node_get(out, keys[1])) {
    PF_CALL(pf_deck_real(d, out, keys[1], &period));
    if (!(period > 0 && isfinite(period)))
      return pf_deck_error(d, pf_node_get(out, keys[1]), keys[1], "must be a positive finite time (got %g)", period);
  } else if (pf_node_get(out, keys[2])) {
    PF_CALL(pf_deck_int(d, out, keys[2], &n));
    if (n < 1) return pf_deck_error(d, pf_node_get(out, keys[2]), keys[2], "must be at least 1 (got %ld)", n);
  } else if (pf_node_get(out, keys[0])) {
    PF_CALL(pf_deck_int(d, out, keys[0], &n));
    if (n < least)
      return pf_deck_error(d, pf_node_get(out, keys[0]), keys[0], "must be at least %ld (got %ld)", least, n);
  }
  return 0;
}

static const char *const frame_keys[3] = {"interval", "time_interval", "frames"};
static const char *const row_keys[3] = {"history_interval", "history_time_interval", "history_frames"};

int pf_sim_check_output_keys(const pf_deck *d) {
  const pf_node *out = pf_node_get(pf_deck_root(d), "output");
  PF_CALL(check_schedule(d, out, frame_keys, 0));
  return check_schedule(d, out, row_keys, 1);
}

/* One schedule (check_schedule's keys) into *every or, by time, *period > 0. */
static int read_schedule(pf_sim *sim, const pf_node *out, const char *const keys[3], long least, long *every,
                         double *period) {
  const pf_deck *d = sim->deck;
  PF_CALL(check_schedule(d, out, keys, least));
  *period = 0;
  if (pf_node_get(out, keys[1])) PF_CALL(pf_deck_real(d, out, keys[1], period));
  else if (pf_node_get(out, keys[2])) {
    long n = 0;
    PF_CALL(pf_deck_int(d, out, keys[2], &n));
    *period = frames_span(sim) / (double)n;
    if (!(*period > 0 && isfinite(*period)))
      return pf_deck_error(d, pf_node_get(out, keys[2]), keys[2], "the run's end time is %g s: no time to divide",
                           frames_span(sim));
  } else PF_CALL(pf_deck_int(d, out, keys[0], every));
  return 0;
}

int pf_sim_output_due(long every, double period, long step, double t_before, double t) {
  /* (1e-9 of a period: a step that lands on a multiple but for rounding counts as reaching it) */
  if (period > 0) return floor(t / period + 1e-9) > floor(t_before / period + 1e-9);
  return every > 0 && step % every == 0;
}

int pf_sim_setup_output(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *out = pf_node_get(pf_deck_root(d), "output");
  const char *file = NULL, *hfile = NULL;
  sim->output_interval = 100;
  sim->history_interval = 10;
  PF_CALL(pf_deck_string(d, out, "file", &file));
  PF_CALL(pf_deck_string(d, out, "history_file", &hfile));
  PF_CALL(read_schedule(sim, out, frame_keys, 0, &sim->output_interval, &sim->output_period));
  PF_CALL(read_schedule(sim, out, row_keys, 1, &sim->history_interval, &sim->history_period));
  PF_CALL(pf_deck_bool(d, out, "fragments", &sim->fragments));
  PF_CALL(pf_sim_fragments_setup(sim));
  PF_CALL(pf_sim_setup_probes(sim));
  PF_CALL(pf_sim_output_name(sim, pf_node_get(out, "file"), "file", file, ".e", sim->exodus_path,
                             sizeof sim->exodus_path));
  PF_CALL(pf_sim_output_name(sim, pf_node_get(out, "history_file"), "history_file", hfile, ".h5", sim->history_path,
                             sizeof sim->history_path));
  return pf_sim_setup_exodus_format(sim, out);
}

int pf_sim_globals_init(const pf_sim *sim, pf_sim_history_row *g) {
  const pf_ledger *l = &sim->ledger;
  g->n = pf_ledger_columns(l);
  PF_MALLOC(g->names, g->n + 2);
  PF_MALLOC(g->units, g->n + 2);
  PF_MALLOC(g->values, g->n + 2);
  g->names[0] = strdup("time"), g->units[0] = "s";
  g->names[1] = strdup("step"), g->units[1] = "";
  for (int k = 0; k < g->n; k++) {
    char buf[192];
    pf_ledger_column(l, k, buf, sizeof buf, &g->units[2 + k]);
    g->names[2 + k] = strdup(buf);
  }
  for (int k = 0; k < g->n + 2; k++) PF_CHECK(g->names[k], PF_ERR_MEMORY, "out of memory");
  return 0;
}

void pf_sim_globals_free(pf_sim_history_row *g) {
  for (int k = 0; g->names && k < g->n + 2; k++) free(g->names[k]);
  PF_FREE(g->names);
  PF_FREE(g->units);
  PF_FREE(g->values);
}

int pf_sim_globals_eval(pf_sim *sim, pf_sim_history_row *g, int first) {
  PF_CALL(pf_sim_accounts_evaluate(sim, first));
  g->values[0] = sim->t;
  g->values[1] = (double)sim->step;
  pf_ledger_values(&sim->ledger, g->values + 2);
  return 0;
}

int pf_sim_spread_output(const pf_sim *sim) { return sim->spread_output && pf_comm_size() > 1; }

/* The spread form <file>.<ranks>.<rank>, the rank zero-padded to the width of <ranks> (the
 * Nemesis convention by which ParaView's Exodus readers open the set as one data set). */
static void spread_name(const char *path, int rank, char *out, size_t len) {
  int size = pf_comm_size(), width = snprintf(NULL, 0, "%d", size);
  snprintf(out, len, "%s.%d.%0*d", path, size, width, rank);
}

/* Rank 0 writes <file> itself as the list of the pieces' names, one a line, relative to its
 * folder: the IOSS "metafile" form. ParaView's default Exodus reader (the IOSS reader, from
 * ParaView 5.10) finds the other pieces of a piece it is given by listing the piece's folder,
 * and a piece named without a folder ("run.e.3.0", as pvpython users type it in the run's
 * folder) gives it no folder to list: it loads that piece alone, silently. A metafile's names
 * are resolved against the metafile's full path, so <file> opened by any path loads every piece
 * (docs/user_guide.md §3.1). */
static int write_piece_list(const char *path) {
  if (pf_comm_rank() != 0) return 0;
  const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
  FILE *f = fopen(path, "w");
  PF_CHECK(f, PF_ERR_RUN, "cannot write the list of the Exodus pieces '%s': %s", path, strerror(errno));
  for (int r = 0; r < pf_comm_size(); r++) {
    char piece[4200];
    spread_name(base, r, piece, sizeof piece);
    fprintf(f, "%s\n", piece);
  }
  const int bad = ferror(f) | (fclose(f) != 0);
  PF_CHECK(!bad, PF_ERR_RUN, "cannot write the list of the Exodus pieces '%s'", path);
  return 0;
}

/* Whether name is a nodal variable the Exodus file can hold; else an error listing them. */
static int known_field(const pf_sim *sim, const pf_node *item) {
  const char *name = pf_node_text(item);
  char known[1024] = "displacement, velocity, force";
  if (!strcmp(name, "displacement") || !strcmp(name, "velocity") || !strcmp(name, "force")) return 0;
  for (int k = 0; k < sim->pts->nfields; k++) {
    const pf_field *f = &sim->pts->fields[k];
    if (!(f->flags & PF_FIELD_OUTPUT)) continue;
    if (!strcmp(f->name, name)) return 0;
    size_t at = strlen(known);
    snprintf(known + at, sizeof known - at, ", %s", f->name);
  }
  return pf_deck_error(sim->deck, item, "fields", "no output field '%s' in this deck (known: %s)", name, known);
}

int pf_sim_setup_exodus_format(pf_sim *sim, const pf_node *out) {
  const pf_deck *d = sim->deck;
  const char *precision = "double";
  long level = 0;
  PF_CALL(pf_deck_string(d, out, "precision", &precision));
  PF_CALL(pf_deck_int(d, out, "compression", &level));
  if (strcmp(precision, "double") && strcmp(precision, "single"))
    return pf_deck_error(d, pf_node_get(out, "precision"), "precision", "double or single (got '%s')", precision);
  if (level < 0 || level > 9)
    return pf_deck_error(d, pf_node_get(out, "compression"), "compression", "0 to 9 (got %ld)", level);
  sim->exo_opt = (pf_exodus_options){&sim->prov, !strcmp(precision, "single"), (int)level, NULL, 0};
  const pf_node *list = pf_node_get(out, "fields");
  if (!list) return 0;
  free(sim->exo_fields);
  PF_MALLOC(sim->exo_fields, pf_node_count(list) + 1);
  for (int k = 0; k < pf_node_count(list); k++) {
    PF_CALL(known_field(sim, pf_node_item(list, k)));
    sim->exo_fields[k] = pf_node_text(pf_node_item(list, k));
  }
  sim->exo_opt.fields = sim->exo_fields, sim->exo_opt.nfields = pf_node_count(list);
  return 0;
}

static int open_exodus(pf_sim *sim, pf_sim_history_row *g) {
  const char *const *names = (const char *const *)g->names + 2;
  if (pf_sim_spread_output(sim)) {
    char path[sizeof sim->exodus_path + 32];
    spread_name(sim->exodus_path, pf_comm_rank(), path, sizeof path);
    PF_CALL(write_piece_list(sim->exodus_path));
    return pf_exodus_create(path, sim->pts, sim->nbodies, sim->body_name, sim->body_start, g->n, names, &sim->exo_opt, &sim->exo);
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
    const pf_mesh *m = pf_body_mesh(&sim->body[b]);
    if (!m || ierr) continue;
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
                                  names, &sim->exo_opt, &sim->exo);
  for (int b = 0; b < sim->nbodies; b++) free(conn[b]);
  return ierr;
}

int pf_sim_open_output(pf_sim *sim, pf_sim_history_row *g) {
  if (sim->opt.no_output) return 0;
  PF_CALL(pf_sim_lock_outputs(sim));
  PF_CALL(pf_agree(open_exodus(sim, g), "creating the Exodus output %s", sim->exodus_path));
  int ierr = pf_history_create(sim->history_path, g->n + 2, (const char *const *)g->names, g->units, &sim->prov, &sim->hist);
  return pf_agree(ierr, "creating the history %s", sim->history_path);
}

static int write_exodus(pf_sim *sim, const double *values) {
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(pf_body_output_fields(&sim->body[b], sim->pts));
  if (pf_sim_spread_output(sim)) return pf_exodus_write(sim->exo, sim->t, sim->pts, values);
  PF_CALL(pf_points_gather(sim->pts, &sim->joined));
  return sim->joined ? pf_exodus_write(sim->exo, sim->t, sim->joined, values) : 0;
}

/* A failed write (rank 0's joined Exodus file or history, or a rank's spread file) is agreed by
 * every rank before the next collective call; the message names the file, step and time. */
int pf_sim_write_output(pf_sim *sim, pf_sim_history_row *g, int exodus, int history, int last) {
  if (exodus) PF_CALL(pf_sim_fragments(sim, last));
  if (sim->opt.no_output) return 0;
  pf_error_context("(output of step %ld, t = %.6e s)", sim->step, sim->t);
  int ierr = exodus ? write_exodus(sim, g->values + 2) : 0;
  ierr = pf_agree(ierr, "writing the Exodus output %s", sim->exodus_path);
  if (!ierr && history) ierr = pf_agree(pf_history_append(sim->hist, g->values), "writing the history %s",
                                        sim->history_path);
  pf_error_context(NULL);
  return ierr;
}

/* The guards stopped the run with every rank back at the start of the failed step: write that
 * state as a last Exodus step (the global variables are those of the last history row; FE
 * stresses are those of the failed step), then fail with the guard's error. Collective. */
int pf_sim_write_last_good(pf_sim *sim, pf_sim_history_row *g, int ierr) {
  if (sim->opt.no_output || write_exodus(sim, g->values + 2)) return ierr;
  pf_log("perifem: the last good state (step %ld, t = %.6e s) is the last step of %s\n", sim->step, sim->t,
         sim->exodus_path);
  return ierr;
}

