/* Linear peridynamic solid (LPS), ordinary state-based (Silling et al. 2007, J. Elasticity
 * 88:151, eqs. 90-94; the form used by Peridigm, Mitchell 2011):
 *   m_i     = sum_j omega |xi|^2 V_j                        (weighted volume)
 *   theta_i = (3 / m_i) sum_j omega |xi| e V_j,  e = |eta + xi| - |xi|   (dilatation)
 *   t_ij    = omega [ (3 K theta_i / m_i) |xi| + (15 G / m_i) (e - theta_i |xi| / 3) ]
 *   f_i     = sum_j (t_ij + t_ji) M_ij V_j,  M_ij = (y_j - y_i) / |y_j - y_i|
 * m and theta use the same quadrature (same neighbour volumes), so theta = 3 eps exactly under
 * u = eps x. Bonds fail on the critical-stretch test in the dilatation pass, so both passes see
 * the same bonds; on the critical-energy test (which needs both ends' t) in the force pass.
 * With a variable horizon the sums of point i run over its own family (j within delta_i) and
 * f_i = sum_j ([j in H_i] t_ij + [i in H_j] t_ji) M_ij V_j; a point of the partial-stress form
 * takes f_i = V_i div nu, nu_i = sum_j t_ij M_ij (x) xi V_j (pd/partial_stress.c). */
#include "pd/bond_batch.h"
#include "pd/pd_impl.h"

#include <stdlib.h>

typedef struct {
  double *m;     /* field "weighted_volume" */
  double *theta; /* field "dilatation" */
  double *mom;   /* field "dilatation_moment": theta m^lost / 3 (pd_impl.h, pf_pd_lps_volumetric) */
  double *nu;    /* field "partial_stress" [9], when some point has the partial-stress form */
  double *Ki;    /* [9n] K^-1 of those points (their bonds never fail) */
  /* the batched loops (lps_force_batched), for a body of one horizon whose points all take the
   * standard force (no transition, no overlap with elements) */
  int batched;
  pf_batch_records rec; /* pass 1: s0 in REC_AUX; pass 2: Q = (3K - 5G) theta */
  double *rm;           /* [store points] 1 / m for pass 2, set with m */
  pf_int rm_n;
} lps;

static int lps_create(const pf_deck *d, const pf_node *mat, pf_pd_body *b) {
  if (!pf_node_get(mat, "bulk_modulus") || !pf_node_get(mat, "shear_modulus"))
    return pf_deck_error(d, mat, pf_node_get(mat, "bulk_modulus") ? "shear_modulus" : "bulk_modulus",
                         "model 'lps' needs 'bulk_modulus' and 'shear_modulus'");
  lps *p;
  PF_MALLOC(p, 1);
  b->mat = p;
  return 0;
}

static int lps_setup(pf_pd_body *b, pf_points *pts) {
  lps *p = b->mat;
  int im, it;
  PF_CALL(pf_points_field_register(pts, "weighted_volume", 1, PF_FIELD_GHOST | PF_FIELD_RESTART, &im));
  PF_CALL(pf_points_field_register(pts, "dilatation", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT, &it));
  p->m = pts->fields[im].data;
  p->theta = pts->fields[it].data;
  PF_CALL(pf_pd_lost_volume_fields(b, pts, &p->mom));
  double nps = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) nps += pf_pd_partial_stress_at(b, i);
  free(p->Ki);
  p->Ki = NULL, p->nu = NULL;
  if (pf_sum_all(nps) > 0) { /* (collective: every rank exchanges the field) */
    int in;
    PF_CALL(pf_points_field_register(pts, "partial_stress", 9, PF_FIELD_GHOST, &in));
    p->nu = pts->fields[in].data;
    PF_MALLOC(p->Ki, 9 * (size_t)b->n + 1);
    for (pf_int i = b->first; i < b->first + b->n; i++)
      if (pf_pd_partial_stress_at(b, i)) pf_pd_shape_tensor_inverse(b, pts, i, &p->Ki[9 * (i - b->first)]);
  }
  double special = 0; /* points of the transition, the overlap or the corrected force */
  for (pf_int i = b->first; i < b->first + b->n; i++) special += b->region[i] != 0;
  p->batched = !b->one_sided && !b->interface_law && b->soft_ratio == 0 &&
               pf_sum_all(special) == 0; /* (the same on every rank) */
  PF_CALL(pf_pd_weighted_volumes(b, pts, p->m));
  free(p->rm); /* (m is fixed, ghosts included, until the next set-up) */
  p->rm_n = pts->n_total;
  PF_MALLOC(p->rm, p->rm_n);
  for (pf_int j = 0; j < p->rm_n; j++) p->rm[j] = (b->part ? pf_pd_G(b, j) / b->shear_modulus : 1.0) / p->m[j];
  return 0;
}

