/* Bonds that soften (law softening, pd/damage_softening.c; docs/theory/bond_failure.md §8): the
 * bonds' state before each force evaluation, and the PMB force. A bond of limits s0 < s1 (s1 the
 * smaller of its ends' field "critical_stretch", s0 = s1 / r) and largest stretch s_max has the
 * damage
 *   d = 0 (s_max <= s0),   1 - s0 (s1 - s_max) / (s_max (s1 - s0)) (s0 < s_max < s1),   1 (s_max >= s1),
 * so that (1 - d) s_max is the linear envelope s0 (s1 - s_max) / (s1 - s0) and the bond unloads
 * along its secant. The energy dissipated while s_max grows from s_a to s_b is the integral of
 * Y = dW/d(1 - d) over d along the envelope, dd/ds = s0 s1 / ((s1 - s0) s^2), over the part of
 * [s_a, s_b] within [s0, s1]. Point i's energy W_i gives, per V_i, bond k's Y per omega V_j:
 *   PMB (sum_j (1/4) c omega s^2 |xi| V_j):  c |xi| s^2 / 4, so that a pair dissipates
 *     c omega |xi| Phi(s_max) V_i V_j, Phi(s) = s0 s1 (s - s0) / (2 (s1 - s0)): (1/2) s0 s1 =
 *     (1/2) s_c^2 at s1, the brittle bond's energy;
 *   LPS (Silling et al. 2007, eq. 92, each bond weighted by 1 - d; a = 15 G / m, m^lost the weighted
 *     volume failed or softened away): a |xi|^2 (s - theta / 3)^2 / 2 + 3 theta (K - a m^lost / 9)
 *     |xi|^2 s / m, with the dilatation theta taken as linear in the bond's stretch from where the
 *     damage was last to now;
 * integrated by 4-point Gauss-Legendre (exact for PMB, whose integrand is constant). Dynamics
 * updates and books at every evaluation; the quasi-static solver at its damage checks, its
 * relaxations after a check taking each evaluation's damage from the pass's start (soft_qs). */
#include "pd/pd_impl.h"

#include <string.h>

enum { SMAX = 0, DAMAGE = 1 };

static double soft_damage(double sm, double s0, double s1) {
  if (!(sm > s0)) return 0.0;
  if (sm >= s1) return 1.0;
  return 1.0 - s0 * (s1 - sm) / (sm * (s1 - s0));
}

/* Bond k of point i, intact: its |xi|, extension, stretch, omega V_j, limits, and its damage from
 * the state from[] (s_max, d) and after this stretch (*breaks: it fails now). */
typedef struct {
  double r0, ext, s, wv, s0, s1, s_max, d_old, d_new;
  int breaks;
} soft_bond;

static int bond_at(const pf_pd_body *b, const pf_points *pts, pf_int i, int64_t k, const double *from, soft_bond *q) {
  const pf_family *fam = &b->fam;
  if (fam->broken[k]) return 0;
  const pf_int j = fam->neighbor[k];
  double r, e[3];
  pf_pd_bond_lengths(pts->X, pts->y, i, j, &q->r0, &r, e);
  q->ext = r - q->r0, q->s = q->ext / q->r0;
  q->wv = pf_pd_omega(&b->influence, q->r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
  const double *s1 = b->frozen.on ? b->frozen.s0 : b->s0; /* (the law's, also while frozen) */
  q->s1 = fmin(s1[i], s1[j]), q->s0 = q->s1 / b->soft_ratio;
  q->s_max = from[2 * k + SMAX], q->d_old = q->d_new = from[2 * k + DAMAGE], q->breaks = 0;
  if (!(q->s > q->s_max) || !isfinite(q->s1)) return 1;
  q->s_max = q->s, q->d_new = soft_damage(q->s, q->s0, q->s1);
  q->breaks = q->d_new >= 1;
  return 1;
}

/* Point i's part of Y = dW/dw at a bond of |xi| r0 and stretch s, per omega V_j: PMB c |xi| s^2 / 4;
 * LPS a |xi|^2 (s - theta / 3)^2 / 2 + 3 P |xi|^2 s / m, P = theta (K - a m^lost / 9), theta varying
 * linearly from theta_a (where the damage was last) to theta_b (now) as the bond's stretch goes
 * from its s_max to its stretch now. */
typedef struct {
  double c;               /* PMB: the micromodulus (0: LPS) */
  double a, kp, m;        /* LPS: 15 G / m, K - a m^lost / 9, m */
  double th_a, th_b;      /* LPS: the dilatation where the damage was last, and now */
} soft_point;

static double Y_at(const soft_point *P, const soft_bond *q, double sa, double s) {
  if (P->c > 0) return 0.25 * P->c * q->r0 * s * s;
  const double th = P->th_a + (P->th_b - P->th_a) * (s - sa) / (q->s - sa), r2 = q->r0 * q->r0;
  return 0.5 * P->a * r2 * (s - th / 3) * (s - th / 3) + 3 * th * P->kp * r2 * s / P->m;
}

/* The integral of Y dd along the envelope (dd/ds = s0 s1 / ((s1 - s0) s^2)) from s_max sa to the
 * bond's stretch now, over the part within [s0, s1], by 4-point Gauss-Legendre (exact for PMB,
 * whose integrand is constant), per omega V_j. */
static double envelope_integral(const soft_point *P, const soft_bond *q, double sa) {
  static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double lo = fmax(sa, q->s0), hi = fmin(q->s, q->s1);
  if (!(hi > lo)) return 0.0;
  double sum = 0;
  for (int g = 0; g < 4; g++) {
    const double s = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x[g];
    sum += w[g] * Y_at(P, q, sa, s) / (s * s);
  }
  return q->s0 * q->s1 / (q->s1 - q->s0) * 0.5 * (hi - lo) * sum;
}

/* LPS: point i's dilatation now and K - a m^lost / 9, with the bonds' new damage. */
static void lps_state(const pf_pd_body *b, const pf_points *pts, pf_int i, const double *from, soft_point *P) {
  const pf_family *fam = &b->fam;
  double sum = 0, lost = b->lost_volume[i];
  soft_bond q;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    if (!bond_at(b, pts, i, k, from, &q)) continue;
    const double w = q.breaks ? 0.0 : 1.0 - q.d_new;
    sum += w * q.wv * q.r0 * q.ext;
    lost += (1 - w) * q.wv * q.r0 * q.r0;
  }
  P->th_b = 3 * sum / P->m;
  P->kp = pf_pd_K(b, i) - P->a * lost / 9;
}

