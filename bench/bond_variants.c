/* Two bond-loop designs perifem does not use, timed against its PMB force pass (issue 9,
 * bench/measurements.md "What 10x would take"). All three on test_bond_loop_speed's 30^3 lattice
 * (pf_test_bond_lattice: horizon 3 spacings, 113 bonds a point inside, random displacements of
 * up to 0.5e-6 m), interleaved, best of 9:
 *  - production: pf_pd_body_force, every directed bond evaluated at its owner (owner computes),
 *    double precision, AVX-512 batches of 8 (pd/material_pmb.c);
 *  - half: each pair once (j > i), its force added to i and subtracted from j (Newton's third
 *    law) by one 256-bit update of j's row of four (scatter_sub), the same batches and
 *    arithmetic;
 *  - mixed: every directed bond, the differences xi = X_j - X_i and eta = u_j - u_i formed in
 *    double, the rest in single precision with the stretch written as
 *    s = (2 xi.eta + eta.eta) / (|xi| (|xi + eta| + |xi|)), which has no cancellation (exactly 0
 *    at rest), and the force sums in double.
 *  - half, fixed point: the half-bond loop with every force summed as a 64-bit integer count of
 *    2^-40 N (one rounding per bond and side), so that the sums do not depend on their order and
 *    therefore not on the partition or the thread count;
 *  - half, gathered: pass 1 computes each pair's force scale w = c s V_i V_j / r once (j > i) and
 *    stores it in both directed slots (i's and, through the reverse index, j's); pass 2 walks
 *    every full row in its order and sums w (y_j - y_i), so each point's sum has the production
 *    loop's order whatever the partition (the "computed once per undirected bond and
 *    gathered in row order").
 * Each prints its rate in directed bond evaluations per second, its ratio to production and
 * its largest force difference from production. Usage: bench_bond_variants (one rank). */
#include "sim/sim.h"
#include "pd/bond_batch.h"
#include "pd/pd.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(PF_BATCH_AVX512)
static const double BULK = 1.0e9, HORIZON = 3.0001e-3; /* those of pf_test_bond_lattice */

/* The pairs (i, j > i) of the family, row by row, with 8 slack entries; for each pair its two
 * directed slots in the full rows, i's (slot) and j's (rev). */
typedef struct {
  int64_t *off;
  int32_t *nb, *slot, *rev;
} half_list;

static half_list half_of(const pf_family *fam, pf_int n) {
  const size_t cap = (size_t)fam->offset[n] / 2 + 16;
  half_list h = {malloc((size_t)(n + 1) * sizeof *h.off), calloc(cap, sizeof *h.nb), calloc(cap, sizeof *h.slot),
                 calloc(cap, sizeof *h.rev)};
  int64_t m = 0;
  for (pf_int i = 0; i < n; i++) {
    h.off[i] = m;
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
      const pf_int j = fam->neighbor[k];
      if (j <= i) continue;
      int64_t kr = fam->offset[j];
      while (fam->neighbor[kr] != i) kr++; /* the family is symmetric on one rank */
      h.nb[m] = j, h.slot[m] = (int32_t)k, h.rev[m] = (int32_t)kr, m++;
    }
  }
  h.off[n] = m;
  return h;
}

static void half_free(half_list *h) { free(h->off), free(h->nb), free(h->slot), free(h->rev); }

/* F[4 j + q] -= v[q] lane l for the nn lanes l (j = idx[l]): the three vectors transposed into
 * rows of four (the fourth 0) by 4 unpacks and 4 permutes, each row one 256-bit
 * load-subtract-store (the lanes' j are distinct). */
static inline void scatter_sub(double *F, const int32_t *idx, int nn, const __m512d v[3]) {
  const __m512d z = _mm512_setzero_pd();
  const __m512d xy0 = _mm512_unpacklo_pd(v[0], v[1]), xy1 = _mm512_unpackhi_pd(v[0], v[1]);
  const __m512d z0 = _mm512_unpacklo_pd(v[2], z), z1 = _mm512_unpackhi_pd(v[2], z);
  const __m512i lo = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0), hi = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4);
  /* rows (lanes) 0, 2 | 4, 6 | 1, 3 | 5, 7 */
  const __m512d r[4] = {_mm512_permutex2var_pd(xy0, lo, z0), _mm512_permutex2var_pd(xy0, hi, z0),
                        _mm512_permutex2var_pd(xy1, lo, z1), _mm512_permutex2var_pd(xy1, hi, z1)};
  static const int lane[4][2] = {{0, 2}, {4, 6}, {1, 3}, {5, 7}};
  for (int q = 0; q < 4; q++)
    for (int hh = 0; hh < 2; hh++) {
      const int l = lane[q][hh];
      if (l >= nn) continue;
      double *fj = F + 4 * (size_t)idx[l];
      const __m256d row = hh ? _mm512_extractf64x4_pd(r[q], 1) : _mm512_castpd512_pd256(r[q]);
      _mm256_storeu_pd(fj, _mm256_sub_pd(_mm256_loadu_pd(fj), row));
    }
}

