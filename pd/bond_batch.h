/* Private to pd/: the neighbours' data of a batch of PF_BATCH bonds, for vector bond loops.
 *
 * A kernel keeps, for every store point, one 64-byte record of eight doubles (for PMB:
 * X, V, y, s0). A batch of bonds reads its PF_BATCH neighbours' records and transposes them,
 * so that field f of the batch's neighbour l lands in out[f][l]: eight whole-line loads and
 * 24 two-source permutes with AVX-512, where the compiler's per-field gathers are
 * load-port-bound (bench/measurements.md, "Where the time goes"); four 4 x 4 transposes with AVX2; a
 * plain copy otherwise. Either way the values are bitwise the records'. */
#ifndef PF_BOND_BATCH_H
#define PF_BOND_BATCH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "pd/pd_impl.h"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif
#if defined(_OPENMP)
#include <omp.h>
#endif

enum { PF_BATCH = 8, PF_REC = 8 }; /* bonds per batch; doubles per record */

/* The standard record of a store point: reference position, volume, current position and one
 * more value (REC_AUX: the critical stretch, or what a material puts there). */
enum { REC_X = 0, REC_V = 3, REC_Y = 4, REC_AUX = 7 };

/* A material's records, 64-byte aligned so that each record is one cache line. */
typedef struct {
  double *rec; /* [PF_REC * cap] */
  size_t cap;
} pf_batch_records;

/* Fill the standard records of every store point (owned and ghosts), with aux[j] (or 0 when
 * aux is NULL) in REC_AUX, growing the array as needed (pd/bond_batch.c). */
int pf_batch_records_fill(pf_batch_records *r, const pf_points *pts, const double *aux);
void pf_batch_records_free(pf_batch_records *r);

#if defined(__AVX512F__)
/* v[f] lane l = rec[PF_REC * idx[l] + f] for f, l < 8, in registers. */
static inline __attribute__((always_inline)) void pf_batch_gather_v(const double *restrict rec,
                                                                    const int32_t *idx, __m512d v[PF_REC]) {
  __m512d r[8], t[8], u[8];
  for (int l = 0; l < 8; l++) r[l] = _mm512_load_pd(rec + (size_t)PF_REC * (size_t)idx[l]);
  /* stage 1: pairs of rows, element-wise interleave: t[2p] = (fields 0 2 4 6 of rows 2p, 2p+1) */
  for (int p = 0; p < 4; p++) {
    t[2 * p] = _mm512_unpacklo_pd(r[2 * p], r[2 * p + 1]);
    t[2 * p + 1] = _mm512_unpackhi_pd(r[2 * p], r[2 * p + 1]);
  }
  /* stage 2: two-element blocks; u[q] (rows 0-3) and u[4 + q] (rows 4-7) take fields q and
   * q + 4 for q = 0, 1, 2, 3 */
  const __m512i lo2 = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i hi2 = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  for (int h = 0; h < 2; h++)
    for (int p = 0; p < 2; p++) {
      u[4 * h + p] = _mm512_permutex2var_pd(t[4 * h + p], lo2, t[4 * h + 2 + p]);
      u[4 * h + 2 + p] = _mm512_permutex2var_pd(t[4 * h + p], hi2, t[4 * h + 2 + p]);
    }
  /* stage 3: u[q] (rows 0-3) and u[4 + q] (rows 4-7) hold fields q and q + 4 */
  const __m512i lo4 = _mm512_set_epi64(11, 10, 9, 8, 3, 2, 1, 0);
  const __m512i hi4 = _mm512_set_epi64(15, 14, 13, 12, 7, 6, 5, 4);
  for (int q = 0; q < 4; q++) {
    v[q] = _mm512_permutex2var_pd(u[q], lo4, u[4 + q]);
    v[q + 4] = _mm512_permutex2var_pd(u[q], hi4, u[4 + q]);
  }
}

/* 1 / sqrt(x) lane-wise: the 14-bit estimate and two Newton steps (see pf_batch_rsqrt). */
static inline __attribute__((always_inline)) __m512d pf_batch_rsqrt_v(__m512d x) {
  const __m512d h = _mm512_mul_pd(x, _mm512_set1_pd(0.5));
  __m512d y = _mm512_rsqrt14_pd(x);
  for (int it = 0; it < 2; it++)
    y = _mm512_mul_pd(y, _mm512_fnmadd_pd(h, _mm512_mul_pd(y, y), _mm512_set1_pd(1.5)));
  return y;
}

