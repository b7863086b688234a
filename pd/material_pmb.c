/* Prototype microelastic brittle (PMB) material, bond-based (Silling 2000; Silling & Askari
 * 2005). Pairwise force density f = c omega(|xi|) s e_eta, s = (|eta + xi| - |xi|) / |xi|,
 * with c = 18 K / (4 pi int omega r^3 dr) = 18 K / (pi delta^4) for omega = 1
 * (Silling & Askari 2005, eq. 7; docs/theory/pd.md). */
#include "pd/bond_batch.h"
#include "pd/pd_impl.h"

#include <stdlib.h>

/* The critical stretch goes in the records' spare slot (pd/bond_batch.h). */
enum { REC_S0 = REC_AUX };

typedef struct {
  double c;             /* micromodulus, N/m^6 (times omega) */
  pf_batch_records rec; /* refilled at each force pass */
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

/* The micromodulus of the bond i - j: c, or across two materials c times the interface rule's
 * factor (pf_pd_bond_stiffness; docs/theory/interfaces.md §2). */
static inline double bond_c(const pf_pd_body *b, pf_int i, pf_int j, double c) {
  return b->part ? c * pf_pd_bond_stiffness(b, i, j) : c;
}

/* The micropotential share of the directed bond k of point i, per V_i, (1/4) c omega s^2 |xi| V_j
 * (Silling & Askari 2005, eq. 6, half of the pair's to each end), as the mean of its values at the
 * positions y and yp; |xi|, omega, c and V_j formed once for both. */
static double pmb_bond_energy_mean(const pf_pd_body *b, const pf_points *pts, const double *y, const double *yp,
                                   pf_int i, int64_t k, double c) {
  const pf_family *fam = &b->fam;
  const pf_int j = fam->neighbor[k];
  double r0, r, rp, e[3];
  pf_pd_bond_lengths(pts->X, y, i, j, &r0, &r, e);
  pf_pd_bond_lengths(pts->X, yp, i, j, &r0, &rp, e);
  const double s = (r - r0) / r0, sp = (rp - r0) / r0;
  const double a = 0.25 * bond_c(b, i, j, c) * pf_pd_omega(&b->influence, r0), vj = pf_pd_bond_volume(fam, pts->vol, k, j);
  return 0.5 * (a * s * s * r0 * vj + a * sp * sp * r0 * vj);
}

/* The energy (J) point i's bonds that failed in this pass held at the middle of the step: the
 * mean of their energies at this pass's positions and at the last pass's (docs/theory/pd.md §5.1,
 * "Time step"); marks them broken (with their rest length in self-contact). Out of line: a bond fails once. */
static __attribute__((noinline)) double pmb_release(const pf_pd_body *b, const pf_points *pts, pf_int i,
                                                    double c) {
  const pf_family *fam = &b->fam;
  const double *yp = pf_pd_previous_positions(pts);
  double w = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
    if (fam->broken[k] == PF_BOND_FRESH) {
      w += pmb_bond_energy_mean(b, pts, pts->y, yp, i, k, c);
      fam->broken[k] = PF_BOND_BROKEN;
      pf_pd_body_rest_at_break(b, pts, i, k);
    }
  return w * pts->vol[i];
}

/* One point's bond loop: returns the force density sum in f[3] and the smallest stretch of
 * its intact bonds. The force density is c omega s V_j e / r with s = (r - r0) / r0 (Silling &
 * Askari 2005, eq. 7), formed from the inverse lengths 1 / r0 and 1 / r (pf_batch_rsqrt):
 * r0 = |xi|^2 (1 / r0), s = (r - r0) (1 / r0), so a bond at rest has s = 0 exactly. Fails
 * bonds whose stretch exceeds min(s0_i, s0_j), and with `energy` (the body's energy limit: law
 * critical_energy, Foster et al. 2011) also bonds in tension whose pair micropotential
 *   w = (1/2) c omega s^2 |xi| > w_c   <=>   omega s^2 |xi| > 2 w_c / c = wlim
 * (w_c the bond's own b->wc_bond where the law gives one, pf_pd_energy_limit).
 * Both ends evaluate it from bitwise equal s, |xi| and omega, so they fail the bond together.
 * Inlined with the influence kind, the partial-volume switch and the energy switch as constants.
 * The bonds go in batches of PF_BATCH: the neighbours' records are transposed into rows of
 * the batch (pd/bond_batch.h), then branch-free passes over the batch, in vector registers,
 * add into per-lane sums, which are summed at the end. The empty lanes of a row's last batch
 * read the rows' slack (pd/pd.h) and are dead. The order of the sums depends only on the
 * bond order, so results do not depend on the partition. With `mixed` (several materials) each
 * bond's micromodulus is c times its interface factor (bond_c). */
static inline __attribute__((always_inline)) double
pmb_point(const pf_pd_body *restrict b, const double *restrict rec, pf_int i, double c, double wlim,
          const int weighted, const int partial, const int energy, const int mixed, double f[3], int *nfresh) {
  enum { L = PF_BATCH };
  const pf_family *fam = &b->fam;
  const float *restrict vfrac = fam->vfrac;
  uint8_t *restrict broken = fam->broken;
  const pf_int *restrict nb = fam->neighbor;
  const double *restrict wlb = b->wc_bond;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const double s0i = ri[REC_S0];
  double f0[L] = {0}, f1[L] = {0}, f2[L] = {0}, sm[L];
  int fresh = 0;
  for (int l = 0; l < L; l++) sm[l] = INFINITY;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += L) {
    if (pf_batch_dead(broken, k0, end)) continue;
    const int n = end - k0 < L ? (int)(end - k0) : L;
    double a[PF_REC][L], live[L], fails[L], cb[L], slim_if[L];
    pf_batch_lengths g;
    pf_batch_live(broken + k0, n, live);
    pf_batch_gather(rec, nb + k0, a);
    pf_batch_lengths_of(ri, a, &g);
    for (int l = 0; mixed && l < L; l++) { /* each bond's micromodulus; the interface's stretch limit */
      cb[l] = bond_c(b, i, nb[k0 + l], c);
      slim_if[l] = b->interface_law && b->part[nb[k0 + l]] != b->part[i] ? b->interface_s0 : NAN;
    }
#pragma omp simd
    for (int l = 0; l < L; l++) {
      const double r0 = g.r0[l], s = (g.r[l] - r0) * g.ir0[l];
      const double om = weighted ? pf_pd_omega(&b->influence, r0) : 1.0;
      const double slim0 = s0i < a[REC_S0][l] ? s0i : a[REC_S0][l];
      const double slim = mixed && !isnan(slim_if[l]) ? slim_if[l] : slim0;
      const double wl = energy && wlb ? 2.0 * wlb[k0 + l] / (mixed ? cb[l] : c) : wlim;
      const int fail = (s > slim) | (energy ? (s > 0) & (om * s * s * r0 > wl) : 0);
      fails[l] = live[l] > 0 && fail ? 1.0 : 0.0;
      const double alive = fail ? 0.0 : live[l];
      sm[l] = alive > 0 && s < sm[l] ? s : sm[l];
      const double vj = partial ? a[REC_V][l] * vfrac[k0 + l] : a[REC_V][l];
      const double fs = alive > 0 ? (mixed ? cb[l] : c) * s * g.ir[l] * vj * om : 0.0;
      f0[l] += fs * g.e[0][l];
      f1[l] += fs * g.e[1][l];
      f2[l] += fs * g.e[2][l];
    }
    for (int l = 0; l < n; l++)
      if (fails[l] > 0) broken[k0 + l] = PF_BOND_FRESH, fresh++;
  }
  double smin = INFINITY;
  f[0] = f[1] = f[2] = 0;
  for (int l = 0; l < L; l++) {
    f[0] += f0[l], f[1] += f1[l], f[2] += f2[l];
    smin = sm[l] < smin ? sm[l] : smin;
  }
  *nfresh = fresh;
  return smin;
}

