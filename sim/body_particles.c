/* The particles body kind (`type: particles`, `from: <an FE body>`): fem/'s particles made from the
 * elements an FE body's erosion converts (fem/particles.c). No bonds and no internal force: the
 * particles act through the deck's contact pairs. */
#include "sim/body.h"
#include "fem/fem.h"

#include <math.h>

static const pf_key *keys(void) { return pf_fem_particles_keys; }

static int create(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data) {
  (void)materials;
  return pf_fem_particles_create(d, body, (pf_fem_particles **)data);
}

static int destroy(void **data) { return pf_fem_particles_destroy((pf_fem_particles **)data); }

static int cloud(void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc) {
  (void)d, (void)body;
  return pf_fem_particles_cloud((pf_fem_particles *)data, pc);
}

/* No bonds: an empty row per point. */
static int rows(const void *data, const pf_points *pts, const pf_body_span *s, pf_bond_rows *out) {
  (void)data, (void)pts;
  for (pf_int i = 0; i < s->n; i++) PF_CALL(pf_bond_rows_append(out, 0, NULL, 0, NULL));
  return 0;
}

static int attach(void *data, pf_points *pts, const pf_body_span *s, const pf_bond_rows *r, const pf_int *local,
                  int fresh) {
  (void)r, (void)local, (void)fresh;
  return pf_fem_particles_attach(data, pts, s->first, s->n, s->gid0);
}

static int force(void *data, pf_points *pts, double dt, double t, long step, int *tripped) {
  (void)data, (void)pts, (void)dt, (void)t, (void)step, (void)tripped;
  return 0;
}

static double stable_dt(const void *data, const pf_points *pts) {
  (void)data, (void)pts;
  return INFINITY;
}

static void energies(const void *data, pf_points *pts, pf_body_energies *e) {
  *e = (pf_body_energies){0};
  e->converted = pf_fem_particles_loss(data, pts);
}

static void material(const void *data, double *density, double *bulk_modulus) {
  pf_fem_particles_material(data, density, bulk_modulus);
}

static double horizon(const void *data) { return pf_fem_particles_horizon(data); }
static pf_fem_particles *as_particles(void *data) { return data; }

const pf_body_ops pf_body_kind_particles = {
    .type = "particles",
    .label = "particles",
    .keys = keys,
    .create = create,
    .destroy = destroy,
    .cloud = cloud,
    .rows = rows,
    .attach = attach,
    .force = force,
    .stable_dt = stable_dt,
    .energies = energies,
    .material = material,
    .horizon = horizon,
    .as_particles = as_particles,
};