/* As scatter_sub for rows of four 64-bit integers: v holds the counts' bits (cast to double
 * only to be transposed by the same permutes); each row one 256-bit integer subtract. Written
 * out again on purpose: with the transpose shared through an array of eight rows, GCC kept the
 * rows in memory and the fixed-point loop measured 1.03x production instead of 1.28x. */
static inline void scatter_sub_q(int64_t *F, const int32_t *idx, int nn, const __m512d v[3]) {
  const __m512d z = _mm512_setzero_pd();
  const __m512d xy0 = _mm512_unpacklo_pd(v[0], v[1]), xy1 = _mm512_unpackhi_pd(v[0], v[1]);
  const __m512d z0 = _mm512_unpacklo_pd(v[2], z), z1 = _mm512_unpackhi_pd(v[2], z);
  const __m512i lo = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0), hi = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4);
  const __m512d r[4] = {_mm512_permutex2var_pd(xy0, lo, z0), _mm512_permutex2var_pd(xy0, hi, z0),
                        _mm512_permutex2var_pd(xy1, lo, z1), _mm512_permutex2var_pd(xy1, hi, z1)};
  static const int lane[4][2] = {{0, 2}, {4, 6}, {1, 3}, {5, 7}};
  for (int q = 0; q < 4; q++)
    for (int hh = 0; hh < 2; hh++) {
      const int l = lane[q][hh];
      if (l >= nn) continue;
      __m256i *fj = (__m256i *)(F + 4 * (size_t)idx[l]);
      const __m256i row = _mm256_castpd_si256(hh ? _mm512_extractf64x4_pd(r[q], 1) : _mm512_castpd512_pd256(r[q]));
      _mm256_storeu_si256(fj, _mm256_sub_epi64(_mm256_loadu_si256(fj), row));
    }
}

/* The lanes of the half-bond batch from k0 of a row ending at end: the neighbours' records in a,
 * the geometry in g, the stretch s; returns the lanes whose bond holds (s <= min(s0_i, s0_j),
 * REC_AUX holding s0). */
static inline __attribute__((always_inline)) __mmask8 half_geom(const half_list *h, const double *rec,
                                                                const double *ri, int64_t k0, int64_t end,
                                                                __m512d a[PF_REC], pf_batch_geom *g, __m512d *s) {
  const int nn = end - k0 < PF_BATCH ? (int)(end - k0) : PF_BATCH;
  pf_batch_gather_v(rec, h->nb + k0, a);
  pf_batch_geom_v(a, ri, g);
  *s = _mm512_mul_pd(_mm512_sub_pd(g->r, g->r0), g->ir0);
  const __mmask8 over = _mm512_cmp_pd_mask(*s, _mm512_min_pd(_mm512_set1_pd(ri[REC_AUX]), a[REC_AUX]), _CMP_GT_OQ);
  return (__mmask8)(((1u << nn) - 1u) & ~over);
}

/* The half-bond PMB batch: the pair force c s V_i V_j e / r (Silling & Askari 2005, eq. 7) as
 * w = c s V_i V_j / r and the vectors fe = w e (zero in the lanes that do not hold). */
static inline __attribute__((always_inline)) void half_batch(const half_list *h, const double *rec, const double *ri,
                                                             int64_t k0, int64_t end, __m512d cc, __m512d *w,
                                                             __m512d fe[3]) {
  __m512d a[PF_REC], s;
  pf_batch_geom g;
  const __mmask8 alive = half_geom(h, rec, ri, k0, end, a, &g, &s);
  *w = _mm512_maskz_mov_pd(alive, _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(cc, s), g.ir),
                                                _mm512_mul_pd(_mm512_set1_pd(ri[REC_V]), a[REC_V])));
  for (int q = 0; q < 3; q++) fe[q] = _mm512_mul_pd(*w, g.e[q]);
}

