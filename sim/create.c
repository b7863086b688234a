/* Building a simulation from a deck: validate every key first, then generate the points of
 * each body (grouped by body, each body in Morton order), families and materials, initial
 * velocities, rigid surfaces and contact, boundary conditions, and the time step. No file is written here. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const pf_key time_keys[] = {
    {"final_time", PF_KEY_REAL, 0, NULL, "s", "end time (give this or steps)", NULL},
    {"steps", PF_KEY_INT, 0, NULL, "", "number of steps (give this or final_time)", NULL},
    {"dt", PF_KEY_REAL, 0, "stable", "s", "fixed time step; default: safety_factor x stable step", NULL},
    {"safety_factor", PF_KEY_REAL, 0, "0.8", "", "fraction of the Silling–Askari stable step", NULL},
    {"max_motion", PF_KEY_REAL, 0, "0.5", "",
     "instability guard: the largest motion of a point in one step, as a fraction of its horizon "
     "(PD) or cell (FE node); beyond it the run stops and writes the last good state", NULL},
    PF_KEY_END};

static const pf_key output_keys[] = {
    {"file", PF_KEY_STRING, 0, "<deck name>.e", "", "Exodus II output file", NULL},
    {"interval", PF_KEY_INT, 0, "100", "", "steps between Exodus outputs (0: first and last only); give at most one "
     "of interval, time_interval, frames", NULL},
    {"time_interval", PF_KEY_REAL, 0, NULL, "s",
     "time between Exodus outputs: a frame at the first step whose time reaches each multiple (quasi-static: "
     "pseudo-time)", NULL},
    {"frames", PF_KEY_INT, 0, NULL, "",
     "Exodus outputs over the run after the first: time_interval = time.final_time / frames (a run given by steps: "
     "steps x the first step)", NULL},
    {"history_file", PF_KEY_STRING, 0, "<deck name>.h5", "", "HDF5 history of global quantities", NULL},
    {"history_interval", PF_KEY_INT, 0, "10", "", "steps between history rows (quasi-static: 1); give at most one of "
     "history_interval, history_time_interval, history_frames", NULL},
    {"history_time_interval", PF_KEY_REAL, 0, NULL, "s", "time between history rows, as time_interval", NULL},
    {"history_frames", PF_KEY_INT, 0, NULL, "", "history rows over the run after the first, as frames", NULL},
    {"fields", PF_KEY_STRLIST, 0, "all", "",
     "the nodal variables of the Exodus file: displacement, velocity, force and any of the output fields "
     "(damage, stress, ...; an unknown name is an error listing the known ones); horizon, region and "
     "blending_weight, constant in a run, are written once as nodal attributes", NULL},
    {"precision", PF_KEY_STRING, 0, "double", "", "double | single: the Exodus file's values in 8 or 4 bytes", NULL},
    {"compression", PF_KEY_INT, 0, "0", "",
     "0 (none) or 1-9: the Exodus file written as netCDF-4 and deflated at that level (--check counts "
     "0.35 of its bytes)", NULL},
    {"layout", PF_KEY_STRING, 0, "joined", "",
     "on several ranks: joined (one Exodus file, written by rank 0) | spread (one file per rank, "
     "<file>.<ranks>.<rank>, which ParaView opens as one data set)", NULL},
    {"fragments", PF_KEY_BOOL, 0, "false", "",
     "label the fragments (connected components of intact bonds) at every Exodus step: field "
     "'fragment' and <file>.fragments.csv", NULL},
    {"probes", PF_KEY_LIST, 0, NULL, "", "mass-averaged quantities over regions, as history columns",
     pf_sim_probe_keys},
    PF_KEY_END};

const pf_key pf_deck_keys[] = {
    {"title", PF_KEY_STRING, 0, "", "", "a title for the output", NULL},
    {"include", PF_KEY_STRLIST, 0, NULL, "",
     "deck files merged in before this one, relative to its folder: mappings merge, lists join (the "
     "included items first), a value given twice is an error; file names inside them are relative to "
     "the main deck", NULL},
    {"parameters", PF_KEY_ANYMAP, 0, NULL, "",
     "named numbers (or expressions of the ones above): ${expression} anywhere in the deck is replaced "
     "by its value, and the names can be used bare in expressions of x, y, z, t", NULL},
    {"units", PF_KEY_STRING, 0, "SI", "", "unit system; only SI is accepted", NULL},
    {"materials", PF_KEY_ANYMAP, 1, NULL, "",
     "named materials, each checked by its model: a peridynamic model (pmb, lps, elastic_plastic) "
     "or a continuum model (FE bodies, and PD bodies as correspondence)", NULL},
    {"bodies", PF_KEY_LIST, 1, NULL, "",
     "the bodies (1 to 64), each checked by its type: peridynamic or finite_element", NULL},
    {"indenters", PF_KEY_LIST, 0, NULL, "", "rigid surfaces with prescribed motion (the same as contact.rigid_surfaces)", pf_rigid_keys},
    {"contact", PF_KEY_MAP, 0, NULL, "", "contact between bodies and rigid surfaces", pf_contact_keys},
    {"walls", PF_KEY_LIST, 0, NULL, "", "rigid frictionless planes", pf_wall_keys},
    {"boundary_conditions", PF_KEY_LIST, 0, NULL, "", "prescribed velocities/displacements and body forces", pf_bc_keys},
    {"time", PF_KEY_MAP, 1, NULL, "", "time stepping", time_keys},
    {"output", PF_KEY_MAP, 0, NULL, "", "output files and intervals", output_keys},
    {"parallel", PF_KEY_MAP, 0, NULL, "", "domain decomposition over MPI ranks", pf_parallel_keys},
    {"restart", PF_KEY_MAP, 0, NULL, "", "checkpoints for restart", pf_restart_keys},
    {"solver", PF_KEY_MAP, 0, NULL, "", "explicit dynamics (the default) or quasi-static loading (docs/theory/quasi_static.md)", pf_sim_solver_keys},
    PF_KEY_END};

/* Each material against the table of its kind, chosen by its model. */
static int validate_materials(const pf_deck *d, const pf_node *materials) {
  for (int k = 0; k < pf_node_count(materials); k++) {
    const char *name, *model = NULL;
    const pf_node *mat = pf_node_map_item(materials, k, &name);
    char where[160];
    snprintf(where, sizeof where, "materials.%s", name);
    if (pf_node_get(mat, "model")) PF_CALL(pf_deck_string(d, mat, "model", &model));
    if (model && pf_material_known(model)) PF_CALL(pf_deck_validate(d, mat, pf_material_keys, where));
    else if (model && pf_pd_material_known(model)) PF_CALL(pf_deck_validate(d, mat, pf_pd_material_keys, where));
    else if (model)
      return pf_deck_error(d, pf_node_get(mat, "model"), "model", "unknown model '%s' (known: %s, %s)", model,
                           pf_pd_material_names(), pf_material_names());
    else
      return pf_deck_error(d, mat, "model", "material '%s' has no 'model' (known: %s, %s)", name,
                           pf_pd_material_names(), pf_material_names());
  }
  return 0;
}

