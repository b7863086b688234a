/* Contact between bodies: the `contact:` deck section, the pick of each pair's method from its
 * two bodies and its `method:` key (the list contact/methods.h; each method, its law and its
 * defaults derived from the materials and the discretization, is a file contact/method_<id>.c),
 * the stable step of the penalties, and the per-step entry point. The generic code here, in
 * search.c and in pairs.c reads a pair's method through its ops (pf_contact_method,
 * contact_impl.h), with one dispatcher below for each optional op.
 *
 * Short range (PD <-> PD, and a PD body with itself): Littlewood's f = C (r_c - r) V_i V_j
 * (contact/method_short_range.c). FE <-> PD (Tupek et al. 2013, sec. 3.2): `method: surface` (the
 * default, contact/method_surface.c) pushes a particle off the closest point of the FE surface
 * with f = k (r_c - g), `method: nodes` (contact/method_nodes.c) is the node-to-particle penalty
 * f = k (r_c - d). FE <-> FE: each body's surface nodes against the other's faces
 * (contact/method_surfaces.c). docs/theory/contact.md. */
#include "contact/contact_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const pf_contact_method *const pf_contact_methods[] = {
#define PF_CONTACT_METHOD(id) &pf_contact_method_##id,
#include "contact/methods.h"
#undef PF_CONTACT_METHOD
};
const int pf_contact_nmethods = (int)(sizeof pf_contact_methods / sizeof pf_contact_methods[0]);

const pf_contact_method *pf_contact_method_find(pf_contact_case cs, const char *name) {
  for (int q = 0; q < pf_contact_nmethods; q++) {
    const pf_contact_method *m = pf_contact_methods[q];
    if (m->claims == cs && (!name || (m->name && !strcmp(m->name, name)))) return m;
  }
  return NULL;
}

/* ---- the dispatchers of the optional ops ---------------------------------------------------- */
double pf_contact_method_length(const pf_contact *c, const pf_contact_pair *p) {
  return p->method->length ? p->method->length(c, p) : p->radius;
}

int pf_contact_method_self_rest_lengths(const pf_contact_pair *p) {
  return p->method->self_rest_lengths ? p->method->self_rest_lengths(p) : 0;
}

int pf_contact_method_side_rebuilt(const pf_contact_method *m, const pf_contact_body *fe, pf_contact_side *sd) {
  return m->side_rebuilt ? m->side_rebuilt(fe, sd) : 0;
}

const pf_key pf_contact_pair_keys[] = {
    {"bodies", PF_KEY_STRLIST, 1, NULL, "", "the two bodies (the same name twice: self-contact of a PD body); each pair once (the same two bodies over the same surfaces again, in either order, is refused)", NULL},
    {"name", PF_KEY_STRING, 0, NULL, "", "name in the history (default <a>_<b>)", NULL},
    {"method", PF_KEY_STRING, 0, "surface", "", "FE <-> PD: surface (closest point of the FE surface) | nodes (node-to-particle only)", NULL},
    {"surface", PF_KEY_STRING, 0, NULL, "", "FE <-> PD: side set of the FE mesh in contact (default: the whole boundary)", NULL},
    {"surfaces", PF_KEY_STRLIST, 0, NULL, "", "FE <-> FE: a side set of each body, in the order of bodies (default: the whole boundaries)", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "contact radius (default: short range 0.9 x the larger spacing, within one body at most 0.9 x the reference distance and a broken bond's length at the break; FE <-> PD half the PD spacing; FE <-> FE 0)", NULL},
    {"stiffness", PF_KEY_REAL, 0, NULL, "N/m | N/m^7", "FE <-> PD: k (default K h of the PD body); FE <-> FE: k (default 10 K h of the softer body); short range: C (default 18 k_s / (pi delta^5))", NULL},
    {"spring_constant", PF_KEY_REAL, 0, NULL, "Pa", "short range: k_s (default: the larger bulk modulus)", NULL},
    {"horizon", PF_KEY_REAL, 0, NULL, "m", "short range: delta (default: the larger horizon)", NULL},
    {"friction", PF_KEY_REAL, 0, "0", "", "Coulomb friction coefficient", NULL},
    {"tangential_stiffness", PF_KEY_REAL, 0, "stiffness", "N/m",
     "quasi_static with friction, pairs with an FE body: k_t of the tangential penalty f_t = -k_t g_t of a point "
     "that sticks (g_t its tangential displacement relative to the surface point it meets since its committed "
     "slip; docs/theory/quasi_static_methods.md §8)",
     NULL},
    {"all_points", PF_KEY_BOOL, 0, "false", "", "short range: also between bonded points", NULL},
    {"soft", PF_KEY_BOOL, 0, "false", "",
     "explicit runs: lower the stiffness (the default or the one given) as far as needed for the pair's stable step "
     "not to fall below the smaller stable step of its two bodies at the start, so that the penalty does not set the "
     "time step (docs/theory/contact.md §4a); refused by the quasi_static solver",
     NULL},
    PF_KEY_END};

