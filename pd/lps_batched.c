/* The batched bond loops of the linear peridynamic solid (pd/material_lps.c has the model and
 * its general loops), for a body of one horizon whose points all take the standard force:
 * the neighbours' records are transposed into batches (pd/bond_batch.h) and each batch is one
 * branch-free vector pass, as in pd/material_pmb.c.
 *   pass 1: theta_i = (3 / m_i) sum_j omega |xi| e V_j            (Silling et al. 2007, eq. 90)
 *   pass 2: f_i = sum_j (t_ij + t_ji) V_j (y_j - y_i) / |y_j - y_i|                   (eq. 94)
 * with t_ij = omega [ (3 K theta_i / m_i) |xi| + (15 G / m_i) (e - theta_i |xi| / 3) ]
 *           = omega (Q_i |xi| + 15 G e) / m_i,   Q_i = (3 K - 5 G) theta_i (less 15 G M_i / m_i once
 *             point i has lost bonds: pf_pd_lps_volumetric, docs/theory/materials.md §1, "Failed bonds"),
 * one expression whichever end evaluates it, so that both ends get the same bits. */
#include "pd/bond_batch.h"
#include "pd/pd_impl.h"

/* Pass 1 at point i: the sum of omega |xi| e V_j over its intact bonds, failing those whose
 * stretch exceeds min(s0_i, s0_j) (REC_AUX holds s0); the smallest stretch into *smin, the
 * number failed into *fresh. */
static inline __attribute__((always_inline)) double
dilatation_point(const pf_pd_body *restrict b, const double *restrict rec, pf_int i, const int weighted,
                 const int partial, double *smin, int *fresh) {
  enum { L = PF_BATCH };
  const pf_family *fam = &b->fam;
  uint8_t *restrict broken = fam->broken;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  double sum[L] = {0}, sm[L];
  for (int l = 0; l < L; l++) sm[l] = INFINITY;
  *fresh = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += L) {
    if (pf_batch_dead(broken, k0, end)) continue;
    const int n = end - k0 < L ? (int)(end - k0) : L;
    int32_t idx[L];
    double a[PF_REC][L], live[L], fails[L];
    pf_batch_lengths g;
    for (int l = 0; l < L; l++) idx[l] = fam->neighbor[k0 + l];
    pf_batch_live(broken + k0, n, live);
    pf_batch_gather(rec, idx, a);
    pf_batch_lengths_of(ri, a, &g);
#pragma omp simd
    for (int l = 0; l < L; l++) {
      const double s = (g.r[l] - g.r0[l]) * g.ir0[l];
      const double slim = ri[REC_AUX] < a[REC_AUX][l] ? ri[REC_AUX] : a[REC_AUX][l];
      const int fail = s > slim;
      fails[l] = live[l] > 0 && fail ? 1.0 : 0.0;
      const double alive = fail ? 0.0 : live[l];
      sm[l] = alive > 0 && s < sm[l] ? s : sm[l];
      const double om = weighted ? pf_pd_omega(&b->influence, g.r0[l]) : 1.0;
      const double vj = partial ? a[REC_V][l] * fam->vfrac[k0 + l] : a[REC_V][l];
      sum[l] += alive > 0 ? om * g.r0[l] * (g.r[l] - g.r0[l]) * vj : 0.0;
    }
    for (int l = 0; l < n; l++)
      if (fails[l] > 0) broken[k0 + l] = PF_BOND_FRESH, ++*fresh;
  }
  double total = 0;
  *smin = INFINITY;
  for (int l = 0; l < L; l++) total += sum[l], *smin = sm[l] < *smin ? sm[l] : *smin;
  return total;
}

/* Pass 2 at point i: the force density sum into f[3]; with `energy` (the body's energy limit:
 * critical_energy, Foster et al. 2011) a bond in tension whose energy per V_i V_j, (t_ij + t_ji) e / 2, exceeds wc (or
 * its own b->wc_bond) fails and gives no force. REC_AUX holds Q, rm[j] = 1 / m_j. Returns the number failed. */
