/* The peridynamic body kind (`type: peridynamic`, the default): pd/'s body over the points of a
 * generated geometry. */
#include "sim/body.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static const pf_key *keys(void) { return pf_pd_body_keys; }

static int create(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data) {
  return pf_pd_body_create(d, body, materials, (pf_pd_body **)data);
}

static int destroy(void **data) { return pf_pd_body_destroy((pf_pd_body **)data); }

/* Horizon against the points, before any bond is searched: a horizon of more than
 * PF_MAX_HORIZON_SPACINGS mean spacings is refused (a horizon in millimetres typed as metres
 * made a neighbour search of every point with every other, ending in "migration of more than
 * 2 GB from one rank"), and so is a model whose bonds would not fit in memory: from the lattice's
 * estimate before its points are generated, and from the points themselves. A horizon larger
 * than the body is warned about. */
#define PF_MAX_HORIZON_SPACINGS 50.0
double pf_body_pd_bonds_per_point(double points, double m) {
  return fmax(0, fmin(points - 1, 4.0 / 3.0 * 3.14159265358979323846 * m * m * m));
}

double pf_body_pd_bytes(double points, double m) {
  return points * (PF_PD_BYTES_PER_POINT + PF_PD_BYTES_PER_BOND * pf_body_pd_bonds_per_point(points, m));
}

/* The memory refusal: key is the one that drives the estimate (a horizon beyond 4 spacings,
 * else the spacing). */
static int refuse_memory(const pf_deck *d, const pf_node *body, double points, double m, const char *what) {
  const double bytes = pf_body_pd_bytes(points, m), limit = pf_memory_limit();
  const int ranks = pf_comm_size();
  if (bytes / ranks <= limit) return 0;
  const char *key = m > 4 ? "horizon" : "spacing";
  const pf_node *n = m > 4 ? pf_node_get(body, "horizon") : pf_node_get(pf_node_get(body, "geometry"), "spacing");
  return pf_deck_error(d, n, key,
                       "%s %.4g points with a horizon of %.3g spacings (about %.0f bonds a point): "
                       "about %.3g GB (%.3g GB on each of %d rank(s)), more than the memory "
                       "available (a rank may use %.3g GB here); use a larger spacing, a smaller "
                       "horizon or more ranks",
                       what, points, m, pf_body_pd_bonds_per_point(points, m), bytes / 1e9, bytes / ranks / 1e9,
                       ranks, limit / 1e9);
}

static int check_estimate(const void *data, const pf_deck *d, const pf_node *body) {
  const double delta = pf_pd_body_horizon(data);
  double points, h;
  PF_CALL(pf_point_cloud_estimate(d, pf_node_get(body, "geometry"), &points, &h));
  if (!(delta > 0) || !(h > 0) || !(points > 0) || delta / h > PF_MAX_HORIZON_SPACINGS) return 0;
  if (points >= INT32_MAX || points * PF_PD_BYTES_PER_POINT / pf_comm_size() > pf_memory_limit())
    return 0; /* the points alone: the lattice refuses them, saying so */
  return refuse_memory(d, body, points, delta / h, "the lattice would make about");
}

static int check_horizon(const void *data, const pf_deck *d, const pf_node *body, const pf_point_cloud *pc) {
  const double delta = pf_pd_body_horizon(data); /* 0: an expression, known once the points are */
  if (!(delta > 0) || pc->n == 0) return 0;
  double vol = 0, lo[3], hi[3];
  for (int c = 0; c < 3; c++) lo[c] = INFINITY, hi[c] = -INFINITY;
  for (pf_int i = 0; i < pc->n; i++) {
    vol += pc->vol[i];
    for (int c = 0; c < 3; c++) lo[c] = fmin(lo[c], pc->X[3 * i + c]), hi[c] = fmax(hi[c], pc->X[3 * i + c]);
  }
  const double h = cbrt(vol / (double)pc->n), m = delta / h;
  const double extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) + h;
  const pf_node *hn = pf_node_get(body, "horizon");
  if (m > PF_MAX_HORIZON_SPACINGS)
    return pf_deck_error(d, hn, "horizon",
                         "the horizon %g m is %.3g point spacings (mean spacing %g m) and %.3g times the "
                         "body's largest extent (%g m); at most %g spacings are accepted, typically 3 "
                         "(a length in millimetres typed as metres? units are SI)",
                         delta, m, h, delta / extent, extent, PF_MAX_HORIZON_SPACINGS);
  if (delta > extent)
    pf_deck_warn(d, hn, "horizon",
                 "the horizon %g m is larger than the body's largest extent (%g m): every point "
                 "is bonded to every other (a length in millimetres typed as metres? units are SI)",
                 delta, extent);
  /* a point far from the others: refused by the neighbour search itself (pd/family.c) */
  return refuse_memory(d, body, (double)pc->n, m, "the body's");
}

/* The body's points: a lattice or a point file (core/), or Peridigm's Exodus discretization
 * (mesh/). */