const pf_key pf_contact_keys[] = {
    {"skin", PF_KEY_REAL, 0, NULL, "m", "search skin: a pair's search is rebuilt when two of its points may have moved more than it relative to each other (docs/theory/contact.md §5; default: the largest contact radius, and half the finer nodal spacing of an FE <-> FE pair)", NULL},
    {"pairs", PF_KEY_LIST, 0, NULL, "", "bodies in contact", pf_contact_pair_keys},
    {"rigid_surfaces", PF_KEY_LIST, 0, NULL, "", "rigid spheres, planes, cylinders", pf_rigid_keys},
    PF_KEY_END};

static int pair_bodies(const pf_deck *d, const pf_node *map, int nbodies, const pf_contact_body *bodies,
                       pf_contact_pair *p) {
  const pf_node *list = pf_node_get(map, "bodies");
  if (pf_node_count(list) != 2)
    return pf_deck_error(d, list, "bodies", "a pair names exactly two bodies (got %d)", pf_node_count(list));
  const char *names[nbodies];
  for (int k = 0; k < nbodies; k++) names[k] = bodies[k].name;
  int a, b;
  PF_CALL(pf_deck_body_index(d, pf_node_item(list, 0), "bodies", nbodies, names, &a));
  PF_CALL(pf_deck_body_index(d, pf_node_item(list, 1), "bodies", nbodies, names, &b));
  if (bodies[a].is_fe && a == b)
    return pf_deck_error(d, list, "bodies", "self-contact of the finite-element body '%s' is not supported",
                         bodies[a].name);
  if (bodies[b].is_fe && !bodies[a].is_fe) { int t = a; a = b; b = t; }
  p->a = a, p->b = b;
  snprintf(p->name, sizeof p->name, "%s_%s", bodies[a].name, bodies[b].name);
  const char *name = NULL;
  PF_CALL(pf_deck_string(d, map, "name", &name));
  if (name) snprintf(p->name, sizeof p->name, "%s", name);
  return 0;
}

int pf_contact_side_read(const pf_deck *d, const pf_node *node, const char *key, const pf_contact_body *fe, int b,
                         pf_contact_side *side) {
  int sideset = -1;
  if (node) {
    const char *name = pf_node_text(node);
    for (int s = 0; s < fe->mesh->nsidesets; s++)
      if (!strcmp(fe->mesh->sideset[s].name, name)) sideset = s;
    if (sideset < 0) return pf_deck_error(d, node, key, "the mesh of body '%s' has no side set '%s'", fe->name, name);
  }
  side->body = b, side->sideset = sideset;
  return pf_contact_surface_faces(fe->mesh, sideset, NULL, &side->face, &side->nface);
}

int pf_contact_refuse_keys(const pf_deck *d, const pf_node *map, const char *const *keys, const char *why) {
  for (const char *const *k = keys; *k; k++)
    if (pf_node_get(map, *k)) return pf_deck_error(d, pf_node_get(map, *k), *k, "'%s' is %s", *k, why);
  return 0;
}

int pf_contact_fe_pd_read(const pf_deck *d, const pf_node *map, const pf_contact_body *fe, const pf_contact_body *pd,
                          pf_contact_pair *p) {
  PF_CALL(pf_contact_refuse_keys(d, map, pf_contact_short_range_keys, "a key of short-range (PD <-> PD) pairs"));
  if (pf_node_get(map, "surfaces"))
    return pf_deck_error(d, pf_node_get(map, "surfaces"), "surfaces",
                         "'surfaces' is a key of FE <-> FE pairs (an FE <-> PD pair takes 'surface')");
  p->nside = 1;
  PF_CALL(pf_contact_side_read(d, pf_node_get(map, "surface"), "surface", fe, p->a, &p->side[0]));
  p->radius = 0.5 * pd->spacing;
  p->stiffness = pd->bulk_modulus * pd->spacing;
  PF_CALL(pf_deck_positive(d, map, "radius", &p->radius));
  PF_CALL(pf_deck_positive(d, map, "stiffness", &p->stiffness));
  return 0;
}

/* A particle on one face and a node carrying up to (face diagonal / h)^2 particles: omega^2 =
 * k / m_p + k max(1, (l / h)^2) / m_n (docs/theory/contact.md). */