/* Half-bond PMB: F (forces, N, rows of four) of the n points; each pair's force goes to i and,
 * negated, to j. */
static void half_pmb(const half_list *h, const double *rec, pf_int n, double c, double *F) {
  const __m512d cc = _mm512_set1_pd(c);
  memset(F, 0, 4 * (size_t)n * sizeof *F);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec + PF_REC * (size_t)i;
    __m512d Fi[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      const int nn = h->off[i + 1] - k0 < PF_BATCH ? (int)(h->off[i + 1] - k0) : PF_BATCH;
      __m512d w, fe[3];
      half_batch(h, rec, ri, k0, h->off[i + 1], cc, &w, fe);
      for (int q = 0; q < 3; q++) Fi[q] = _mm512_add_pd(Fi[q], fe[q]);
      scatter_sub(F, h->nb + k0, nn, fe);
    }
    for (int q = 0; q < 3; q++) F[4 * i + q] += pf_batch_sum_v(Fi[q]);
  }
}

enum { FIX_BITS = 40 }; /* the fixed-point unit: 2^-40 N */

/* Half-bond PMB summed in fixed point: Fq (rows of four 64-bit counts of 2^-40 N) gets each
 * pair's force, rounded once, added to i and subtracted from j; integer sums are exact, so the
 * result does not depend on the order of the pairs. F (rows of three) is Fq in newtons. */
static void half_fixed_pmb(const half_list *h, const double *rec, pf_int n, double c, int64_t *Fq, double *F) {
  const __m512d cc = _mm512_set1_pd(c), unit = _mm512_set1_pd(ldexp(1.0, FIX_BITS));
  memset(Fq, 0, 4 * (size_t)n * sizeof *Fq);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec + PF_REC * (size_t)i;
    __m512i Fi[3] = {_mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512()};
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      __m512d w, fe[3];
      half_batch(h, rec, ri, k0, h->off[i + 1], cc, &w, fe);
      __m512d fq[3];
      for (int q = 0; q < 3; q++) {
        const __m512i k = _mm512_cvtpd_epi64(_mm512_mul_pd(fe[q], unit));
        Fi[q] = _mm512_add_epi64(Fi[q], k);
        fq[q] = _mm512_castsi512_pd(k);
      }
      const int nn = h->off[i + 1] - k0 < PF_BATCH ? (int)(h->off[i + 1] - k0) : PF_BATCH;
      scatter_sub_q(Fq, h->nb + k0, nn, fq);
    }
    for (int q = 0; q < 3; q++) Fq[4 * i + q] += _mm512_reduce_add_epi64(Fi[q]);
  }
  for (pf_int i = 0; i < n; i++)
    for (int q = 0; q < 3; q++) F[3 * i + q] = ldexp((double)Fq[4 * i + q], -FIX_BITS);
}

/* Half-bond PMB, gathered: pass 1 stores each pair's w = c s V_i V_j / r once, in pair order
 * (wh); pass 2 walks every full row in row order, gathers w through the slot's pair index (pk)
 * and y_j from rows of four (y4), and sums w (y_j - y_i): production's order of the terms. */
