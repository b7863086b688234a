/* A simulation's output: the history's columns and rows (global quantities), the Exodus file
 * (joined or spread) with its fields, and the last good state when a guard stops the run. The
 * time loop that writes them at their intervals is sim/run.c. */
#include "sim/sim_impl.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const fixed_names[G_FIXED] = {
    "kinetic_energy", "elastic_energy", "contact_energy", "external_work", "energy_error",
    "momentum_x",     "momentum_y",     "momentum_z",     "damage_fraction",
    "fe_internal_energy", "hourglass_energy", "bulk_viscosity_work", "wall_dissipation", "contact_dissipation",
    "damage_dissipation"};
static const char *const fixed_units[G_FIXED] = {"J", "J", "J", "J", "J", "kg m/s", "kg m/s", "kg m/s", "",
                                                 "J", "J", "J", "J", "J", "J"};

/* The columns appended after the probes' (sim_impl.h gives their order): */
static const char *const body_names[PF_BODY_SUMS] = {
    "kinetic_energy", "internal_energy", "hourglass_energy", "viscous_work", "damage_dissipation",
    "damage_redistribution", "external_work", "momentum_x", "momentum_y", "momentum_z"};
static const char *const body_units[PF_BODY_SUMS] = {"J", "J", "J", "J", "J", "J", "J", "kg m/s", "kg m/s", "kg m/s"};
enum { PF_BC_COLUMNS = 6, PF_RIGID_COLUMNS = 4, PF_WALL_COLUMNS = 3 };

/* Name column j (after time and step) name_suffix, with units. */
static void column(pf_sim_history_row *g, int j, const char *name, const char *suffix, const char *units) {
  char buf[192];
  snprintf(buf, sizeof buf, "%s_%s", name, suffix);
  g->names[2 + j] = strdup(buf);
  g->units[2 + j] = units;
}

/* The appended columns: damage_redistribution; per body its energies, work and momentum; per
 * prescribed condition its reaction (N) and impulse (N s); per rigid surface its impulse on the
 * points and the work of its prescribed motion; per wall its impulse on the points. */
/* 1 when some body's particles come from converted elements: the history then ends with the
 * kinetic energy the conversions removed (docs/theory/fem.md §9b). */
static int converts(const pf_sim *sim) {
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->as_particles) return 1;
  return 0;
}