/* The body's kind (sim/body_kinds.h), and the body checked against the kind's keys. */
static int body_kind(const pf_deck *d, const pf_node *body, int b, const pf_body_ops **ops) {
  char where[64];
  snprintf(where, sizeof where, "bodies[%d]", b);
  PF_CALL(pf_body_kind(d, body, ops));
  return pf_deck_validate(d, body, (*ops)->keys(), where);
}

/* The node set a body's initial velocity is limited to (initial_velocity_set), or NULL. */
static int initial_set(pf_sim *sim, int b, const pf_node *body, const char *key, const pf_point_set **set) {
  const pf_node *n = pf_node_get(body, "initial_velocity_set");
  *set = NULL;
  if (!n || strcmp(key, "initial_velocity")) return 0;
  return pf_point_sets_find(&sim->sets, sim->deck, n, "initial_velocity_set", pf_node_text(n), 0, b, set);
}

/* initial_velocity or initial_displacement (key) of body b's owned points into v, or into u
 * (and y = X + u). */
static int set_initial_field(pf_sim *sim, int b, const pf_node *body, const char *key) {
  if (!pf_node_get(body, key)) return 0;
  const pf_point_set *set;
  PF_CALL(initial_set(sim, b, body, key, &set));
  pf_expr *e[3];
  PF_CALL(pf_expr3_create(sim->deck, body, key, e));
  pf_points *p = sim->pts;
  const int disp = !strcmp(key, "initial_displacement");
  double *out = disp ? p->u : p->v;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++)
    for (int c = 0; c < 3 && (!set || pf_point_set_has(set, p->gid[i])); c++) { /* owned points only: an error here may be one rank's */
      const double *x = &p->X[3 * i];
      out[3 * i + c] = pf_expr_eval(e[c], x[0], x[1], x[2], 0.0);
      if (disp) p->y[3 * i + c] = x[c] + out[3 * i + c];
      if (isfinite(out[3 * i + c])) continue;
      pf_expr3_destroy(e);
      return pf_deck_error(sim->deck, pf_node_item(pf_node_get(body, key), c), key,
                           "component %d is %g at the point (%g, %g, %g)", c, out[3 * i + c], x[0], x[1], x[2]);
    }
  pf_expr3_destroy(e);
  return 0;
}