/* The energy dissipated (J) at point i as its bonds' damage grows from the state from[], the
 * point's dilatation there theta_a. */
static double dissipation(const pf_pd_body *b, const pf_points *pts, pf_int i, double c, const double *m,
                          const double *from, double theta_a) {
  const pf_family *fam = &b->fam;
  soft_point P = {c, 0, 0, 1, 0, 0};
  if (m) {
    P.c = 0, P.m = m[i], P.a = 15 * pf_pd_G(b, i) / m[i], P.th_a = theta_a;
    lps_state(b, pts, i, from, &P);
  }
  soft_bond q;
  double d = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
    if (bond_at(b, pts, i, k, from, &q) && q.d_new > q.d_old)
      d += q.wv * envelope_integral(&P, &q, from[2 * k + SMAX]);
  return pts->vol[i] * d;
}

/* A relaxation after a check: each bond's damage from the pass's start and its stretch now, for
 * the weights of this evaluation alone (no bond fails, nothing is booked). */
static void trial(pf_pd_body *b, const pf_points *pts) {
  pf_family *fam = &b->fam;
  soft_bond q;
  for (pf_int i = b->first; i < b->first + b->n; i++)
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      if (bond_at(b, pts, i, k, b->soft_qs.base, &q))
        fam->state[2 * k + SMAX] = q.s_max, fam->state[2 * k + DAMAGE] = q.d_new;
}

int pf_pd_softening_update(pf_pd_body *b, const pf_points *pts, double c, const double *m, const double *theta) {
  pf_family *fam = &b->fam;
  const int qs = b->soft_qs.pass > 0;
  if (qs && b->soft_qs.theta_stale && theta) /* (the pass's start: the last evaluation's) */
    memcpy(b->soft_qs.theta, &theta[b->first], sizeof(double) * (size_t)b->n), b->soft_qs.theta_stale = 0;
  if (b->frozen.on) { /* (a quasi-static relaxation: the checks grow the damage) */
    if (b->soft_qs.pass == 2) trial(b, pts);
    return 0;
  }
  const double *from = qs ? b->soft_qs.base : fam->state; /* (dynamics: from the last step) */
  soft_bond q;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
    int grows = 0;
    for (int64_t k = k0; k < k1 && !grows; k++) grows = bond_at(b, pts, i, k, from, &q) && q.d_new > q.d_old;
    const double theta_a = !m ? 0.0 : qs ? b->soft_qs.theta[i - b->first] : theta[i];
    if (grows) b->damage_work += dissipation(b, pts, i, c, m, from, theta_a);
    for (int64_t k = k0; k < k1; k++) {
      if (!bond_at(b, pts, i, k, from, &q)) continue;
      fam->state[2 * k + SMAX] = q.s_max, fam->state[2 * k + DAMAGE] = q.d_new;
      b->soft_grown += !q.breaks && q.d_new - q.d_old > PF_PD_SOFT_TOL;
      if (!q.breaks) continue;
      fam->broken[k] = PF_BOND_BROKEN;
      pf_pd_body_rest_at_break(b, pts, i, k);
      if (b->lost_volume) b->lost_volume[i] += q.wv * q.r0 * q.r0;
    }
  }
  if (qs) { /* (the next pass starts here) */
    memcpy(b->soft_qs.base, fam->state, sizeof(double) * (size_t)b->soft_qs.n);
    b->soft_qs.pass = 2, b->soft_qs.theta_stale = 1;
  }
  return 0;
}

void pf_pd_softening_pmb_force(pf_pd_body *b, pf_points *pts, double c) {
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double f[3] = {0, 0, 0}, e[3], r0, r, smin = INFINITY;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (fam->broken[k]) continue;
      const pf_int j = fam->neighbor[k];
      pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
      const double s = (r - r0) / r0;
      smin = fmin(smin, s);
      const double fs = pf_pd_soft_weight(b, k) * c * pf_pd_omega(&b->influence, r0) * s *
                        pf_pd_bond_volume(fam, pts->vol, k, j) / r;
      for (int a = 0; a < 3; a++) f[a] += fs * e[a];
    }
    b->smin[i - b->first] = smin;
    for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * f[a];
  }
}
