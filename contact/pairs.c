/* Contact forces of the candidates of each owned entity: the loop over the entities and their
 * candidates, which hands each entity's candidates of a pair to the pair's method
 * (pf_contact_method evaluate: contact/method_<id>.c), the sums, the FE nodes' shares, and the
 * kernels the methods share (the push off a surface point, the closest face).
 *
 * Friction (all pairs): regularized Coulomb on the tangential part v_t of the relative
 * mid-step velocity, F_t = -min(mu |F_n|, m* |v_t| / dt) v_t / |v_t| with m* the reduced mass of
 * the two sides: never more than stops the sliding in one step (the stick limit of explicit
 * codes), so the regularization adds no stability limit. Its work |F_t| |v_t| dt is dissipated.
 * Under the quasi-static solver a pushed entity's friction is a tangential penalty on its slip
 * relative to the surface point it meets (static_friction below).
 *
 * Each interaction is computed by the owner of its particle (short range: by each end's owner,
 * with the same arithmetic on the pair ordered by global id, so the two ends get exactly
 * opposite forces). An FE node receives its shares from the particles' owners, sorted by
 * (pair, particle id) before they are summed: every point sums its contact forces in an order
 * that does not depend on the partition. */
#include "contact/contact_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(_OPENMP)
#include <omp.h>
#endif

/* A share of an interaction's force for an FE node (7 doubles on the wire). */
typedef struct {
  double body, node, pair, key, f[3];
} node_share;

struct pf_contact_shares {
  node_share *s;
  int64_t n, cap;
};
typedef pf_contact_shares share_list;

static int share_append(share_list *l, const node_share *x) {
  PF_GROW(l->s, l->n, l->cap, 256);
  l->s[l->n++] = *x;
  return 0;
}

static int share_push(share_list *l, int body, pf_gid node, int pair, pf_gid key, const double f[3], double w) {
  const node_share x = {body, (double)node, pair, (double)key, {-w * f[0], -w * f[1], -w * f[2]}};
  return share_append(l, &x);
}

double pf_contact_friction(double mu, double Fn, const double n[3], const double vrel[3], double m, double dt,
                           double ft[3]) {
  ft[0] = ft[1] = ft[2] = 0;
  if (mu == 0 || dt == 0) return 0;
  double vn = vrel[0] * n[0] + vrel[1] * n[1] + vrel[2] * n[2], vt[3];
  for (int a = 0; a < 3; a++) vt[a] = vrel[a] - vn * n[a];
  double s = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
  if (s == 0) return 0;
  double F = fmin(mu * Fn, m * s / dt);
  for (int a = 0; a < 3; a++) ft[a] = -F * vt[a] / s;
  return F * s * dt;
}

/* r = u_e - sum_q wt_q u_q: the displacement of entity e relative to the surface point
 * sum_q wt_q x_q of the view entities nv[nn]. */
static void relative_displacement(const pf_contact *c, pf_int e, const pf_int *nv, int nn, const double *wt,
                                  double r[3]) {
  for (int a = 0; a < 3; a++) r[a] = c->y[3 * e + a] - c->X[3 * e + a];
  for (int q = 0; q < nn; q++)
    for (int a = 0; a < 3; a++) r[a] -= wt[q] * (c->y[3 * nv[q] + a] - c->X[3 * nv[q] + a]);
}

void pf_contact_slip_near(pf_contact *c, pf_int e, const pf_int *nv, int nn, const double *wt, double d) {
  double *near = &c->commit[PF_CONTACT_COMMIT * (size_t)e];
  if (!(d < near[PF_CONTACT_COMMIT_DIST])) return;
  relative_displacement(c, e, nv, nn, wt, &near[PF_CONTACT_COMMIT_NEAR]);
  near[PF_CONTACT_COMMIT_DIST] = d;
}

/* Quasi-static friction of entity e pushed off the surface point sum_q wt_q x_q (the file head of
 * contact/rigid.c and docs/theory/quasi_static_methods.md §8, on the relative displacement): with
 * r = u_e - sum_q wt_q u_q and s_e its committed slip (c->slip; none yet: no elastic part),
 * g_t = (I - n n^T)(r - s_e) and f_t = -k_t g_t while k_t |g_t| <= mu F (stick), else
 * -mu F g_t / |g_t| (slip). Returns the elastic part's energy |f_t|^2 / (2 k_t). While the slips
 * are committed, adds F (r + f_t / k_t) and F to e's sums of new slips and the slip increment's
 * work |f_t| |g_t + f_t / k_t| to e's (pf_contact.commit). */