static int cloud(void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc) {
  const pf_node *g = pf_node_get(body, "geometry");
  const char *shape = pf_node_text(pf_node_get(g, "shape"));
  PF_CALL(check_estimate(data, d, body));
  if (shape && !strcmp(shape, "exodus")) PF_CALL(pf_mesh_exodus_points_from_deck(d, g, pc));
  else PF_CALL(pf_point_cloud_from_deck(d, g, pc));
  PF_CALL(check_horizon(data, d, body, pc));
  return pf_pd_body_take_blocks(data, pc);
}

static int find_rows(void *data, const pf_point_cloud *pc, const pf_points *pts, const pf_body_span *s,
                     pf_bond_rows *rows) {
  pf_pd_cloud cloud = {pc->X, pc->cell, pc->n, s->gid0};
  return pf_pd_body_find_bonds(data, &cloud, pts, s->first, s->n, rows);
}

static int rows(const void *data, const pf_points *pts, const pf_body_span *s, pf_bond_rows *out) {
  (void)s;
  return pf_pd_body_bond_rows(data, pts, out);
}

static int bond_fields(const void *data, pf_bond_rows *out) { return pf_pd_body_bond_fields(data, out); }

static int attach(void *data, pf_points *pts, const pf_body_span *s, const pf_bond_rows *r, const pf_int *local,
                  int fresh) {
  return pf_pd_body_attach(data, pts, s->first, s->n, r, local, fresh);
}

static int force(void *data, pf_points *pts, double dt, double t, long step, int *tripped) {
  (void)t, (void)step, (void)tripped;
  return pf_pd_body_force(data, pts, dt);
}

static double stable_dt(const void *data, const pf_points *pts) { return pf_pd_body_stable_dt(data, pts); }
static int stiffness_bounds(void *data, pf_points *pts, pf_int first, pf_int n, double *k) {
  return pf_pd_body_stiffness_bounds(data, pts, first, n, k);
}
static int step_varies(const void *data) { return pf_pd_body_step_varies(data); }
static int uses_velocity(const void *data) { return pf_pd_body_uses_velocity(data); }
static int post_step(void *data, pf_points *pts) { return pf_pd_body_post_step(data, pts); }
static double failure_ratio(const void *data, const pf_points *pts) { return pf_pd_body_failure_ratio(data, pts); }
static int64_t softened(const void *data) { return pf_pd_body_softened(data); }
static int freeze_damage(void *data, const pf_points *pts, int frozen) {
  return pf_pd_body_freeze_damage(data, pts, frozen);
}
static int history(void *data, pf_points *pts, pf_history_op op) {
  if (op == PF_HISTORY_KEPT) return pf_pd_body_keeps_history(data);
  return pf_pd_body_history(data, pts, op == PF_HISTORY_RESTORE);
}
static int failures(void *data, int restore) { return pf_pd_body_failures(data, restore); }
static void take_damage_work(void *data, double w[2]) {
  w[0] = pf_pd_body_take_damage_work(data), w[1] = pf_pd_body_take_damage_redistribution(data);
}

static void energies(const void *data, pf_points *pts, pf_body_energies *e) {
  *e = (pf_body_energies){0};
  e->elastic = pf_pd_body_energy(data, pts);
  e->broken = (double)pf_pd_body_damage(data, pts);
  e->bonds = (double)pf_pd_body_nbonds(data);
}

static const pf_family *family(const void *data) { return pf_pd_body_family(data); }
static double bytes_per_bond(const void *data) { return pf_pd_body_bytes_per_bond(data); }
static double bond_rate(const void *data) { return pf_pd_body_bond_rate(data); }
static void record_breaks(void *data, const pf_points *pts) { pf_pd_body_record_breaks(data, pts); }

static void material(const void *data, double *density, double *bulk_modulus) {
  *density = pf_pd_body_density(data), *bulk_modulus = pf_pd_body_bulk_modulus(data);
}

static double horizon(const void *data) { return pf_pd_body_horizon(data); }
static double point_horizon(const void *data, pf_int i) { return pf_pd_body_point_horizon(data, i); }
static double reach(const void *data, const pf_points *pts, pf_int i) {
  (void)pts;
  return pf_pd_body_point_horizon(data, i);
}
static pf_pd_body *as_pd(void *data) { return data; }

const pf_body_ops pf_body_kind_pd = {
    .type = "peridynamic",
    .label = "PD",
    .keys = keys,
    .create = create,
    .destroy = destroy,
    .cloud = cloud,
    .find_rows = find_rows,
    .rows = rows,
    .bond_fields = bond_fields,
    .attach = attach,
    .force = force,
    .stable_dt = stable_dt,
    .stiffness_bounds = stiffness_bounds,
    .step_varies = step_varies,
    .uses_velocity = uses_velocity,
    .post_step = post_step,
    .freeze_damage = freeze_damage,
    .failure_ratio = failure_ratio,
    .softened = softened,
    .history = history,
    .failures = failures,
    .take_damage_work = take_damage_work,
    .energies = energies,
    .family = family,
    .bytes_per_bond = bytes_per_bond,
    .bond_rate = bond_rate,
    .record_breaks = record_breaks,
    .material = material,
    .horizon = horizon,
    .point_horizon = point_horizon,
    .reach = reach,
    .reach_name = "horizon",
    .as_pd = as_pd,
};
