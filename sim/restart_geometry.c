/* The bodies' geometry, recorded in every checkpoint and compared on restart: per body the number
 * of its points, of its elements (0 without a mesh) and two 64-bit FNV-1a hashes of what the
 * set-up made them from: the point cloud's reference positions, volumes, cells and blocks, and
 * the mesh's connectivity and element blocks. The deck's hash of `bodies` cannot see a mesh or point file
 * whose content changed under the same name; this can. A restart makes the clouds again from its
 * deck (sim/create.c) and refuses a checkpoint whose geometry differs, naming the body, the file
 * it is made from and what differs. */
#include "sim/sim_impl.h"

#include <string.h>

/* Take each body's geometry from its set-up cloud pc[nbodies] (and its mesh). */
void pf_sim_geometry_take(pf_sim *sim, const pf_point_cloud *pc) {
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_point_cloud *c = &pc[b];
    const pf_body *body = &sim->body[b];
    const pf_mesh *m = pf_body_mesh(body);
    uint64_t h = PF_FNV1A_SEED, hc = PF_FNV1A_SEED;
    const size_t n = (size_t)c->n;
    h = pf_fnv1a(h, c->X, 3 * n * sizeof(double));
    if (c->vol) h = pf_fnv1a(h, c->vol, n * sizeof(double));
    if (c->cell) h = pf_fnv1a(h, c->cell, n * sizeof(double));
    if (c->block) h = pf_fnv1a(h, c->block, n * sizeof(int32_t));
    if (m) {
      hc = pf_fnv1a(hc, m->conn, 8 * (size_t)m->nelem * sizeof(pf_int));
      hc = pf_fnv1a(hc, m->block, (size_t)m->nelem * sizeof(int32_t));
    }
    sim->geometry[b] = (pf_sim_geometry){(double)c->n, m ? (double)m->nelem : 0.0, {h, hc}};
  }
}

/* v[PF_GEOMETRY_SCALARS nbodies]: per body its points, elements and the two hashes' 32-bit
 * halves (positions, then connectivity). */
void pf_sim_geometry_scalars(const pf_sim *sim, double *v) {
  for (int b = 0; b < sim->nbodies; b++, v += PF_GEOMETRY_SCALARS) {
    const pf_sim_geometry *g = &sim->geometry[b];
    v[0] = g->points, v[1] = g->elements;
    for (int k = 0; k < 2; k++)
      v[2 + 2 * k] = (double)(g->hash[k] >> 32), v[3 + 2 * k] = (double)(g->hash[k] & 0xffffffffu);
  }
}

/* What body b is made from, as the deck says: "mesh file 'x'", "point file 'x'", ... */
static void source_of(const pf_sim *sim, int b, char *out, size_t len) {
  const pf_node *body = pf_node_item(pf_node_get(pf_deck_root(sim->deck), "bodies"), b);
  const pf_node *mesh = pf_node_get(body, "mesh"), *geo = pf_node_get(body, "geometry");
  const char *file = NULL;
  if (mesh && pf_node_get(mesh, "file") && !pf_deck_string(sim->deck, mesh, "file", &file))
    snprintf(out, len, "mesh file '%s'", file);
  else if (mesh) snprintf(out, len, "inline Pamgen mesh (mesh.pamgen)");
  else if (geo && pf_node_get(geo, "file") && !pf_deck_string(sim->deck, geo, "file", &file))
    snprintf(out, len, "point file '%s'", file);
  else snprintf(out, len, "lattice (geometry:)");
}

/* saved[PF_GEOMETRY_SCALARS nbodies] as pf_sim_geometry_scalars wrote them, against this
 * set-up's geometry. */
int pf_sim_check_restart_geometry(const pf_sim *sim, const double *saved) {
  enum { G = PF_GEOMETRY_SCALARS };
  double now[G * PF_MAX_BODIES];
  pf_sim_geometry_scalars(sim, now);
  for (int b = 0; b < sim->nbodies; b++) {
    const double *s = &saved[G * b], *n = &now[G * b];
    if (!memcmp(s, n, G * sizeof(double))) continue;
    char src[4200];
    source_of(sim, b, src, sizeof src);
    const int meshed = n[1] > 0 || s[1] > 0;
    const char *pts = meshed ? "nodes" : "points";
    PF_CHECK(s[0] == n[0] && s[1] == n[1], PF_ERR_INPUT,
             "%s: body '%s': its %s gives %.0f %s and %.0f elements, the checkpoint %s was written with %.0f %s and "
             "%.0f elements: a restart needs the geometry the checkpoint was written with",
             pf_deck_path(sim->deck), sim->body_name[b], src, n[0], pts, n[1], sim->opt.restart_from, s[0], pts, s[1]);
    const int moved = s[2] != n[2] || s[3] != n[3];
    const char *what = !moved ? "element connectivity (or element blocks)"
                       : meshed ? "node coordinates" : "point positions (or volumes)";
    PF_CHECK(0, PF_ERR_INPUT,
             "%s: body '%s': its %s gives the same %.0f %s and %.0f elements as the checkpoint %s was written with, "
             "but other %s%s: the file or the deck's placement changed since; a restart needs the geometry the "
             "checkpoint was written with",
             pf_deck_path(sim->deck), sim->body_name[b], src, n[0], pts, n[1], sim->opt.restart_from, what,
             moved && (s[4] != n[4] || s[5] != n[5]) ? " and element connectivity" : "");
  }
  return 0;
}
