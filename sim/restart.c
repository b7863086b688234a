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

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const pf_key pf_restart_keys[] = {
    {"file", PF_KEY_STRING, 0, "<deck name>.restart.h5", "", "checkpoint file (HDF5, written through <file>.tmp)", NULL},
    {"interval", PF_KEY_INT, 0, "0", "", "steps between checkpoints (0: only on SIGTERM/SIGINT)", NULL},
    PF_KEY_END};

/* The parts of the deck whose change changes the physics (output, parallel and the run length
 * may change on restart). */
static const char *const physics_parts[] = {"units", "materials", "bodies", "indenters", "contact", "boundary_conditions",
                                            "walls", "time.dt", "time.safety_factor"};
enum { NPARTS = sizeof physics_parts / sizeof physics_parts[0], NFIXED = 10 };

static uint64_t part_hash(const pf_deck *d, const char *part) {
  const pf_node *root = pf_deck_root(d);
  const char *dot = strchr(part, '.');
  if (!dot) return pf_node_hash(pf_node_get(root, part));
  char top[32];
  snprintf(top, sizeof top, "%.*s", (int)(dot - part), part);
  return pf_node_hash(pf_node_get(pf_node_get(root, top), dot + 1));
}

/* The walls and contact pairs as the deck lists them (known before they are built: a restart
 * reads the scalars with the points). */
static int deck_walls(const pf_sim *sim) { return pf_node_count(pf_node_get(pf_deck_root(sim->deck), "walls")); }
static int deck_pairs(const pf_sim *sim) {
  return pf_node_count(pf_node_get(pf_node_get(pf_deck_root(sim->deck), "contact"), "pairs"));
}

/* Where each group of scalars starts (see scalars_make). */
static int at_rigid(void) { return NFIXED + 2 * NPARTS; }
static int at_stable(const pf_sim *sim) { return at_rigid() + 6 * sim->nrigid; }
static int at_geometry(const pf_sim *sim) { return at_stable(sim) + sim->nbodies; }
static int at_walls(const pf_sim *sim) { return at_geometry(sim) + PF_GEOMETRY_SCALARS * sim->nbodies; }
static int at_pairs(const pf_sim *sim) { return at_walls(sim) + 3 * deck_walls(sim); }
static int at_sums(const pf_sim *sim) { return at_pairs(sim) + 3 * deck_pairs(sim); } /* (format 3 on) */
static int deck_bcs(const pf_sim *sim) {
  return pf_node_count(pf_node_get(pf_deck_root(sim->deck), "boundary_conditions"));
}

/* The history's running sums (format 3): damage_redistribution; per body its damage
 * dissipation, redistribution and prescribed work; per condition its last step's and total
 * impulse; per rigid surface its impulse and work; per wall its impulse. */
enum { SUMS_BODY = 3, SUMS_BC = 6, SUMS_RIGID = 4, SUMS_WALL = 3 };
static int nsums(const pf_sim *sim) {
  return 1 + SUMS_BODY * sim->nbodies + SUMS_BC * deck_bcs(sim) + SUMS_RIGID * sim->nrigid + SUMS_WALL * deck_walls(sim);
}

static void sums_names(const pf_sim *sim, pf_sim_scalars *s) {
  char (*name)[96] = &s->name[at_sums(sim)];
  const char *body[SUMS_BODY] = {"damage", "redistribution", "bc_work"};
  snprintf(*name++, 96, "damage_redistribution");
  for (int b = 0; b < sim->nbodies; b++)
    for (int q = 0; q < SUMS_BODY; q++) snprintf(*name++, 96, "body_%d_%s_%s", b, sim->body_name[b], body[q]);
  for (int k = 0; k < deck_bcs(sim); k++)
    for (int q = 0; q < SUMS_BC; q++) snprintf(*name++, 96, "bc_%d_%s_%c", k, q < 3 ? "step_impulse" : "impulse", 'x' + q % 3);
  for (int k = 0; k < sim->nrigid; k++) {
    for (int a = 0; a < 3; a++) snprintf(*name++, 96, "indenter_%d_%s_impulse_%c", k, pf_rigid_name(sim->rigid[k]), 'x' + a);
    snprintf(*name++, 96, "indenter_%d_%s_work", k, pf_rigid_name(sim->rigid[k]));
  }
  for (int k = 0; k < deck_walls(sim); k++)
    for (int a = 0; a < 3; a++) snprintf(*name++, 96, "wall_%d_impulse_%c", k, 'x' + a);
}