static void half_gathered_pmb(const half_list *h, const pf_family *fam, const int32_t *pk, const double *rec,
                              const double *y4, pf_int n, double c, double *wh, double *F) {
  const __m512d cc = _mm512_set1_pd(c);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec + PF_REC * (size_t)i;
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      __m512d w, fe[3];
      half_batch(h, rec, ri, k0, h->off[i + 1], cc, &w, fe);
      _mm512_storeu_pd(wh + k0, w);
    }
  }
  const __m512i lo = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0), hi = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  for (pf_int i = 0; i < n; i++) {
    const __m512d yi[3] = {_mm512_set1_pd(y4[4 * i]), _mm512_set1_pd(y4[4 * i + 1]), _mm512_set1_pd(y4[4 * i + 2])};
    __m512d Fi[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
    const int64_t end = fam->offset[i + 1];
    for (int64_t k0 = fam->offset[i]; k0 < end; k0 += PF_BATCH) {
      const __mmask8 lanes = (__mmask8)((1u << (end - k0 < PF_BATCH ? end - k0 : PF_BATCH)) - 1u);
      const int32_t *j = fam->neighbor + k0;
      /* rows l and l + 4 of y4 in one register each, then the 8 x 4 transpose */
      __m512d r[4], t[4];
      for (int l = 0; l < 4; l++)
        r[l] = _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_loadu_pd(y4 + 4 * (size_t)j[l])),
                                  _mm256_loadu_pd(y4 + 4 * (size_t)j[l + 4]), 1);
      t[0] = _mm512_unpacklo_pd(r[0], r[1]), t[1] = _mm512_unpackhi_pd(r[0], r[1]);
      t[2] = _mm512_unpacklo_pd(r[2], r[3]), t[3] = _mm512_unpackhi_pd(r[2], r[3]);
      /* t[0] = x0 x1 z0 z1 | x4 x5 z4 z5, t[1] = y0 y1 . . | y4 y5 . ., t[2], t[3] rows 2, 3, 6, 7 */
      const __m512d yx = _mm512_permutex2var_pd(t[0], lo, t[2]), yz = _mm512_permutex2var_pd(t[0], hi, t[2]);
      const __m512d yy = _mm512_permutex2var_pd(t[1], lo, t[3]);
      const __m512d yj[3] = {yx, yy, yz};
      const __m512d w = _mm512_mask_i32gather_pd(_mm512_setzero_pd(), lanes,
                                                 _mm256_loadu_si256((const __m256i *)(pk + k0)), wh, 8);
      for (int q = 0; q < 3; q++) Fi[q] = _mm512_fmadd_pd(w, _mm512_sub_pd(yj[q], yi[q]), Fi[q]);
    }
    for (int q = 0; q < 3; q++) F[3 * i + q] = pf_batch_sum_v(Fi[q]);
  }
}

/* Half-bond LPS (omega = 1) summed in fixed point, both passes (pd/lps_batched.c has the
 * production loops): pass 1 adds omega |xi| e V_j to i's and omega |xi| e V_i to j's dilatation
 * sum, as counts of 2^-100 m^5; pass 2 adds the pair force (t_ij + t_ji) V_i V_j (y_j - y_i) / r,
 * t_ij = (Q_i |xi| + 15 G e) / m_i, to i and subtracts it from j, as counts of 2^-40 N. rec holds
 * s0 in REC_AUX for pass 1 and is refilled with Q = (3 K - 5 G) theta for pass 2 (fill). */
typedef struct {
  const half_list *h;
  const double *rm; /* 1 / m_i */
  double g15, k3g5; /* 15 G, 3 K - 5 G */
  int64_t *Tq, *Fq; /* [n], [4 n] */
  double *q;        /* [n], Q_i = (3 K - 5 G) theta_i */
} half_lps;