/* Bodies whose points coincide: every point of one body at a point of another (the same body
 * given twice, or one lattice inside another's with the same origin) is refused naming both; a
 * partial coincidence (e.g. bodies sharing a boundary plane of lattice points) is reported. */
typedef struct {
  const double *x;
  int body;
} overlap_item;
static int by_position_body(const void *a, const void *b) {
  const overlap_item *p = a, *q = b;
  for (int c = 0; c < 3; c++)
    if (p->x[c] != q->x[c]) return p->x[c] < q->x[c] ? -1 : 1;
  return (p->body > q->body) - (p->body < q->body);
}

/* Each body's points finite and within 1e6 m of the origin (the bound the deck's lengths keep):
 * a mesh or point file in millimetres or with a corrupt coordinate is refused here, before any
 * output is written, not at the first step. Collective. */
static int check_extent(const pf_sim *sim, const pf_point_cloud *pc, const pf_node *bodies) {
  for (int b = 0; b < sim->nbodies; b++) {
    double far = 0;
    for (pf_int i = 0; i < 3 * pc[b].n; i++) {
      const double a = fabs(pc[b].X[i]);
      far = isnan(a) ? INFINITY : fmax(far, a);
    }
    far = pf_max_all(far);
    if (far <= 1e6) continue;
    const pf_node *body = pf_node_item(bodies, b);
    const char *key = pf_node_get(body, "mesh") ? "mesh" : "geometry";
    return pf_deck_error(sim->deck, pf_node_get(body, key) ? pf_node_get(body, key) : body, key,
                         "%s coordinates of body '%s' reach %g m: at most 1e6 m from the origin (a length in the "
                         "wrong units, or a corrupt file?)",
                         key, sim->body_name[b], far);
  }
  return 0;
}