/* Their values: sums over the ranks (collective), the rigid surfaces' work as it is (the same on
 * every rank). */
static void sums_fill(const pf_sim *sim, double *v) {
  *v++ = pf_sum_all(sim->damage_redistribution);
  for (int b = 0; b < sim->nbodies; b++) {
    *v++ = pf_sum_all(sim->body_damage[b]);
    *v++ = pf_sum_all(sim->body_redistribution[b]);
    *v++ = pf_sum_all(sim->body_bc_work[b]);
  }
  for (int k = 0; k < deck_bcs(sim); k++) {
    double step[3] = {0, 0, 0}, total[3] = {0, 0, 0};
    if (k < sim->nbcs) pf_bc_impulse(sim->bcs[k], step, total); /* (none before they are built) */
    for (int a = 0; a < 3; a++) *v++ = pf_sum_all(step[a]);
    for (int a = 0; a < 3; a++) *v++ = pf_sum_all(total[a]);
  }
  for (int k = 0; k < sim->nrigid; k++) {
    for (int a = 0; a < 3; a++) *v++ = pf_sum_all(sim->rigid_impulse[k][a]);
    *v++ = sim->rigid_work[k];
  }
  for (int k = 0; k < deck_walls(sim); k++)
    for (int a = 0; a < 3; a++) *v++ = k < sim->nwalls ? pf_sum_all(sim->wall_impulse[k][a]) : 0;
}

/* Take them back: rank 0 carries each sum over the ranks, the others start from 0. */
static void sums_restore(pf_sim *sim, const double *v) {
  const double root = pf_comm_rank() == 0;
  sim->damage_redistribution = root * *v++;
  for (int b = 0; b < sim->nbodies; b++) {
    sim->body_damage[b] = root * *v++;
    sim->body_redistribution[b] = root * *v++;
    sim->body_bc_work[b] = root * *v++;
  }
  for (int k = 0; k < sim->nbcs; k++, v += SUMS_BC) {
    double step[3], total[3];
    for (int a = 0; a < 3; a++) step[a] = root * v[a], total[a] = root * v[3 + a];
    pf_bc_impulse_set(sim->bcs[k], step, total);
  }
  for (int k = 0; k < sim->nrigid; k++, v += SUMS_RIGID) {
    for (int a = 0; a < 3; a++) sim->rigid_impulse[k][a] = root * v[a];
    sim->rigid_work[k] = v[3];
  }
  for (int k = 0; k < sim->nwalls; k++, v += SUMS_WALL)
    for (int a = 0; a < 3; a++) sim->wall_impulse[k][a] = root * v[a];
}

/* Scalar names and values: time, step, dt, contact_energy, external_work, initial_energy,
 * wall_loss, bc_work, contact_dissipation and damage_dissipation (sums over the ranks), the
 * deck-part hashes (two 32-bit halves each), per rigid surface its position and reaction, per
 * body the carried stable step of the last force evaluation (FE and coupled bodies; 0 for the
 * others), per body its geometry (points, elements, hash halves: sim/restart_geometry.c), and
 * the last forces on each wall and contact pair (the history row of the restarted step), and
 * the history's running sums (sums_names). */