double pf_contact_fe_pd_stable_w2(const pf_contact *c, const pf_contact_pair *p, const pf_points *pts) {
  const pf_contact_body *a = &c->body[p->a], *b = &c->body[p->b];
  double mb = pf_contact_min_mass(b, pts), ma = pf_contact_min_mass(a, pts);
  return pf_contact_node_on_face_w2(p->stiffness, mb, b->spacing, ma, a->spacing);
}

/* The method of a pair of case cs: the one its `method:` names, or the case's first. An unknown
 * name is refused here when the case has several named methods; else the case's one method
 * refuses it in its own words (its read). */
static int pick_method(const pf_deck *d, const pf_node *map, pf_contact_case cs, const pf_contact_method **out) {
  const char *name = NULL;
  PF_CALL(pf_deck_string(d, map, "method", &name));
  *out = pf_contact_method_find(cs, name);
  if (*out) return 0;
  char known[256];
  size_t len = 0;
  int named = 0;
  known[0] = '\0';
  for (int q = 0; q < pf_contact_nmethods && len < sizeof known; q++) {
    const pf_contact_method *m = pf_contact_methods[q];
    if (m->claims == cs && m->name)
      len += (size_t)snprintf(known + len, sizeof known - len, "%s%s", named++ ? ", " : "", m->name);
  }
  if (named > 1)
    return pf_deck_error(d, pf_node_get(map, "method"), "method", "unknown method '%s' (known: %s)", name, known);
  *out = pf_contact_method_find(cs, NULL);
  PF_CHECK(*out, PF_ERR_INPUT, "no contact method claims this pair of bodies");
  return 0;
}

static int read_pair(const pf_deck *d, const pf_node *map, int nbodies, const pf_contact_body *bodies,
                     pf_contact_pair *p) {
  PF_CALL(pair_bodies(d, map, nbodies, bodies, p));
  const pf_contact_body *a = &bodies[p->a], *b = &bodies[p->b];
  const pf_contact_case cs = !a->is_fe ? PF_CONTACT_PD_PD : b->is_fe ? PF_CONTACT_FE_FE : PF_CONTACT_FE_PD;
  PF_CALL(pick_method(d, map, cs, &p->method));
  PF_CALL(p->method->read(d, map, a, b, p));
  PF_CALL(pf_deck_real(d, map, "friction", &p->friction));
  if (!(p->friction >= 0))
    return pf_deck_error(d, pf_node_get(map, "friction"), "friction", "must not be negative (got %g)", p->friction);
  PF_CALL(pf_deck_bool(d, map, "soft", &p->soft));
  p->tangential = p->stiffness;
  if (pf_node_get(map, "tangential_stiffness") && !p->method->pushes)
    return pf_deck_error(d, pf_node_get(map, "tangential_stiffness"), "tangential_stiffness",
                         "'tangential_stiffness' is a key of pairs with an FE body (short-range pairs have no "
                         "quasi-static friction)");
  return pf_deck_positive(d, map, "tangential_stiffness", &p->tangential);
}

/* Mark the mesh nodes of each FE body that lie on some pair's surface. */
static int mark_surfaces(pf_contact *c) {
  if (!c->surface_node) {
    PF_MALLOC(c->surface_node, c->nbodies);
    PF_MALLOC(c->node_view, c->nbodies);
    PF_MALLOC(c->body_used, c->nbodies);
    PF_MALLOC(c->eroded_seen, c->nbodies);
  }
  for (int b = 0; b < c->nbodies; b++)
    if (c->surface_node[b]) memset(c->surface_node[b], 0, (size_t)c->body[b].mesh->nnodes);
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    c->body_used[p->a] = c->body_used[p->b] = 1;
    for (int s = 0; s < p->nside; s++) {
      const pf_contact_side *sd = &p->side[s];
      pf_int nn = c->body[sd->body].mesh->nnodes;
      if (!c->surface_node[sd->body]) {
        PF_MALLOC(c->surface_node[sd->body], nn);
        PF_MALLOC(c->node_view[sd->body], nn);
      }
      for (pf_int f = 0; f < sd->nface; f++)
        for (int q = 0; q < 4; q++) c->surface_node[sd->body][sd->face[f].node[q]] = 1;
    }
  }
  return 0;
}

/* The faces of side sd (sorted by element and face, as pf_contact_surface_faces gives them) that
 * the previous faces old[0 .. nold) did not have: uncovered by this deletion. */