static double static_friction(pf_contact *c, const pf_contact_pair *p, pf_int e, const pf_int *nv, int nn,
                              const double *wt, double F, const double n[3], double ft[3]) {
  const double *s = &c->slip[4 * (size_t)c->local[e]], kt = p->tangential;
  double r[3], g[3], gn = 0, gt = 0;
  relative_displacement(c, e, nv, nn, wt, r);
  for (int a = 0; a < 3; a++) g[a] = s[3] > 0 ? r[a] - s[a] : 0.0, gn += g[a] * n[a];
  for (int a = 0; a < 3; a++) g[a] -= gn * n[a], gt += g[a] * g[a];
  gt = sqrt(gt);
  const double lim = p->friction * F, scale = kt * gt <= lim ? kt : lim / gt; /* stick | slip */
  for (int a = 0; a < 3; a++) ft[a] = gt > 0 ? -scale * g[a] : 0.0;
  const double T = scale * gt; /* |f_t| */
  if (c->commit) {
    double *next = &c->commit[PF_CONTACT_COMMIT * (size_t)e];
    for (int a = 0; a < 3; a++) next[a] += F * (r[a] + ft[a] / kt);
    next[3] += F;
    next[PF_CONTACT_COMMIT_WORK] += T * fmax(gt - T / kt, 0.0); /* (0 while it sticks, to round-off) */
  }
  return 0.5 * T * T / kt;
}

/* A chunk's sums (contact_impl.h). */
enum {
  SUM_ENERGY = PF_CONTACT_SUM_ENERGY,
  SUM_DISSIPATION = PF_CONTACT_SUM_DISSIPATION,
  SUM_FORCE = PF_CONTACT_SUM_FORCE
};

int pf_contact_push(pf_contact *c, int k, int body, pf_int e, const pf_int *nv, int nn, const double *wt, double g,
                    const double n[3], double dt, pf_contact_eval *w) {
  const pf_contact_pair *p = &c->pair[k];
  double *sums = w->sums;
  double vs[3] = {0, 0, 0}, ms = 0, vrel[3], ft[3], f[3];
  for (int q = 0; q < nn; q++) {
    ms += wt[q] * c->m[nv[q]];
    for (int a = 0; a < 3; a++) vs[a] += wt[q] * c->v[3 * nv[q] + a];
  }
  for (int a = 0; a < 3; a++) vrel[a] = c->v[3 * e + a] - vs[a];
  const double rc = fmin(p->radius, c->rad[e]); /* (a particle made from an element: its own radius) */
  double F = p->stiffness * (rc - g);
  pf_contact_gap_note(sums, c, k, g / p->length);
  if (c->slip && p->friction > 0) sums[SUM_ENERGY] += static_friction(c, p, e, nv, nn, wt, F, n, ft);
  else sums[SUM_DISSIPATION] += pf_contact_friction(p->friction, F, n, vrel, c->m[e] * ms / (c->m[e] + ms), dt, ft);
  const double on_a = body == p->a ? -1.0 : 1.0;
  for (int a = 0; a < 3; a++) {
    f[a] = F * n[a] + ft[a];
    c->force[3 * e + a] += f[a], sums[SUM_FORCE + 3 * k + a] += on_a * f[a];
  }
  sums[SUM_ENERGY] += 0.5 * p->stiffness * (rc - g) * (rc - g);
  for (int q = 0; q < nn; q++)
    if (wt[q] != 0) PF_CALL(share_push(w->shares, body, c->gid[nv[q]], k, c->gid[e], f, wt[q]));
  return 0;
}