#if defined(PF_BATCH_AVX512)
/* pmb_point for a stretch law, in AVX-512 registers: pmb_point's operations, but the squared
 * lengths and the force sums with fused multiply-adds, so the last bits differ from
 * pmb_point's; the lanes are summed in the same order. omega (influence `kind`) is 1, the
 * 1 / |xi| the geometry holds, or exp(-|xi|^2 / sigma^2) by pf_batch_exp_v. */
static inline __attribute__((always_inline)) double pmb_point_avx512(const pf_pd_body *restrict b,
                                                                     const double *restrict rec, pf_int i,
                                                                     double c, const int kind, const int partial,
                                                                     double f[3], int *nfresh) {
  const __m512d nis2 = _mm512_set1_pd(-1.0 / (b->influence.length * b->influence.length));
  const pf_family *fam = &b->fam;
  uint8_t *restrict broken = fam->broken;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const __m512d s0i = _mm512_set1_pd(ri[REC_S0]), cc = _mm512_set1_pd(c);
  __m512d F[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d SM = _mm512_set1_pd(INFINITY);
  int fresh = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += PF_BATCH) {
    if (pf_batch_dead(broken, k0, end)) continue;
    __m512d a[PF_REC];
    pf_batch_geom g;
    pf_batch_stretch t;
    pf_batch_load_v(fam, rec, ri, k0, end, s0i, partial, a, &g, &SM, &t);
    __m512d fs = _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(cc, t.s), g.ir), t.vj);
    if (kind == PF_INFLUENCE_INVERSE_DISTANCE) fs = _mm512_mul_pd(fs, g.ir0);
    if (kind == PF_INFLUENCE_GAUSSIAN) fs = _mm512_mul_pd(fs, pf_batch_exp_v(_mm512_mul_pd(_mm512_mul_pd(g.r0, g.r0), nis2)));
    fs = _mm512_maskz_mov_pd(t.alive, fs);
    for (int q = 0; q < 3; q++) F[q] = _mm512_fmadd_pd(fs, g.e[q], F[q]);
    fresh += pf_batch_mark_fresh(broken + k0, t.fail);
  }
  const double smin = pf_batch_min_v(SM);
  for (int q = 0; q < 3; q++) f[q] = pf_batch_sum_v(F[q]);
  *nfresh = fresh;
  return smin;
}
#endif