static void half_fixed_lps(half_lps *L, pf_batch_records *rec, const pf_points *p, const double *s0, pf_int n,
                           double *F) {
  const half_list *h = L->h;
  const __m512d tu = _mm512_set1_pd(ldexp(1.0, 100)), fu = _mm512_set1_pd(ldexp(1.0, FIX_BITS));
  memset(L->Tq, 0, (size_t)n * sizeof *L->Tq), memset(L->Fq, 0, 4 * (size_t)n * sizeof *L->Fq);
  if (pf_batch_records_fill(rec, p, s0)) return;
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec->rec + PF_REC * (size_t)i;
    __m512i Ti = _mm512_setzero_si512();
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      const int nn = h->off[i + 1] - k0 < PF_BATCH ? (int)(h->off[i + 1] - k0) : PF_BATCH;
      __m512d a[PF_REC], st;
      pf_batch_geom g;
      const __mmask8 alive = half_geom(h, rec->rec, ri, k0, h->off[i + 1], a, &g, &st);
      const __m512d we = _mm512_maskz_mov_pd(alive, _mm512_mul_pd(_mm512_mul_pd(g.r0, _mm512_sub_pd(g.r, g.r0)), tu));
      Ti = _mm512_add_epi64(Ti, _mm512_cvtpd_epi64(_mm512_mul_pd(we, a[REC_V])));
      int64_t tj[PF_BATCH];
      _mm512_storeu_si512(tj, _mm512_cvtpd_epi64(_mm512_mul_pd(we, _mm512_set1_pd(ri[REC_V]))));
      for (int l = 0; l < nn; l++) L->Tq[h->nb[k0 + l]] += tj[l];
    }
    L->Tq[i] += _mm512_reduce_add_epi64(Ti);
  }
  for (pf_int i = 0; i < n; i++) L->q[i] = 3.0 * ldexp((double)L->Tq[i], -100) * L->rm[i] * L->k3g5;
  if (pf_batch_records_fill(rec, p, L->q)) return; /* Q_i in REC_AUX */
  const __m512d G = _mm512_set1_pd(L->g15);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec->rec + PF_REC * (size_t)i;
    const __m512d qi = _mm512_set1_pd(ri[REC_AUX]), rmi = _mm512_set1_pd(L->rm[i]), vi = _mm512_set1_pd(ri[REC_V]);
    __m512i Fi[3] = {_mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512()};
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      const int nn = h->off[i + 1] - k0 < PF_BATCH ? (int)(h->off[i + 1] - k0) : PF_BATCH;
      const int32_t *idx = h->nb + k0;
      __m512d a[PF_REC];
      pf_batch_geom g;
      pf_batch_gather_v(rec->rec, idx, a);
      const __m512d rmj = _mm512_i32gather_pd(_mm256_loadu_si256((const __m256i *)idx), L->rm, 8);
      pf_batch_geom_v(a, ri, &g);
      const __m512d gext = _mm512_mul_pd(G, _mm512_sub_pd(g.r, g.r0));
      const __m512d tij = _mm512_mul_pd(_mm512_fmadd_pd(qi, g.r0, gext), rmi);
      const __m512d tji = _mm512_mul_pd(_mm512_fmadd_pd(a[REC_AUX], g.r0, gext), rmj);
      const __m512d fs = _mm512_maskz_mov_pd((__mmask8)((1u << nn) - 1u),
                                             _mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(tij, tji), _mm512_mul_pd(vi, a[REC_V])),
                                                           _mm512_mul_pd(g.ir, fu)));
      __m512d fq[3];
      for (int q = 0; q < 3; q++) {
        const __m512i k = _mm512_cvtpd_epi64(_mm512_mul_pd(fs, g.e[q]));
        Fi[q] = _mm512_add_epi64(Fi[q], k), fq[q] = _mm512_castsi512_pd(k);
      }
      scatter_sub_q(L->Fq, idx, nn, fq);
    }
    for (int q = 0; q < 3; q++) L->Fq[4 * i + q] += _mm512_reduce_add_epi64(Fi[q]);
  }
  for (pf_int i = 0; i < n; i++)
    for (int q = 0; q < 3; q++) F[3 * i + q] = ldexp((double)L->Fq[4 * i + q], -FIX_BITS);
}

/* 1 / sqrt(x) and 1 / x in single precision: the 14-bit estimates and one Newton step. */
static inline __m256 rsqrt_ps(__m256 x) {
  const __m256 y = _mm256_rsqrt14_ps(x);
  return _mm256_mul_ps(y, _mm256_fnmadd_ps(_mm256_mul_ps(x, _mm256_set1_ps(0.5f)), _mm256_mul_ps(y, y),
                                           _mm256_set1_ps(1.5f)));
}
static inline __m256 rcp_ps(__m256 x) {
  const __m256 y = _mm256_rcp14_ps(x);
  return _mm256_mul_ps(y, _mm256_fnmadd_ps(x, y, _mm256_set1_ps(2.0f)));
}