static int mark_fresh(pf_contact_side *sd, const pf_contact_face *old, pf_int nold) {
  PF_FREE(sd->fresh);
  PF_MALLOC(sd->fresh, sd->nface);
  for (pf_int f = 0, j = 0; f < sd->nface; f++) {
    const pf_contact_face *x = &sd->face[f];
    while (j < nold && (old[j].elem < x->elem || (old[j].elem == x->elem && old[j].face < x->face))) j++;
    sd->fresh[f] = !(j < nold && old[j].elem == x->elem && old[j].face == x->face);
  }
  return 0;
}

/* When elements of an FE body were deleted since the surfaces were built (fem/erosion.c), the
 * pairs' sides on that body become the faces of its live elements (newly exposed faces
 * included), the surface nodes are marked anew and the search is rebuilt. Every rank holds the
 * same deleted elements, so every rank sees the same surfaces (docs/theory/contact.md sec. 2.5). */
static int follow_erosion(pf_contact *c) {
  int changed = 0;
  for (int b = 0; b < c->nbodies; b++) {
    long n = 0;
    const pf_contact_body *cb = &c->body[b];
    const uint8_t *dead = cb->eroded ? cb->eroded(cb->eroded_ctx, &n) : NULL;
    if (!dead || n == c->eroded_seen[b]) continue;
    c->eroded_seen[b] = n, changed = 1;
    for (int k = 0; k < c->npairs; k++)
      for (int s = 0; s < c->pair[k].nside; s++) {
        pf_contact_side *sd = &c->pair[k].side[s];
        if (sd->body != b) continue;
        pf_contact_face *old = sd->face;
        const pf_int nold = sd->nface;
        int ierr = pf_contact_surface_faces(c->body[b].mesh, sd->sideset, dead, &sd->face, &sd->nface);
        if (!ierr) ierr = mark_fresh(sd, old, nold);
        free(old);
        PF_CALL(ierr);
        PF_CALL(pf_contact_method_side_rebuilt(c->pair[k].method, &c->body[b], sd));
      }
  }
  if (!changed) return 0;
  PF_CALL(mark_surfaces(c));
  c->built = 0;
  return 0;
}

/* A pair's bodies and surfaces in a fixed order: the lower body index, the higher, and the side
 * set each meets by (-1 the whole boundary, -2 none: a PD body). */
static void pair_key(const pf_contact_pair *p, int key[4]) {
  key[0] = p->a < p->b ? p->a : p->b, key[1] = p->a < p->b ? p->b : p->a;
  key[2] = key[3] = -2;
  for (int k = 0; k < p->nside; k++) key[2 + (p->side[k].body != key[0])] = p->side[k].sideset;
}

/* The same two bodies over the same surfaces twice, in either order, would push twice as hard. */
static int check_repeated_pairs(const pf_deck *d, const pf_node *pairs, const pf_contact *c) {
  for (int j = 1; j < c->npairs; j++)
    for (int k = 0; k < j; k++) {
      int kj[4], kk[4];
      pair_key(&c->pair[j], kj), pair_key(&c->pair[k], kk);
      if (memcmp(kj, kk, sizeof kj)) continue;
      const pf_node *list = pf_node_get(pf_node_item(pairs, j), "bodies");
      return pf_deck_error(d, list ? list : pf_node_item(pairs, j), "bodies",
                           "pair %d repeats pair %d of contact.pairs (bodies '%s' and '%s'%s): the two would push "
                           "twice as hard; list each pair once", j + 1, k + 1, c->body[kj[0]].name,
                           c->body[kj[1]].name, c->pair[j].nside ? ", the same surfaces" : "");
    }
  return 0;
}

static int contact_setup(const pf_deck *d, const pf_node *map, pf_contact *c) {
  const pf_node *pairs = pf_node_get(map, "pairs");
  PF_MALLOC(c->pair, c->npairs);
  double rmax = 0;
  for (int k = 0; k < c->npairs; k++) {
    PF_CALL(read_pair(d, pf_node_item(pairs, k), c->nbodies, c->body, &c->pair[k]));
    rmax = fmax(rmax, c->pair[k].radius);
    c->pair[k].length = pf_contact_method_length(c, &c->pair[k]), c->pair[k].gap = INFINITY;
    rmax = fmax(rmax, c->pair[k].length);
    c->has_fe |= c->body[c->pair[k].a].is_fe || c->body[c->pair[k].b].is_fe;
  }
  PF_CALL(check_repeated_pairs(d, pairs, c));
  c->skin = rmax;
  PF_CALL(pf_deck_positive(d, map, "skin", &c->skin));
  PF_CALL(mark_surfaces(c));
  c->nranks = pf_comm_size();
  PF_MALLOC(c->scount, 4 * c->nranks);
  c->sdispl = c->scount + c->nranks, c->rcount = c->sdispl + c->nranks, c->rdispl = c->rcount + c->nranks;
  return 0;
}

