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

/* What contact needs of each body. Collective (spacings). A body with bonds is a particle body
 * to contact, whether or not it also has elements: a coupled body's nodes are the particles that
 * fracture, so an FE projectile meets them node-to-particle (surface to particle) and its
 * fragments meet each other by short-range forces, as a PD body's do. A body without bonds meets
 * others through its mesh's surface. */
static void contact_bodies(const pf_sim *sim, pf_contact_body *cb) {
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    pf_contact_body *c = &cb[b];
    memset(c, 0, sizeof *c);
    c->name = sim->body_name[b];
    c->gid0 = sim->gid0[b];
    c->first = sim->body_start[b];
    c->n = sim->body_start[b + 1] - sim->body_start[b];
    c->spacing = body_spacing(sim, b);
    body->ops->material(body->data, &c->density, &c->bulk_modulus);
    c->fam = body->ops->family ? body->ops->family(body->data) : NULL;
    c->horizon = body->ops->horizon ? body->ops->horizon(body->data) : 0;
    c->is_fe = !c->fam && body->ops->mesh;
    if (c->is_fe) c->mesh = body->ops->mesh(body->data), c->eroded = body->ops->eroded, c->eroded_ctx = body->data;
  }
}

static int add_rigid(pf_sim *sim, const pf_node *list) {
  for (int k = 0; k < pf_node_count(list); k++, sim->nrigid++)
    PF_CALL(pf_rigid_create(sim->deck, pf_node_item(list, k), sim->nbodies, sim->body_name, &sim->rigid[sim->nrigid]));
  return 0;
}

int pf_sim_build_rigid(pf_sim *sim) {
  const pf_node *root = pf_deck_root(sim->deck), *contact = pf_node_get(root, "contact");
  const pf_node *inds = pf_node_get(root, "indenters"), *surf = pf_node_get(contact, "rigid_surfaces");
  int n = pf_node_count(inds) + pf_node_count(surf);
  PF_MALLOC(sim->rigid, n);
  PF_MALLOC(sim->reaction, n);
  PF_CALL(add_rigid(sim, inds));
  return add_rigid(sim, surf);
}

int pf_sim_build_contact(pf_sim *sim) {
  const pf_node *contact = pf_node_get(pf_deck_root(sim->deck), "contact");
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

/* The step's contact forces: rigid surfaces, pairs, then walls (which take the normal force off
 * points on them), each rank's part first; the reactions, the pairs' forces and the penalty
 * energies are then summed over the ranks in one reduction. */
int pf_sim_contact_forces(pf_sim *sim, double dt) {
  const int nc = sim->contact ? pf_contact_nsums(sim->contact) : 0, at_c = 4 * sim->nrigid,
            at_w = at_c + nc, n = at_w + 3 * sim->nwalls;
  if (n > sim->nsums) { /* (once: the counts are set at set-up) */
    free(sim->sums);
    PF_MALLOC(sim->sums, 2 * (size_t)n);
    sim->nsums = n;
  }
  double *local = sim->sums, *sum = local ? local + n : NULL; /* (NULL: no contact of any kind) */
  int ierr = 0;
  for (int k = 0; k < sim->nrigid && !ierr; k++)
    ierr = pf_rigid_force_local(sim->rigid[k], sim->pts, dt, &local[4 * k], &sim->contact_dissipation);
  for (int b = 0; b < sim->nbodies && sim->contact && !ierr; b++) {
    const pf_body *body = &sim->body[b];
    if (body->ops->record_breaks && pf_contact_self_pair(sim->contact, b))
      body->ops->record_breaks(body->data, sim->pts);
  }
  if (sim->contact && !ierr)
    ierr = pf_contact_force(sim->contact, sim->pts, dt, &local[at_c], &sim->contact_dissipation);
  for (int k = 0; k < sim->nwalls && !ierr; k++) pf_wall_enforce_force_local(sim->walls[k], sim->pts, &local[at_w + 3 * k]);
  if (!ierr && n > 0 && MPI_Allreduce(local, sum, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS)
    ierr = pf_error_raise(PF_ERR_LIB, __FILE__, __LINE__, __func__, "MPI_Allreduce failed summing the contact forces");
  double total = 0;
  for (int k = 0; k < sim->nrigid && !ierr; k++) {
    for (int a = 0; a < 3; a++) sim->reaction[k][a] = sum[4 * k + a];
    total += sum[4 * k + 3];
  }
  if (sim->contact && !ierr) {
    double U;
    pf_contact_sums_take(sim->contact, &sum[at_c], &U);
    total += U;
  }
  for (int k = 0; k < sim->nwalls && !ierr; k++)
    for (int a = 0; a < 3; a++) sim->wall_reaction[k][a] = sum[at_w + 3 * k + a];
  if (!ierr) sim->contact_energy = total;
  return ierr;
}

double pf_sim_contact_stable_dt(pf_sim *sim) {
  double dt = INFINITY;
  for (int k = 0; k < sim->nrigid; k++) dt = fmin(dt, pf_rigid_stable_dt(sim->rigid[k], sim->pts));
  if (sim->contact) dt = fmin(dt, pf_contact_stable_dt(sim->contact, sim->pts));
  return dt;
}