static int check_overlap(const pf_sim *sim, const pf_point_cloud *pc, const pf_node *bodies) {
  const int nb = sim->nbodies;
  double lo[PF_MAX_BODIES][3], hi[PF_MAX_BODIES][3];
  int take[PF_MAX_BODIES] = {0}, any = 0;
  for (int b = 0; b < nb; b++) {
    for (int c = 0; c < 3; c++) lo[b][c] = INFINITY, hi[b][c] = -INFINITY;
    for (pf_int i = 0; i < pc[b].n; i++)
      for (int c = 0; c < 3; c++)
        lo[b][c] = fmin(lo[b][c], pc[b].X[3 * i + c]), hi[b][c] = fmax(hi[b][c], pc[b].X[3 * i + c]);
  }
  for (int b = 0; b < nb; b++) /* only bodies whose bounding boxes meet another's */
    for (int q = 0; q < b; q++) {
      int meet = pc[b].n > 0 && pc[q].n > 0;
      for (int c = 0; c < 3; c++) meet &= lo[b][c] <= hi[q][c] && lo[q][c] <= hi[b][c];
      if (meet) take[b] = take[q] = any = 1;
    }
  if (!any) return 0;
  size_t n = 0;
  for (int b = 0; b < nb; b++) n += take[b] ? (size_t)pc[b].n : 0;
  overlap_item *it = malloc(sizeof *it * n);
  pf_gid *shared = calloc((size_t)nb * nb, sizeof *shared); /* [b * nb + q]: points of b at one of q */
  if (!it || !shared) {
    free(it), free(shared);
    return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory comparing the bodies' points");
  }
  size_t k = 0;
  for (int b = 0; b < nb; b++)
    for (pf_int i = 0; take[b] && i < pc[b].n; i++) it[k++] = (overlap_item){&pc[b].X[3 * i], b};
  qsort(it, n, sizeof *it, by_position_body);
  for (size_t g = 0, e; g < n; g = e) { /* a group of points at one position */
    for (e = g + 1; e < n && !memcmp(it[e].x, it[g].x, 3 * sizeof(double)); e++) {}
    if (it[e - 1].body == it[g].body) continue; /* (sorted by body within the group) */
    for (size_t i = g; i < e; i++) {
      int last = -1;
      for (size_t j = g; j < e; j++)
        if (it[j].body != it[i].body && it[j].body != last) shared[it[i].body * nb + it[j].body]++, last = it[j].body;
    }
  }
  free(it);
  int ierr = 0;
  for (int b = 1; b < nb && !ierr; b++)
    for (int q = 0; q < b && !ierr; q++) {
      const pf_gid sb = shared[b * nb + q], sq = shared[q * nb + b];
      if (!sb && !sq) continue;
      const int full_b = sb == pc[b].n, full_q = sq == pc[q].n;
      if (full_b || full_q) {
        const int in = full_b ? b : q, other = full_b ? q : b; /* every point of `in` is one of `other`'s */
        ierr = pf_deck_error(sim->deck, pf_node_get(pf_node_item(bodies, b), "name"), "name",
                             "bodies '%s' and '%s' overlap: every one of the %" PF_INT_FMT " points of '%s' "
                             "coincides with a point of '%s' (the same points twice); give each region of "
                             "material to one body",
                             sim->body_name[q], sim->body_name[b], pc[in].n, sim->body_name[in],
                             sim->body_name[other]);
      } else
        pf_log("note: bodies '%s' and '%s' share %" PF_GID_FMT " point positions (of %" PF_INT_FMT
               " and %" PF_INT_FMT " points)\n",
               sim->body_name[q], sim->body_name[b], sb, pc[q].n, pc[b].n);
    }
  free(shared);
  return ierr;
}

