/* Short-range forces between PD particles (PD <-> PD, and a PD body with itself): Littlewood
 * (2014, "Contact in peridynamic simulations"; Silling & Askari 2005) f = C (r_c - r) V_i V_j for
 * r < r_c, along the line of centres, with C = 18 k_s / (pi delta^5): Peridigm's short-range
 * force c = 9 k_s / (pi delta^4) per unit volume per unit (r_c - r)/delta, which Peridigm applies
 * from both ends of each pair, so one pair carries twice it. By default bonded points do not
 * interact (their bond carries the load); `all_points: true` acts on every pair within r_c, as
 * Peridigm does. Two points of one body use min(r_c, 0.9 |x_i - x_j|, the rest length of their
 * broken bond) (pair_radius, docs/theory/contact.md sec. 1.1).
 *
 * Each end's owner computes the pair, with the same arithmetic on the pair ordered by global id,
 * so the two ends get exactly opposite forces. */
#include "contact/contact_impl.h"

#include <math.h>

const char *const pf_contact_short_range_keys[] = {"spring_constant", "horizon", "all_points", NULL};

static int read_short_range(const pf_deck *d, const pf_node *map, const pf_contact_body *a, const pf_contact_body *b,
                            pf_contact_pair *p) {
  PF_CALL(pf_contact_refuse_keys(d, map, (const char *const[]){"method", "surface", "surfaces", NULL},
                                 "a key of pairs with an FE body"));
  double ks = fmax(a->bulk_modulus, b->bulk_modulus), delta = fmax(a->horizon, b->horizon);
  PF_CALL(pf_deck_positive(d, map, "spring_constant", &ks));
  PF_CALL(pf_deck_positive(d, map, "horizon", &delta));
  p->stiffness = 18.0 * ks / (PF_PI * pow(delta, 5));
  p->radius = 0.9 * fmax(a->spacing, b->spacing);
  PF_CALL(pf_deck_positive(d, map, "stiffness", &p->stiffness));
  PF_CALL(pf_deck_positive(d, map, "radius", &p->radius));
  PF_CALL(pf_deck_bool(d, map, "all_points", &p->all_points));
  return 0;
}

/* The contact radius of view entities i and j of short-range pair p, the bond between them k
 * (-1: none; k indexes the family of e, the owned one of the two). With a particle made from an
 * element (fem/particles.c) at most its own radius c->rad (the distance from its centre to its
 * element's nearest face when it was made) plus the other's (its own radius, or half its body's
 * spacing), so that a new particle starts without force against its neighbours. Between bodies r_c. Within one
 * body at most 0.9 of their reference distance (Parks et al. 2008, PDLAMMPS; LAMMPS pair peri
 * takes d_ij = min(0.9 |x0_i - x0_j|, 1.35 l_c), here r_c for 1.35 l_c), so that no two points
 * of a body touch in the reference configuration whatever the shape of its cells; and for a
 * broken bond at most its rest length, its length when it broke, so that a bond breaking in
 * compression sets no contact force free (energy from nothing: docs/theory/contact.md sec. 1.1). */
static double pair_radius(const pf_contact *c, const pf_contact_pair *p, pf_int i, pf_int j, int64_t k) {
  if (c->rad[i] < INFINITY || c->rad[j] < INFINITY) /* a particle made from an element: its own radius */
    return fmin(p->radius, (c->rad[i] < INFINITY ? c->rad[i] : 0.5 * c->body[c->vbody[i]].spacing) +
                               (c->rad[j] < INFINITY ? c->rad[j] : 0.5 * c->body[c->vbody[j]].spacing));
  if (c->vbody[i] != c->vbody[j]) return p->radius;
  const double *Xi = &c->X[3 * i], *Xj = &c->X[3 * j];
  const double d0 = Xi[0] - Xj[0], d1 = Xi[1] - Xj[1], d2 = Xi[2] - Xj[2];
  double rc = fmin(p->radius, 0.9 * sqrt(d0 * d0 + d1 * d1 + d2 * d2));
  if (k >= 0 && !p->all_points) {
    const float rest = c->body[c->vbody[i]].fam->rest[k];
    if (rest > 0) rc = fmin(rc, (double)rest);
  }
  return rc;
}

/* Short range between owned particle e and view entity j of pair k, joined by the (broken) bond
 * b of e's family (-1: none): the force on e. The pair is evaluated ordered by global id
 * (lo, hi), f on lo = C (r_c - r) V_lo V_hi (y_lo - y_hi) / r, r_c the pair's radius
 * (pair_radius). */