static inline __attribute__((always_inline)) int
force_point(const pf_pd_body *restrict b, const double *restrict rec, const double *restrict rm, pf_int i,
            double g15, double wc, const int weighted, const int partial, const int energy, double f[3]) {
  enum { L = PF_BATCH };
  const pf_family *fam = &b->fam;
  uint8_t *restrict broken = fam->broken;
  const double *restrict wcb = b->wc_bond;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const double qi = ri[REC_AUX], rmi = rm[i];
  double f0[L] = {0}, f1[L] = {0}, f2[L] = {0};
  int failed = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += L) {
    if (pf_batch_dead(broken, k0, end)) continue;
    const int n = end - k0 < L ? (int)(end - k0) : L;
    int32_t idx[L];
    double a[PF_REC][L], live[L], fails[L], rmj[L];
    pf_batch_lengths g;
    for (int l = 0; l < L; l++) idx[l] = fam->neighbor[k0 + l];
    pf_batch_live(broken + k0, n, live);
    pf_batch_gather(rec, idx, a);
    pf_batch_gather1(rm, idx, rmj);
    pf_batch_lengths_of(ri, a, &g);
#pragma omp simd
    for (int l = 0; l < L; l++) {
      const double ext = g.r[l] - g.r0[l];
      const double om = weighted ? pf_pd_omega(&b->influence, g.r0[l]) : 1.0;
      const double tij = om * (qi * g.r0[l] + g15 * ext) * rmi;
      const double tji = om * (a[REC_AUX][l] * g.r0[l] + g15 * ext) * rmj[l];
      const double wcl = energy && wcb ? wcb[k0 + l] : wc;
      const int fail = energy ? (ext > 0) & (0.5 * (tij + tji) * ext > wcl) : 0;
      fails[l] = live[l] > 0 && fail ? 1.0 : 0.0;
      const double vj = partial ? a[REC_V][l] * fam->vfrac[k0 + l] : a[REC_V][l];
      const double fs = live[l] > 0 && !fail ? (tij + tji) * vj * g.ir[l] : 0.0;
      f0[l] += fs * g.e[0][l];
      f1[l] += fs * g.e[1][l];
      f2[l] += fs * g.e[2][l];
    }
    if (energy)
      for (int l = 0; l < n; l++)
        if (fails[l] > 0) broken[k0 + l] = PF_BOND_FRESH, failed++;
  }
  f[0] = f[1] = f[2] = 0;
  for (int l = 0; l < L; l++) f[0] += f0[l], f[1] += f1[l], f[2] += f2[l];
  return failed;
}

#if defined(PF_BATCH_AVX512)
/* omega(|xi|) of a batch for the influence function `kind` (pd/influence.c), in registers: 1,
 * the 1 / |xi| the geometry already holds, or exp(-|xi|^2 / sigma^2) (pf_batch_exp_v; nis2 =
 * -1 / sigma^2). Both ends of a bond compute it from the same |xi| bits, so they agree. */
static inline __attribute__((always_inline)) __m512d omega_v(const pf_batch_geom *g, const int kind, double nis2) {
  if (kind == PF_INFLUENCE_INVERSE_DISTANCE) return g->ir0;
  if (kind == PF_INFLUENCE_GAUSSIAN) return pf_batch_exp_v(_mm512_mul_pd(_mm512_mul_pd(g->r0, g->r0), _mm512_set1_pd(nis2)));
  return _mm512_set1_pd(1.0);
}

/* dilatation_point in AVX-512 registers (pf_batch_geom_v: the squared lengths with fused
 * multiply-adds, so the last bits differ from dilatation_point's). */