/* The normal of a quadrilateral, (x2 - x0) x (x3 - x1) (twice its area for a flat face). */
static void face_normal(const double x[4][3], double n[3]) {
  const double a[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
  const double b[3] = {x[3][0] - x[1][0], x[3][1] - x[1][1], x[3][2] - x[1][2]};
  n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
}

/* The view positions of face nd's nodes on body `body`; 0 when one is not in the view. */
static int face_nodes(const pf_contact *c, const pf_int *view, const pf_int nd[4], double x[4][3], pf_int nv[4]) {
  for (int v = 0; v < 4; v++) {
    nv[v] = view[nd[v]];
    if (nv[v] < 0) return 0;
    memcpy(x[v], &c->y[3 * nv[v]], sizeof x[v]);
  }
  return 1;
}

/* 1 when point y is farther than d from every point of the face of nodes x: farther from the
 * nodes' bounding box, which holds the face (pf_contact_face_closest's closest point is a convex
 * combination of the nodes), by more than round-off (1e-9 of d and of the box's size). A face
 * beyond the closest one found so far cannot be chosen (surface: strictly closer wins), so it is
 * passed over without its closest point. */
static int beyond(const double x[4][3], const double y[3], double d) {
  double lb2 = 0, size = 0;
  for (int a = 0; a < 3; a++) {
    double lo = x[0][a], hi = x[0][a];
    for (int v = 1; v < 4; v++) lo = x[v][a] < lo ? x[v][a] : lo, hi = x[v][a] > hi ? x[v][a] : hi;
    const double out = y[a] < lo ? lo - y[a] : y[a] > hi ? y[a] - hi : 0.0;
    lb2 += out * out, size = hi - lo > size ? hi - lo : size;
  }
  const double lim = d + 1e-9 * (d + size);
  return lb2 > lim * lim;
}

/* 1 when point y lies over the face of normal nf (face_normal) whose closest point to y is cp:
 * the offset y - cp along the face is below a tenth of the face's size (a point past the face's
 * edge is beside the face, not over it, however far it is behind the face's plane). */
static int projects_inside(const double nf[3], const double cp[3], const double y[3]) {
  const double a2 = nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]; /* (2 area)^2 */
  double d[3] = {y[0] - cp[0], y[1] - cp[1], y[2] - cp[2]};
  const double dn = (d[0] * nf[0] + d[1] * nf[1] + d[2] * nf[2]) / a2;
  for (int a = 0; a < 3; a++) d[a] -= dn * nf[a];
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= 0.01 * 0.5 * sqrt(a2);
}

/* The outward normal of FE node e on its own side of a pair of FE bodies: the sum of its
 * faces' normals (area-weighted). */
static void node_normal(const pf_contact *c, const pf_contact_side *own, pf_int e, double n[3]) {
  const pf_int node = (pf_int)(c->gid[e] - c->body[own->body].gid0), *view = c->node_view[own->body];
  n[0] = n[1] = n[2] = 0;
  for (pf_int q = own->node_off[node]; q < own->node_off[node + 1]; q++) {
    double x[4][3], nf[3];
    pf_int nv[4];
    if (!face_nodes(c, view, own->face[own->node_face[q]].node, x, nv)) continue;
    face_normal((const double(*)[3])x, nf);
    for (int a = 0; a < 3; a++) n[a] += nf[a];
  }
}

/* The penetration owned particle e keeps without force against the surface of a body that
 * deletes elements (docs/theory/contact.md sec. 2.5), given its gap g to the closest face
 * (INFINITY: none in reach) and its radius rc; `fresh` when that face was uncovered at this
 * evaluation. Its offset o (the point field "contact_offset") is set to its penetration
 * max(0, rc - g) when the face was uncovered under it, when the particle is new (o < 0:
 * fem/particles.c), or when it is behind the face (g < 0) without having been in reach of the
 * surface at the previous evaluation (a step moves a point by far less than rc: the surface came
 * to it, by a deletion or by a change of the face that holds it); otherwise it only shrinks to
 * the penetration, where the penalty k ((rc - g) - o) is zero: it never sets energy free.
 * The point field "contact_reach" keeps (previous, this) evaluation's "in reach". Returns o,
 * which the gap takes on. */
static double held(pf_contact *c, pf_int e, double g, double rc, int fresh) {
  double *o = &c->offset[c->local[e]], *reach = &c->reach[2 * (size_t)c->local[e]];
  const double pen = g < INFINITY ? fmax(0.0, rc - g) : 0.0;
  if (*o < 0 || fresh || (reach[0] == 0 && g < 0) || pen < *o) *o = pen;
  reach[1] = pen > 0;
  return *o;
}

/* 1 when a face at gap g is closer than the closest so far (|gap| best, gap bg; INFINITY: none).
 * Two faces at the same distance (to round-off) that disagree on the side: the closest point is
 * an edge or corner they share, which is convex (at a concave one a point whose closest point is
 * the edge is behind both faces), so the point is outside: the face that sees it in front wins,
 * as the sign of the edge's pseudonormal says (Baerentzen & Aanaes 2005). A fold of the surface
 * (a sheet one crushed element thick, left by deletions) gives such ties (docs/theory/contact.md
 * sec. 2). Otherwise the nearer; at equal distance the first. */