int pf_contact_create(const pf_deck *d, const pf_node *map, int nbodies, const pf_contact_body *bodies,
                      pf_contact **out) {
  *out = NULL;
  int npairs = pf_node_count(pf_node_get(map, "pairs"));
  if (!npairs) {
    if (pf_node_get(map, "skin")) pf_log("warning: contact: 'skin' given but no pair\n");
    return 0;
  }
  pf_contact *c;
  PF_MALLOC(c, 1);
  c->npairs = npairs, c->nbodies = nbodies;
  int ierr = 0;
  c->body = malloc(sizeof *c->body * (size_t)nbodies);
  if (!c->body) ierr = PF_ERR_MEMORY;
  else memcpy(c->body, bodies, sizeof *c->body * (size_t)nbodies);
  if (!ierr) ierr = contact_setup(d, map, c);
  if (ierr) {
    pf_contact_destroy(&c);
    return ierr;
  }
  *out = c;
  return 0;
}

int pf_contact_destroy(pf_contact **cp) {
  pf_contact *c = *cp;
  if (!c) return 0;
  for (int k = 0; c->pair && k < c->npairs; k++)
    for (int s = 0; s < 2; s++)
      free(c->pair[k].side[s].face), free(c->pair[k].side[s].node_off), free(c->pair[k].side[s].node_face),
          free(c->pair[k].side[s].fresh);
  for (int b = 0; b < c->nbodies; b++) {
    if (c->surface_node) free(c->surface_node[b]);
    if (c->node_view) free(c->node_view[b]);
  }
  free(c->surface_node), free(c->node_view), free(c->body_used), free(c->eroded_seen);
  free(c->pair), free(c->body);
  free(c->local), free(c->gid), free(c->vbody), free(c->rank);
  free(c->y), free(c->v), free(c->vol), free(c->m), free(c->rad), free(c->X), free(c->y_build), free(c->stale), free(c->built_at);
  pf_exchange_destroy(&c->exchange);
  free(c->scount), free(c->send), free(c->cand_off), free(c->cand), free(c->force);
  PF_FREE(*cp);
  return 0;
}

int pf_contact_attach(pf_contact *c, const pf_contact_body *bodies) {
  for (int b = 0; b < c->nbodies; b++) {
    c->body[b].first = bodies[b].first;
    c->body[b].n = bodies[b].n;
    c->body[b].fam = bodies[b].fam;
  }
  c->built = c->prepared = 0;
  return 0;
}

/* Add the contact forces to the points' and keep them in the output field "contact_force" (the
 * points that are no entity of any pair are never written, so they stay zero). */
static int add_forces(pf_contact *c, pf_points *pts) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "contact_force", 3, PF_FIELD_OUTPUT, &idx));
  double *fc = pts->fields[idx].data;
#pragma omp parallel for schedule(static)
  for (pf_int e = 0; e < c->nown; e++)
    for (int a = 0; a < 3; a++) {
      fc[3 * c->local[e] + a] = c->force[3 * e + a];
      pts->f[3 * c->local[e] + a] += c->force[3 * e + a];
    }
  return 0;
}

int pf_contact_nsums(const pf_contact *c) { return 3 * c->npairs + 1; }

void pf_contact_rebuild(pf_contact *c) { c->built = c->prepared = 0; }

void pf_contact_sums_take(pf_contact *c, const double *sums, double *energy) {
  for (int k = 0; k < c->npairs; k++) memcpy(c->pair[k].force, &sums[3 * k], sizeof c->pair[k].force);
  *energy = sums[3 * c->npairs];
}

/* The point fields "contact_offset" and "contact_reach" when a pair meets, with particles, the
 * surface of a body that deletes elements (registered at the first such evaluation, or read from
 * a checkpoint), this evaluation's "in reach" moved to the previous one's; else NULL
 * (docs/theory/contact.md sec. 2.5). */
static int offsets(pf_contact *c, pf_points *pts) {
  c->offset = c->reach = NULL;
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    const pf_contact_body *fb = &c->body[p->side[0].body];
    long n = 0;
    if (!p->method->holds_offsets || !fb->eroded || !fb->eroded(fb->eroded_ctx, &n)) continue;
    int idx;
    PF_CALL(pf_points_field_register(pts, "contact_offset", 1, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &idx));
    c->offset = pts->fields[idx].data;
    PF_CALL(pf_points_field_register(pts, "contact_reach", 2, PF_FIELD_RESTART, &idx));
    c->reach = pts->fields[idx].data;
    for (pf_int i = 0; i < pts->n_owned; i++) c->reach[2 * (size_t)i] = c->reach[2 * (size_t)i + 1], c->reach[2 * (size_t)i + 1] = 0;
    return 0;
  }
  return 0;
}