static int scalars_make(const pf_sim *sim, pf_sim_scalars *s) {
  const int nw = deck_walls(sim), np = deck_pairs(sim);
  s->n = at_sums(sim) + nsums(sim);
  PF_MALLOC(s->name, s->n);
  PF_MALLOC(s->names, s->n);
  PF_MALLOC(s->value, s->n);
  const char *fixed[NFIXED] = {"time", "step", "dt", "contact_energy", "external_work", "initial_energy", "wall_loss", "bc_work", "contact_dissipation",
                               "damage_dissipation"};
  int k = 0;
  for (; k < NFIXED; k++) snprintf(s->name[k], 96, "%s", fixed[k]);
  for (int p = 0; p < NPARTS; p++, k += 2) {
    snprintf(s->name[k], 96, "deck_hash_%s_hi", physics_parts[p]);
    snprintf(s->name[k + 1], 96, "deck_hash_%s_lo", physics_parts[p]);
  }
  for (int q = 0, at = k; q < sim->nrigid; q++)
    for (int a = 0; a < 3; a++) {
      snprintf(s->name[at + 6 * q + a], 96, "indenter_%d_%s_position_%c", q, pf_rigid_name(sim->rigid[q]), 'x' + a);
      snprintf(s->name[at + 6 * q + 3 + a], 96, "indenter_%d_%s_reaction_%c", q, pf_rigid_name(sim->rigid[q]), 'x' + a);
    }
  const char *geo[PF_GEOMETRY_SCALARS] = {"points", "elements", "positions_hash_hi", "positions_hash_lo",
                                          "connectivity_hash_hi", "connectivity_hash_lo"};
  for (int b = 0; b < sim->nbodies; b++) {
    snprintf(s->name[at_stable(sim) + b], 96, "body_%d_%s_stable_dt", b, sim->body_name[b]);
    for (int c = 0; c < PF_GEOMETRY_SCALARS; c++)
      snprintf(s->name[at_geometry(sim) + PF_GEOMETRY_SCALARS * b + c], 96, "body_%d_%s_%s", b, sim->body_name[b], geo[c]);
  }
  for (int q = 0; q < nw; q++)
    for (int a = 0; a < 3; a++) snprintf(s->name[at_walls(sim) + 3 * q + a], 96, "wall_%d_force_%c", q, 'x' + a);
  for (int q = 0; q < np; q++)
    for (int a = 0; a < 3; a++) snprintf(s->name[at_pairs(sim) + 3 * q + a], 96, "contact_pair_%d_force_%c", q, 'x' + a);
  sums_names(sim, s);
  for (int q = 0; q < s->n; q++) s->names[q] = s->name[q];
  return 0;
}

static void scalars_free(pf_sim_scalars *s) {
  PF_FREE(s->name);
  PF_FREE(s->names);
  PF_FREE(s->value);
}

static void scalars_fill(const pf_sim *sim, pf_sim_scalars *s) {
  double *v = s->value;
  v[0] = sim->t, v[1] = (double)sim->step, v[2] = sim->dt;
  v[3] = sim->contact_energy, v[4] = sim->external_work, v[5] = sim->e0;
  v[6] = pf_sum_all(sim->wall_loss), v[7] = pf_sum_all(sim->bc_work); /* collective */
  v[8] = pf_sum_all(sim->contact_dissipation), v[9] = pf_sum_all(sim->damage_dissipation);
  for (int p = 0; p < NPARTS; p++) {
    uint64_t h = part_hash(sim->deck, physics_parts[p]);
    v[NFIXED + 2 * p] = (double)(h >> 32), v[NFIXED + 2 * p + 1] = (double)(h & 0xffffffffu);
  }
  for (int q = 0, at = at_rigid(); q < sim->nrigid; q++) {
    double x[3];
    pf_rigid_position(sim->rigid[q], x);
    for (int a = 0; a < 3; a++) v[at + 6 * q + a] = x[a], v[at + 6 * q + 3 + a] = sim->reaction[q][a];
  }
  for (int b = 0, at = at_stable(sim); b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b]; /* the carried stable steps (collective) */
    v[at + b] = body->ops->set_stable_dt ? pf_min_all(body->ops->stable_dt(body->data, sim->pts)) : 0;
  }
  pf_sim_geometry_scalars(sim, &v[at_geometry(sim)]);
  for (int q = 0; q < deck_walls(sim); q++) /* (0 before the walls are built: only compared then) */
    for (int a = 0; a < 3; a++) v[at_walls(sim) + 3 * q + a] = q < sim->nwalls ? sim->wall_reaction[q][a] : 0;
  for (int q = 0; q < deck_pairs(sim); q++) {
    double f[3] = {0, 0, 0};
    if (sim->contact) pf_contact_pair_force(sim->contact, q, f);
    for (int a = 0; a < 3; a++) v[at_pairs(sim) + 3 * q + a] = f[a];
  }
  sums_fill(sim, &v[at_sums(sim)]);
}

