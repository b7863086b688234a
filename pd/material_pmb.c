/* Prototype microelastic brittle (PMB) material, bond-based (Silling 2000; Silling & Askari
 * 2005). Pairwise force density f = c omega(|xi|) s e_eta, s = (|eta + xi| - |xi|) / |xi|,
 * with c = 18 K / (4 pi int omega r^3 dr) = 18 K / (pi delta^4) for omega = 1
 * (Silling & Askari 2005, eq. 7; docs/theory/pd.md). */
#include "pd/pd_impl.h"

#include <stdlib.h>

typedef struct {
  double c; /* micromodulus, N/m^6 (times omega) */
} pmb;

static int pmb_create(const pf_deck *d, const pf_node *mat, pf_pd_body *b) {
  if (!pf_node_get(mat, "bulk_modulus"))
    return pf_deck_error(d, mat, "bulk_modulus", "model 'pmb' needs 'bulk_modulus'");
  pmb *p;
  PF_MALLOC(p, 1);
  p->c = pf_pd_pmb_micromodulus(b->bulk_modulus, &b->influence, b->horizon);
  b->mat = p;
  return 0;
}

/* The micropotential share of the directed bond k of point i, per V_i:
 * (1/4) c omega s^2 |xi| V_j (Silling & Askari 2005, eq. 6, half of the pair's to each end). */
static double pmb_bond_energy(const pf_pd_body *b, const pf_points *pts, pf_int i, int64_t k, double c) {
  const pf_family *fam = &b->fam;
  pf_int j = fam->neighbor[k];
  double r0 = 0, r = 0;
  for (int a = 0; a < 3; a++) {
    double d = pts->X[3 * j + a] - pts->X[3 * i + a], e = pts->y[3 * j + a] - pts->y[3 * i + a];
    r0 += d * d, r += e * e;
  }
  r0 = sqrt(r0), r = sqrt(r);
  double s = (r - r0) / r0;
  return 0.25 * c * pf_pd_omega(&b->influence, r0) * s * s * r0 * pf_pd_bond_volume(fam, pts->vol, k, j);
}

/* The energy (J) point i's bonds that failed in this pass held, at this pass's positions; marks
 * them broken. Out of line: a bond fails once. */
static __attribute__((noinline)) double pmb_release(const pf_pd_body *b, const pf_points *pts, pf_int i,
                                                    double c) {
  const pf_family *fam = &b->fam;
  double w = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
    if (fam->broken[k] == PF_BOND_FRESH) w += pmb_bond_energy(b, pts, i, k, c), fam->broken[k] = PF_BOND_BROKEN;
  return w * pts->vol[i];
}

/* One point's bond loop: returns the force density sum in f[3] and the smallest stretch of
 * its intact bonds; fails bonds whose stretch exceeds min(s0_i, s0_j), or with `energy` (law
 * critical_energy, Foster et al. 2011) bonds in tension whose pair micropotential
 *   w = (1/2) c omega s^2 |xi| > w_c   <=>   omega s^2 |xi| > 2 w_c / c = wlim.
 * Both ends evaluate it from bitwise equal s, |xi| and omega, so they fail the bond together.
 * Inlined with the influence kind, the partial-volume switch and the law as constants, so the
 * common case (omega = 1, whole cells, critical stretch) is a branch-light loop. */
static inline __attribute__((always_inline)) double
pmb_point(const pf_pd_body *restrict b, const pf_points *restrict pts, pf_int i, double c,
          double wlim, const int weighted, const int partial, const int energy, double f[3], int *nfresh) {
  const pf_family *fam = &b->fam;
  const double *restrict X = pts->X, *restrict Y = pts->y, *restrict vol = pts->vol;
  const double *restrict s0 = b->s0;
  const float *restrict vfrac = fam->vfrac;
  uint8_t *restrict broken = fam->broken;
  const pf_int *restrict nb = fam->neighbor;
  const double xi0 = X[3 * i], xi1 = X[3 * i + 1], xi2 = X[3 * i + 2];
  const double yi0 = Y[3 * i], yi1 = Y[3 * i + 1], yi2 = Y[3 * i + 2], s0i = s0[i];
  double f0 = 0, f1 = 0, f2 = 0, smin = INFINITY;
  int fresh = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  const int64_t begin = fam->offset[i - fam->first];
  /* Branch-free so that the compiler vectorizes it (gathers of the neighbours' data). */
#pragma omp simd reduction(+ : f0, f1, f2, fresh) reduction(min : smin)
  for (int64_t k = begin; k < end; k++) {
    const pf_int j = nb[k];
    const double d0 = X[3 * j] - xi0, d1 = X[3 * j + 1] - xi1, d2 = X[3 * j + 2] - xi2;
    const double e0 = Y[3 * j] - yi0, e1 = Y[3 * j + 1] - yi1, e2 = Y[3 * j + 2] - yi2;
    const double r0 = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    const double r = sqrt(e0 * e0 + e1 * e1 + e2 * e2);
    const double s = (r - r0) / r0;
    const double om = weighted ? pf_pd_omega(&b->influence, r0) : 1.0;
    const int fails = energy ? (s > 0) & (om * s * s * r0 > wlim) : s > fmin(s0i, s0[j]);
    const int alive = !broken[k] && !fails, now = fails & !broken[k];
    fresh += now;
    broken[k] = (uint8_t)(broken[k] | (now * PF_BOND_FRESH));
    smin = alive ? fmin(smin, s) : smin;
    double fs = c * s * vol[j] / r;
    if (weighted) fs *= om;
    if (partial) fs *= vfrac[k];
    fs = alive ? fs : 0.0;
    f0 += fs * e0;
    f1 += fs * e1;
    f2 += fs * e2;
  }
  f[0] = f0, f[1] = f1, f[2] = f2;
  *nfresh = fresh;
  return smin;
}