static int closer(double g, double best, double bg) {
  const int split = best < INFINITY && (g < 0) != (bg < 0) && fabs(fabs(g) - best) <= 1e-9 * best;
  return split ? g >= 0 : fabs(g) < best;
}

/* Entity e (a particle, or an FE node of a pair of FE bodies: fe_node) against the closest face
 * among its candidates [s, t) of pair k, on the side its body faces. An FE node meets only the
 * faces that face it, whose normal opposes its own (at an edge of the other body the side faces
 * lie in the plane of the node's approach and would hide the face it hits). A face counts an entity behind
 * its plane as inside only when the entity lies over it: one beside a convex edge is behind the
 * plane of the face but outside the body (docs/theory/contact.md sec. 2, 2.4). */
int pf_contact_closest_face(pf_contact *c, int k, pf_int e, int64_t s, int64_t t, double dt, pf_contact_eval *ev,
                            int fe_node, int may_uncover) {
  const pf_contact_pair *p = &c->pair[k];
  const pf_contact_side *sd = pf_contact_facing(p, c->vbody[e]);
  const pf_int *view = c->node_view[sd->body];
  double best = INFINITY, bg = 0, bn[3] = {0, 0, 0}, bw[4] = {0, 0, 0, 0}, ne[3] = {0, 0, 0};
  pf_int bv[4] = {0, 0, 0, 0}, bf = -1;
  double far = INFINITY, far_g = 0; /* the closest face beyond the reach: |g|, g (health only) */
  if (fe_node) node_normal(c, sd == &p->side[0] ? &p->side[1] : &p->side[0], e, ne);
  const pf_contact_body *fb = &c->body[sd->body];
  long ndead = 0; /* (the faces' body deletes elements: its erosion flags exist) */
  const int uncovers = may_uncover && fb->eroded && fb->eroded(fb->eroded_ctx, &ndead) != NULL;
  for (int64_t q = s; q < t; q++) {
    double x[4][3], cp[3], w[4], n[3], nf[3];
    pf_int nv[4];
    if (!face_nodes(c, view, sd->face[c->cand[q].j].node, x, nv))
      return PF_ERR_RUN; /* cannot happen: candidates have every node in the view */
    if (best < INFINITY && beyond((const double(*)[3])x, &c->y[3 * e], best)) continue;
    face_normal((const double(*)[3])x, nf);
    const double facing = nf[0] * ne[0] + nf[1] * ne[1] + nf[2] * ne[2];
    if (facing > 0 || (fe_node && facing == 0)) continue;
    double g = pf_contact_face_closest((const double(*)[3])x, &c->y[3 * e], cp, w, n);
    if (g < 0 && !projects_inside(nf, cp, &c->y[3 * e])) continue;
    /* a face of a body that deletes elements: a particle deeper behind it than its body's spacing
     * was not pushed through it but uncovered by a deletion (the face was inside the body until
     * then); it is not pulled back through (docs/theory/contact.md sec. 2.5) */
    if (uncovers && g < -c->body[c->vbody[e]].spacing) continue;
    /* a face farther than the pair's length (r_c; half the finer spacing for FE <-> FE), in front
     * or behind, is out of reach: the search finds every face within it whatever the skin, and
     * only some beyond it, so a face there would make the forces depend on the skin. The closest
     * of those (the same tie rule as below) goes to the run's health alone, when no face is in
     * reach and the entity is behind it */
    if (fabs(g) > p->length) {
      if (closer(g, far, far_g)) far = fabs(g), far_g = g;
      continue;
    }
    if (closer(g, best, bg)) {
      best = fabs(g), bg = g, bf = c->cand[q].j;
      memcpy(bn, n, sizeof bn), memcpy(bw, w, sizeof bw), memcpy(bv, nv, sizeof bv);
    }
  }
  if (best == INFINITY && far_g < 0 && !uncovers) /* (inside the other body, out of reach) */
    pf_contact_gap_note(ev->sums, c, k, far_g / p->length);
  if (uncovers && c->offset)
    bg += held(c, e, best < INFINITY ? bg : INFINITY, fmin(p->radius, c->rad[e]), sd->fresh && bf >= 0 && sd->fresh[bf]);
  if (best == INFINITY || bg >= fmin(p->radius, c->rad[e])) {
    if (c->commit && best < INFINITY && p->friction > 0) pf_contact_slip_near(c, e, bv, 4, bw, best);
    return 0;
  }
  return pf_contact_push(c, k, sd->body, e, bv, 4, bw, bg, bn, dt, ev);
}