/* Pass 1: dilatation of point i; fails bonds beyond the critical stretch, booking the energy
 * they release. Where the bonds soften each bond has the weight (1 - d) omega, and the weighted
 * volume the softening took, sum_j d omega |xi|^2 V_j, goes into soft_lost (a failed bond's
 * generalised: pf_pd_dilatation_moment; docs/theory/bond_failure.md §8). */
static double lps_dilatation(pf_pd_body *b, const pf_points *pts, pf_int i, double m) {
  const pf_family *fam = &b->fam;
  double sum = 0, smin = INFINITY, e[3], r0, r, took = 0;
  int fresh = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    if (fam->broken[k]) continue;
    pf_int j = fam->neighbor[k];
    pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
    double s = (r - r0) / r0;
    if (pf_pd_stretch_fails(b, i, j, s) && pf_pd_may_fail(b, i, j)) {
      fam->broken[k] = PF_BOND_FRESH;
      fresh++;
      continue;
    }
    if (!pf_pd_in_family(b, i, r0)) continue;
    smin = fmin(smin, s);
    const double term = pf_pd_omega(&b->influence, r0) * r0 * (r - r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
    if (b->soft_ratio == 0) {
      sum += term;
      continue;
    }
    const double w = pf_pd_soft_weight(b, k);
    sum += term * w;
    took += (1 - w) * pf_pd_omega(&b->influence, r0) * r0 * r0 * pf_pd_bond_volume(fam, pts->vol, k, j);
  }
  if (b->soft_lost) b->soft_lost[i - b->first] = took;
  b->smin[i - b->first] = smin;
  if (fresh) b->damage_work += pf_pd_lps_release(b, pts, i, m, NULL, 0);
  return 3.0 * sum / m;
}

/* Scalar force state of one end of a bond, that end having dilatation theta, a = 3 K theta / m
 * and bc = 15 G / m: t = omega [ a |xi| + bc (e - theta |xi| / 3) ]. One function for both
 * ends, so that t_ij is the same bits whichever end evaluates it. */
static inline double lps_t(double a, double bc, double theta, double w, double r0, double ext) {
  return w * (a * r0 + bc * (ext - theta * r0 / 3));
}

/* After pass 1: the ghosts' theta, and every point's dilatation moment M (pf_pd_lps_volumetric;
 * 0 while it lost no bond), owned then ghosts, for the force pass. */
static int lps_moments(pf_pd_body *b, pf_points *pts) {
  lps *p = b->mat;
  PF_CALL(pf_points_exchange(pts, p->theta, 1));
  for (pf_int i = b->first; i < b->first + b->n; i++) p->mom[i] = pf_pd_dilatation_moment(b, i, p->theta[i], 0.0, 1.0);
  return pf_points_exchange(pts, p->mom, 1);
}

/* Pass 2: forces. With the critical-energy law (Foster et al. 2011) a bond in tension fails
 * when its energy per V_i V_j, w = (1/2) (t_ij + t_ji) e, exceeds w_c: by Euler's theorem for
 * the quadratic LPS energy, W_i = sum_j (1/2) t_ij e V_j exactly (lps_energy), so w is the
 * bond's share of the energy of both ends. Floating-point addition commutes, so end j's
 * t_ji + t_ij equals end i's t_ij + t_ji bitwise and both ends fail the bond in the same step.
 * The failing evaluation gives the bond no force (the forces of the other bonds keep this
 * evaluation's theta); theta is then recomputed without it, for the energy and the output. */
