/* Two bond-loop designs perifem does not use, timed against its PMB force pass (issue 9,
 * bench/README.md "What 10x would take"). All three on test_bond_loop_speed's 30^3 lattice
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

/* The pairs (i, j > i) of the family, row by row, with 8 slack entries. */
typedef struct {
  int64_t *off;
  int32_t *nb;
} half_list;

static half_list half_of(const pf_family *fam, pf_int n) {
  half_list h = {malloc((size_t)(n + 1) * sizeof *h.off), calloc((size_t)fam->offset[n] / 2 + 16, sizeof *h.nb)};
  int64_t m = 0;
  for (pf_int i = 0; i < n; i++) {
    h.off[i] = m;
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++)
      if (fam->neighbor[k] > i) h.nb[m++] = fam->neighbor[k];
  }
  h.off[n] = m;
  return h;
}

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

/* Half-bond PMB: F (forces, N, rows of four) of the n points; the pair force c s V_i V_j e / r (Silling &
 * Askari 2005, eq. 7) goes to i and, negated, to j. */
static void half_pmb(const half_list *h, const double *rec, pf_int n, double c, double *F) {
  const __m512d cc = _mm512_set1_pd(c);
  memset(F, 0, 4 * (size_t)n * sizeof *F);
  for (pf_int i = 0; i < n; i++) {
    const double *ri = rec + PF_REC * (size_t)i;
    const __m512d s0i = _mm512_set1_pd(ri[REC_AUX]), vi = _mm512_set1_pd(ri[REC_V]);
    __m512d Fi[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
    for (int64_t k0 = h->off[i]; k0 < h->off[i + 1]; k0 += PF_BATCH) {
      const int nn = h->off[i + 1] - k0 < PF_BATCH ? (int)(h->off[i + 1] - k0) : PF_BATCH;
      __m512d a[PF_REC];
      pf_batch_geom g;
      pf_batch_gather_v(rec, h->nb + k0, a);
      pf_batch_geom_v(a, ri, &g);
      const __m512d s = _mm512_mul_pd(_mm512_sub_pd(g.r, g.r0), g.ir0);
      const __mmask8 over = _mm512_cmp_pd_mask(s, _mm512_min_pd(s0i, a[REC_AUX]), _CMP_GT_OQ);
      const __mmask8 alive = (__mmask8)(((1u << nn) - 1u) & ~over);
      const __m512d w = _mm512_maskz_mov_pd(
          alive, _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(cc, s), g.ir), _mm512_mul_pd(vi, a[REC_V])));
      __m512d fe[3];
      for (int q = 0; q < 3; q++) fe[q] = _mm512_mul_pd(w, g.e[q]), Fi[q] = _mm512_add_pd(Fi[q], fe[q]);
      scatter_sub(F, h->nb + k0, nn, fe);
    }
    for (int q = 0; q < 3; q++) F[4 * i + q] += pf_batch_sum_v(Fi[q]);
  }
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

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pf_sim *sim = pf_test_bond_lattice("pmb");
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  const pf_family *fam = pf_pd_body_family(b);
  const pf_int n = p->n_owned;
  const half_list h = half_of(fam, n);
  const double c = 18 * BULK / (acos(-1.0) * pow(HORIZON, 4)), bonds = (double)fam->offset[n];
  double *s0 = malloc((size_t)n * sizeof *s0), *Fh = aligned_alloc(64, (32 * (size_t)n + 63) / 64 * 64),
         *Fm = malloc(3 * (size_t)n * sizeof *Fm);
  for (pf_int i = 0; i < n; i++) s0[i] = 0.5;
  pf_batch_records rec = {0};
  double best[3] = {INFINITY, INFINITY, INFINITY};
  for (int rep = 0; rep < 9; rep++) {
    memset(p->f, 0, 3 * (size_t)n * sizeof *p->f);
    double t[4];
    t[0] = pf_wtime();
    if (pf_pd_body_force(b, p, 0.0)) return 1;
    t[1] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    half_pmb(&h, rec.rec, n, c, Fh);
    t[2] = pf_wtime();
    if (pf_batch_records_fill(&rec, p, s0)) return 1;
    mixed_pmb(fam, rec.rec, n, c, Fm);
    t[3] = pf_wtime();
    for (int v = 0; v < 3; v++) best[v] = fmin(best[v], t[v + 1] - t[v]);
  }
  double fmax_ = 0;
  for (pf_int k = 0; k < 3 * n; k++) fmax_ = fmax(fmax_, fabs(p->f[k]));
  printf("lattice 30^3, %.0f directed bonds; largest force %.3g N\n", bonds, fmax_);
  printf("production: %6.0f M directed bonds/s\n", bonds / best[0] / 1e6);
  printf("half:       %6.0f M directed bonds/s, %.2fx production, max force difference %.2g N\n",
         bonds / best[1] / 1e6, best[0] / best[1], max_diff(Fh, 4, p->f, n));
  printf("mixed:      %6.0f M directed bonds/s, %.2fx production, max force difference %.2g N\n",
         bonds / best[2] / 1e6, best[0] / best[2], max_diff(Fm, 3, p->f, n));
  pf_batch_records_free(&rec);
  free(s0), free(Fh), free(Fm), free(h.off), free(h.nb);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
#else
int main(void) {
  puts("bench_bond_variants: needs AVX-512 (the batches of pd/bond_batch.h); skipped");
  return 77;
}
#endif
