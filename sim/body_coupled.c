/* The coupled body kind (`type: finite_element` with a `peridynamic:` map): coupling/'s
 * composition of an FE body and a PD operator on the same nodes. To the rest of the run it is a
 * particle body (its nodes are the points that fracture: contact meets them as particles) that
 * also has elements (output blocks, element state, erosion): the element parts are the FE
 * kind's ops on its FE body, the bond parts the PD kind's on its PD operator. */
#include "coupling/coupling.h"
#include "sim/body.h"

#include <math.h>

extern const pf_body_ops pf_body_kind_fe, pf_body_kind_pd;
static const pf_body_ops *const fe = &pf_body_kind_fe, *const pd = &pf_body_kind_pd;
static pf_fem_body *fem_of(const void *data) { return pf_coupled_body_fem(data); }
static pf_pd_body *pd_of(const void *data) { return pf_coupled_body_pd(data); }

static int claims(const pf_node *body) { return pf_coupled_body_requested(body); }

static int create(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data) {
  return pf_coupled_body_create(d, body, materials, (pf_coupled_body **)data);
}

static int destroy(void **data) { return pf_coupled_body_destroy((pf_coupled_body **)data); }

static int cloud(void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc) {
  return fe->cloud(fem_of(data), d, body, pc);
}

static int rows(const void *data, const pf_points *pts, const pf_body_span *s, pf_bond_rows *out) {
  return pf_coupled_body_rows(data, pts, s->first, s->n, s->gid0, out);
}

static int bond_fields(const void *data, pf_bond_rows *out) { return pd->bond_fields(pd_of(data), out); }

static int attach(void *data, pf_points *pts, const pf_body_span *s, const pf_bond_rows *r, const pf_int *local,
                  int fresh) {
  return pf_coupled_body_attach(data, s->index, pts, s->first, s->n, s->gid0, r, local, fresh);
}

static int force(void *data, pf_points *pts, double dt, double t, long step, int *tripped) {
  if (pf_coupled_body_force(data, pts, dt, t, step)) *tripped = 1;
  return 0;
}

static double stable_dt(const void *data, const pf_points *pts) { return fe->stable_dt(fem_of(data), pts); }
static int post_step(void *data, pf_points *pts) { return pd->post_step(pd_of(data), pts); }
static int freeze_damage(void *data, const pf_points *pts, int frozen) {
  return pd->freeze_damage(pd_of(data), pts, frozen);
}
static void take_damage_work(void *data, double w[2]) { pd->take_damage_work(pd_of(data), w); }
static int failures(void *data, int restore) { return pd->failures(pd_of(data), restore); }
/* History: the elements' and the PD operator's (both read the load step's increment over one
 * velocity field, so both take one increment from the committed state). */
static int history(void *data, pf_points *pts, pf_history_op op) {
  if (op == PF_HISTORY_KEPT) return 1;
  PF_CALL(fe->history(fem_of(data), pts, op));
  return pd->history(pd_of(data), pts, PF_HISTORY_KEPT) == 1 ? pd->history(pd_of(data), pts, op) : 0;
}

/* The elements' energies, each weighted by its share 1 - beta, and the PD operator's blended
 * share. */
static void energies(const void *data, pf_points *pts, pf_body_energies *e) {
  pf_body_energies p;
  fe->energies(fem_of(data), pts, e);
  pd->energies(pd_of(data), pts, &p);
  e->elastic = p.elastic, e->bonds = p.bonds, e->broken = p.broken;
}

static const pf_family *family(const void *data) { return pd->family(pd_of(data)); }
static double bytes_per_bond(const void *data) { return pd->bytes_per_bond(pd_of(data)); }
static double bond_rate(const void *data) { return pd->bond_rate(pd_of(data)); }
static void record_breaks(void *data, const pf_points *pts) { pd->record_breaks(pd_of(data), pts); }
static void material(const void *data, double *density, double *bulk) { fe->material(fem_of(data), density, bulk); }
static double horizon(const void *data) { return pd->horizon(pd_of(data)); }
static double point_horizon(const void *data, pf_int i) { return pd->point_horizon(pd_of(data), i); }
static const pf_mesh *mesh(const void *data) { return fe->mesh(fem_of(data)); }
static const uint8_t *eroded(const void *data, long *count) { return fe->eroded(fem_of(data), count); }

/* The nodes' stress and history are the PD points'; their bond damage. */
static int output_fields(void *data, pf_points *pts) {
  pf_pd_body_damage(pd_of(data), pts);
  return 0;
}

static void table_shape(const void *data, pf_gid *total, int *ncomp, pf_int *nlocal) {
  fe->table_shape(fem_of(data), total, ncomp, nlocal);
}
static pf_int table_get(const void *data, pf_gid *ids, double *out) { return fe->table_get(fem_of(data), ids, out); }
static void table_set(void *data, const double *full) { fe->table_set(fem_of(data), full); }
static void set_stable_dt(void *data, double dt) { fe->set_stable_dt(fem_of(data), dt); }
static pf_fem_body *as_fem(void *data) { return fem_of(data); }

const pf_body_ops pf_body_kind_coupled = {
    .type = "finite_element",
    .label = "coupled",
    .keys = pf_coupled_body_keys,
    .claims = claims,
    .create = create,
    .destroy = destroy,
    .cloud = cloud,
    .rows = rows,
    .bond_fields = bond_fields,
    .attach = attach,
    .force = force,
    .stable_dt = stable_dt,
    .step_varies = pf_body_always,
    .uses_velocity = pf_body_always,
    .post_step = post_step,
    .freeze_damage = freeze_damage,
    .history = history,
    .take_damage_work = take_damage_work,
    .failures = failures,
    .energies = energies,
    .family = family,
    .bytes_per_bond = bytes_per_bond,
    .bond_rate = bond_rate,
    .record_breaks = record_breaks,
    .material = material,
    .horizon = horizon,
    .point_horizon = point_horizon,
    .mesh = mesh,
    .eroded = eroded,
    .output_fields = output_fields,
    .table_shape = table_shape,
    .table_get = table_get,
    .table_set = table_set,
    .set_stable_dt = set_stable_dt,
    .as_fem = as_fem,
};
