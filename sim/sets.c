/* The bodies' named point sets (core/point_sets.c), gathered once at set-up from what each body
 * was built from: an FE or coupled body's mesh (its node sets, and the nodes of its side sets'
 * faces), a peridynamic body's cloud (the node sets of a Peridigm Exodus discretization). A point's global id is
 * the body's first id plus its index in the body's cloud (sim/distribute.c), and an FE body's
 * cloud is its mesh's nodes in mesh order (fem/), so a set's ids follow from its indices. */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <string.h>

/* The nodes of a side set's faces (Exodus HEX8 sides, mesh/hex8.c), as global ids. */
static int side_set_nodes(const pf_mesh *m, const pf_mesh_set *s, pf_gid gid0, pf_gid **out, pf_gid *n) {
  PF_MALLOC(*out, 4 * (size_t)s->n + 1);
  *n = 0;
  for (pf_int i = 0; i < s->n; i++)
    for (int v = 0; v < 4; v++) (*out)[(*n)++] = gid0 + m->conn[8 * (size_t)s->item[i] + pf_hex8_face[s->face[i]][v]];
  return 0;
}

static int add_mesh_sets(pf_sim *sim, int b, const pf_mesh *m, pf_gid gid0) {
  for (int side = 0; side < 2; side++) {
    const int count = side ? m->nsidesets : m->nnodesets;
    for (int k = 0; k < count; k++) {
      const pf_mesh_set *s = side ? &m->sideset[k] : &m->nodeset[k];
      pf_gid *ids = NULL, n = 0;
      if (side) PF_CALL(side_set_nodes(m, s, gid0, &ids, &n));
      else {
        PF_MALLOC(ids, (size_t)s->n + 1);
        for (pf_int i = 0; i < s->n; i++) ids[n++] = gid0 + s->item[i];
      }
      int ierr = pf_point_sets_add(&sim->sets, s->name, b, side, ids, n);
      free(ids);
      PF_CALL(ierr);
    }
  }
  return 0;
}

static int add_cloud_sets(pf_sim *sim, int b, const pf_point_cloud *pc, pf_gid gid0) {
  for (int k = 0; k < pc->nsets; k++) {
    const pf_point_set *s = &pc->sets[k];
    pf_gid *ids = NULL;
    PF_MALLOC(ids, (size_t)s->n + 1);
    for (pf_gid i = 0; i < s->n; i++) ids[i] = gid0 + s->gid[i];
    int ierr = pf_point_sets_add(&sim->sets, s->name, b, s->side, ids, s->n);
    free(ids);
    PF_CALL(ierr);
  }
  return 0;
}

int pf_sim_sets_build(pf_sim *sim, const pf_point_cloud *pc) {
  pf_point_sets_free(&sim->sets);
  sim->sets.body_name = sim->body_name;
  pf_gid gid0 = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    const pf_mesh *m = pf_body_mesh(body);
    if (m) PF_CALL(add_mesh_sets(sim, b, m, gid0));
    PF_CALL(add_cloud_sets(sim, b, &pc[b], gid0));
    gid0 += pc[b].n;
  }
  return 0;
}