static inline __attribute__((always_inline)) double dilatation_point_avx512(const pf_pd_body *restrict b,
                                                                            const double *restrict rec,
                                                                            pf_int i, const int kind,
                                                                            const int partial, double *smin,
                                                                            int *fresh) {
  const double nis2 = -1.0 / (b->influence.length * b->influence.length);
  const pf_family *fam = &b->fam;
  uint8_t *restrict broken = fam->broken;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const __m512d s0i = _mm512_set1_pd(ri[REC_AUX]);
  __m512d SUM = _mm512_setzero_pd(), SM = _mm512_set1_pd(INFINITY);
  *fresh = 0;
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += PF_BATCH) {
    if (pf_batch_dead(fam->broken, k0, end)) continue;
    __m512d a[PF_REC];
    pf_batch_geom g;
    pf_batch_stretch t;
    pf_batch_load_v(fam, rec, ri, k0, end, s0i, partial, a, &g, &SM, &t);
    const __m512d ext = _mm512_sub_pd(g.r, g.r0);
    const __m512d wr0 = kind == PF_INFLUENCE_CONSTANT ? g.r0 : _mm512_mul_pd(omega_v(&g, kind, nis2), g.r0);
    SUM = _mm512_add_pd(SUM, _mm512_maskz_mov_pd(t.alive, _mm512_mul_pd(_mm512_mul_pd(wr0, ext), t.vj)));
    *fresh += pf_batch_mark_fresh(broken + k0, t.fail);
  }
  *smin = pf_batch_min_v(SM);
  return pf_batch_sum_v(SUM);
}

/* force_point for a stretch law in AVX-512 registers. */
static inline __attribute__((always_inline)) void force_point_avx512(const pf_pd_body *restrict b,
                                                                     const double *restrict rec,
                                                                     const double *restrict rm, pf_int i,
                                                                     double g15, const int kind,
                                                                     const int partial, double f[3]) {
  const double nis2 = -1.0 / (b->influence.length * b->influence.length);
  const pf_family *fam = &b->fam;
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const __m512d qi = _mm512_set1_pd(ri[REC_AUX]), rmi = _mm512_set1_pd(rm[i]), G = _mm512_set1_pd(g15);
  __m512d F[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
  const int64_t end = fam->offset[i - fam->first + 1];
  for (int64_t k0 = fam->offset[i - fam->first]; k0 < end; k0 += PF_BATCH) {
    if (pf_batch_dead(fam->broken, k0, end)) continue;
    const int n = end - k0 < PF_BATCH ? (int)(end - k0) : PF_BATCH;
    const int32_t *idx = fam->neighbor + k0;
    __m512d a[PF_REC];
    pf_batch_geom g;
    pf_batch_gather_v(rec, idx, a);
    const __m512d rmj = _mm512_set_pd(rm[idx[7]], rm[idx[6]], rm[idx[5]], rm[idx[4]], rm[idx[3]], rm[idx[2]],
                                      rm[idx[1]], rm[idx[0]]);
    const __mmask8 live = pf_batch_live_m(fam->broken + k0, n);
    pf_batch_geom_v(a, ri, &g);
    const __m512d ext = _mm512_sub_pd(g.r, g.r0), gext = _mm512_mul_pd(G, ext);
    __m512d tij = _mm512_add_pd(_mm512_mul_pd(qi, g.r0), gext);
    __m512d tji = _mm512_add_pd(_mm512_mul_pd(a[REC_AUX], g.r0), gext);
    if (kind != PF_INFLUENCE_CONSTANT) {
      const __m512d om = omega_v(&g, kind, nis2);
      tij = _mm512_mul_pd(om, tij), tji = _mm512_mul_pd(om, tji);
    }
    tij = _mm512_mul_pd(tij, rmi), tji = _mm512_mul_pd(tji, rmj);
    __m512d vj = a[REC_V];
    if (partial) vj = _mm512_mul_pd(vj, _mm512_cvtps_pd(_mm256_loadu_ps(fam->vfrac + k0)));
    const __m512d fs = _mm512_maskz_mov_pd(live, _mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(tij, tji), vj), g.ir));
    for (int q = 0; q < 3; q++) F[q] = _mm512_add_pd(F[q], _mm512_mul_pd(fs, g.e[q]));
  }
  for (int q = 0; q < 3; q++) f[q] = pf_batch_sum_v(F[q]);
}
#endif