/* Mixed-precision PMB over every directed bond (see the head of the file). */
static void mixed_pmb(const pf_family *fam, const double *rec, pf_int n, double c, double *F) {
  const __m256 cc = _mm256_set1_ps((float)c), two = _mm256_set1_ps(2.0f);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec + PF_REC * (size_t)i;
    const __m256 s0i = _mm256_set1_ps((float)ri[REC_AUX]);
    __m512d Fi[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
    const int64_t end = fam->offset[i + 1];
    for (int64_t k0 = fam->offset[i]; k0 < end; k0 += PF_BATCH) {
      __m512d a[PF_REC];
      pf_batch_gather_v(rec, fam->neighbor + k0, a);
      const __mmask8 live = pf_batch_live_m(fam->broken + k0, end - k0 < PF_BATCH ? (int)(end - k0) : PF_BATCH);
      __m256 d[3], h[3], e[3];
      for (int q = 0; q < 3; q++) {
        const __m512d xi = _mm512_sub_pd(a[REC_X + q], _mm512_set1_pd(ri[REC_X + q]));
        const __m512d ye = _mm512_sub_pd(a[REC_Y + q], _mm512_set1_pd(ri[REC_Y + q]));
        d[q] = _mm512_cvtpd_ps(xi), h[q] = _mm512_cvtpd_ps(_mm512_sub_pd(ye, xi));
        e[q] = _mm256_add_ps(d[q], h[q]);
      }
      const __m256 d2 = _mm256_fmadd_ps(d[0], d[0], _mm256_fmadd_ps(d[1], d[1], _mm256_mul_ps(d[2], d[2])));
      const __m256 dh = _mm256_fmadd_ps(d[0], h[0], _mm256_fmadd_ps(d[1], h[1], _mm256_mul_ps(d[2], h[2])));
      const __m256 hh = _mm256_fmadd_ps(h[0], h[0], _mm256_fmadd_ps(h[1], h[1], _mm256_mul_ps(h[2], h[2])));
      const __m256 num = _mm256_fmadd_ps(two, dh, hh), r2 = _mm256_add_ps(d2, num);
      const __m256 ir0 = rsqrt_ps(d2), ir = rsqrt_ps(r2);
      const __m256 sum = _mm256_fmadd_ps(d2, ir0, _mm256_mul_ps(r2, ir)); /* |xi| + |xi + eta| */
      const __m256 s = _mm256_mul_ps(_mm256_mul_ps(num, ir0), rcp_ps(sum));
      const __mmask8 over = _mm256_cmp_ps_mask(s, _mm256_min_ps(s0i, _mm512_cvtpd_ps(a[REC_AUX])), _CMP_GT_OQ);
      const __m256 w = _mm256_maskz_mov_ps((__mmask8)(live & ~over),
                                           _mm256_mul_ps(_mm256_mul_ps(cc, s), _mm256_mul_ps(ir, _mm512_cvtpd_ps(a[REC_V]))));
      for (int q = 0; q < 3; q++) Fi[q] = _mm512_add_pd(Fi[q], _mm512_cvtps_pd(_mm256_mul_ps(w, e[q])));
    }
    for (int q = 0; q < 3; q++) F[3 * i + q] = ri[REC_V] * pf_batch_sum_v(Fi[q]);
  }
}

/* The largest |a - b| over the n points' three components; a's rows hold stride doubles. */
static double max_diff(const double *a, int stride, const double *b, pf_int n) {
  double m = 0;
  for (pf_int i = 0; i < n; i++)
    for (int q = 0; q < 3; q++) m = fmax(m, fabs(a[stride * i + q] - b[3 * i + q]));
  return m;
}

/* The LPS lattice (pf_test_bond_lattice: K = 1e9, G = 0.6e9 Pa, omega = 1): the production
 * force (both passes) against half_fixed_lps, best of 9, interleaved. */