/* The faces uncovered at this evaluation are fresh for it only; a new particle is new at its
 * first evaluation only (its offset, -1 until then, is 0 unless a face took it). */
static void fresh_done(pf_contact *c) {
  for (pf_int e = 0; c->offset && e < c->nown; e++)
    if (c->offset[c->local[e]] < 0) c->offset[c->local[e]] = 0;
  for (int k = 0; k < c->npairs; k++)
    for (int s = 0; s < c->pair[k].nside; s++) PF_FREE(c->pair[k].side[s].fresh);
}

int pf_contact_restored(pf_contact *c) {
  c->prepared = 0;
  PF_CALL(follow_erosion(c));
  fresh_done(c);
  return 0;
}

/* The owned entities (when not built), the ghosts' positions and the candidates at the current
 * positions. Collective. */
static int search_here(pf_contact *c, pf_points *pts) {
  if (!c->built) PF_CALL(pf_contact_collect_owned(c, pts));
  PF_CALL(pf_contact_exchange(c, pts));
  return pf_contact_search(c, pts);
}

int pf_contact_prepare(pf_contact *c, pf_points *pts) {
  if (c->nranks == 1) return 0; /* (no rank to wait for; the search beside the pair forces keeps the
                                 * positions it reads warm for them: the bench's PMB 3-5 % faster) */
  const double t0 = pf_wtime();
  PF_CALL(search_here(c, pts)); /* (elements are deleted only in the bodies' forces: evaluate sees them) */
  c->prepared = 1;
  c->seconds += pf_wtime() - t0;
  return 0;
}

/* The interactions at the current positions into c->force, *U and *dissipation; the search done
 * ahead (pf_contact_prepare) is kept unless the bodies' forces since deleted elements (the
 * search is then done here from the start). Collective. */
static int evaluate(pf_contact *c, pf_points *pts, double dt, double *U, double *dissipation) {
  const int ahead = c->prepared;
  c->prepared = 0;
  PF_CALL(offsets(c, pts));
  PF_CALL(follow_erosion(c));
  if (!ahead || !c->built) PF_CALL(search_here(c, pts));
  c->slip = c->static_friction ? pf_points_field_get(pts, "contact_slip") : NULL;
  PF_CALL(pf_contact_pairs_evaluate(c, dt, U, dissipation));
  fresh_done(c);
  return 0;
}

int pf_contact_force(pf_contact *c, pf_points *pts, double dt, double *sums, double *dissipation) {
  double t0 = pf_wtime();
  double U = 0;
  PF_CALL(evaluate(c, pts, dt, &U, dissipation));
  PF_CALL(add_forces(c, pts));
  for (int k = 0; k < c->npairs; k++) memcpy(&sums[3 * k], c->pair[k].force, sizeof c->pair[k].force);
  sums[3 * c->npairs] = U;
  c->seconds += pf_wtime() - t0;
  return 0;
}

int pf_contact_quasi_static(pf_contact *c, const pf_deck *d, const pf_node *map, pf_points *pts) {
  const pf_node *pairs = pf_node_get(map, "pairs");
  for (int k = 0; k < c->npairs; k++)
    if (c->pair[k].soft)
      return pf_deck_error(d, pf_node_get(pf_node_item(pairs, k), "soft"), "soft",
                           "a soft pair's stiffness is set by the bodies' stable time step, which the quasi_static "
                           "solver does not take; give the pair its 'stiffness' instead");
  for (int k = 0; k < c->npairs; k++) {
    if (!(c->pair[k].friction > 0)) continue;
    if (!c->pair[k].method->pushes)
      return pf_deck_error(d, pf_node_get(pf_node_item(pairs, k), "friction"), "friction",
                           "the friction of short-range pairs (PD <-> PD) is not supported with the quasi_static "
                           "solver (its regularized Coulomb force needs a time step); pairs with an FE body take "
                           "friction there");
    c->static_friction = 1;
  }
  if (!c->static_friction || pf_points_field_get(pts, "contact_slip")) return 0; /* (a restart's: kept) */
  int idx;
  PF_CALL(pf_points_field_register(pts, "contact_slip", 4, PF_FIELD_RESTART, &idx));
  /* at rest at the start (u = 0): every point's slip is set there, r = 0, whatever it meets first */
  double *slip = pts->fields[idx].data;
  for (pf_int i = 0; i < pts->n_total; i++) slip[4 * (size_t)i] = slip[4 * (size_t)i + 1] = slip[4 * (size_t)i + 2] = 0, slip[4 * (size_t)i + 3] = 1;
  return 0;
}