static int build_bodies(pf_sim *sim, const pf_node *root) {
  const pf_node *bodies = pf_node_get(root, "bodies");
  sim->nbodies = pf_node_count(bodies);
  char where[512];
  pf_node_where(sim->deck, bodies, where, sizeof where);
  PF_CHECK(sim->nbodies > 0 && sim->nbodies <= PF_MAX_BODIES, PF_ERR_INPUT,
           "%s: 'bodies' must list 1 to %d bodies (got %d)", where, PF_MAX_BODIES, sim->nbodies);
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_node *body = pf_node_item(bodies, b);
    PF_CALL(pf_deck_string(sim->deck, body, "name", &sim->body_name[b]));
    for (int q = 0; q < b; q++)
      if (!strcmp(sim->body_name[q], sim->body_name[b]))
        return pf_deck_error(sim->deck, pf_node_get(body, "name"), "name", "two bodies named '%s'",
                             sim->body_name[b]);
    pf_body *bd = &sim->body[b];
    PF_CALL(body_kind(sim->deck, body, b, &bd->ops));
    bd->name = sim->body_name[b];
    PF_CALL(bd->ops->create(sim->deck, body, pf_node_get(root, "materials"), &bd->data));
    sim->nmeshed += pf_body_mesh(bd) != NULL;
  }
  if (sim->spread_output && sim->nmeshed)
    return pf_deck_error(sim->deck, pf_node_get(pf_node_get(root, "output"), "layout"), "layout",
                         "finite_element bodies are written joined (a spread file set would cut "
                         "elements at the rank boundaries); use output.layout: joined");
  PF_CALL(pf_sim_link_particles(sim));
  pf_point_cloud pc[PF_MAX_BODIES];
  memset(pc, 0, sizeof pc);
  int ierr = 0;
  for (int b = 0; b < sim->nbodies && !ierr; b++)
    ierr = sim->body[b].ops->cloud(sim->body[b].data, sim->deck, pf_node_item(bodies, b), &pc[b]);
  if (!ierr) pf_sim_geometry_take(sim, pc); /* (checkpoints record it; a restart compares) */
  if (!ierr) ierr = pf_sim_sets_build(sim, pc);
  if (!ierr && sim->opt.restart_from) { /* points and velocities from the file */
    ierr = pf_sim_restore_points(sim, pc);
    for (int b = 0; b < sim->nbodies; b++) pf_point_cloud_free(&pc[b]);
    return ierr;
  }
  if (!ierr) ierr = check_extent(sim, pc, bodies);
  if (!ierr) ierr = check_overlap(sim, pc, bodies);
  if (!ierr) ierr = pf_sim_distribute(sim, pc);
  for (int b = 0; b < sim->nbodies; b++) pf_point_cloud_free(&pc[b]);
  if (ierr) return ierr;
  for (int b = 0; b < sim->nbodies; b++) {
    PF_CALL(set_initial_field(sim, b, pf_node_item(bodies, b), "initial_velocity"));
    PF_CALL(set_initial_field(sim, b, pf_node_item(bodies, b), "initial_displacement"));
  }
  return 0;
}

/* The prescribed motions and loads finite over the run, before any output (an infinite indenter
 * velocity would otherwise run to the end with a NaN energy): sampled at 101 times over
 * [0, final_time] (a run given by steps: [0, steps x dt]). Collective. */
static int check_expressions(pf_sim *sim) {
  const double t_end = isfinite(sim->final_time) ? sim->final_time : (double)sim->nsteps * sim->dt;
  return pf_sim_interactions_check_finite(sim, t_end, 100);
}

static int check_units(const pf_sim *sim, const pf_node *root) {
  const char *units = "SI";
  PF_CALL(pf_deck_string(sim->deck, root, "units", &units));
  if (strcmp(units, "SI"))
    return pf_deck_error(sim->deck, pf_node_get(root, "units"), "units",
                         "only SI units are supported (got '%s')", units);
  return 0;
}

