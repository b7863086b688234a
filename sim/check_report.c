/* What `perifem --check` prints about the run a deck makes, once the model is built and before
 * any step: per body its kind, points, directed bonds, elements, horizon/spacing ratio and
 * material; the time step and the number of steps; the memory per rank, estimated from the point
 * counts and horizons with the constants the set-up refuses PD bodies by (sim/body_pd.c) and an
 * element's measured here, and beside it the set-up's measured growth; the output and checkpoint sizes; and a rough run time
 * from bond and element rates measured on a 2-core Xeon (stated in the output). Collective. */
#include "sim/sim_impl.h"

#include <math.h>
#include <string.h>

/* Rates per rank measured on this project's 2-core benchmark machine: hex8 element cycles per
 * second (80 000-element bar, 300 steps); the bodies give their models' bond rates (pd/: PMB and
 * LPS directed bond evaluations per second, 87 451-point target, 150 steps). */
#define PF_RATE_ELEMENTS 1.1e6
/* Memory constants of the estimate: a node of a meshed body (as a PD point without bonds) and
 * an element, measured as the set-up's growth of resident memory: 15.1 MB for a pamgen block of
 * 11 849 nodes and 10 240 elements, 22.1 MB for the Taylor bar's gmsh mesh of 11 440 nodes and
 * 10 206 elements (1 KB a node, 0.3 and 1.1 KB an element). */
#define PF_BYTES_PER_NODE PF_PD_BYTES_PER_POINT
#define PF_BYTES_PER_ELEMENT 1024.0

typedef struct {
  double points, bonds, elements, cell, m, bytes, rate;
  const char *kind, *model, *material;
} body_row;

static double sum(double x) {
  MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return x;
}

/* The body's material name and model, as the deck gives them ("?" when not a plain name). */
static void body_material(const pf_sim *sim, int b, body_row *r) {
  const pf_node *root = pf_deck_root(sim->deck), *body = pf_node_item(pf_node_get(root, "bodies"), b);
  r->material = pf_node_text(pf_node_get(body, "material"));
  const pf_node *mat = r->material ? pf_node_get(pf_node_get(root, "materials"), r->material) : NULL;
  r->model = pf_node_text(pf_node_get(mat, "model"));
  if (!r->material) r->material = "?";
  if (!r->model) r->model = "?";
}

/* The memory estimate of a body with bonds: a constant horizon of m spacings as the set-up's
 * refusal (sim/body_pd.c); a variable one point by point, each point's horizon over its cell. */
static double body_bond_bytes(const pf_sim *sim, int b, double points) {
  const pf_body *bd = &sim->body[b];
  const pf_points *p = sim->pts;
  double bytes = 0;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) {
    const double d = pf_body_point_horizon(bd, i);
    bytes += pf_body_pd_bytes(points, d / p->cell[i]) / points;
  }
  return sum(bytes);
}

static void body_counts(const pf_sim *sim, int b, body_row *r) {
  const pf_body *bd = &sim->body[b];
  const pf_family *fam = pf_body_family(bd);
  const pf_mesh *mesh = pf_body_mesh(bd);
  double cells = 0;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) cells += sim->pts->cell[i];
  r->points = (double)(sim->gid0[b + 1] - sim->gid0[b]);
  r->bonds = sum(fam ? (double)pf_pd_family_nbonds(fam) : 0);
  r->elements = mesh ? (double)mesh->nelem : 0;
  r->cell = r->points > 0 ? sum(cells) / r->points : 0;
  const double delta = fam ? pf_body_horizon(bd) : 0;
  r->m = r->cell > 0 ? delta / r->cell : 0;
  r->kind = bd->ops->label;
  body_material(sim, b, r);
  r->bytes = fam ? body_bond_bytes(sim, b, r->points) : r->points * PF_BYTES_PER_NODE;
  r->bytes += r->elements * PF_BYTES_PER_ELEMENT;
  r->rate = pf_body_bond_rate(bd);
}

/* bytes as "1.73 MB" in out (at least 16 characters); returns out. */
static const char *size_text(char *out, double bytes) {
  const char *unit[] = {"B", "KB", "MB", "GB", "TB"};
  int k = 0;
  while (bytes >= 1000 && k < 4) bytes /= 1000, k++;
  snprintf(out, 16, "%.3g %s", bytes, unit[k]);
  return out;
}

/* Exodus: coordinates, connectivity and the frames of every nodal variable (9 built-in, then
 * the output fields' components); the history's rows; a checkpoint's points and bonds. */