/* 1 when entity e's candidates are all of pair k (or it has none). */
static int only_pair(const pf_contact *c, pf_int e, int k) {
  const int64_t q0 = c->cand_off[e], q1 = c->cand_off[e + 1];
  return q0 == q1 || (c->cand[q0].pair == k && c->cand[q1 - 1].pair == k); /* (sorted by pair) */
}

/* The interactions of the owned entities [e0, e1): their forces (cleared first), the nodes'
 * shares into l, the energy, dissipation and pairs' forces into sums. An entity's candidates are
 * sorted by pair: each pair's run goes to the pair's method, and a run of entities whose
 * candidates are all of one pair goes to it in one call. Entity by entity, pair by pair, as the
 * calls come: the order of the sums is that of the entities' candidates. */
static int particle_range(pf_contact *c, pf_int e0, pf_int e1, double dt, share_list *l, double *sums) {
  pf_contact_eval w = {sums, l, 0, 0};
  memset(&c->force[3 * e0], 0, sizeof(double) * 3 * (size_t)(e1 - e0));
  for (pf_int e = e0; e < e1;) {
    if (c->cand_off[e] == c->cand_off[e + 1]) {
      e++;
      continue;
    }
    const int k0 = c->cand[c->cand_off[e]].pair;
    if (only_pair(c, e, k0)) {
      pf_int f = e + 1;
      while (f < e1 && only_pair(c, f, k0)) f++;
      PF_CALL(c->pair[k0].method->evaluate(c, k0, e, f, c->cand_off[e], c->cand_off[f], dt, &w));
      e = f;
      continue;
    }
    for (int64_t q = c->cand_off[e]; q < c->cand_off[e + 1];) {
      int k = c->cand[q].pair;
      int64_t t = q;
      while (t < c->cand_off[e + 1] && c->cand[t].pair == k) t++;
      PF_CALL(c->pair[k].method->evaluate(c, k, e, e + 1, q, t, dt, &w));
      q = t;
    }
    e++;
  }
  const int64_t tested = w.tested, reads = w.reads;
#if defined(_OPENMP)
#pragma omp atomic
#endif
  c->pairs_tested += tested;
#if defined(_OPENMP)
#pragma omp atomic
#endif
  c->family_reads += reads;
  return 0;
}

/* Owner computes: a particle's interactions write only its own force, so OpenMP threads take
 * fixed chunks of particles, each with its own share list (the shares are sorted before they
 * are summed) and its own sums, added in chunk order: the bits do not depend on the thread
 * count. Sets the pairs' forces; adds to *U and *diss. */
static int particle_forces(pf_contact *c, double dt, share_list *l, double *U, double *diss) {
  enum { CHUNK = 2048 };
  const int ns = SUM_FORCE + 4 * c->npairs;
  const int64_t nchunk = (c->nown + CHUNK - 1) / CHUNK;
  int nthreads = 1, ierr = 0;
#if defined(_OPENMP)
  nthreads = omp_get_max_threads();
#endif
  double *sums = calloc((size_t)(nchunk * ns + 1), sizeof *sums);
  share_list *tl = calloc((size_t)nthreads, sizeof *tl);
  if (!sums || !tl) free(sums), free(tl);
  PF_CHECK(sums && tl, PF_ERR_MEMORY, "out of memory for the contact sums of %lld chunks", (long long)nchunk);
  for (int64_t q = 0; q < nchunk; q++)
    for (int k = 0; k < c->npairs; k++) sums[q * ns + SUM_FORCE + 3 * c->npairs + k] = INFINITY;
#pragma omp parallel for schedule(dynamic, 1) reduction(max : ierr)
  for (int64_t q = 0; q < nchunk; q++) {
    int t = 0;
#if defined(_OPENMP)
    t = omp_get_thread_num();
#endif
    const pf_int e0 = (pf_int)(q * CHUNK), e1 = (pf_int)(q + 1 < nchunk ? (q + 1) * CHUNK : c->nown);
    const int err = particle_range(c, e0, e1, dt, &tl[t], &sums[q * ns]);
    ierr = err > ierr ? err : ierr; /* (the reduction's private copy starts at INT_MIN) */
  }
  for (int k = 0; k < c->npairs; k++) memset(c->pair[k].force, 0, sizeof c->pair[k].force), c->pair[k].gap = INFINITY;
  for (int64_t q = 0; !ierr && q < nchunk; q++) {
    const double *s = &sums[q * ns];
    *U += s[SUM_ENERGY], *diss += s[SUM_DISSIPATION];
    for (int k = 0; k < c->npairs; k++)
      for (int a = 0; a < 3; a++) c->pair[k].force[a] += s[SUM_FORCE + 3 * k + a];
    for (int k = 0; k < c->npairs; k++) c->pair[k].gap = fmin(c->pair[k].gap, s[SUM_FORCE + 3 * c->npairs + k]);
  }
  for (int t = 0; !ierr && t < nthreads; t++) /* one list: each thread's in turn */
    for (int64_t q = 0; q < tl[t].n && !ierr; q++) ierr = share_append(l, &tl[t].s[q]);
  for (int t = 0; t < nthreads; t++) free(tl[t].s);
  free(tl), free(sums);
  return ierr;
}