/* The partial stress of every owned point, nu_i = sum_j t_ij M (x) xi V_j over its own family,
 * then the ghosts'. */
static int lps_partial_stress(pf_pd_body *b, pf_points *pts) {
  lps *p = b->mat;
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double *nu = &p->nu[9 * i], e[3], r0, r;
    const double thi = p->theta[i], bi = 15 * pf_pd_G(b, i) / p->m[i];
    const double ai = pf_pd_lps_volumetric(pf_pd_K(b, i), pf_pd_G(b, i), thi, p->mom[i], p->m[i]);
    for (int k = 0; k < 9; k++) nu[k] = 0.0;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (fam->broken[k]) continue;
      pf_int j = fam->neighbor[k];
      pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
      if (!pf_pd_in_family(b, i, r0) || r == 0) continue;
      const double t = lps_t(ai, bi, thi, pf_pd_omega(&b->influence, r0), r0, r - r0);
      const double s = t * pf_pd_bond_volume(fam, pts->vol, k, j) / r;
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) nu[3 * a + c] += s * e[a] * (pts->X[3 * j + c] - pts->X[3 * i + c]);
    }
  }
  return pf_points_exchange(pts, p->nu, 9);
}

/* Bond k of point i's energy per V_i V_j, w = (1/2) (t_ij + t_ji) e, with the last evaluation's
 * dilatations and moments (the force pass's critical-energy test). */
static double lps_bond_energy_at(const pf_pd_body *b, pf_int i, int64_t k, double r0, double ext) {
  const lps *p = b->mat;
  const pf_int j = b->fam.neighbor[k];
  const double w = pf_pd_omega(&b->influence, r0);
  const double ai = pf_pd_lps_volumetric(pf_pd_K(b, i), pf_pd_G(b, i), p->theta[i], p->mom[i], p->m[i]);
  const double aj = pf_pd_lps_volumetric(pf_pd_K(b, j), pf_pd_G(b, j), p->theta[j], p->mom[j], p->m[j]);
  const double tij = pf_pd_in_family(b, i, r0) ? lps_t(ai, 15 * pf_pd_G(b, i) / p->m[i], p->theta[i], w, r0, ext) : 0.0;
  const double tji = pf_pd_in_family(b, j, r0) ? lps_t(aj, 15 * pf_pd_G(b, j) / p->m[j], p->theta[j], w, r0, ext) : 0.0;
  return 0.5 * (tij + tji) * ext;
}

/* The batched passes (pd/lps_batched.c): records with s0, then with Q = (3K - 5G) theta. */
static int lps_force_batched(pf_pd_body *b, pf_points *pts, int64_t *nfailed) {
  lps *p = b->mat;
  const size_t n = (size_t)pts->n_total;
  PF_CALL(pf_batch_records_fill(&p->rec, pts, b->s0));
  pf_pd_lps_batched_dilatation(b, pts, p->rec.rec, p->m, p->theta);
  PF_CALL(lps_moments(b, pts));
  PF_CHECK(p->rm_n == pts->n_total, PF_ERR_RUN, "LPS body '%s': the store changed since the set-up", b->name);
  const double q = 3 * b->bulk_modulus - 5 * b->shear_modulus, g15 = 15 * b->shear_modulus;
  for (size_t j = 0; j < n && !b->part; j++) /* Q = m (a - 5 G theta / m) (pf_pd_lps_volumetric) */
    p->rec.rec[PF_REC * j + REC_AUX] = p->mom[j] == 0.0 ? q * p->theta[j] : q * p->theta[j] - g15 * p->mom[j] / p->m[j];
  for (pf_int j = 0; j < (pf_int)n && b->part; j++) { /* several materials: Q_j / g_j with rm_j = g_j / m_j,
                                                         g_j = G_j / G (docs/theory/interfaces.md §3) */
    const double Kj = pf_pd_K(b, j), Gj = pf_pd_G(b, j), qj = (3 * Kj - 5 * Gj) * p->theta[j];
    p->rec.rec[PF_REC * j + REC_AUX] = (p->mom[j] == 0.0 ? qj : qj - 15 * Gj * p->mom[j] / p->m[j]) * (b->shear_modulus / Gj);
  }
  *nfailed = pf_pd_lps_batched_force(b, pts, p->rec.rec, p->rm);
  return 0;
}