static void short_range(pf_contact *c, int k, pf_int e, pf_int j, int64_t b, double dt, double *sums) {
  const pf_contact_pair *p = &c->pair[k];
  int flip = c->gid[e] > c->gid[j];
  pf_int lo = flip ? j : e, hi = flip ? e : j;
  double d[3], r = 0;
  for (int a = 0; a < 3; a++) d[a] = c->y[3 * lo + a] - c->y[3 * hi + a], r += d[a] * d[a];
  r = sqrt(r);
  const double rc = pair_radius(c, p, lo, hi, b);
  if (r >= rc || r == 0) return;
  pf_contact_gap_note(sums, c, k, r / rc);
  double n[3] = {d[0] / r, d[1] / r, d[2] / r}, vrel[3], ft[3];
  double F = p->stiffness * (rc - r) * (c->vol[lo] * c->vol[hi]);
  for (int a = 0; a < 3; a++) vrel[a] = c->v[3 * lo + a] - c->v[3 * hi + a];
  double mr = c->m[lo] * c->m[hi] / (c->m[lo] + c->m[hi]);
  sums[PF_CONTACT_SUM_DISSIPATION] += 0.5 * pf_contact_friction(p->friction, F, n, vrel, mr, dt, ft); /* half: each end counts it */
  const double sign = flip ? -1.0 : 1.0;
  for (int a = 0; a < 3; a++) {
    double fa = sign * (F * n[a] + ft[a]);
    c->force[3 * e + a] += fa;
    if (c->vbody[e] == p->a && p->a != p->b) sums[PF_CONTACT_SUM_FORCE + 3 * k + a] += fa;
  }
  sums[PF_CONTACT_SUM_ENERGY] += 0.5 * 0.5 * p->stiffness * (c->vol[lo] * c->vol[hi]) * (rc - r) * (rc - r);
}

/* Owned particles [e0, e1) against their candidates of pair k in [q0, q1): most are out of
 * reach, which is tested first; a bonded pair (the bond resolved at the build) interacts once its
 * bond broke. */
static int evaluate_short_range(pf_contact *c, int k, pf_int e0, pf_int e1, int64_t q0, int64_t q1, double dt,
                                pf_contact_eval *w) {
  const pf_contact_pair *p = &c->pair[k];
  const double r2 = p->radius * p->radius;
  int64_t reads = 0;
  w->tested += q1 - q0;
  for (pf_int e = e0; e < e1; e++) {
    int64_t s0, s1;
    pf_contact_entity_candidates(c, e, q0, q1, &s0, &s1);
    const double ye[3] = {c->y[3 * e], c->y[3 * e + 1], c->y[3 * e + 2]};
    const pf_family *fam = c->body[c->vbody[e]].fam;
    const uint8_t *broken = fam ? fam->broken : NULL; /* (a body without bonds: never bonded) */
    for (int64_t s = s0; s < s1; s++) {
      const pf_int j = c->cand[s].j;
      const double *yj = &c->y[3 * j];
      const double d0 = ye[0] - yj[0], d1 = ye[1] - yj[1], d2 = ye[2] - yj[2];
      if (d0 * d0 + d1 * d1 + d2 * d2 >= r2) continue;
      const int64_t b = c->cand[s].bond; /* (resolved at the build) */
      reads += b >= 0 && !p->all_points;
      if (p->all_points || b < 0 || broken[b]) short_range(c, k, e, j, b, dt, w->sums);
    }
  }
  w->reads += reads;
  return 0;
}

/* A particle inside the spheres of radius r_c + h/2 of partners filling it: omega^2 =
 * C (4/3) pi (r_c + h/2)^3 / rho_min. */
static double stable_w2_short_range(const pf_contact *c, const pf_contact_pair *p, const pf_points *pts) {
  (void)pts;
  const pf_contact_body *a = &c->body[p->a], *b = &c->body[p->b];
  double h = fmax(a->spacing, b->spacing), rho = fmin(a->density, b->density);
  return p->stiffness * 4.0 / 3.0 * PF_PI * pow(p->radius + 0.5 * h, 3) / rho;
}

/* Within one body, bonded points are left out unless all_points: a broken bond's rest length
 * bounds its points' radius (pair_radius). */
static int self_rest_lengths_short_range(const pf_contact_pair *p) { return !p->all_points; }

const pf_contact_method pf_contact_method_short_range = {
    .id = "short_range",
    .name = NULL, /* the one method of PD <-> PD pairs: no `method:` key */
    .claims = PF_CONTACT_PD_PD,
    .partners = PF_CONTACT_PARTNER_POINTS,
    .bonds = 1,
    .read = read_short_range,
    .evaluate = evaluate_short_range,
    .stable_w2 = stable_w2_short_range,
    .self_rest_lengths = self_rest_lengths_short_range,
};