int pf_contact_commit_slips(pf_contact *c, pf_points *pts, double *terms) {
  memset(terms, 0, sizeof *terms * (size_t)pts->n_owned);
  if (!c->static_friction) return 0;
  c->commit = malloc(sizeof *c->commit * PF_CONTACT_COMMIT * ((size_t)c->nown + 1));
  for (pf_int e = 0; c->commit && e < c->nown; e++) {
    double *m = &c->commit[PF_CONTACT_COMMIT * (size_t)e];
    for (int q = 0; q < PF_CONTACT_COMMIT; q++) m[q] = 0;
    m[PF_CONTACT_COMMIT_DIST] = INFINITY;
  }
  double U = 0, diss = 0;
  int ierr = c->commit ? evaluate(c, pts, 0.0, &U, &diss) : PF_ERR_MEMORY;
  for (pf_int e = 0; e < c->nown && !ierr; e++) {
    /* pushed: the new slips; else near a surface: the displacement relative to it (no elastic
     * part); else none */
    const double *m = &c->commit[PF_CONTACT_COMMIT * (size_t)e], w = m[3];
    const int near = !(w > 0) && m[PF_CONTACT_COMMIT_DIST] < INFINITY;
    double *s = &c->slip[4 * (size_t)c->local[e]];
    for (int a = 0; a < 3; a++) s[a] = w > 0 ? m[a] / w : near ? m[PF_CONTACT_COMMIT_NEAR + a] : 0.0;
    s[3] = w > 0 || near;
    terms[c->local[e]] = m[PF_CONTACT_COMMIT_WORK];
  }
  PF_FREE(c->commit);
  PF_CHECK(ierr != PF_ERR_MEMORY, PF_ERR_MEMORY, "out of memory for the contact slips of %lld points",
           (long long)c->nown);
  return ierr;
}

double pf_contact_min_mass(const pf_contact_body *b, const pf_points *pts) {
  double m = INFINITY;
  for (pf_int i = b->first; i < b->first + b->n; i++)
    m = fmin(m, pts->m[i] > 0 ? pts->m[i] : b->density * pts->vol[i]);
  return pf_min_all(m);
}

double pf_contact_node_on_face_w2(double k, double m, double h, double mf, double l) {
  double d = sqrt(2.0) * l, many = fmax(1.0, (d / h) * (d / h));
  return k / m + k * many / mf;
}

/* 2 / omega of the stiffest pair (each method's stable_w2). */
double pf_contact_stable_dt(const pf_contact *c, const pf_points *pts) {
  double dt = INFINITY;
  for (int k = 0; k < c->npairs; k++) dt = fmin(dt, 2.0 / sqrt(c->pair[k].method->stable_w2(c, &c->pair[k], pts)));
  return dt;
}

/* Pair p's stiffness set to k, its tangential penalty (quasi-static friction) scaled with it. */
static void set_stiffness(pf_contact_pair *p, double k) {
  p->tangential *= k / p->stiffness;
  p->stiffness = k;
}

/* Soft pairs: every penalty of a pair is linear in its stiffness, so is its omega^2; the stiffness
 * times w2_b / w2, w2_b = 4 / dt_b^2, puts the pair's stable step 2 / omega at dt_b, the smaller of
 * its bodies' (when it is below). Collective (stable_w2 reduces). */
int pf_contact_soften(pf_contact *c, const pf_points *pts, const double *body_dt, const char *const *body_name) {
  for (int k = 0; k < c->npairs; k++) {
    pf_contact_pair *p = &c->pair[k];
    if (!p->soft) continue;
    const double dt_b = fmin(body_dt[p->a], body_dt[p->b]), w2 = p->method->stable_w2(c, p, pts);
    const int by = body_dt[p->a] <= body_dt[p->b] ? p->a : p->b;
    if (!(dt_b > 0 && isfinite(dt_b) && w2 > 4.0 / (dt_b * dt_b))) continue; /* (its step is not below) */
    const double k0 = p->stiffness;
    set_stiffness(p, k0 * (4.0 / (dt_b * dt_b) / w2));
    pf_log("contact pair '%s' (soft): stiffness %.4g -> %.4g %s, its stable step %.4g -> %.4g s, that of body '%s'\n",
           p->name, k0, p->stiffness, p->nside ? "N/m" : "N/m^7", 2.0 / sqrt(w2), dt_b, body_name[by]);
  }
  return 0;
}

int pf_contact_pair_soft(const pf_contact *c, int k) { return c->pair[k].soft; }