/* The points [lo, hi) of the body for one combination of the compile-time switches; returns 1
 * when some point lost bonds (its lost flag is set). */
static inline __attribute__((always_inline)) int pmb_loop(pf_pd_body *b, pf_points *pts, double c, pf_int lo,
                                                          pf_int hi, const int kind, const int partial,
                                                          const int energy, const int mixed) {
  const int weighted = kind != PF_INFLUENCE_CONSTANT;
  double *restrict F = pts->f;
  const double *restrict vol = pts->vol;
  const double *rec = ((const pmb *)b->mat)->rec.rec;
  const double wlim = 2.0 * b->critical_energy / c;
  int any = 0;
  for (pf_int i = lo; i < hi; i++) {
    double f[3];
    int fresh;
#if defined(PF_BATCH_AVX512)
    if (!energy && !mixed) b->smin[i - b->first] = pmb_point_avx512(b, rec, i, c, kind, partial, f, &fresh);
    else
#endif
      b->smin[i - b->first] = pmb_point(b, rec, i, c, wlim, weighted, partial, energy, mixed, f, &fresh);
    b->lost[i - b->first] = fresh > 0;
    any |= fresh > 0;
    F[3 * i] += vol[i] * f[0];
    F[3 * i + 1] += vol[i] * f[1];
    F[3 * i + 2] += vol[i] * f[2];
  }
  return any;
}

/* The energy-limit loops, out of line so that the stretch-law loops of pmb_force keep
 * their code and layout. */