/* exp(x) lane-wise for -708 < x < 709, to about one unit in the last place: x = n ln 2 + r with
 * n = round(x / ln 2) and ln 2 split in two (Cody & Waite 1980), so |r| <= ln 2 / 2 exactly;
 * e^r by its Taylor series to r^13 / 13! (the first term left out, r^14 / 14! < 5e-18, is below
 * half an ulp); times 2^n by scalef. Deterministic: the same x gives the same bits. */
static inline __attribute__((always_inline)) __m512d pf_batch_exp_v(__m512d x) {
  const __m512d n = _mm512_roundscale_pd(_mm512_mul_pd(x, _mm512_set1_pd(1.4426950408889634)),
                                         _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m512d r = _mm512_fnmadd_pd(n, _mm512_set1_pd(6.93147180369123816490e-01), x);
  r = _mm512_fnmadd_pd(n, _mm512_set1_pd(1.90821492927058770002e-10), r);
  static const double inv_factorial[14] = {1.0, 1.0, 0.5, 0.16666666666666666,
      0.041666666666666664, 0.008333333333333333, 0.001388888888888889, 0.0001984126984126984,
      2.48015873015873e-05, 2.7557319223985893e-06, 2.755731922398589e-07, 2.505210838544172e-08,
      2.08767569878681e-09, 1.6059043836821613e-10};
  __m512d p = _mm512_set1_pd(inv_factorial[13]);
  for (int k = 12; k >= 0; k--) p = _mm512_fmadd_pd(p, r, _mm512_set1_pd(inv_factorial[k]));
  return _mm512_scalef_pd(p, n);
}
#if defined(__AVX512BW__) && defined(__AVX512VL__)
#define PF_BATCH_AVX512 1
/* The live lanes of a batch: l < n and broken[l] == 0. */
static inline __attribute__((always_inline)) __mmask8 pf_batch_live_m(const uint8_t *broken, int n) {
  return (__mmask8)(_mm_cmpeq_epi8_mask(_mm_loadl_epi64((const __m128i *)broken), _mm_setzero_si128()) &
                    ((1u << n) - 1u));
}

/* A batch's bond geometry in registers: r0 = |xi|, r = |y_j - y_i|, their inverses, e = y_j - y_i.
 * The squared lengths are summed with fused multiply-adds (so the last bits differ from the
 * portable loops'); the two ends of a bond square negated differences, so they still agree. */
typedef struct {
  __m512d r0, r, ir0, ir, e[3];
} pf_batch_geom;

static inline __attribute__((always_inline)) void pf_batch_geom_v(const __m512d a[PF_REC], const double *ri,
                                                                  pf_batch_geom *g) {
  __m512d d[3];
  for (int c = 0; c < 3; c++) {
    d[c] = _mm512_sub_pd(a[REC_X + c], _mm512_set1_pd(ri[REC_X + c]));
    g->e[c] = _mm512_sub_pd(a[REC_Y + c], _mm512_set1_pd(ri[REC_Y + c]));
  }
  const __m512d d2 = _mm512_fmadd_pd(d[0], d[0], _mm512_fmadd_pd(d[1], d[1], _mm512_mul_pd(d[2], d[2])));
  const __m512d e2 =
      _mm512_fmadd_pd(g->e[0], g->e[0], _mm512_fmadd_pd(g->e[1], g->e[1], _mm512_mul_pd(g->e[2], g->e[2])));
  g->ir0 = pf_batch_rsqrt_v(d2), g->ir = pf_batch_rsqrt_v(e2);
  g->r0 = _mm512_mul_pd(d2, g->ir0), g->r = _mm512_mul_pd(e2, g->ir);
}

/* The stretch test of a batch (Silling & Askari 2005): s = (r - r0) / r0; a live bond fails
 * when s > min(s0_i, s0_j) (s0 in REC_AUX); *smin keeps, lane by lane, the smallest stretch of
 * the bonds that stay; vj is V_j, times the partial-volume fraction when vfrac is given (the
 * batch's eight). */
typedef struct {
  __m512d s, vj;
  __mmask8 fail, alive; /* fail: live bonds that fail now; alive: live bonds that stay */
} pf_batch_stretch;

static inline __attribute__((always_inline)) void pf_batch_stretch_v(const pf_batch_geom *g, const __m512d a[PF_REC],
                                                                     __m512d s0i, __mmask8 live,
                                                                     const float *vfrac, __m512d *smin,
                                                                     pf_batch_stretch *t) {
  t->s = _mm512_mul_pd(_mm512_sub_pd(g->r, g->r0), g->ir0);
  const __mmask8 over = _mm512_cmp_pd_mask(t->s, _mm512_min_pd(s0i, a[REC_AUX]), _CMP_GT_OQ);
  t->fail = (__mmask8)(live & over), t->alive = (__mmask8)(live & ~over);
  *smin = _mm512_mask_mov_pd(*smin, (__mmask8)(t->alive & _mm512_cmp_pd_mask(t->s, *smin, _CMP_LT_OQ)), t->s);
  t->vj = vfrac ? _mm512_mul_pd(a[REC_V], _mm512_cvtps_pd(_mm256_loadu_ps(vfrac))) : a[REC_V];
}

/* Load the batch of bonds from k0 of point i (record ri; its row ends at end): the neighbours'
 * records into a, the geometry into g, the stretch test into t (pf_batch_stretch_v). */
static inline __attribute__((always_inline)) void pf_batch_load_v(const pf_family *fam, const double *rec,
                                                                  const double *ri, int64_t k0, int64_t end,
                                                                  __m512d s0i, int partial, __m512d a[PF_REC],
                                                                  pf_batch_geom *g, __m512d *smin,
                                                                  pf_batch_stretch *t) {
  pf_batch_gather_v(rec, fam->neighbor + k0, a);
  pf_batch_geom_v(a, ri, g);
  const int n = end - k0 < PF_BATCH ? (int)(end - k0) : PF_BATCH;
  pf_batch_stretch_v(g, a, s0i, pf_batch_live_m(fam->broken + k0, n), partial ? fam->vfrac + k0 : NULL, smin, t);
}

/* Mark the bonds of mask fail (lanes of the batch at broken) PF_BOND_FRESH; returns their number. */
static inline int pf_batch_mark_fresh(uint8_t *broken, __mmask8 fail) {
  int n = 0;
  for (int l = 0; fail && l < PF_BATCH; l++)
    if ((unsigned)fail >> l & 1u) broken[l] = PF_BOND_FRESH, n++;
  return n;
}

/* The sum of the lanes in lane order. */
static inline double pf_batch_sum_v(__m512d v) {
  double x[PF_BATCH], s = 0;
  _mm512_storeu_pd(x, v);
  for (int l = 0; l < PF_BATCH; l++) s += x[l];
  return s;
}

/* The smallest lane of v (the ?: keeps it branch-free; lanes that are NaN are passed over). */
static inline double pf_batch_min_v(__m512d v) {
  double x[PF_BATCH], m = INFINITY;
  _mm512_storeu_pd(x, v);
  for (int l = 0; l < PF_BATCH; l++) m = x[l] < m ? x[l] : m;
  return m;
}
#endif
#endif

/* out[f][l] = rec[PF_REC * idx[l] + f] for f, l < 8. */
static inline void pf_batch_gather(const double *restrict rec, const int32_t idx[PF_BATCH],
                                   double out[PF_REC][PF_BATCH]) {
#if defined(__AVX512F__)
  __m512d v[PF_REC];
  pf_batch_gather_v(rec, idx, v);
  for (int f = 0; f < PF_REC; f++) _mm512_storeu_pd(out[f], v[f]);
#elif defined(__AVX2__)
  /* four 4 x 4 transposes: rows l0..l0+3, fields h..h+3 (two unpacks and two lane swaps) */
  for (int l0 = 0; l0 < PF_BATCH; l0 += 4)
    for (int h = 0; h < PF_REC; h += 4) {
      __m256d r[4];
      for (int q = 0; q < 4; q++) r[q] = _mm256_loadu_pd(rec + (size_t)PF_REC * (size_t)idx[l0 + q] + h);
      const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
      const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
      _mm256_storeu_pd(&out[h][l0], _mm256_permute2f128_pd(t0, t2, 0x20));
      _mm256_storeu_pd(&out[h + 1][l0], _mm256_permute2f128_pd(t1, t3, 0x20));
      _mm256_storeu_pd(&out[h + 2][l0], _mm256_permute2f128_pd(t0, t2, 0x31));
      _mm256_storeu_pd(&out[h + 3][l0], _mm256_permute2f128_pd(t1, t3, 0x31));
    }
#else
  for (int l = 0; l < PF_BATCH; l++)
    for (int f = 0; f < PF_REC; f++) out[f][l] = rec[(size_t)PF_REC * (size_t)idx[l] + f];
#endif
}

/* x[l] = 1 / sqrt(x[l]) for the PF_BATCH lanes, to about one unit in the last place: with
 * AVX-512 the 14-bit estimate refined by two Newton steps y <- y (3/2 - x y^2 / 2) (14, 28,
 * 56 bits), half the time of a square root alone; else 1 / sqrt. The same inputs give the
 * same bits, so the two ends of a bond still agree. */
static inline void pf_batch_rsqrt(double x[PF_BATCH]) {
#if defined(__AVX512F__)
  _mm512_storeu_pd(x, pf_batch_rsqrt_v(_mm512_loadu_pd(x)));
#else
  for (int l = 0; l < PF_BATCH; l++) x[l] = 1.0 / sqrt(x[l]);
#endif
}

/* live[l] = 1 where l < n and broken[l] == 0, else 0 (broken: the batch's PF_BATCH flags;
 * the rows' slack makes the whole batch readable). One vector store, so that the bond loop's
 * vector load of live[] is forwarded from it (eight scalar stores are not). */
static inline void pf_batch_live(const uint8_t *broken, int n, double live[PF_BATCH]) {
#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
  const __mmask8 intact = (__mmask8)(_mm_cmpeq_epi8_mask(_mm_loadl_epi64((const __m128i *)broken),
                                                         _mm_setzero_si128()) &
                                     ((1u << n) - 1u));
  _mm512_storeu_pd(live, _mm512_maskz_mov_pd(intact, _mm512_set1_pd(1.0)));
#elif defined(__AVX2__)
  const __m128i z = _mm_cmpeq_epi8(_mm_loadl_epi64((const __m128i *)broken), _mm_setzero_si128());
  const __m128i nn = _mm_set1_epi32(n);
  const __m128i in0 = _mm_cmpgt_epi32(nn, _mm_setr_epi32(0, 1, 2, 3)), in1 = _mm_cmpgt_epi32(nn, _mm_setr_epi32(4, 5, 6, 7));
  /* -1 for a live lane, 0 else, as doubles, negated */
  const __m256d m0 = _mm256_cvtepi32_pd(_mm_and_si128(_mm_cvtepi8_epi32(z), in0));
  const __m256d m1 = _mm256_cvtepi32_pd(_mm_and_si128(_mm_cvtepi8_epi32(_mm_srli_si128(z, 4)), in1));
  _mm256_storeu_pd(live, _mm256_sub_pd(_mm256_setzero_pd(), m0));
  _mm256_storeu_pd(live + 4, _mm256_sub_pd(_mm256_setzero_pd(), m1));
#else
  for (int l = 0; l < PF_BATCH; l++) live[l] = l < n && !broken[l] ? 1.0 : 0.0;
#endif
}

/* 1 when every bond of the batch [k0, min(k0 + PF_BATCH, end)) is broken. A bond loop skips such
 * a batch: its lanes would add zeros (masked, or multiplied by a zero live[l]) to sums that are
 * never -0, so the sums keep their bits, and a broken bond neither fails again nor sets smin. */
static inline int pf_batch_dead(const uint8_t *broken, int64_t k0, int64_t end) {
  const int n = end - k0 < PF_BATCH ? (int)(end - k0) : PF_BATCH;
#if defined(PF_BATCH_AVX512)
  return !pf_batch_live_m(broken + k0, n);
#else
  for (int l = 0; l < n; l++)
    if (!broken[k0 + l]) return 0;
  return 1;
#endif
}

/* out[l] = v[idx[l]]: eight scalar loads into one register and one vector store (see
 * pf_batch_live). */
static inline void pf_batch_gather1(const double *restrict v, const int32_t idx[PF_BATCH],
                                    double out[PF_BATCH]) {
#if defined(__AVX512F__)
  _mm512_storeu_pd(out, _mm512_set_pd(v[idx[7]], v[idx[6]], v[idx[5]], v[idx[4]], v[idx[3]], v[idx[2]],
                                      v[idx[1]], v[idx[0]]));
#elif defined(__AVX2__)
  _mm256_storeu_pd(out, _mm256_set_pd(v[idx[3]], v[idx[2]], v[idx[1]], v[idx[0]]));
  _mm256_storeu_pd(out + 4, _mm256_set_pd(v[idx[7]], v[idx[6]], v[idx[5]], v[idx[4]]));
#else
  for (int l = 0; l < PF_BATCH; l++) out[l] = v[idx[l]];
#endif
}

/* This thread's contiguous share [*lo, *hi) of the n points from first, inside an OpenMP
 * parallel region (without OpenMP: all of them). */
static inline void pf_thread_range(pf_int first, pf_int n, pf_int *lo, pf_int *hi) {
#if defined(_OPENMP)
  const pf_int t = omp_get_thread_num(), nt = omp_get_num_threads();
  *lo = first + (pf_int)((int64_t)n * t / nt), *hi = first + (pf_int)((int64_t)n * (t + 1) / nt);
#else
  *lo = first, *hi = first + n;
#endif
}

/* The bond geometry of one batch of point i (record ri) from its neighbours' transposed records
 * a, in the portable form: r0 = |xi|, r = |y_j - y_i|, their inverses and the current bond
 * vectors e[3][l]. */
typedef struct {
  double r0[PF_BATCH], r[PF_BATCH], ir0[PF_BATCH], ir[PF_BATCH], e[3][PF_BATCH];
} pf_batch_lengths;

static inline __attribute__((always_inline)) void pf_batch_lengths_of(const double *restrict ri,
                                                                      double a[PF_REC][PF_BATCH],
                                                                      pf_batch_lengths *restrict g) {
  double d2[PF_BATCH], e2[PF_BATCH];
#pragma omp simd
  for (int l = 0; l < PF_BATCH; l++) {
    const double d0 = a[REC_X][l] - ri[REC_X], d1 = a[REC_X + 1][l] - ri[REC_X + 1],
                 dz = a[REC_X + 2][l] - ri[REC_X + 2];
    for (int c = 0; c < 3; c++) g->e[c][l] = a[REC_Y + c][l] - ri[REC_Y + c];
    g->ir0[l] = d2[l] = d0 * d0 + d1 * d1 + dz * dz;
    g->ir[l] = e2[l] = g->e[0][l] * g->e[0][l] + g->e[1][l] * g->e[1][l] + g->e[2][l] * g->e[2][l];
  }
  pf_batch_rsqrt(g->ir0);
  pf_batch_rsqrt(g->ir);
#pragma omp simd
  for (int l = 0; l < PF_BATCH; l++) g->r0[l] = d2[l] * g->ir0[l], g->r[l] = e2[l] * g->ir[l];
}

/* The lengths of one batch by square roots, as pf_pd_bond_lengths computes them, to the same
 * bits: r0 = |xi|, r = |y_j - y_i| and the current bond vectors e[3][l] (the elastic-plastic
 * passes and the LPS energy, which take differences of these lengths). */
static inline __attribute__((always_inline)) void pf_batch_sqrt_lengths(const double *restrict ri,
                                                                        double a[PF_REC][PF_BATCH],
                                                                        double r0[PF_BATCH], double r[PF_BATCH],
                                                                        double e[3][PF_BATCH]) {
#pragma omp simd
  for (int l = 0; l < PF_BATCH; l++) {
    double d2 = 0, e2 = 0;
    for (int c = 0; c < 3; c++) {
      const double d = a[REC_X + c][l] - ri[REC_X + c];
      e[c][l] = a[REC_Y + c][l] - ri[REC_Y + c];
      d2 += d * d, e2 += e[c][l] * e[c][l];
    }
    r0[l] = sqrt(d2), r[l] = sqrt(e2);
  }
}

#endif