/* The general passes (any horizon, partial stress, overlap): dilatations, then forces. */
static int lps_force_general(pf_pd_body *b, pf_points *pts, int64_t *nfailed) {
  lps *p = b->mat;
  const int energy = pf_pd_energy_limited(b);
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) p->theta[i] = lps_dilatation(b, pts, i, p->m[i]);
  PF_CALL(lps_moments(b, pts));
  if (p->nu) PF_CALL(lps_partial_stress(b, pts));
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    if (pf_pd_partial_stress_at(b, i)) {
      pf_pd_partial_stress_force(b, pts, i, p->nu, 9, &p->Ki[9 * (i - b->first)]);
      continue;
    }
    double f[3] = {0, 0, 0}, e[3], r0, r;
    const double Ki = pf_pd_K(b, i), Gi = pf_pd_G(b, i), thi = p->theta[i];
    const double ai = pf_pd_lps_volumetric(Ki, Gi, thi, p->mom[i], p->m[i]), bi = 15 * Gi / p->m[i];
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (fam->broken[k]) continue;
      pf_int j = fam->neighbor[k];
      pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
      const double ext = r - r0, w = pf_pd_omega(&b->influence, r0) * pf_pd_soft_weight(b, k);
      const double Kj = pf_pd_K(b, j), Gj = pf_pd_G(b, j), thj = p->theta[j];
      const double aj = pf_pd_lps_volumetric(Kj, Gj, thj, p->mom[j], p->m[j]), bj = 15 * Gj / p->m[j];
      const double tij = pf_pd_in_family(b, i, r0) ? lps_t(ai, bi, thi, w, r0, ext) : 0.0;
      const double tji = pf_pd_in_family(b, j, r0) ? lps_t(aj, bj, thj, w, r0, ext) : 0.0;
      if (energy && ext > 0 && 0.5 * (tij + tji) * ext > pf_pd_energy_limit(b, k)) {
        fam->broken[k] = PF_BOND_FRESH;
        ++*nfailed;
        continue;
      }
      const double fs = (tij + tji) * pf_pd_bond_volume(fam, pts->vol, k, j) / r;
      for (int a = 0; a < 3; a++) f[a] += fs * e[a];
    }
    for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * f[a];
  }
  return 0;
}

static int lps_force(pf_pd_body *b, pf_points *pts) {
  lps *p = b->mat;
  int64_t nfailed = 0;
  if (b->soft_ratio > 0) /* (pd/softening.c; theta still the last evaluation's) */
    PF_CALL(pf_pd_softening_update(b, pts, 0.0, p->m, p->theta));
  PF_CALL(p->batched ? lps_force_batched(b, pts, &nfailed) : lps_force_general(b, pts, &nfailed));
  if (nfailed) /* (the same bits for the points that lost no bond) */
    for (pf_int i = b->first; i < b->first + b->n; i++) {
      b->damage_work += pf_pd_lps_release(b, pts, i, p->m[i], NULL, 0);
      p->theta[i] = lps_dilatation(b, pts, i, p->m[i]);
    }
  return 0;
}

/* W_i = (K/2) theta^2 + (15 G / (2 m)) sum_j omega (e^d - e^dp)^2 V_j (Silling et al. 2007, eq.
 * 92; e^dp = ep[stride k], a plastic extension, or 0 when ep is NULL; where the bonds soften omega
 * times the bond's weight 1 - d), per reference volume, over
 * the intact bonds (not broken, not failing now). The neighbours come from the batch records rec
 * of every store point (X, V and y: pf_batch_records_fill), eight at a time, one cache line each;
 * their lengths are formed as pf_pd_bond_lengths forms them and summed in the row's order. */