/* Pass 1 over the points [lo, hi); returns 1 when some point lost bonds (its lost flag set). */
static inline __attribute__((always_inline)) int dilatations(pf_pd_body *b, const double *rec, const double *m,
                                                             double *theta, pf_int lo, pf_int hi,
                                                             const int kind, const int partial) {
  int any = 0;
  for (pf_int i = lo; i < hi; i++) {
    int fresh;
#if defined(PF_BATCH_AVX512)
    const double sum = dilatation_point_avx512(b, rec, i, kind, partial, &b->smin[i - b->first], &fresh);
#else
    const double sum = dilatation_point(b, rec, i, kind != PF_INFLUENCE_CONSTANT, partial, &b->smin[i - b->first],
                                        &fresh);
#endif
    b->lost[i - b->first] = fresh > 0;
    any |= fresh > 0;
    theta[i] = 3.0 * sum / m[i];
  }
  return any;
}

/* Owner computes: a point writes only its own theta, force, smin and row, so the threads (each a
 * contiguous range of points) share nothing; the released energy is booked after, in point
 * order, so the bits do not depend on the thread count. */
void pf_pd_lps_batched_dilatation(pf_pd_body *b, const pf_points *pts, const double *rec, const double *m,
                                  double *theta) {
  const pf_influence_kind kind = b->influence.kind;
  const int partial = b->fam.vfrac != NULL;
  int any = 0;
#pragma omp parallel reduction(| : any)
  {
    pf_int lo, hi;
    pf_thread_range(b->first, b->n, &lo, &hi);
#define PF_DILATATIONS(K)                                                                          \
  any = partial ? dilatations(b, rec, m, theta, lo, hi, K, 1) : dilatations(b, rec, m, theta, lo, hi, K, 0)
    if (kind == PF_INFLUENCE_CONSTANT) PF_DILATATIONS(PF_INFLUENCE_CONSTANT);
    else if (kind == PF_INFLUENCE_INVERSE_DISTANCE) PF_DILATATIONS(PF_INFLUENCE_INVERSE_DISTANCE);
    else PF_DILATATIONS(PF_INFLUENCE_GAUSSIAN);
#undef PF_DILATATIONS
  }
  for (pf_int i = b->first; any && i < b->first + b->n; i++)
    if (b->lost[i - b->first]) b->damage_work += pf_pd_lps_release(b, pts, i, m[i], NULL, 0);
}

/* Pass 2 over the points [lo, hi); returns the number of bonds failed. */
static inline __attribute__((always_inline)) int64_t forces(pf_pd_body *b, pf_points *pts, const double *rec,
                                                            const double *rm, pf_int lo, pf_int hi,
                                                            const int kind, const int partial,
                                                            const int energy) {
  const double g15 = 15.0 * b->shear_modulus, wc = b->critical_energy;
  const int weighted = kind != PF_INFLUENCE_CONSTANT;
  int64_t failed = 0;
  for (pf_int i = lo; i < hi; i++) {
    double f[3];
#if defined(PF_BATCH_AVX512)
    if (!energy) force_point_avx512(b, rec, rm, i, g15, kind, partial, f);
    else
#endif
      failed += force_point(b, rec, rm, i, g15, wc, weighted, partial, energy, f);
    for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * f[a];
  }
  return failed;
}

int64_t pf_pd_lps_batched_force(pf_pd_body *b, pf_points *pts, const double *rec, const double *rm) {
  const pf_influence_kind kind = b->influence.kind;
  const int partial = b->fam.vfrac != NULL, energy = pf_pd_energy_limited(b);
  int64_t failed = 0;
#pragma omp parallel reduction(+ : failed)
  {
    pf_int lo, hi;
    pf_thread_range(b->first, b->n, &lo, &hi);
#define PF_FORCES(K)                                                                               \
  failed = partial ? forces(b, pts, rec, rm, lo, hi, K, 1, 0) : forces(b, pts, rec, rm, lo, hi, K, 0, 0)
    if (energy) failed = forces(b, pts, rec, rm, lo, hi, kind, partial, 1);
    else if (kind == PF_INFLUENCE_CONSTANT) PF_FORCES(PF_INFLUENCE_CONSTANT);
    else if (kind == PF_INFLUENCE_INVERSE_DISTANCE) PF_FORCES(PF_INFLUENCE_INVERSE_DISTANCE);
    else PF_FORCES(PF_INFLUENCE_GAUSSIAN);
#undef PF_FORCES
  }
  return failed;
}