static void appended_columns(const pf_sim *sim, pf_sim_history_row *g) {
  int j = g->extra0;
  g->names[2 + j] = strdup("damage_redistribution"), g->units[2 + j++] = "J";
  for (int b = 0; b < sim->nbodies; b++)
    for (int q = 0; q < PF_BODY_SUMS; q++) column(g, j++, sim->body_name[b], body_names[q], body_units[q]);
  for (int k = 0; k < sim->nbcs; k++) {
    const char *q[PF_BC_COLUMNS] = {"reaction_x", "reaction_y", "reaction_z", "impulse_x", "impulse_y", "impulse_z"};
    for (int c = 0; c < PF_BC_COLUMNS; c++) column(g, j++, pf_bc_name(sim->bcs[k]), q[c], c < 3 ? "N" : "N s");
  }
  for (int k = 0; k < sim->nrigid; k++) {
    const char *q[PF_RIGID_COLUMNS] = {"impulse_x", "impulse_y", "impulse_z", "work"};
    for (int c = 0; c < PF_RIGID_COLUMNS; c++) column(g, j++, pf_rigid_name(sim->rigid[k]), q[c], c < 3 ? "N s" : "J");
  }
  for (int k = 0; k < sim->nwalls; k++) {
    const char *q[PF_WALL_COLUMNS] = {"impulse_x", "impulse_y", "impulse_z"};
    for (int c = 0; c < PF_WALL_COLUMNS; c++) column(g, j++, pf_wall_name(sim->walls[k]), q[c], "N s");
  }
  if (converts(sim)) g->names[2 + j] = strdup("conversion_loss"), g->units[2 + j++] = "J";
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Two columns of one name (a body, condition, surface or wall named so that its column takes
 * another's name, e.g. a body "fe" and fe_internal_energy) would make the history unwritable:
 * refuse at set-up, naming the column. */
static int unique_columns(const pf_sim *sim, const pf_sim_history_row *g) {
  char **sorted;
  PF_MALLOC(sorted, g->n + 2);
  memcpy(sorted, g->names, sizeof *sorted * (size_t)(g->n + 2));
  qsort(sorted, (size_t)g->n + 2, sizeof *sorted, by_name);
  const char *twice = NULL;
  for (int k = 1; k < g->n + 2 && !twice; k++)
    if (!strcmp(sorted[k - 1], sorted[k])) twice = sorted[k];
  char name[192] = "";
  if (twice) snprintf(name, sizeof name, "%s", twice);
  free(sorted);
  PF_CHECK(!twice, PF_ERR_INPUT,
           "%s: the history would have two columns named '%s' (a body's, condition's, rigid surface's or "
           "wall's columns are its name followed by _<quantity>, e.g. <body>_internal_energy): rename the body, "
           "condition (name:), surface or wall",
           pf_deck_path(sim->deck), name);
  return 0;
}

int pf_sim_globals_init(const pf_sim *sim, pf_sim_history_row *g) {
  int npairs = pf_contact_npairs(sim->contact);
  const int body0 = g->body0 = G_FIXED + 3 * (sim->nrigid + sim->nwalls + npairs);
  const int probe0 = g->probe0 = body0 + 6 * sim->nbodies;
  const int extra0 = g->extra0 = probe0 + pf_sim_probe_columns(sim);
  g->n = extra0 + 1 + PF_BODY_SUMS * sim->nbodies + PF_BC_COLUMNS * sim->nbcs + PF_RIGID_COLUMNS * sim->nrigid +
         PF_WALL_COLUMNS * sim->nwalls + converts(sim);
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
  for (int k = 0; k < extra0 - probe0; k++) {
    char buf[160];
    pf_sim_probe_column(sim, k, buf, sizeof buf, &g->units[2 + probe0 + k]);
    g->names[2 + probe0 + k] = strdup(buf);
  }
  appended_columns(sim, g);
  for (int k = 0; k < g->n + 2; k++) PF_CHECK(g->names[k], PF_ERR_MEMORY, "out of memory");
  return unique_columns(sim, g);
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

void pf_sim_globals_free(pf_sim_history_row *g) {
  for (int k = 0; g->names && k < g->n + 2; k++) free(g->names[k]);
  PF_FREE(g->names);
  PF_FREE(g->units);
  PF_FREE(g->values);
}

/* The appended columns' values (appended_columns), from the last pf_sim_globals_get. */
static void appended_values(const pf_sim *sim, const pf_sim_globals *s, double *v) {
  const double *x = pf_sim_row_sums(sim);
  *v++ = s->damage_redistribution;
  for (int q = 0; q < PF_BODY_SUMS * sim->nbodies; q++) *v++ = *x++;
  for (int k = 0; k < sim->nbcs; k++, x += 6, v += PF_BC_COLUMNS)
    for (int a = 0; a < 3; a++) v[a] = sim->step > 0 ? x[a] / sim->dt : 0.0, v[3 + a] = x[3 + a];
  for (int k = 0; k < sim->nrigid; k++, x += 3, v += PF_RIGID_COLUMNS) {
    for (int a = 0; a < 3; a++) v[a] = x[a];
    v[3] = sim->rigid_work[k];
  }
  for (int k = 0; k < sim->nwalls; k++, x += 3, v += PF_WALL_COLUMNS)
    for (int a = 0; a < 3; a++) v[a] = x[a];
  if (converts(sim)) *v = s->conversion_loss;
}

/* Fill values[0..n+1]: time, step, globals. */
int pf_sim_globals_eval(pf_sim *sim, pf_sim_history_row *g, int first) {
  pf_sim_globals s;
  PF_CALL(pf_sim_globals_get(sim, &s));
  double total = s.kinetic_centred + s.elastic + s.contact - s.external_work + s.fe_internal + s.hourglass +
                 s.bulk_viscosity + s.wall_loss + s.contact_dissipation + s.damage_dissipation +
                 s.damage_redistribution + s.conversion_loss;
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
  PF_CALL(pf_sim_probes_eval(sim, &v[g->probe0]));
  appended_values(sim, &s, &v[g->extra0]);
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
                                  names, &sim->exo_opt, &sim->exo);
  for (int b = 0; b < sim->nbodies; b++) free(conn[b]);
  return ierr;
}

int pf_sim_open_output(pf_sim *sim, pf_sim_history_row *g) {
  if (sim->opt.no_output) return 0;
  PF_CALL(pf_agree(open_exodus(sim, g), "creating the Exodus output %s", sim->exodus_path));
  int ierr = pf_history_create(sim->history_path, g->n + 2, (const char *const *)g->names, g->units, &sim->prov, &sim->hist);
  return pf_agree(ierr, "creating the history %s", sim->history_path);
}

static int write_exodus(pf_sim *sim, const double *values) {
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops->output_fields) PF_CALL(sim->body[b].ops->output_fields(sim->body[b].data, sim->pts));
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

