/* Checkpoint and restart of a simulation (core/checkpoint.c holds the file format). A
 * checkpoint holds the owned points with every field, the bond rows with their broken flags
 * (PD families, FE node adjacency), the FE bodies' element state as whole tables, and the
 * scalars of the run: time, step, dt, energies booked so far, the indenters' positions and
 * reactions, the FE bodies' stable steps, the walls' and contact pairs' last forces, each
 * body's geometry (sim/restart_geometry.c) and a hash of each part of the deck that sets the
 * physics. A restart reads
 * the points on any number of ranks and re-partitions them like the set-up does, so the run
 * continues bitwise as if it had not stopped. What it reads is checked before use: by the reader
 * (core/checkpoint_check.c) and against the deck (sim/restart_check.c). */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <string.h>

const pf_key pf_restart_keys[] = {
    {"file", PF_KEY_STRING, 0, "<deck name>.restart.h5", "", "checkpoint file (HDF5, written through <file>.tmp)", NULL},
    {"interval", PF_KEY_INT, 0, "0", "", "steps between checkpoints (0: only on SIGTERM/SIGINT)", NULL},
    PF_KEY_END};

/* The parts of the deck whose change changes the physics (output, parallel and the run length
 * may change on restart). */
static const char *const physics_parts[] = {"units", "materials", "bodies", "indenters", "contact", "boundary_conditions",
                                            "walls", "time.dt", "time.safety_factor", "solver"};
enum { NPARTS = sizeof physics_parts / sizeof physics_parts[0], NFIXED = 3 };

static uint64_t part_hash(const pf_deck *d, const char *part) {
  const pf_node *root = pf_deck_root(d);
  const char *dot = strchr(part, '.');
  if (!dot) return pf_node_hash(pf_node_get(root, part));
  char top[32];
  snprintf(top, sizeof top, "%.*s", (int)(dot - part), part);
  return pf_node_hash(pf_node_get(pf_node_get(root, top), dot + 1));
}

/* Where each group of scalars starts (see scalars_make); the run's books (the ledger's records)
 * and the interactions' state come after the geometry. */
static int at_stable(void) { return NFIXED + 2 * NPARTS; }
static int at_geometry(const pf_sim *sim) { return at_stable() + sim->nbodies; }
static int at_books(const pf_sim *sim) { return at_geometry(sim) + PF_GEOMETRY_SCALARS * sim->nbodies; }
static int nbooks(const pf_sim *sim) { return pf_ledger_records(&sim->ledger) + pf_sim_interactions_nstate(sim); }

/* Scalar names and values: time, step, dt, the deck-part hashes (two 32-bit halves each), per
 * body the carried stable step of the last force evaluation (FE and coupled bodies; 0 for the
 * others) and its geometry (points, elements, hash halves: sim/restart_geometry.c); then, once the
 * interactions and the ledger exist (books: 1), the ledger's records and the interactions'
 * state. A restart reads the first part with the points and the books after the set-up. */
static int scalars_make(const pf_sim *sim, int books, pf_sim_scalars *s) {
  s->n = at_books(sim) + (books ? nbooks(sim) : 0);
  PF_MALLOC(s->name, s->n);
  PF_MALLOC(s->names, s->n);
  PF_MALLOC(s->value, s->n);
  const char *fixed[NFIXED] = {"time", "step", "dt"};
  int k = 0;
  for (; k < NFIXED; k++) snprintf(s->name[k], 96, "%s", fixed[k]);
  for (int p = 0; p < NPARTS; p++, k += 2) {
    snprintf(s->name[k], 96, "deck_hash_%s_hi", physics_parts[p]);
    snprintf(s->name[k + 1], 96, "deck_hash_%s_lo", physics_parts[p]);
  }
  const char *geo[PF_GEOMETRY_SCALARS] = {"points", "elements", "positions_hash_hi", "positions_hash_lo",
                                          "connectivity_hash_hi", "connectivity_hash_lo"};
  for (int b = 0; b < sim->nbodies; b++) {
    snprintf(s->name[at_stable() + b], 96, "body_%d_%s_stable_dt", b, sim->body_name[b]);
    for (int c = 0; c < PF_GEOMETRY_SCALARS; c++)
      snprintf(s->name[at_geometry(sim) + PF_GEOMETRY_SCALARS * b + c], 96, "body_%d_%s_%s", b, sim->body_name[b], geo[c]);
  }
  if (books) {
    pf_ledger_record_names(&sim->ledger, &s->name[at_books(sim)]);
    pf_sim_interactions_state_names(sim, &s->name[at_books(sim) + pf_ledger_records(&sim->ledger)]);
  }
  for (int q = 0; q < s->n; q++) s->names[q] = s->name[q];
  return 0;
}