static void print_output(const pf_sim *sim, double points, double bonds, double elements, double bond_bytes) {
  int vars = 9, once = 0, keep = 16; /* restart: X, u, v, f, y, m, vol, cell, gid, body */
  for (int k = 0; k < sim->pts->nfields; k++) {
    const int flags = sim->pts->fields[k].flags;
    if ((flags & PF_FIELD_OUTPUT) && (flags & PF_FIELD_CONSTANT)) once += sim->pts->fields[k].ncomp;
    else if (flags & PF_FIELD_OUTPUT) vars += sim->pts->fields[k].ncomp;
    if (sim->pts->fields[k].flags & PF_FIELD_RESTART) keep += sim->pts->fields[k].ncomp;
  }
  const long n = sim->nsteps, every = sim->output_interval, hevery = sim->history_interval;
  const double span = isfinite(sim->final_time) ? sim->final_time : (double)n * sim->dt; /* (by time: of the run) */
  const double frames = sim->output_period > 0 ? 1 + ceil(span / sim->output_period - 1e-9)
                        : every > 0            ? 1 + ceil((double)n / (double)every)
                                               : 2;
  const double rows = sim->history_period > 0 ? 1 + ceil(span / sim->history_period - 1e-9)
                      : hevery > 0            ? 1 + ceil((double)n / (double)hevery)
                                              : 2;
  pf_sim_history_row g = {0};
  const double columns = pf_sim_globals_init(sim, &g) ? 0 : g.n + 2;
  pf_sim_globals_free(&g);
  char exodus[16], history[16], checkpoint[16];
  pf_log("  output: Exodus %s (%.0f frames x %d nodal variables x %.0f points x 8 bytes, and %d written once), "
         "history %s (%.0f rows x %.0f columns)\n",
         size_text(exodus, points * 8 * (3 + frames * vars + once) + elements * 8 * 4), frames, vars, points, once,
         size_text(history, rows * columns * 8), rows, columns);
  size_text(checkpoint, points * keep * 8 + bonds * (8 + bond_bytes));
  if (sim->restart_interval > 0) pf_log("  checkpoint: %s each, every %ld steps\n", checkpoint, sim->restart_interval);
  else pf_log("  checkpoint: %s each (none written: restart.interval is 0)\n", checkpoint);
}

/* The estimate against the peak the set-up reached, both beyond the process's own before the
 * set-up (libraries, MPI: rss0), the largest over the ranks. */
static void print_memory(const pf_sim *sim, double bytes) {
  const int ranks = pf_comm_size();
  double peak[2] = {pf_memory_peak(), sim->rss0};
  MPI_Allreduce(MPI_IN_PLACE, peak, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  char estimate[16], used[16], top[16], before[16], limit[16];
  pf_log("  memory per rank: estimated %s before allocating (%.0f KB a point, %.0f bytes a bond, %.0f KB an element, "
         "over %d rank(s)); measured %s (peak %s less %s before the set-up, largest over the ranks); a rank may use "
         "%s\n",
         size_text(estimate, bytes / ranks), PF_BYTES_PER_NODE / 1024, PF_PD_BYTES_PER_BOND,
         PF_BYTES_PER_ELEMENT / 1024, ranks, size_text(used, peak[0] - peak[1]), size_text(top, peak[0]),
         size_text(before, peak[1]), size_text(limit, pf_memory_limit()));
}

/* bond_rate: the bodies' bond rates, weighted by their bonds (0: no bonds). */
static void print_time(double bond_seconds, double element_seconds, double bond_rate) {
  const int ranks = pf_comm_size();
  const double s = (bond_seconds + element_seconds) / ranks;
  char when[32];
  if (s < 120) snprintf(when, sizeof when, "%.2g s", s);
  else if (s < 7200) snprintf(when, sizeof when, "%.2g min", s / 60);
  else snprintf(when, sizeof when, "%.3g h", s / 3600);
  pf_log("  rough run time: %s on %d rank(s) (at %.2g directed bond evaluations/s per rank for these models, %.2g "
         "element cycles/s, measured on a 2-core Xeon; contact and output not counted)\n",
         when, ranks, bond_rate, PF_RATE_ELEMENTS);
}

int pf_sim_check_report(pf_sim *sim) {
  double points = 0, bonds = 0, elements = 0, bytes = 0, tb = 0, bond_bytes = 0;
  pf_log("%s: deck is valid (%" PF_GID_FMT " points, %s%ld steps of %.4e s%s)\n", pf_deck_path(sim->deck),
         sim->pts->n_global, sim->adaptive ? "about " : "", sim->nsteps, sim->dt,
         sim->adaptive ? " at the start; the step follows the deformation" : "");
  pf_log("  %-16s %-8s %12s %15s %10s %16s  %s\n", "body", "kind", "points", "directed bonds", "elements",
         "horizon/spacing", "material (model)");
  for (int b = 0; b < sim->nbodies; b++) {
    body_row r;
    body_counts(sim, b, &r);
    if (r.m > 0)
      pf_log("  %-16s %-8s %12.0f %15.0f %10.0f %16.3f  %s (%s)\n", sim->body_name[b], r.kind, r.points, r.bonds,
             r.elements, r.m, r.material, r.model);
    else
      pf_log("  %-16s %-8s %12.0f %15.0f %10.0f %16s  %s (%s)\n", sim->body_name[b], r.kind, r.points, r.bonds,
             r.elements, "-", r.material, r.model);
    points += r.points, bonds += r.bonds, elements += r.elements, bytes += r.bytes;
    tb += r.bonds * (double)sim->nsteps / r.rate;
    const pf_body *bd = &sim->body[b];
    if (r.bonds > 0) bond_bytes = fmax(bond_bytes, pf_body_bytes_per_bond(bd));
  }
  for (int k = 0; k < sim->ninter; k++) /* rigid surfaces, contact, walls, conditions */
    pf_log("  %-16s %-8s %12s %15s %10s %16s  -\n", pf_sim_interaction_name(sim, k), sim->inter[k].ops->kind, "-", "-",
           "-", "-");
  char until[48] = "";
  if (isfinite(sim->final_time)) snprintf(until, sizeof until, " to %.4g s", sim->final_time);
  pf_log("  time step: %.4e s (%s), %s%ld steps%s\n", sim->dt,
         sim->adaptive ? "at the start: the step follows the deformation" : "fixed", sim->adaptive ? "about " : "",
         sim->nsteps, until);
  print_memory(sim, bytes);
  print_output(sim, points, bonds, elements, bond_bytes);
  print_time(tb, elements * (double)sim->nsteps / PF_RATE_ELEMENTS, tb > 0 ? bonds * (double)sim->nsteps / tb : 0);
  return 0;
}
