/* The simulation's contact: rigid surfaces (`contact: rigid_surfaces:` and the foundation's
 * `indenters:`, which are the same surfaces) and contact pairs between bodies (contact/). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The largest cell edge of body b's points over all ranks. Collective. */
static double body_spacing(const pf_sim *sim, int b) {
  double h = 0;
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) h = fmax(h, sim->pts->cell[i]);
  return pf_max_all(h);
}

/* What contact needs of each body. Collective (spacings). An FE body with coupled
 * peridynamics (a `peridynamic:` map) is a particle body to contact: its nodes are the
 * particles that fracture, so an FE projectile meets them node-to-particle (surface to
 * particle) and its fragments meet each other by short-range forces, as a PD body's do. */
static void contact_bodies(const pf_sim *sim, pf_contact_body *cb) {
  for (int b = 0; b < sim->nbodies; b++) {
    pf_contact_body *c = &cb[b];
    memset(c, 0, sizeof *c);
    c->name = sim->body_name[b];
    const pf_pd_body *coupled = sim->fem[b] ? pf_fem_body_pd(sim->fem[b]) : NULL;
    c->is_fe = sim->fem[b] != NULL && !coupled;
    c->gid0 = sim->gid0[b];
    c->first = sim->body_start[b];
    c->n = sim->body_start[b + 1] - sim->body_start[b];
    c->spacing = body_spacing(sim, b);
    if (sim->fem[b]) {
      const pf_material *m = pf_fem_body_material(sim->fem[b]);
      c->bulk_modulus = pf_material_bulk_modulus(m);
      c->density = pf_material_density(m);
      if (coupled) c->horizon = pf_pd_body_horizon(coupled), c->fam = pf_pd_body_family(coupled);
      else c->mesh = pf_fem_body_mesh(sim->fem[b]), c->fem = sim->fem[b];
    } else {
      c->bulk_modulus = pf_pd_body_bulk_modulus(sim->body[b]);
      c->density = pf_pd_body_density(sim->body[b]);
      c->horizon = pf_pd_body_horizon(sim->body[b]);
      c->fam = pf_pd_body_family(sim->body[b]);
    }
  }
}

static int add_rigid(pf_sim *sim, const pf_node *list) {
  for (int k = 0; k < pf_node_count(list); k++, sim->nrigid++)
    PF_CALL(pf_rigid_create(sim->deck, pf_node_item(list, k), sim->nbodies, sim->body_name, &sim->rigid[sim->nrigid]));
  return 0;
}

int pf_sim_build_contact(pf_sim *sim) {
  const pf_node *root = pf_deck_root(sim->deck), *contact = pf_node_get(root, "contact");
  const pf_node *inds = pf_node_get(root, "indenters"), *surf = pf_node_get(contact, "rigid_surfaces");
  int n = pf_node_count(inds) + pf_node_count(surf);
  PF_MALLOC(sim->rigid, n);
  PF_MALLOC(sim->reaction, n);
  PF_CALL(add_rigid(sim, inds));
  PF_CALL(add_rigid(sim, surf));
  if (!contact) return 0;
  pf_contact_body cb[PF_MAX_BODIES];
  contact_bodies(sim, cb);
  return pf_contact_create(sim->deck, contact, sim->nbodies, cb, &sim->contact);
}

int pf_sim_contact_attach(pf_sim *sim) {
  if (!sim->contact) return 0;
  pf_contact_body cb[PF_MAX_BODIES];
  contact_bodies(sim, cb);
  return pf_contact_attach(sim->contact, cb);
}

int pf_sim_contact_forces(pf_sim *sim, double dt) {
  double total = 0;
  for (int k = 0; k < sim->nrigid; k++) {
    double U;
    PF_CALL(pf_rigid_force(sim->rigid[k], sim->pts, dt, sim->reaction[k], &U, &sim->contact_dissipation));
    total += U;
  }
  if (sim->contact) {
    for (int b = 0; b < sim->nbodies; b++) {
      pf_pd_body *pd = sim->body[b] ? sim->body[b] : pf_fem_body_pd(sim->fem[b]);
      if (pd && pf_contact_self_pair(sim->contact, b)) pf_pd_body_record_breaks(pd, sim->pts);
    }
    double U;
    PF_CALL(pf_contact_force(sim->contact, sim->pts, dt, &U, &sim->contact_dissipation));
    total += U;
  }
  sim->contact_energy = total;
  return 0;
}

double pf_sim_contact_stable_dt(pf_sim *sim) {
  double dt = INFINITY;
  for (int k = 0; k < sim->nrigid; k++) dt = fmin(dt, pf_rigid_stable_dt(sim->rigid[k], sim->pts));
  if (sim->contact) dt = fmin(dt, pf_contact_stable_dt(sim->contact, sim->pts));
  return dt;
}