static void scalars_free(pf_sim_scalars *s) {
  PF_FREE(s->name);
  PF_FREE(s->names);
  PF_FREE(s->value);
}

/* Collective (the books' sums, the carried stable steps). */
static int scalars_fill(pf_sim *sim, int books, pf_sim_scalars *s) {
  double *v = s->value;
  v[0] = sim->t, v[1] = (double)sim->step, v[2] = sim->dt;
  for (int p = 0; p < NPARTS; p++) {
    uint64_t h = part_hash(sim->deck, physics_parts[p]);
    v[NFIXED + 2 * p] = (double)(h >> 32), v[NFIXED + 2 * p + 1] = (double)(h & 0xffffffffu);
  }
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b]; /* the carried stable steps */
    v[at_stable() + b] = pf_body_carries_stable_dt(body) ? pf_body_stable_dt_all(body, sim->pts) : 0;
  }
  pf_sim_geometry_scalars(sim, &v[at_geometry(sim)]);
  if (!books) return 0;
  PF_CALL(pf_ledger_record_values(&sim->ledger, &v[at_books(sim)]));
  pf_sim_interactions_state_get(sim, &v[at_books(sim) + pf_ledger_records(&sim->ledger)]);
  return 0;
}

int pf_sim_setup_restart(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *r = pf_node_get(pf_deck_root(d), "restart");
  const char *file = NULL;
  PF_CALL(pf_deck_string(d, r, "file", &file));
  PF_CALL(pf_deck_int(d, r, "interval", &sim->restart_interval));
  if (sim->restart_interval < 0)
    return pf_deck_error(d, pf_node_get(r, "interval"), "interval", "must not be negative");
  return pf_sim_output_name(sim, pf_node_get(r, "file"), "file", file, ".restart.h5", sim->restart_path,
                            sizeof sim->restart_path);
}

int pf_sim_checkpoint(pf_sim *sim) {
  pf_bond_rows rows;
  pf_sim_scalars s = {0};
  pf_table tables[PF_MAX_BODIES];
  int ntables = 0;
  PF_CALL(pf_bond_rows_init(&rows));
  int ierr = scalars_make(sim, 1, &s);
  if (!ierr) ierr = pf_sim_bond_rows(sim, &rows);
  if (!ierr) ierr = pf_sim_body_tables(sim, tables, &ntables);
  if (!ierr) ierr = scalars_fill(sim, 1, &s);
  if (!ierr) {
    pf_points owned = *sim->pts; /* the owned points only */
    owned.n_total = owned.n_owned;
    pf_error_context("(checkpoint of step %ld, t = %.6e s)", sim->step, sim->t);
    ierr = pf_checkpoint_write(sim->restart_path, &owned, &rows, s.n, s.names, s.value, ntables, tables);
    pf_error_context(NULL);
  }
  pf_sim_body_tables_free(tables, ntables);
  pf_bond_rows_free(&rows);
  scalars_free(&s);
  if (!ierr) pf_log("step %ld: checkpoint %s\n", sim->step, sim->restart_path);
  return ierr;
}

/* Refuse a checkpoint written with a deck whose physics differs, naming the part: after the
 * geometry checks (which name what moved), before the masses are checked (a changed density
 * would otherwise be reported as damaged masses). */
static int check_deck(const pf_sim *sim, const double *saved) {
  for (int p = 0; p < NPARTS; p++) {
    const uint64_t h = part_hash(sim->deck, physics_parts[p]);
    const int k = NFIXED + 2 * p;
    if (saved[k] == (double)(h >> 32) && saved[k + 1] == (double)(h & 0xffffffffu)) continue;
    PF_CHECK(0, PF_ERR_INPUT,
             "%s: '%s' differs from the deck the checkpoint %s was written with; a restart may change "
             "only output, restart, parallel, title and the run length (time.final_time/steps)",
             pf_deck_path(sim->deck), physics_parts[p], sim->opt.restart_from);
  }
  return 0;
}

/* The bodies' global ids as pf_sim_distribute numbered them, from the checkpoint's point counts
 * of each body. Collective. */
