/* Two FE bodies (docs/theory/contact.md sec. 2.4): each body's surface nodes against the other's
 * faces, f = k (r_c - g) with r_c = 0 by default (the surfaces meet) and k = 10 K h of the softer
 * side (K the bulk modulus, h the nodal spacing), in two passes (each body's nodes in turn), a
 * node meeting only the faces that face it (pf_contact_closest_face, pairs.c). `surfaces:` names
 * a side set of each body, in the order of `bodies:`. */
#include "contact/contact_impl.h"

#include <math.h>
#include <string.h>

/* The faces of each mesh node of a side (CSR), for the nodal normals. */
static int side_node_faces(const pf_contact_body *fe, pf_contact_side *sd) {
  pf_int nn = fe->mesh->nnodes;
  PF_MALLOC(sd->node_off, nn + 1);
  PF_MALLOC(sd->node_face, 4 * sd->nface);
  for (pf_int f = 0; f < sd->nface; f++)
    for (int q = 0; q < 4; q++) sd->node_off[sd->face[f].node[q] + 1]++;
  for (pf_int i = 0; i < nn; i++) sd->node_off[i + 1] += sd->node_off[i];
  for (pf_int f = 0; f < sd->nface; f++)
    for (int q = 0; q < 4; q++) sd->node_face[sd->node_off[sd->face[f].node[q]]++] = f;
  for (pf_int i = nn; i > 0; i--) sd->node_off[i] = sd->node_off[i - 1];
  sd->node_off[0] = 0;
  return 0;
}

static int read_surfaces(const pf_deck *d, const pf_node *map, const pf_contact_body *a, const pf_contact_body *b,
                         pf_contact_pair *p) {
  const char *method = pf_contact_method_surfaces.name;
  PF_CALL(pf_deck_string(d, map, "method", &method));
  if (strcmp(method, pf_contact_method_surfaces.name))
    return pf_deck_error(d, pf_node_get(map, "method"), "method",
                         "two finite-element bodies meet surface to surface only (got '%s')", method);
  PF_CALL(pf_contact_refuse_keys(d, map, pf_contact_short_range_keys, "a key of short-range (PD <-> PD) pairs"));
  if (pf_node_get(map, "surface"))
    return pf_deck_error(d, pf_node_get(map, "surface"), "surface",
                         "an FE <-> FE pair names a side set of each body under 'surfaces', in the order of 'bodies'");
  const pf_node *key = pf_node_get(map, "surfaces");
  if (key && pf_node_count(key) != 2)
    return pf_deck_error(d, key, "surfaces", "names two side sets, one of each body, in the order of 'bodies' (got %d)",
                         pf_node_count(key));
  p->nside = 2;
  PF_CALL(pf_contact_side_read(d, key ? pf_node_item(key, 0) : NULL, "surfaces", a, p->a, &p->side[0]));
  PF_CALL(pf_contact_side_read(d, key ? pf_node_item(key, 1) : NULL, "surfaces", b, p->b, &p->side[1]));
  PF_CALL(side_node_faces(a, &p->side[0]));
  PF_CALL(side_node_faces(b, &p->side[1]));
  p->radius = 0;
  p->stiffness = 10 * fmin(a->bulk_modulus * a->spacing, b->bulk_modulus * b->spacing);
  PF_CALL(pf_deck_real(d, map, "radius", &p->radius));
  if (!(p->radius >= 0))
    return pf_deck_error(d, pf_node_get(map, "radius"), "radius", "must not be negative (got %g)", p->radius);
  PF_CALL(pf_deck_positive(d, map, "stiffness", &p->stiffness));
  return 0;
}

/* FE nodes [e0, e1) against the faces of the other body among their candidates of pair k in
 * [q0, q1). */
static int evaluate_surfaces(pf_contact *c, int k, pf_int e0, pf_int e1, int64_t q0, int64_t q1, double dt,
                             pf_contact_eval *w) {
  for (pf_int e = e0; e < e1; e++) {
    int64_t s0, s1;
    pf_contact_entity_candidates(c, e, q0, q1, &s0, &s1);
    if (s0 < s1) PF_CALL(pf_contact_closest_face(c, k, e, s0, s1, dt, w, 1, 0));
  }
  return 0;
}

/* Each node is pushed as a node and as a face's: twice the larger of the two ways round of
 * pf_contact_node_on_face_w2. */
static double stable_w2_surfaces(const pf_contact *c, const pf_contact_pair *p, const pf_points *pts) {
  const pf_contact_body *a = &c->body[p->a], *b = &c->body[p->b];
  double mb = pf_contact_min_mass(b, pts), ma = pf_contact_min_mass(a, pts);
  double w2 = pf_contact_node_on_face_w2(p->stiffness, mb, b->spacing, ma, a->spacing);
  return 2 * fmax(w2, pf_contact_node_on_face_w2(p->stiffness, ma, a->spacing, mb, b->spacing));
}

/* r_c may be 0 (the surfaces meet): the gap's scale is then half the finer spacing. */
static double length_surfaces(const pf_contact *c, const pf_contact_pair *p) {
  return fmax(p->radius, 0.5 * fmin(c->body[p->a].spacing, c->body[p->b].spacing));
}

/* After a deletion: the nodes' faces anew. */
static int side_rebuilt_surfaces(const pf_contact_body *fe, pf_contact_side *sd) {
  PF_FREE(sd->node_off);
  PF_FREE(sd->node_face);
  return side_node_faces(fe, sd);
}

const pf_contact_method pf_contact_method_surfaces = {
    .id = "surfaces",
    .name = "surface",
    .claims = PF_CONTACT_FE_FE,
    .partners = PF_CONTACT_PARTNER_FACES,
    .fe_entities = 1,
    .signed_gap = 1,
    .pushes = 1,
    .candidate_work = 8, /* a face's closest point: about 8 bond evaluations (docs/parallel.md sec. 5) */
    .read = read_surfaces,
    .evaluate = evaluate_surfaces,
    .stable_w2 = stable_w2_surfaces,
    .length = length_surfaces,
    .side_rebuilt = side_rebuilt_surfaces,
};