static int sim_build(pf_sim *sim, const char *deck_path) {
  if (!sim->opt.keep_signals) pf_sim_catch_signals(); /* a SIGTERM during the set-up ends the process at once */
  sim->rss0 = pf_memory_peak();
  if (sim->opt.deck_text)
    PF_CALL(pf_deck_load_text(deck_path, sim->opt.deck_text, sim->opt.sets, sim->opt.nsets, &sim->deck));
  else PF_CALL(pf_deck_load_with(deck_path, sim->opt.sets, sim->opt.nsets, &sim->deck));
  const pf_node *root = pf_deck_root(sim->deck);
  PF_CALL(pf_deck_validate(sim->deck, root, pf_deck_keys, "the deck"));
  PF_CALL(check_units(sim, root));
  PF_CALL(pf_sim_provenance(sim));
  PF_CALL(validate_materials(sim->deck, pf_node_get(root, "materials")));
  pf_sim_warn_unit_slips(sim->deck, pf_node_get(root, "materials"));
  PF_CALL(pf_sim_setup_parallel(sim));
  PF_CALL(pf_sim_check_time_keys(sim));
  PF_CALL(pf_sim_check_solver_keys(sim->deck));
  PF_CALL(pf_sim_check_output_keys(sim->deck));
  PF_CALL(build_bodies(sim, root));
  PF_CALL(pf_sim_interactions_build(sim));
  PF_CALL(pf_sim_setup_time(sim));
  PF_CALL(pf_sim_setup_output(sim));
  PF_CALL(pf_sim_setup_solver(sim));
  PF_CALL(check_expressions(sim));
  PF_CALL(pf_sim_accounts_open(sim));
  PF_CALL(pf_sim_setup_restart(sim));
  if (sim->opt.restart_from) PF_CALL(pf_sim_restore_state(sim)); /* (renames the outputs) */
  /* (the restored masses; a soft contact pair's restored stiffness) */
  if (sim->opt.restart_from) PF_CALL(pf_sim_refresh_fixed_step(sim));
  if (sim->opt.restart_from) PF_CALL(pf_sim_interactions_restored(sim));
  pf_sim_fragments_name(sim);
  PF_CALL(pf_sim_check_paths(sim));
  sim->rss_setup = pf_memory_peak();
  return 0;
}

int pf_sim_create(const char *deck_path, const pf_sim_options *opt, pf_sim **out) {
  *out = NULL;
  pf_sim *sim;
  PF_MALLOC(sim, 1);
  if (opt) sim->opt = *opt;
  int ierr = sim_build(sim, deck_path);
  pf_sim_setup_done(); /* from here a SIGTERM stops the run at the end of a step */
  if (ierr) {
    pf_sim_destroy(&sim);
    return ierr;
  }
  *out = sim;
  return 0;
}

int pf_sim_destroy(pf_sim **s) {
  pf_sim *sim = *s;
  if (!sim) return 0;
  pf_exodus_destroy(&sim->exo);
  pf_history_destroy(&sim->hist);
  pf_sim_unlock_outputs(sim);
  pf_sim_provenance_free(sim);
  free(sim->exo_fields);
  free(sim->row_work), free(sim->row_work_gid);
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b].ops) sim->body[b].ops->destroy(&sim->body[b].data);
  pf_sim_interactions_destroy(sim);
  pf_ledger_free(&sim->ledger);
  free(sim->probes);
  pf_points_destroy(&sim->pts);
  pf_points_destroy(&sim->joined);
  pf_point_sets_free(&sim->sets);
  pf_sim_restart_free(sim);
  pf_sim_guard_free(sim);
  pf_sim_run_free(sim);
  pf_sim_solver_free(sim);
  pf_deck_destroy(&sim->deck);
  PF_FREE(*s);
  return 0;
}

pf_points *pf_sim_points(pf_sim *sim) { return sim->pts; }
int pf_sim_nbodies(const pf_sim *sim) { return sim->nbodies; }
pf_pd_body *pf_sim_body(pf_sim *sim, int b) {
  return pf_body_as_pd(&sim->body[b]);
}
pf_contact *pf_sim_contact(pf_sim *sim) { return sim->contact; }
pf_fem_body *pf_sim_fem_body(pf_sim *sim, int b) {
  return pf_body_as_fem(&sim->body[b]);
}
int pf_sim_body_force(pf_sim *sim, int b, double dt) {
  int tripped = 0;
  PF_CALL(sim->body[b].ops->force(sim->body[b].data, sim->pts, dt, sim->t, sim->step, &tripped));
  PF_CHECK(!tripped, PF_ERR_RUN, "body '%s': the force evaluation failed", sim->body_name[b]);
  return 0;
}
double pf_sim_dt(const pf_sim *sim) { return sim->dt; }
long pf_sim_nsteps(const pf_sim *sim) { return sim->nsteps; }
int pf_sim_adaptive(const pf_sim *sim) { return sim->adaptive; }