/* Send the shares of nodes other ranks own to them; keep ours. Collective. */
static int route_shares(pf_contact *c, share_list *l, share_list *mine) {
  int R = c->nranks, *cnt, *sc, *sd, *rc, *rd;
  PF_MALLOC(cnt, 5 * R);
  sc = cnt + R, sd = sc + R, rc = sd + R, rd = rc + R;
  int *dest;
  PF_MALLOC(dest, l->n);
  for (int64_t q = 0; q < l->n; q++) {
    pf_int j = c->node_view[(int)l->s[q].body][(pf_int)((pf_gid)l->s[q].node - c->body[(int)l->s[q].body].gid0)];
    dest[q] = c->rank[j];
    cnt[dest[q]]++;
  }
  int64_t total = 0;
  for (int r = 0; r < R; r++) sd[r] = (int)(7 * total), sc[r] = 7 * cnt[r], total += cnt[r];
  node_share *buf;
  PF_MALLOC(buf, total);
  int *at;
  PF_MALLOC(at, R);
  for (int r = 0; r < R; r++) at[r] = sd[r] / 7;
  for (int64_t q = 0; q < l->n; q++) buf[at[dest[q]]++] = l->s[q];
  free(at), free(dest);
  MPI_Alltoall(sc, 1, MPI_INT, rc, 1, MPI_INT, MPI_COMM_WORLD);
  int64_t nrecv = 0;
  for (int r = 0; r < R; r++) rd[r] = (int)nrecv, nrecv += rc[r];
  mine->n = nrecv / 7;
  mine->cap = mine->n;
  mine->s = malloc(sizeof *mine->s * (size_t)(mine->n + 1));
  int ierr = mine->s ? 0 : PF_ERR_MEMORY;
  if (!ierr)
    ierr = MPI_Alltoallv(buf, sc, sd, MPI_DOUBLE, mine->s, rc, rd, MPI_DOUBLE, MPI_COMM_WORLD) != MPI_SUCCESS;
  free(buf), free(cnt);
  PF_CHECK(!ierr, PF_ERR_LIB, "the exchange of contact node forces failed");
  return 0;
}

static int share_cmp(const void *a, const void *b) {
  const node_share *x = a, *y = b;
  if (x->body != y->body) return x->body < y->body ? -1 : 1;
  if (x->node != y->node) return x->node < y->node ? -1 : 1;
  if (x->pair != y->pair) return x->pair < y->pair ? -1 : 1;
  return x->key < y->key ? -1 : x->key > y->key;
}

/* Sum each owned node's shares in (pair, particle) order. */
static void sum_shares(pf_contact *c, share_list *mine) {
  if (mine->n > 1) qsort(mine->s, (size_t)mine->n, sizeof *mine->s, share_cmp); /* (s is NULL when empty) */
  for (int64_t q = 0; q < mine->n; q++) {
    const node_share *s = &mine->s[q];
    pf_int j = c->node_view[(int)s->body][(pf_int)((pf_gid)s->node - c->body[(int)s->body].gid0)];
    for (int a = 0; a < 3; a++) c->force[3 * j + a] += s->f[a];
  }
}

int pf_contact_pairs_evaluate(pf_contact *c, double dt, double *energy, double *dissipation) {
  share_list l = {NULL, 0, 0}, mine = {NULL, 0, 0};
  int ierr = particle_forces(c, dt, &l, energy, dissipation);
  if (!ierr && c->has_fe) ierr = route_shares(c, &l, &mine);
  if (!ierr) sum_shares(c, &mine);
  free(l.s), free(mine.s);
  return ierr;
}