static __attribute__((noinline)) int pmb_force_energy(pf_pd_body *b, pf_points *pts, double c, pf_int lo,
                                                      pf_int hi, int partial) {
  const pf_influence_kind kind = b->influence.kind;
#define PF_PMB_LOOP(K) return partial ? pmb_loop(b, pts, c, lo, hi, K, 1, 1, 0) : pmb_loop(b, pts, c, lo, hi, K, 0, 1, 0)
  if (kind == PF_INFLUENCE_CONSTANT) PF_PMB_LOOP(PF_INFLUENCE_CONSTANT);
  if (kind == PF_INFLUENCE_INVERSE_DISTANCE) PF_PMB_LOOP(PF_INFLUENCE_INVERSE_DISTANCE);
  PF_PMB_LOOP(PF_INFLUENCE_GAUSSIAN);
#undef PF_PMB_LOOP
}

/* Several materials, any influence function; an energy limit only on the interface's bonds
 * (wc_bond; pf_pd_parts_read refuses the body's own). */
static __attribute__((noinline)) int pmb_force_mixed(pf_pd_body *b, pf_points *pts, double c, pf_int lo,
                                                     pf_int hi, int partial, int energy) {
  if (energy)
    return partial ? pmb_loop(b, pts, c, lo, hi, PF_INFLUENCE_GAUSSIAN, 1, 1, 1)
                   : pmb_loop(b, pts, c, lo, hi, PF_INFLUENCE_GAUSSIAN, 0, 1, 1);
  return partial ? pmb_loop(b, pts, c, lo, hi, PF_INFLUENCE_GAUSSIAN, 1, 0, 1)
                 : pmb_loop(b, pts, c, lo, hi, PF_INFLUENCE_GAUSSIAN, 0, 0, 1);
}

/* Owner computes: a point writes only its own force, smin and row, so the threads (each a
 * contiguous range of points) share nothing; the released energy is booked after, in point
 * order, so the bits do not depend on the thread count. */
static int pmb_force(pf_pd_body *b, pf_points *pts) {
  const double c = ((const pmb *)b->mat)->c;
  if (b->soft_ratio > 0) { /* bonds that soften (pd/softening.c) */
    PF_CALL(pf_pd_softening_update(b, pts, c, NULL, NULL));
    pf_pd_softening_pmb_force(b, pts, c);
    return 0;
  }
  PF_CALL(pf_batch_records_fill(&((pmb *)b->mat)->rec, pts, b->s0));
  const pf_influence_kind kind = b->influence.kind;
  const int partial = b->fam.vfrac != NULL, energy = pf_pd_energy_limited(b);
  int any = 0;
#pragma omp parallel reduction(| : any)
  {
    pf_int lo, hi;
    pf_thread_range(b->first, b->n, &lo, &hi);
#define PF_PMB_LOOP(K) any = partial ? pmb_loop(b, pts, c, lo, hi, K, 1, 0, 0) : pmb_loop(b, pts, c, lo, hi, K, 0, 0, 0)
    if (b->part) any = pmb_force_mixed(b, pts, c, lo, hi, partial, energy);
    else if (energy) any = pmb_force_energy(b, pts, c, lo, hi, partial);
    else if (kind == PF_INFLUENCE_CONSTANT) PF_PMB_LOOP(PF_INFLUENCE_CONSTANT);
    else if (kind == PF_INFLUENCE_INVERSE_DISTANCE) PF_PMB_LOOP(PF_INFLUENCE_INVERSE_DISTANCE);
    else PF_PMB_LOOP(PF_INFLUENCE_GAUSSIAN);
#undef PF_PMB_LOOP
  }
  for (pf_int i = b->first; any && i < b->first + b->n; i++)
    if (b->lost[i - b->first]) b->damage_work += pmb_release(b, pts, i, c);
  return 0;
}

/* Point i's share of the stored energy per V_i, sum_j (1/4) c omega s^2 |xi| V_j over its
 * intact bonds (each times its weight 1 - d where the bonds soften), in batches as pmb_point. */