static void body_gids(pf_sim *sim) {
  double n[PF_MAX_BODIES] = {0};
  pf_gid count[PF_MAX_BODIES];
  for (pf_int i = 0; i < sim->pts->n_owned; i++) n[sim->pts->body[i]] += 1;
  MPI_Allreduce(MPI_IN_PLACE, n, sim->nbodies, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (int b = 0; b < sim->nbodies; b++) count[b] = (pf_gid)n[b];
  pf_sim_number_bodies(sim, count);
}

int pf_sim_restore_points(pf_sim *sim, const pf_point_cloud *pc) {
  pf_bond_rows rows;
  PF_CALL(pf_bond_rows_init(&rows));
  PF_CALL(scalars_make(sim, 0, &sim->restart_scalars));
  pf_sim_scalars *s = &sim->restart_scalars;
  int ierr = pf_sim_bond_fields(sim, &rows);
  if (!ierr) ierr = pf_checkpoint_read(sim->opt.restart_from, &sim->pts, &rows, s->n, s->names, s->value, s->n,
                                       &sim->restart_format);
  if (!ierr) ierr = pf_sim_check_restart_geometry(sim, &s->value[at_geometry(sim)]);
  if (!ierr) ierr = pf_sim_check_restart_scalars(sim, s->value, &s->value[at_stable()]);
  if (!ierr) ierr = pf_sim_check_restart_bodies(sim);
  if (!ierr) body_gids(sim);
  if (!ierr) ierr = pf_sim_check_restart_gids(sim);
  if (!ierr) ierr = pf_sim_check_restart_reference(sim, pc);
  if (!ierr) ierr = check_deck(sim, s->value); /* (the geometry named first; then the deck, before the masses) */
  sim->restart_nfields = sim->pts ? sim->pts->nfields : 0;
  if (!ierr) ierr = pf_sim_settle(sim, &rows, NULL, 0, NULL);
  pf_bond_rows_free(&rows);
  for (int b = 0; b < sim->nbodies && !ierr; b++) { /* the elements' state, whole on every rank */
    pf_body *body = &sim->body[b];
    pf_table t;
    pf_int nlocal;
    if (!pf_sim_table_shape(sim, b, &t, &nlocal)) continue;
    double *full = malloc(sizeof(double) * ((size_t)t.total * t.ncomp + 1));
    if (!full) return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    ierr = pf_checkpoint_read_table(sim->opt.restart_from, &t, full);
    if (!ierr) pf_body_table_set(body, full);
    if (!ierr) pf_body_set_stable_dt(body, s->value[at_stable() + b]);
    free(full);
  }
  return ierr;
}

/* A restarted run writes new output files: <name>-restart<step>.<ext>, leaving the first run's. */
static void rename_output(char *path, size_t len, long step) {
  char *slash = strrchr(path, '/'), *dot = strrchr(path, '.'), tail[64] = "";
  if (!dot || (slash && dot < slash)) dot = path + strlen(path);
  snprintf(tail, sizeof tail, "%s", dot);
  snprintf(dot, len - (size_t)(dot - path), "-restart%ld%s", step, tail);
}

/* The books as the checkpoint holds them: the ledger's records and the interactions' state. */
static int restore_books(pf_sim *sim) {
  pf_sim_scalars all = {0};
  PF_CALL(scalars_make(sim, 1, &all));
  const int at = at_books(sim);
  int ierr = pf_checkpoint_read_scalars(sim->opt.restart_from, all.n - at, all.names + at, all.value + at);
  if (!ierr) {
    pf_ledger_restore(&sim->ledger, &all.value[at]);
    pf_sim_interactions_state_set(sim, &all.value[at + pf_ledger_records(&sim->ledger)]);
  }
  scalars_free(&all);
  return ierr;
}

/* After the set-up: take time and the books from the file. */
int pf_sim_restore_state(pf_sim *sim) {
  const double *v = sim->restart_scalars.value;
  PF_CALL(pf_sim_check_restart_time(sim, v));
  PF_CALL(pf_sim_check_restart_fields(sim));
  if (sim->adaptive) sim->dt = v[2]; /* the step follows the elements: the last one taken */
  PF_CHECK(v[2] == sim->dt, PF_ERR_INPUT, "the checkpoint %s was written with dt = %.17g s, this set-up gives %.17g s",
           sim->opt.restart_from, v[2], sim->dt);
  sim->t = v[0], sim->step = (long)v[1];
  PF_CALL(restore_books(sim));
  rename_output(sim->exodus_path, sizeof sim->exodus_path, sim->step);
  rename_output(sim->history_path, sizeof sim->history_path, sim->step);
  pf_log("restarted from %s at step %ld, t = %.6e s\n", sim->opt.restart_from, sim->step, sim->t);
  return 0;
}

void pf_sim_restart_free(pf_sim *sim) { scalars_free(&sim->restart_scalars); }