double pf_pd_lps_energy_density(const pf_pd_body *b, const double *rec, pf_int i, double theta, double m,
                                const double *ep, int stride) {
  enum { L = PF_BATCH };
  const pf_family *fam = &b->fam;
  const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  double dev = 0;
  for (int64_t kb = k0; kb < k1; kb += L) {
    const int n = k1 - kb < L ? (int)(k1 - kb) : L;
    int32_t idx[L];
    double a[PF_REC][L], r0[L], r[L], e[3][L];
    for (int l = 0; l < L; l++) idx[l] = l < n ? fam->neighbor[kb + l] : i; /* (past the row: i itself) */
    pf_batch_gather(rec, idx, a);
    pf_batch_sqrt_lengths(ri, a, r0, r, e);
    for (int l = 0; l < n; l++) { /* (in the row's order) */
      const int64_t k = kb + l;
      if (fam->broken[k] & (PF_BOND_BROKEN | PF_BOND_FRESH) || !pf_pd_in_family(b, i, r0[l])) continue;
      const double ed = (r[l] - r0[l]) - theta * r0[l] / 3 - (ep ? ep[stride * k] : 0.0);
      const double vj = fam->vfrac ? a[REC_V][l] * fam->vfrac[k] : a[REC_V][l];
      dev += pf_pd_omega(&b->influence, r0[l]) * ed * ed * vj * pf_pd_soft_weight(b, k);
    }
  }
  return 0.5 * pf_pd_K(b, i) * theta * theta + 7.5 * pf_pd_G(b, i) / m * dev;
}

/* Bond k of point i not yet broken and in i's own family: its |xi| into *r0, its omega V_j into
 * *wv and its deformed lengths at the two positions y[0], y[1] into r[2] (the bits of
 * pf_pd_bond_lengths); else 0. */
