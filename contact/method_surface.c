/* FE <-> PD, `method: surface` (the default; Tupek et al. 2013, sec. 3.2, with the particle-to-
 * face check): the gap g of a particle to the closest point of the FE surface - a node, an edge
 * or a face, which stops particles between the nodes of a coarse mesh - and a push
 * f = k (r_c - g) along the surface normal, the reaction going to the face's nodes with the
 * weights of the closest point (pf_contact_closest_face, pairs.c; docs/theory/contact.md sec. 2).
 * A particle behind a face that a deletion uncovered keeps its penetration without force (the
 * offsets, sec. 2.5). */
#include "contact/contact_impl.h"

static int evaluate_surface(pf_contact *c, int k, pf_int e0, pf_int e1, int64_t q0, int64_t q1, double dt,
                            pf_contact_eval *w) {
  for (pf_int e = e0; e < e1; e++) {
    int64_t s0, s1;
    pf_contact_entity_candidates(c, e, q0, q1, &s0, &s1);
    if (s0 < s1) PF_CALL(pf_contact_closest_face(c, k, e, s0, s1, dt, w, 0, 1));
  }
  return 0;
}

const pf_contact_method pf_contact_method_surface = {
    .id = "surface",
    .name = "surface",
    .claims = PF_CONTACT_FE_PD,
    .partners = PF_CONTACT_PARTNER_FACES,
    .signed_gap = 1,
    .holds_offsets = 1,
    .pushes = 1,
    .candidate_work = 8, /* a face's closest point: about 8 bond evaluations (docs/parallel.md sec. 5) */
    .read = pf_contact_fe_pd_read,
    .evaluate = evaluate_surface,
    .stable_w2 = pf_contact_fe_pd_stable_w2,
};
