/* What `perifem --check` prints about the run a deck makes, once the model is built: per body
 * its kind, points, directed bonds, elements, horizon/spacing ratio and material; the time step
 * and the number of steps; the memory per rank, estimated from the point counts and horizons
 * with the constants the set-up refuses PD bodies by (sim/body_pd.c) and an element's measured
 * here, and beside it the set-up's measured growth; the output and checkpoint sizes in the
 * deck's precision and compression; and the run time from a few timed steps
 * (sim/check_calibrate.c), or, when none can be timed, a rough one from bond and element rates
 * measured on a 2-core Xeon. Collective; the model is spent afterwards. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
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
/* The share of its bytes an Exodus file keeps at output.compression > 0 (deflate on the
 * frames): measured 0.20 (wave_in_bar), 0.33 (panel_impact), 0.64 (fragmenting_cylinder to
 * 25 us), single precision, compression 1; their middle, so each within a factor 2. The rates
 * a frame's bytes (before compression) are written at, bytes of CPU time per second, without
 * and with compression: from fragmenting_cylinder to 25 us with 2 and 13 frames. */
#define PF_COMPRESSED_SHARE 0.35
#define PF_WRITE_RATE 100e6
#define PF_WRITE_RATE_COMPRESSED 25e6

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

/* The frames of the Exodus file and the rows of the history the run writes. */
static void output_counts(const pf_sim *sim, double *frames, double *rows) {
  const long n = sim->nsteps, every = sim->output_interval, hevery = sim->history_interval;
  const double span = isfinite(sim->final_time) ? sim->final_time : (double)n * sim->dt; /* (by time: of the run) */
  *frames = sim->output_period > 0 ? 1 + ceil(span / sim->output_period - 1e-9)
            : every > 0            ? 1 + ceil((double)n / (double)every)
                                   : 2;
  *rows = sim->history_period > 0 ? 1 + ceil(span / sim->history_period - 1e-9)
          : hevery > 0            ? 1 + ceil((double)n / (double)hevery)
                                  : 2;
}

/* output.fields names the field (every field when it is not given). */
static int selected(const pf_sim *sim, const char *name) {
  if (!sim->exo_opt.fields) return 1;
  for (int k = 0; k < sim->exo_opt.nfields; k++)
    if (!strcmp(sim->exo_opt.fields[k], name)) return 1;
  return 0;
}

/* The Exodus file's nodal variables (*vars, in every frame) and attributes (*once). */
static void exodus_variables(const pf_sim *sim, int *vars, int *once) {
  *vars = 3 * (selected(sim, "displacement") + selected(sim, "velocity") + selected(sim, "force"));
  *once = 0;
  for (int k = 0; k < sim->pts->nfields; k++) {
    const pf_field *f = &sim->pts->fields[k];
    if (!(f->flags & PF_FIELD_OUTPUT) || !selected(sim, f->name)) continue;
    if (f->flags & PF_FIELD_CONSTANT) *once += f->ncomp;
    else *vars += f->ncomp;
  }
}

/* Exodus: coordinates, connectivity, the attributes and the frames of every nodal variable, in
 * the deck's precision, times the share deflate leaves at compression > 0; the history's rows;
 * a checkpoint's points and bonds. *frame_bytes: one frame's values before compression. */