int pf_sim_setup_restart(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *r = pf_node_get(pf_deck_root(d), "restart");
  const char *file = NULL;
  PF_CALL(pf_deck_string(d, r, "file", &file));
  PF_CALL(pf_deck_int(d, r, "interval", &sim->restart_interval));
  if (sim->restart_interval < 0)
    return pf_deck_error(d, pf_node_get(r, "interval"), "interval", "must not be negative");
  pf_sim_output_name(sim, file, ".restart.h5", sim->restart_path, sizeof sim->restart_path);
  return 0;
}

int pf_sim_checkpoint(pf_sim *sim) {
  pf_bond_rows rows;
  pf_sim_scalars s = {0};
  pf_table tables[PF_MAX_BODIES];
  int ntables = 0;
  PF_CALL(pf_bond_rows_init(&rows));
  int ierr = scalars_make(sim, &s);
  if (!ierr) ierr = pf_sim_bond_rows(sim, &rows);
  if (!ierr) ierr = pf_sim_body_tables(sim, tables, &ntables);
  if (!ierr) {
    scalars_fill(sim, &s);
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

/* Refuse a checkpoint written with a deck whose physics differs, naming the part. */
static int check_deck(const pf_sim *sim, const pf_sim_scalars *saved, const pf_sim_scalars *now) {
  for (int p = 0; p < NPARTS; p++) {
    int k = NFIXED + 2 * p;
    if (saved->value[k] == now->value[k] && saved->value[k + 1] == now->value[k + 1]) continue;
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

int pf_sim_restore_points(pf_sim *sim) {
  pf_bond_rows rows;
  PF_CALL(pf_bond_rows_init(&rows));
  PF_CALL(scalars_make(sim, &sim->restart_scalars));
  pf_sim_scalars *s = &sim->restart_scalars;
  int ierr = pf_sim_bond_fields(sim, &rows);
  if (!ierr) ierr = pf_checkpoint_read(sim->opt.restart_from, &sim->pts, &rows, s->n, s->names, s->value, at_sums(sim),
                                       &sim->restart_format);
  if (!ierr) ierr = pf_sim_check_restart_geometry(sim, &s->value[at_geometry(sim)]);
  if (!ierr) ierr = pf_sim_check_restart_scalars(sim, s->value, &s->value[at_stable(sim)]);
  if (!ierr) ierr = pf_sim_check_restart_bodies(sim);
  if (!ierr) body_gids(sim);
  if (!ierr) ierr = pf_sim_check_restart_gids(sim);
  if (!ierr) ierr = pf_sim_settle(sim, &rows, 0);
  pf_bond_rows_free(&rows);
  for (int b = 0; b < sim->nbodies && !ierr; b++) { /* the elements' state, whole on every rank */
    pf_body *body = &sim->body[b];
    pf_table t;
    pf_int nlocal;
    if (!pf_sim_table_shape(sim, b, &t, &nlocal)) continue;
    double *full = malloc(sizeof(double) * ((size_t)t.total * t.ncomp + 1));
    if (!full) return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    ierr = pf_checkpoint_read_table(sim->opt.restart_from, &t, full);
    if (!ierr) body->ops->table_set(body->data, full);
    if (!ierr && body->ops->set_stable_dt)
      body->ops->set_stable_dt(body->data, s->value[at_stable(sim) + b]);
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

/* After the set-up: check the deck and take time, energies and indenter state from the file. */
int pf_sim_restore_state(pf_sim *sim) {
  pf_sim_scalars now = {0}, *saved = &sim->restart_scalars;
  PF_CALL(scalars_make(sim, &now));
  scalars_fill(sim, &now);
  int ierr = check_deck(sim, saved, &now);
  scalars_free(&now);
  if (ierr) return ierr;
  const double *v = saved->value;
  PF_CALL(pf_sim_check_restart_time(sim, v));
  if (sim->adaptive) sim->dt = v[2]; /* the step follows the elements: the last one taken */
  PF_CHECK(v[2] == sim->dt, PF_ERR_INPUT, "the checkpoint %s was written with dt = %.17g s, this set-up gives %.17g s",
           sim->opt.restart_from, v[2], sim->dt);
  sim->t = v[0], sim->step = (long)v[1], sim->contact_energy = v[3], sim->external_work = v[4];
  sim->e0 = v[5], sim->have_e0 = 1;
  int root = pf_comm_rank() == 0; /* per-rank sums: rank 0 carries the total */
  sim->wall_loss = root ? v[6] : 0, sim->bc_work = root ? v[7] : 0;
  sim->contact_dissipation = root ? v[8] : 0, sim->damage_dissipation = root ? v[9] : 0;
  for (int q = 0, at = at_rigid(); q < sim->nrigid; q++) {
    pf_rigid_set_position(sim->rigid[q], &v[at + 6 * q]);
    for (int a = 0; a < 3; a++) sim->reaction[q][a] = v[at + 6 * q + 3 + a];
  }
  for (int q = 0; q < sim->nwalls; q++)
    for (int a = 0; a < 3; a++) sim->wall_reaction[q][a] = v[at_walls(sim) + 3 * q + a];
  for (int q = 0; q < deck_pairs(sim) && sim->contact; q++) pf_contact_pair_force_set(sim->contact, q, &v[at_pairs(sim) + 3 * q]);
  if (sim->restart_format < 4) pf_pd_correspondence_upgrade(sim->pts);
  if (sim->restart_format >= 3) sums_restore(sim, &v[at_sums(sim)]);
  else
    pf_log("note: %s is a checkpoint of format %d, without the history's running sums per body, condition, "
           "rigid surface and wall: those columns start again from 0 (the global ones continue)\n",
           sim->opt.restart_from, sim->restart_format);
  rename_output(sim->exodus_path, sizeof sim->exodus_path, sim->step);
  rename_output(sim->history_path, sizeof sim->history_path, sim->step);
  pf_log("restarted from %s at step %ld, t = %.6e s\n", sim->opt.restart_from, sim->step, sim->t);
  return 0;
}

/* SIGTERM / SIGINT: during the set-up, stop at once (nothing is written during the set-up, so
 * nothing is left half-written: a long mesh generation or neighbour search can be stopped);
 * afterwards, checkpoint at the end of the current step, then stop. Under mpirun every rank
 * receives the signal (mpirun forwards it) and ends; rank 0 prints the message. */
static volatile sig_atomic_t stop_signal = 0, in_setup = 0;
static char setup_msg[2][160]; /* [0] SIGTERM, [1] SIGINT; formatted before they are needed */
static size_t setup_len[2];

static void on_signal(int sig) {
  if (in_setup) {
    int k = sig == SIGINT;
    if (setup_len[k] && write(STDERR_FILENO, setup_msg[k], setup_len[k]) < 0) setup_len[k] = 0;
    _exit(128 + sig);
  }
  stop_signal = sig;
}

void pf_sim_catch_signals(void) {
  const int rank0 = pf_comm_rank() == 0;
  const int sigs[2] = {SIGTERM, SIGINT};
  for (int k = 0; k < 2; k++) {
    snprintf(setup_msg[k], sizeof setup_msg[k],
             "perifem: %s (signal %d) during the set-up: stopped (exit status %d); nothing was run "
             "or written\n",
             k ? "SIGINT" : "SIGTERM", sigs[k], 128 + sigs[k]);
    setup_len[k] = rank0 ? strlen(setup_msg[k]) : 0;
  }
  in_setup = 1;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (int k = 0; k < 2; k++) sigaction(sigs[k], &sa, NULL);
}

void pf_sim_setup_done(void) { in_setup = 0; }

int pf_sim_signal_here(void) { return (int)stop_signal; }

void pf_sim_restart_free(pf_sim *sim) { scalars_free(&sim->restart_scalars); }
