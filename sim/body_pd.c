/* The peridynamic body kind (`type: peridynamic`, the default): pd/'s body over the points of a
 * generated geometry. */
#include "sim/body.h"

static const pf_key *keys(void) { return pf_pd_body_keys; }

static int create(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data) {
  return pf_pd_body_create(d, body, materials, (pf_pd_body **)data);
}

static int destroy(void **data) { return pf_pd_body_destroy((pf_pd_body **)data); }

static int cloud(const void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc) {
  (void)data;
  return pf_point_cloud_from_deck(d, pf_node_get(body, "geometry"), pc);
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
static int step_varies(const void *data) { return pf_pd_body_step_varies(data); }
static int uses_velocity(const void *data) { return pf_pd_body_uses_velocity(data); }
static int post_step(void *data, pf_points *pts) { return pf_pd_body_post_step(data, pts); }
static double take_damage_work(void *data) { return pf_pd_body_take_damage_work(data); }

static void energies(const void *data, pf_points *pts, pf_body_energies *e) {
  *e = (pf_body_energies){0};
  e->elastic = pf_pd_body_energy(data, pts);
  e->broken = (double)pf_pd_body_damage(data, pts);
  e->bonds = (double)pf_pd_body_nbonds(data);
}

static const pf_family *family(const void *data) { return pf_pd_body_family(data); }
static double bytes_per_bond(const void *data) { return pf_pd_body_bytes_per_bond(data); }
static void record_breaks(void *data, const pf_points *pts) { pf_pd_body_record_breaks(data, pts); }

static void material(const void *data, double *density, double *bulk_modulus) {
  *density = pf_pd_body_density(data), *bulk_modulus = pf_pd_body_bulk_modulus(data);
}

static double horizon(const void *data) { return pf_pd_body_horizon(data); }
static double reach(const void *data, const pf_points *pts, pf_int i) {
  (void)pts;
  return pf_pd_body_point_horizon(data, i);
}
static pf_pd_body *as_pd(void *data) { return data; }

const pf_body_ops pf_body_kind_pd = {
    .type = "peridynamic",
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
    .step_varies = step_varies,
    .uses_velocity = uses_velocity,
    .post_step = post_step,
    .take_damage_work = take_damage_work,
    .energies = energies,
    .family = family,
    .bytes_per_bond = bytes_per_bond,
    .record_breaks = record_breaks,
    .material = material,
    .horizon = horizon,
    .reach = reach,
    .reach_name = "horizon",
    .as_pd = as_pd,
};