static double pmb_point_energy(const pf_pd_body *b, const double *rec, pf_int i, double c) {
  enum { L = PF_BATCH };
  const pf_family *fam = &b->fam;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  double w[L] = {0}, total = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += L) {
    if (pf_batch_dead(fam->broken, k0, end)) continue; /* (its lanes would add +0 to sums never -0) */
    const int n = end - k0 < L ? (int)(end - k0) : L;
    double a[PF_REC][L], live[L], cb[L], sw[L];
    pf_batch_lengths g;
    pf_batch_live(fam->broken + k0, n, live);
    pf_batch_gather(rec, fam->neighbor + k0, a);
    pf_batch_lengths_of(ri, a, &g);
    for (int l = 0; l < L; l++) cb[l] = bond_c(b, i, fam->neighbor[k0 + l], c);
    for (int l = 0; l < L; l++) sw[l] = l < n ? pf_pd_soft_weight(b, k0 + l) : 1.0; /* (the state has no slack) */
#pragma omp simd
    for (int l = 0; l < L; l++) {
      const double r0 = g.r0[l], s = (g.r[l] - r0) * g.ir0[l];
      const double vj = fam->vfrac ? a[REC_V][l] * fam->vfrac[k0 + l] : a[REC_V][l];
      const double wl = 0.25 * cb[l] * pf_pd_omega(&b->influence, r0) * s * s * r0 * vj;
      w[l] += live[l] > 0 ? (b->soft_ratio > 0 ? wl * sw[l] : wl) : 0.0;
    }
  }
  for (int l = 0; l < L; l++) total += w[l];
  return total;
}

static double pmb_vol_energy(const pf_pd_body *b, const pf_points *pts, pf_int i) {
  const pmb *p = b->mat;
  return pts->vol[i] * pmb_point_energy(b, p->rec.rec, i, p->c);
}

/* Stored energy: W = sum_i V_i sum_j (1/4) c omega s^2 |xi| V_j (Silling & Askari 2005, eq. 6). */
static double pmb_energy(const pf_pd_body *b, const pf_points *pts) {
  pmb *p = b->mat;
  if (pf_batch_records_fill(&p->rec, pts, b->s0)) return NAN; /* (out of memory: shows in the balance) */
  return pf_pd_body_point_sum(b, pts, pmb_vol_energy);
}

static double pmb_micromodulus(const pf_pd_body *b, double delta) {
  (void)delta; /* (PMB has a constant horizon) */
  return ((const pmb *)b->mat)->c;
}

/* Bond k of point i's pair micropotential per V_i V_j, (1/2) c omega s^2 |xi| (Silling & Askari
 * 2005, eq. 6; the force pass's critical-energy test). */
static double pmb_bond_energy_at(const pf_pd_body *b, pf_int i, int64_t k, double r0, double ext) {
  const double s = ext / r0, c = bond_c(b, i, b->fam.neighbor[k], ((const pmb *)b->mat)->c);
  return 0.5 * c * pf_pd_omega(&b->influence, r0) * s * s * r0;
}

static double pmb_critical_stretch(const pf_pd_body *b, double G0) {
  return pf_pd_pmb_critical_stretch(G0, b->bulk_modulus, b->horizon);
}

static void pmb_destroy(pf_pd_body *b) {
  if (b->mat) pf_batch_records_free(&((pmb *)b->mat)->rec);
  PF_FREE(b->mat);
}

const pf_pd_material_ops pf_pd_material_pmb = {
    .name = "pmb",
    .create = pmb_create,
    .force = pmb_force,
    .energy = pmb_energy,
    .micromodulus = pmb_micromodulus,
    .critical_stretch = pmb_critical_stretch,
    .destroy = pmb_destroy,
    .bond_energy = 1,
    .bond_energy_at = pmb_bond_energy_at,
    .several_materials = 1,
    .records_rest = 1,
    .bond_rate = 2.3e8,
};
