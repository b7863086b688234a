/* The finite-element body kind (`type: finite_element`): fem/'s hexahedral body, whose nodes are
 * points of the store. */
#include "coupling/coupling.h"
#include "sim/body.h"

#include <math.h>

/* A finite_element body's keys include the optional `peridynamic:` map, which makes it the
 * coupled kind (sim/body_coupled.c): both are checked against one table. */
static const pf_key *keys(void) { return pf_coupled_body_keys(); }

static int create(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data) {
  return pf_fem_body_create(d, body, materials, (pf_fem_body **)data);
}

static int destroy(void **data) { return pf_fem_body_destroy((pf_fem_body **)data); }

static int cloud(void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc) {
  (void)d, (void)body;
  return pf_fem_body_cloud(data, pc);
}

static int rows(const void *data, const pf_points *pts, const pf_body_span *s, pf_bond_rows *out) {
  return pf_fem_body_node_rows(data, pts, s->first, s->n, s->gid0, out);
}

static int attach(void *data, pf_points *pts, const pf_body_span *s, const pf_bond_rows *r, const pf_int *local,
                  int fresh) {
  (void)r, (void)local, (void)fresh;
  return pf_fem_body_attach(data, s->index, pts, s->first, s->n, s->gid0);
}

/* An inverted element stops every rank at the step's end (sim/guard.c), not here. */
static int force(void *data, pf_points *pts, double dt, double t, long step, int *tripped) {
  if (pf_fem_body_force(data, pts, dt, t, step)) *tripped = 1;
  return 0;
}

static double stable_dt(const void *data, const pf_points *pts) {
  (void)pts;
  return pf_fem_body_stable_dt(data);
}

static void energies(const void *data, pf_points *pts, pf_body_energies *e) {
  (void)pts;
  *e = (pf_body_energies){0};
  pf_fem_body_energies(data, e->fe);
}

/* Contact's constants: with several materials, the lightest density and the stiffest modulus. */
static void material(const void *data, double *density, double *bulk_modulus) {
  pf_fem_body_material_bounds(data, density, bulk_modulus);
}

static const pf_mesh *mesh(const void *data) { return pf_fem_body_mesh(data); }
static const uint8_t *eroded(const void *data, long *count) { return pf_fem_body_eroded(data, count); }
static int output_fields(void *data, pf_points *pts) { return pf_fem_body_output_fields(data, pts); }

static void table_shape(const void *data, pf_gid *total, int *ncomp, pf_int *nlocal) {
  *total = pf_fem_body_mesh(data)->nelem;
  *ncomp = pf_fem_body_state_ncomp(data);
  *nlocal = pf_fem_body_nlocal(data);
}

static pf_int table_get(const void *data, pf_gid *ids, double *out) { return pf_fem_body_state_get(data, ids, out); }
static void table_set(void *data, const double *full) { pf_fem_body_state_set(data, full); }
static void set_stable_dt(void *data, double dt) { pf_fem_body_set_stable_dt(data, dt); }
static pf_fem_body *as_fem(void *data) { return data; }
static int history(void *data, pf_points *pts, pf_history_op op) {
  (void)pts;
  return op == PF_HISTORY_KEPT ? 1 : pf_fem_body_history(data, op == PF_HISTORY_RESTORE);
}

const pf_body_ops pf_body_kind_fe = {
    .type = "finite_element",
    .label = "FE",
    .keys = keys,
    .create = create,
    .destroy = destroy,
    .cloud = cloud,
    .rows = rows,
    .attach = attach,
    .force = force,
    .stable_dt = stable_dt,
    .step_varies = pf_body_always,  /* the elements' step follows their deformation */
    .uses_velocity = pf_body_always, /* rates of deformation */
    .energies = energies,
    .material = material,
    .mesh = mesh,
    .contact_surface = mesh,
    .eroded = eroded,
    .output_fields = output_fields,
    .table_shape = table_shape,
    .table_get = table_get,
    .table_set = table_set,
    .set_stable_dt = set_stable_dt,
    .history = history,
    .as_fem = as_fem,
};