static void lps_variant(pf_batch_records *rec) {
  pf_sim *sim = pf_test_bond_lattice("lps");
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  const pf_family *fam = pf_pd_body_family(b);
  const pf_int n = p->n_owned;
  half_list h = half_of(fam, n);
  double *s0 = malloc((size_t)n * sizeof *s0), *rm = malloc((size_t)n * sizeof *rm),
         *q = malloc((size_t)n * sizeof *q), *F = malloc(3 * (size_t)n * sizeof *F);
  int64_t *Tq = malloc((size_t)n * sizeof *Tq), *Fq = aligned_alloc(64, (32 * (size_t)n + 63) / 64 * 64);
  for (pf_int i = 0; i < n; i++) {
    double m = 0;
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
      const pf_int j = fam->neighbor[k];
      double d2 = 0;
      for (int a = 0; a < 3; a++) d2 += (p->X[3 * j + a] - p->X[3 * i + a]) * (p->X[3 * j + a] - p->X[3 * i + a]);
      m += d2 * p->vol[j];
    }
    s0[i] = 0.5, rm[i] = 1.0 / m;
  }
  half_lps L = {&h, rm, 15 * 0.6e9, 3 * BULK - 5 * 0.6e9, Tq, Fq, q};
  double best[2] = {INFINITY, INFINITY};
  for (int rep = 0; rep < 9; rep++) {
    memset(p->f, 0, 3 * (size_t)n * sizeof *p->f);
    const double t0 = pf_wtime();
    if (pf_pd_body_force(b, p, 0.0)) return;
    const double t1 = pf_wtime();
    half_fixed_lps(&L, rec, p, s0, n, F);
    const double t2 = pf_wtime();
    best[0] = fmin(best[0], t1 - t0), best[1] = fmin(best[1], t2 - t1);
  }
  double fmax_ = 0;
  for (pf_int k = 0; k < 3 * n; k++) fmax_ = fmax(fmax_, fabs(p->f[k]));
  const double bonds = (double)fam->offset[n];
  printf("LPS (omega = 1), largest force %.3g N\n", fmax_);
  printf("%-19s %6.0f M directed bonds/s (both passes)\n", "production:", bonds / best[0] / 1e6);
  printf("%-19s %6.0f M directed bonds/s, %.2fx production, max force difference %.2g N\n", "half, fixed point:",
         bonds / best[1] / 1e6, best[0] / best[1], max_diff(F, 3, p->f, n));
  free(s0), free(rm), free(q), free(F), free(Tq), free(Fq), half_free(&h);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pf_sim *sim = pf_test_bond_lattice("pmb");
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  const pf_family *fam = pf_pd_body_family(b);
  const pf_int n = p->n_owned;
  half_list h = half_of(fam, n);
  const double c = 18 * BULK / (acos(-1.0) * pow(HORIZON, 4)), bonds = (double)fam->offset[n];
  double *s0 = malloc((size_t)n * sizeof *s0), *Fh = aligned_alloc(64, (32 * (size_t)n + 63) / 64 * 64),
         *Fm = malloc(3 * (size_t)n * sizeof *Fm), *Fx = malloc(3 * (size_t)n * sizeof *Fx),
         *Fg = malloc(3 * (size_t)n * sizeof *Fg), *wh = calloc((size_t)bonds / 2 + 16, sizeof *wh),
         *y4 = calloc(4 * (size_t)n, sizeof *y4);
  int32_t *pk = calloc((size_t)bonds + 16, sizeof *pk);
  for (int64_t m = 0; m < h.off[n]; m++) pk[h.slot[m]] = (int32_t)m, pk[h.rev[m]] = (int32_t)m;
  for (pf_int i = 0; i < n; i++)
    for (int q = 0; q < 3; q++) y4[4 * i + q] = p->y[3 * i + q];
  int64_t *Fq = aligned_alloc(64, (32 * (size_t)n + 63) / 64 * 64);
  for (pf_int i = 0; i < n; i++) s0[i] = 0.5;
  pf_batch_records rec = {0};
  enum { NV = 5 };
  static const char *name[NV] = {"production:", "half:", "mixed:", "half, fixed point:", "half, gathered:"};
  const double *force[NV] = {p->f, Fh, Fm, Fx, Fg};
  const int stride[NV] = {3, 4, 3, 3, 3};
  double best[NV] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
  for (int rep = 0; rep < 9; rep++) {
    memset(p->f, 0, 3 * (size_t)n * sizeof *p->f);
    double t[NV + 1];
    t[0] = pf_wtime();
    if (pf_pd_body_force(b, p, 0.0)) return 1;
    t[1] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    half_pmb(&h, rec.rec, n, c, Fh);
    t[2] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    mixed_pmb(fam, rec.rec, n, c, Fm);
    t[3] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    half_fixed_pmb(&h, rec.rec, n, c, Fq, Fx);
    t[4] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    half_gathered_pmb(&h, fam, pk, rec.rec, y4, n, c, wh, Fg);
    t[5] = pf_wtime();
    for (int v = 0; v < NV; v++) best[v] = fmin(best[v], t[v + 1] - t[v]);
  }
  double fmax_ = 0;
  for (pf_int k = 0; k < 3 * n; k++) fmax_ = fmax(fmax_, fabs(p->f[k]));
  printf("lattice 30^3, %.0f directed bonds; largest force %.3g N\n", bonds, fmax_);
  for (int v = 0; v < NV; v++)
    printf("%-19s %6.0f M directed bonds/s, %.2fx production, max force difference %.2g N\n", name[v],
           bonds / best[v] / 1e6, best[0] / best[v], v ? max_diff(force[v], stride[v], p->f, n) : 0.0);
  lps_variant(&rec);
  pf_batch_records_free(&rec);
  free(s0), free(Fh), free(Fm), free(Fx), free(Fg), free(wh), free(y4), free(pk), free(Fq), half_free(&h);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
#else
int main(void) {
  puts("bench_bond_variants: needs AVX-512 (the batches of pd/bond_batch.h); skipped");
  return 77;
}
#endif