/* The loop over the body's points for one combination of the compile-time switches. */
static inline __attribute__((always_inline)) void pmb_loop(pf_pd_body *b, pf_points *pts, double c,
                                                           const int weighted, const int partial,
                                                           const int energy) {
  double *restrict F = pts->f;
  const double *restrict vol = pts->vol;
  const double wlim = 2.0 * b->critical_energy / c;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double f[3];
    int fresh;
    b->smin[i - b->first] = pmb_point(b, pts, i, c, wlim, weighted, partial, energy, f, &fresh);
    if (fresh) b->damage_work += pmb_release(b, pts, i, c);
    F[3 * i] += vol[i] * f[0];
    F[3 * i + 1] += vol[i] * f[1];
    F[3 * i + 2] += vol[i] * f[2];
  }
}

/* The critical-energy loops, out of line so that the stretch-law loops of pmb_force keep
 * their code and layout. */
static __attribute__((noinline)) void pmb_force_energy(pf_pd_body *b, pf_points *pts, double c,
                                                       int weighted, int partial) {
  if (!weighted && !partial) pmb_loop(b, pts, c, 0, 0, 1);
  else if (!weighted) pmb_loop(b, pts, c, 0, 1, 1);
  else if (!partial) pmb_loop(b, pts, c, 1, 0, 1);
  else pmb_loop(b, pts, c, 1, 1, 1);
}

static int pmb_force(pf_pd_body *b, pf_points *pts) {
  const double c = ((const pmb *)b->mat)->c;
  const int weighted = b->influence.kind != PF_INFLUENCE_CONSTANT, partial = b->fam.vfrac != NULL;
  if (b->law == PF_DAMAGE_CRITICAL_ENERGY) pmb_force_energy(b, pts, c, weighted, partial);
  else if (!weighted && !partial) pmb_loop(b, pts, c, 0, 0, 0);
  else if (!weighted) pmb_loop(b, pts, c, 0, 1, 0);
  else if (!partial) pmb_loop(b, pts, c, 1, 0, 0);
  else pmb_loop(b, pts, c, 1, 1, 0);
  return 0;
}

/* Stored energy: W = sum_i V_i sum_j (1/4) c omega s^2 |xi| V_j (Silling & Askari 2005, eq. 6). */
static double pmb_energy(const pf_pd_body *b, const pf_points *pts) {
  const pf_family *fam = &b->fam;
  const double c = ((const pmb *)b->mat)->c;
  double w = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double wi = 0;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      if (!fam->broken[k]) wi += pmb_bond_energy(b, pts, i, k, c);
    w += wi * pts->vol[i];
  }
  return w;
}

static double pmb_micromodulus(const pf_pd_body *b, double delta) {
  (void)delta; /* (PMB has a constant horizon) */
  return ((const pmb *)b->mat)->c;
}

static double pmb_critical_stretch(const pf_pd_body *b, double G0) {
  return pf_pd_pmb_critical_stretch(G0, b->bulk_modulus, b->horizon);
}

static void pmb_destroy(pf_pd_body *b) { PF_FREE(b->mat); }

const pf_pd_material_ops pf_pd_material_pmb = {
    .name = "pmb",
    .create = pmb_create,
    .force = pmb_force,
    .energy = pmb_energy,
    .micromodulus = pmb_micromodulus,
    .critical_stretch = pmb_critical_stretch,
    .destroy = pmb_destroy,
};