static void print_output(const pf_sim *sim, double points, double bonds, double elements, double bond_bytes,
                         double *frame_bytes) {
  int vars, once, keep = 16; /* restart: X, u, v, f, y, m, vol, cell, gid, body */
  exodus_variables(sim, &vars, &once);
  for (int k = 0; k < sim->pts->nfields; k++)
    if (sim->pts->fields[k].flags & PF_FIELD_RESTART) keep += sim->pts->fields[k].ncomp;
  double frames, rows;
  output_counts(sim, &frames, &rows);
  const int ws = sim->exo_opt.single ? 4 : 8, level = sim->exo_opt.compression;
  const double share = level > 0 ? PF_COMPRESSED_SHARE : 1;
  *frame_bytes = points * vars * ws;
  const double ids = points * 3 * 4 + elements * (8 + 1) * 4; /* maps and connectivity, 4-byte integers */
  const double exodus = share * (points * ws * (3 + once) + frames * *frame_bytes + ids);
  pf_sim_history_row g = {0};
  const double columns = pf_sim_globals_init(sim, &g) ? 0 : g.n + 2;
  pf_sim_globals_free(&g);
  char exo[16], history[16], checkpoint[16], how[64] = "";
  if (level > 0) snprintf(how, sizeof how, " x %.2g (compression %d: the share deflate leaves)", share, level);
  pf_log("  output: Exodus %s (%.0f frames x %d nodal variables x %.0f points x %d bytes%s, and %d written once), "
         "history %s (%.0f rows x %.0f columns)\n",
         size_text(exo, exodus), frames, vars, points, ws, how, once, size_text(history, rows * columns * 8), rows,
         columns);
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

/* seconds as "42 s", "4.6 min" or "2.31 h" in out (at least 32 characters); returns out. */
static const char *time_text(char *out, double s) {
  if (s < 120) snprintf(out, 32, "%.2g s", s);
  else if (s < 7200) snprintf(out, 32, "%.2g min", s / 60);
  else snprintf(out, 32, "%.3g h", s / 3600);
  return out;
}

/* No step was timed: bonds and elements at the rates measured on a 2-core Xeon.
 * bond_rate: the bodies' bond rates, weighted by their bonds (0: no bonds). */
static void print_rough_time(double bond_seconds, double element_seconds, double bond_rate, const char *why) {
  const int ranks = pf_comm_size();
  char when[32];
  pf_log("  rough run time: %s on %d rank(s) (at %.2g directed bond evaluations/s per rank for these models, %.2g "
         "element cycles/s, measured on a 2-core Xeon; contact and output not counted; %s)\n",
         time_text(when, (bond_seconds + element_seconds) / ranks), ranks, bond_rate, PF_RATE_ELEMENTS, why);
}

/* The run time from the calibration: the set-up as this one took, the forces at t = 0, the
 * steps left at the median step, a history row and a frame's fields at their counts, and the
 * frames' bytes at the write rate. */
static void print_time(const pf_sim *sim, const pf_sim_calibration *c, double frame_bytes) {
  double frames, rows;
  output_counts(sim, &frames, &rows);
  const double steps = (double)(sim->nsteps - c->from);
  const double rate = sim->exo_opt.compression > 0 ? PF_WRITE_RATE_COMPRESSED : PF_WRITE_RATE;
  const double out = rows * c->row + frames * (c->frame + frame_bytes / rate / pf_comm_size());
  const double total = c->setup + c->first + steps * c->step + out;
  char when[32], set[32], step[32], put[32];
  pf_log("  run time: about %s on %d rank(s) (CPU time per rank: set-up %s, %.0f steps x %s (the median of %d steps "
         "timed here after %d warm-up), output %s; an estimate: contact and damage that grow later in the run cost "
         "more than these first steps%s)\n",
         time_text(when, total), pf_comm_size(), time_text(set, c->setup), steps, time_text(step, c->step), c->steps,
         c->warmup, time_text(put, out),
         sim->adaptive ? ", and elements that deform shorten the step: more steps than at the start's step" : "");
}

typedef struct {
  double points, bonds, elements, bytes, bond_seconds, bond_bytes;
} totals;

/* The body table (and the interactions' rows); their sums in *t. */
static void print_bodies(const pf_sim *sim, totals *t) {
  *t = (totals){0};
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
    t->points += r.points, t->bonds += r.bonds, t->elements += r.elements, t->bytes += r.bytes;
    t->bond_seconds += r.bonds * (double)sim->nsteps / r.rate;
    if (r.bonds > 0) t->bond_bytes = fmax(t->bond_bytes, pf_body_bytes_per_bond(&sim->body[b]));
  }
  for (int k = 0; k < sim->ninter; k++) /* rigid surfaces, contact, walls, conditions */
    pf_log("  %-16s %-8s %12s %15s %10s %16s  -\n", pf_sim_interaction_name(sim, k), sim->inter[k].ops->kind, "-", "-",
           "-", "-");
}