int pf_contact_nsoft(const pf_contact *c) {
  int n = 0;
  for (int k = 0; c && k < c->npairs; k++) n += c->pair[k].soft;
  return n;
}

void pf_contact_soft_stiffness_get(const pf_contact *c, double *v) {
  for (int k = 0, q = 0; k < c->npairs; k++)
    if (c->pair[k].soft) v[q++] = c->pair[k].stiffness;
}

void pf_contact_soft_stiffness_set(pf_contact *c, const double *v) {
  for (int k = 0, q = 0; k < c->npairs; k++) {
    pf_contact_pair *p = &c->pair[k];
    if (!p->soft) continue;
    if (v[q] != p->stiffness) /* (the set-up's fit logged its own: say which the run keeps) */
      pf_log("contact pair '%s' (soft): stiffness %.4g %s from the checkpoint, not the set-up's %.4g\n", p->name, v[q],
             p->nside ? "N/m" : "N/m^7", p->stiffness);
    set_stiffness(p, v[q++]);
  }
}

/* Quasi-static: a bound of the row sums of the penalties' stiffness at each owned point of a
 * pair's bodies. A pair's stable_w2 is at least k_i / m_i for the stiffest point of either body
 * (the sum of its partners' penalties k_i over its mass m_i: a node k, a face node the shares of
 * the nodes on its face, a particle its neighbours' C V_i V_j), so m_i w2 bounds k_i; a penalty
 * between two points adds k_i to the diagonal and as much off it, along one direction n, whose
 * 3 x 3 block n n^T has row sums of |n_a n_b| at most sqrt 3: 2 sqrt(3) m_i w2. Every point of the
 * bodies takes it (contact may reach any of them), which slows the relaxation of a body in contact
 * by at most that of its stiffest penalty. With quasi-static friction each penalty k has a
 * tangential one k_t (I - n n^T) beside it, whose rows sum to at most (1 + sqrt 3) k_t: the pair's
 * k_t / k of that on and off the diagonal. Collective (stable_w2 reduces). */
void pf_contact_stiffness_bounds(const pf_contact *c, const pf_points *pts, double *k) {
  for (int q = 0; q < c->npairs; q++) {
    const pf_contact_pair *p = &c->pair[q];
    const double w2 = p->method->stable_w2(c, p, pts);
    for (int side = 0; side < (p->a == p->b ? 1 : 2); side++) {
      const pf_contact_body *b = &c->body[side ? p->b : p->a];
      for (pf_int i = b->first; i < b->first + b->n && i < pts->n_owned; i++) {
        const double m = pts->m[i] > 0 ? pts->m[i] : b->density * pts->vol[i];
        k[i] += 2 * sqrt(3.0) * m * w2;
        if (c->static_friction && p->friction > 0) k[i] += 2 * (1 + sqrt(3.0)) * m * w2 * p->tangential / p->stiffness;
      }
    }
  }
}

void pf_contact_stats(const pf_contact *c, long *rebuilds, double *seconds) {
  *rebuilds = c->rebuilds;
  *seconds = c->seconds;
}

void pf_contact_counts(const pf_contact *c, int64_t *pairs_tested, int64_t *family_reads) {
  *pairs_tested = c->pairs_tested;
  *family_reads = c->family_reads;
}

void pf_contact_work(const pf_contact *c, int *w) {
  if (!c->built) return;
  for (pf_int e = 0; e < c->nown; e++)
    for (int64_t q = c->cand_off[e]; q < c->cand_off[e + 1]; q++) {
      const int cost = c->pair[c->cand[q].pair].method->candidate_work;
      w[c->local[e]] += cost > 0 ? cost : 1;
    }
}

int pf_contact_self_pair(const pf_contact *c, int b) {
  for (int k = 0; c && k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    if (p->a == b && p->b == b && pf_contact_method_self_rest_lengths(p)) return 1;
  }
  return 0;
}

int pf_contact_npairs(const pf_contact *c) { return c ? c->npairs : 0; }
const char *pf_contact_pair_name(const pf_contact *c, int k) { return c->pair[k].name; }
void pf_contact_pair_force(const pf_contact *c, int k, double f[3]) { memcpy(f, c->pair[k].force, sizeof c->pair[k].force); }

double pf_contact_pair_gap(const pf_contact *c, int k, pf_contact_gap *info) {
  const pf_contact_pair *p = &c->pair[k];
  *info = (pf_contact_gap){p->a, p->b, p->method->signed_gap, p->length};
  return p->gap;
}
void pf_contact_pair_force_set(pf_contact *c, int k, const double f[3]) { memcpy(c->pair[k].force, f, sizeof c->pair[k].force); }
