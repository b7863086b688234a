/* FE <-> PD, `method: nodes` (Tupek et al. 2013, sec. 3.2): the node-to-particle penalty
 * f = k (r_c - d) between every surface node and particle closer than r_c, along the line of
 * centres, the reaction on the node. */
#include "contact/contact_impl.h"

#include <math.h>

/* Particles [e0, e1) against their candidate surface nodes of pair k in [q0, q1). */
static int evaluate_nodes(pf_contact *c, int k, pf_int e0, pf_int e1, int64_t q0, int64_t q1, double dt,
                          pf_contact_eval *w) {
  const pf_contact_pair *p = &c->pair[k];
  for (pf_int e = e0; e < e1; e++) {
    int64_t s0, s1;
    pf_contact_entity_candidates(c, e, q0, q1, &s0, &s1);
    for (int64_t s = s0; s < s1; s++) {
      pf_int j = c->cand[s].j;
      double d[3], r = 0;
      for (int a = 0; a < 3; a++) d[a] = c->y[3 * e + a] - c->y[3 * j + a], r += d[a] * d[a];
      r = sqrt(r);
      if (r >= fmin(p->radius, c->rad[e]) || r == 0) {
        if (c->commit && r > 0 && p->friction > 0) pf_contact_slip_near(c, e, &j, 1, (const double[]){1.0}, r);
        continue;
      }
      double n[3] = {d[0] / r, d[1] / r, d[2] / r}, wt = 1;
      PF_CALL(pf_contact_push(c, k, p->a, e, &j, 1, &wt, r, n, dt, w));
    }
  }
  return 0;
}

const pf_contact_method pf_contact_method_nodes = {
    .id = "nodes",
    .name = "nodes",
    .claims = PF_CONTACT_FE_PD,
    .partners = PF_CONTACT_PARTNER_POINTS,
    .pushes = 1,
    .read = pf_contact_fe_pd_read,
    .evaluate = evaluate_nodes,
    .stable_w2 = pf_contact_fe_pd_stable_w2,
};