/* Entry k's stable step: body k, else interaction k - nbodies. Collective. */
static double stable_step_of(const pf_sim *sim, int k) {
  if (k < sim->nbodies) return pf_body_stable_dt_all(&sim->body[k], sim->pts);
  return pf_sim_interaction_stable_dt(sim, k - sim->nbodies);
}

/* Each body's and each interaction's stable step over all ranks, and which sets the time step
 * (the smallest; docs/user_guide.md, "What `--check` prints"): where one body's step is much
 * smaller than the others', its share of the step's work bounds what subcycling it could gain.
 * Collective. An explicit run's alone (a quasi-static run's load steps are not bounded by it). */
static int print_stable_steps(const pf_sim *sim) {
  if (sim->solver.load_step) return 0;
  const int n = sim->nbodies + sim->ninter;
  double *dt, smallest = INFINITY;
  PF_MALLOC(dt, n);
  int at = -1;
  for (int k = 0; k < n; k++) {
    dt[k] = stable_step_of(sim, k); /* (collective: every rank, every entry) */
    if (dt[k] < smallest * (1 - 1e-12)) smallest = dt[k], at = k; /* (a soft pair equal to a body: the body) */
  }
  char line[1024];
  size_t len = (size_t)snprintf(line, sizeof line, "  stable steps:");
  for (int k = 0, shown = 0; k < n; k++) {
    if (!isfinite(dt[k]) || len >= sizeof line) continue;
    const char *name = k < sim->nbodies ? sim->body_name[k] : pf_sim_interaction_name(sim, k - sim->nbodies);
    len += (size_t)snprintf(line + len, sizeof line - len, "%s %s %.4e s%s", shown++ ? "," : "", name, dt[k],
                            k == at ? " (the smallest)" : "");
  }
  free(dt);
  pf_log("%s%s%s\n", line, at < 0 ? " none bounds the step" : "",
         at >= sim->nbodies ? "; a penalty sets the step (a contact pair's stiffness, with `soft: true`, is lowered "
                              "until its bodies set it: docs/theory/contact.md §4a)"
                            : "");
  return 0;
}

/* The calibration's steps and the run time from them; without them (or when they failed) the
 * rough estimate from the rates. */
static void estimate_time(const pf_sim *sim, const totals *t, const pf_sim_calibration *c, int ierr,
                          double frame_bytes) {
  if (!ierr && c->steps > 0) {
    print_time(sim, c, frame_bytes);
    return;
  }
  const char *why = ierr ? "the calibration steps stopped on the error above, as the run would"
                    : sim->solver.load_step ? "a quasi-static run's load steps are not timed"
                    : sim->run             ? "the run had begun: no step was timed"
                                           : "no step to time";
  if (ierr) pf_error_clear();
  const double tb = t->bond_seconds;
  print_rough_time(tb, t->elements * (double)sim->nsteps / PF_RATE_ELEMENTS,
                   tb > 0 ? t->bonds * (double)sim->nsteps / tb : 0, why);
}

int pf_sim_check_report(pf_sim *sim) {
  pf_log("%s: deck is valid (%" PF_GID_FMT " points, %s%ld steps of %.4e s%s)\n", pf_deck_path(sim->deck),
         sim->pts->n_global, sim->adaptive ? "about " : "", sim->nsteps, sim->dt,
         sim->adaptive ? " at the start; the step follows the deformation" : "");
  totals t;
  print_bodies(sim, &t);
  char until[48] = "";
  if (isfinite(sim->final_time)) snprintf(until, sizeof until, " to %.4g s", sim->final_time);
  pf_log("  time step: %.4e s (%s), %s%ld steps%s\n", sim->dt,
         sim->adaptive ? "at the start: the step follows the deformation" : "fixed", sim->adaptive ? "about " : "",
         sim->nsteps, until);
  print_memory(sim, t.bytes);
  pf_sim_calibration c; /* (before the output's count: the fields the first forces register count) */
  const int ierr = pf_sim_check_calibrate(sim, &c);
  if (!ierr) PF_CALL(print_stable_steps(sim)); /* (after the first forces: the elements' step is theirs) */
  double frame_bytes;
  print_output(sim, t.points, t.bonds, t.elements, t.bond_bytes, &frame_bytes);
  estimate_time(sim, &t, &c, ierr, frame_bytes);
  return 0;
}