static int release_bond(const pf_pd_body *b, const pf_points *pts, const double *const y[2], pf_int i, int64_t k,
                        double *r0, double *wv, double r[2]) {
  const pf_family *fam = &b->fam;
  if (fam->broken[k] == PF_BOND_BROKEN) return 0;
  const pf_int j = fam->neighbor[k];
  double d2 = 0, e2[2] = {0, 0};
  for (int a = 0; a < 3; a++) {
    const double d = pts->X[3 * j + a] - pts->X[3 * i + a];
    d2 += d * d;
    for (int t = 0; t < 2; t++) {
      const double e = y[t][3 * j + a] - y[t][3 * i + a];
      e2[t] += e * e;
    }
  }
  *r0 = sqrt(d2), r[0] = sqrt(e2[0]), r[1] = sqrt(e2[1]);
  if (!pf_pd_in_family(b, i, *r0)) return 0;
  *wv = pf_pd_omega(&b->influence, *r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
  return 1;
}

/* The change of point i's energy per reference volume when its PF_BOND_FRESH bonds F fail, at
 * each of the positions y[0], y[1] (q[t] for y[t]; docs/theory/pd.md §5.1). With S the bonds that
 * stay, a = 15 G / m and ed = e - theta |xi| / 3 - ep,
 *   W(theta, B) = (K/2) theta^2 + (a/2) sum_B omega ed^2 V,   g(theta) = W(theta, S),
 *   theta_w = (3/m) sum_{S+F} omega |xi| e V  (with F),   theta_o = (3/m) sum_S ...  (without),
 * the exact change W(theta_w, S+F) - W(theta_o, S) = Q + C of a quadratic g, delta = theta_w - theta_o:
 *   Q = (a/2) sum_F omega ed(theta_w)^2 V + (1/2) g'' delta^2 >= 0,  g'' = K + (a/9) sum_S omega |xi|^2 V,
 *   C = g'(theta_o) delta,  g'(theta_o) = K theta_o - (a/3) sum_S omega |xi| ed(theta_o) V,
 * the cross term of the dilatation that stays with the one the bonds took: negative where a
 * bond in tension leaves a point in compression more compressed. Q into q[t][0], C into q[t][1],
 * the weighted volume of F, sum_F omega |xi|^2 V, into q[t][2]. Both positions in each pass
 * over the family; the first pass keeps each bond's geometry for the second (a row of up to
 * RELEASE_ROW bonds; a longer row's further bonds are formed again, to the same bits). */
enum { RELEASE_ROW = 256 };
static void release_at(const pf_pd_body *b, const pf_points *pts, const double *const y[2], pf_int i, double m,
                       const double *ep, int stride, double q[2][3]) {
  const pf_family *fam = &b->fam;
  const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
  const double K = pf_pd_K(b, i), a = 15.0 * pf_pd_G(b, i) / m;
  double sum_s[2] = {0, 0}, sum_f[2] = {0, 0}, m_s[2] = {0, 0}, r0, wv, r[2];
  double geo[RELEASE_ROW][4]; /* r0 (-1: the bond takes no part), wv, r[0], r[1] */
  q[0][2] = q[1][2] = 0.0;
  for (int64_t k = k0; k < k1; k++) { /* the dilatation sums of S and F, their weighted volumes */
    double *g = k - k0 < RELEASE_ROW ? geo[k - k0] : NULL;
    if (g) g[0] = -1.0;
    if (!release_bond(b, pts, y, i, k, &r0, &wv, r)) continue;
    if (g) g[0] = r0, g[1] = wv, g[2] = r[0], g[3] = r[1];
    for (int t = 0; t < 2; t++)
      if (fam->broken[k] == PF_BOND_FRESH) sum_f[t] += wv * r0 * (r[t] - r0), q[t][2] += wv * r0 * r0;
      else sum_s[t] += wv * r0 * (r[t] - r0), m_s[t] += wv * r0 * r0;
  }
  double th_o[2], delta[2], th_w[2], dev_f[2] = {0, 0}, cross_s[2] = {0, 0};
  for (int t = 0; t < 2; t++) th_o[t] = 3.0 * sum_s[t] / m, delta[t] = 3.0 * sum_f[t] / m, th_w[t] = th_o[t] + delta[t];
  for (int64_t k = k0; k < k1; k++) { /* F's deviatoric energy at theta_w, S's slope at theta_o */
    if (k - k0 < RELEASE_ROW) {
      const double *g = geo[k - k0];
      if (g[0] < 0) continue;
      r0 = g[0], wv = g[1], r[0] = g[2], r[1] = g[3];
    } else if (!release_bond(b, pts, y, i, k, &r0, &wv, r))
      continue;
    const double p = ep ? ep[stride * k] : 0.0;
    for (int t = 0; t < 2; t++)
      if (fam->broken[k] == PF_BOND_FRESH) {
        const double ed = (r[t] - r0) - th_w[t] * r0 / 3 - p;
        dev_f[t] += wv * ed * ed;
      } else
        cross_s[t] += wv * r0 * ((r[t] - r0) - th_o[t] * r0 / 3 - p);
  }
  for (int t = 0; t < 2; t++) {
    q[t][0] = 0.5 * a * dev_f[t] + 0.5 * (K + a * m_s[t] / 9.0) * delta[t] * delta[t];
    q[t][1] = (K * th_o[t] - a * cross_s[t] / 3.0) * delta[t];
  }
}

/* The energy (J) point i's PF_BOND_FRESH bonds release, booked at the middle of the step: the
 * mean of the change at this pass's positions and at the last pass's (docs/theory/pd.md §5.1,
 * "Time step"); marks them broken (with their rest length in self-contact), and adds their weighted volume to i's lost_volume. Q + max(C, 0)
 * is released (returned with C's negative part: the total change), min(C, 0) is booked as
 * redistribution. */
double pf_pd_lps_release_point(pf_pd_body *b, const pf_points *pts, pf_int i, double m, const double *ep,
                               int stride, double *redistribution) {
  pf_family *fam = &b->fam;
  const int64_t k1 = fam->offset[i - b->first + 1];
  int64_t k = fam->offset[i - b->first];
  *redistribution = 0.0;
  while (k < k1 && fam->broken[k] != PF_BOND_FRESH) k++;
  if (k == k1) return 0.0;
  const double *const y[2] = {pts->y, pf_pd_previous_positions(pts)};
  double q[2][3];
  release_at(b, pts, y, i, m, ep, stride, q);
  const double *now = q[0], *before = q[1];
  for (; k < k1; k++)
    if (fam->broken[k] == PF_BOND_FRESH) fam->broken[k] = PF_BOND_BROKEN, pf_pd_body_rest_at_break(b, pts, i, k);
  b->lost_volume[i] += now[2];
  *redistribution = pts->vol[i] * 0.5 * (fmin(now[1], 0.0) + fmin(before[1], 0.0));
  return pts->vol[i] * 0.5 * (now[0] + now[1] + before[0] + before[1]);
}

double pf_pd_lps_release(pf_pd_body *b, const pf_points *pts, pf_int i, double m, const double *ep,
                         int stride) {
  double redistribution;
  const double released = pf_pd_lps_release_point(b, pts, i, m, ep, stride, &redistribution);
  b->damage_redistribution += redistribution;
  return released;
}

static double lps_point_energy(const pf_pd_body *b, const pf_points *pts, pf_int i) {
  const lps *p = b->mat;
  return pts->vol[i] * pf_pd_lps_energy_density(b, p->rec.rec, i, p->theta[i], p->m[i], NULL, 0);
}

static double lps_energy(const pf_pd_body *b, const pf_points *pts) {
  lps *p = b->mat; /* (the records are scratch: every force pass fills them again) */
  if (pf_batch_records_fill(&p->rec, pts, NULL)) return NAN; /* (out of memory: shows in the balance) */
  return pf_pd_body_point_sum(b, pts, lps_point_energy);
}

/* For the stable step: the PMB micromodulus of equal P-wave modulus, K_eq = (K + 4G/3) / 1.8. */
double pf_pd_lps_micromodulus(const pf_pd_body *b, double delta) {
  double keq = (b->bulk_modulus + 4.0 * b->shear_modulus / 3.0) / 1.8;
  return pf_pd_pmb_micromodulus(keq, &b->influence, delta);
}

/* Critical stretch from G0 (Madenci & Oterkus 2014 / CabanaPD's LPS):
 * omega = 1/|xi|: sqrt(5 G0 / (9 K delta)); omega = 1: sqrt(8 G0 / (15 K delta)). */
double pf_pd_lps_critical_stretch(const pf_pd_body *b, double G0) {
  double K = b->bulk_modulus, d = b->horizon;
  if (b->influence.kind == PF_INFLUENCE_INVERSE_DISTANCE) return sqrt(5 * G0 / (9 * K * d));
  if (b->influence.kind == PF_INFLUENCE_CONSTANT) return sqrt(8 * G0 / (15 * K * d));
  return NAN;
}

static void lps_destroy(pf_pd_body *b) {
  free(((lps *)b->mat)->Ki);
  free(((lps *)b->mat)->rm);
  pf_batch_records_free(&((lps *)b->mat)->rec);
  PF_FREE(b->mat);
}

const pf_pd_material_ops pf_pd_material_lps = {
    .name = "lps",
    .create = lps_create,
    .setup = lps_setup,
    .force = lps_force,
    .energy = lps_energy,
    .micromodulus = pf_pd_lps_micromodulus,
    .critical_stretch = pf_pd_lps_critical_stretch,
    .destroy = lps_destroy,
    .partial_stress = 1,
    .bond_energy = 1,
    .family_stiffness = 1,
    .bond_energy_at = lps_bond_energy_at,
    .several_materials = 1,
    .records_rest = 1,
};
