/* The batched bond loops (pd/bond_batch.h, pd/material_pmb.c, pd/lps_batched.c) against
 * their definitions:
 * - the transpose of eight records, the one-field gather and the live mask are exact copies;
 * - the inverse square root is within 2 units in the last place of 1 / sqrt (2^-52 relative);
 * - on a 7 x 6 x 5 lattice, horizon 3.0001 spacings (rows of 28 to 119 bonds, every remainder
 *   modulo a batch of 8 among them), with a random displacement field and some bonds broken,
 *   the PMB and LPS forces, and the LPS
 *   dilatations, equal direct sums of the textbook formulas (Silling & Askari 2005, eq. 7;
 *   Silling et al. 2007, eqs. 90-94) written here with sqrt and division, to 1e-12 relative;
 *   both for each influence function the deck offers (1, 1 / |xi|, exp(-|xi|^2 / sigma^2)),
 *   omega written here with division and the C library's exp, the PMB micromodulus
 *   18 K / (4 pi int omega r^3 dr) in closed form;
 * - with AVX-512, the kernels' vector exp within 2 units in the last place of exp over
 *   [-20, 20] (the Gaussian's argument lies in [-4, 0]).
 */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pd/bond_batch.h"

static double urand(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return (double)((*s >> 8) & 0xffffff) / 16777216.0;
}

static void check_kernels(void) {
  unsigned seed = 7;
  enum { N = 64 };
  double *rec = aligned_alloc(64, sizeof(double) * PF_REC * N), v[N];
  for (int k = 0; k < PF_REC * N; k++) rec[k] = urand(&seed) - 0.5;
  for (int k = 0; k < N; k++) v[k] = urand(&seed);
  for (int trial = 0; trial < 100; trial++) {
    int32_t idx[PF_BATCH];
    double out[PF_REC][PF_BATCH], one[PF_BATCH];
    for (int l = 0; l < PF_BATCH; l++) idx[l] = (int32_t)(urand(&seed) * N);
    pf_batch_gather(rec, idx, out);
    pf_batch_gather1(v, idx, one);
    for (int l = 0; l < PF_BATCH; l++) {
      for (int f = 0; f < PF_REC; f++) PF_TEST_TRUE(out[f][l] == rec[PF_REC * idx[l] + f]);
      PF_TEST_TRUE(one[l] == v[idx[l]]);
    }
  }
  free(rec);
  for (int trial = 0; trial < 2000; trial++) {
    double x[PF_BATCH], y[PF_BATCH];
    for (int l = 0; l < PF_BATCH; l++) x[l] = y[l] = pow(10.0, 40 * urand(&seed) - 20);
    pf_batch_rsqrt(y);
    for (int l = 0; l < PF_BATCH; l++) PF_TEST_CLOSE(y[l], 1.0 / sqrt(x[l]), 4.5e-16, 0);
  }
#if defined(PF_BATCH_AVX512)
  for (int trial = 0; trial < 2000; trial++) {
    double x[PF_BATCH], y[PF_BATCH];
    for (int l = 0; l < PF_BATCH; l++) x[l] = trial < 1000 ? 40 * urand(&seed) - 20 : -4 * urand(&seed);
    _mm512_storeu_pd(y, pf_batch_exp_v(_mm512_loadu_pd(x)));
    for (int l = 0; l < PF_BATCH; l++) PF_TEST_CLOSE(y[l], exp(x[l]), 4.5e-16, 0);
  }
#endif
  for (int n = 0; n <= PF_BATCH; n++)
    for (int trial = 0; trial < 20; trial++) {
      uint8_t br[PF_BATCH];
      double live[PF_BATCH];
      for (int l = 0; l < PF_BATCH; l++) br[l] = (uint8_t)(urand(&seed) * 3);
      pf_batch_live(br, n, live);
      for (int l = 0; l < PF_BATCH; l++) PF_TEST_TRUE(live[l] == (l < n && br[l] == 0 ? 1.0 : 0.0));
    }
}

/* A lattice body of the model (with its keys), displaced at random, some bonds broken. */
static pf_sim *lattice(const char *model, const char *influence) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 1000, bulk_modulus: 1.0e9, shear_modulus: 0.6e9}}\n"
           "bodies:\n  - {name: b, material: m, horizon: 3.0001e-3, influence: %s,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [6e-3, 5e-3, 4e-3], spacing: 1e-3}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           model, influence);
  pf_sim *sim = pf_test_sim("bond_batch", deck);
  pf_points *p = pf_sim_points(sim);
  unsigned seed = 11;
  for (pf_int k = 0; k < 3 * p->n_owned; k++) p->u[k] = 2e-5 * (urand(&seed) - 0.5);
  for (pf_int k = 0; k < 3 * p->n_owned; k++) p->y[k] = p->X[k] + p->u[k], p->f[k] = 0;
  pf_family *fam = (pf_family *)pf_pd_body_family(pf_sim_body(sim, 0));
  for (int64_t k = 0; k < pf_pd_family_nbonds(fam); k++) /* (symmetrize makes both ends alike) */
    fam->broken[k] = (uint8_t)(k % 13 == 0);
  return sim;
}

/* Bond k of point i: reference and current lengths, current vector. */
static void bond(const pf_points *p, pf_int i, pf_int j, double *r0, double *r, double e[3]) {
  double d2 = 0, e2 = 0;
  for (int a = 0; a < 3; a++) {
    double d = p->X[3 * j + a] - p->X[3 * i + a];
    e[a] = p->y[3 * j + a] - p->y[3 * i + a];
    d2 += d * d, e2 += e[a] * e[a];
  }
  *r0 = sqrt(d2), *r = sqrt(e2);
}

/* Is bond k of i intact? Breaks symmetric pairs: the flag of i -> j, or of j -> i. */
static int intact(const pf_family *fam, pf_int i, int64_t k) {
  pf_int j = fam->neighbor[k];
  for (int64_t q = fam->offset[j - fam->first]; q < fam->offset[j - fam->first + 1]; q++)
    if (fam->neighbor[q] == i) return !fam->broken[k] && !fam->broken[q];
  return 0;
}

static void symmetrize(pf_family *fam) {
  uint8_t *keep = malloc((size_t)pf_pd_family_nbonds(fam));
  for (pf_int i = fam->first; i < fam->first + fam->n; i++)
    for (int64_t k = fam->offset[i - fam->first]; k < fam->offset[i - fam->first + 1]; k++)
      keep[k] = (uint8_t)!intact(fam, i, k);
  for (int64_t k = 0; k < pf_pd_family_nbonds(fam); k++) fam->broken[k] = keep[k];
  free(keep);
}

/* omega(r) of the deck's influence function, written out (sigma = horizon / 2, the default). */
static double omega(const char *influence, double r) {
  const double sigma = 0.5 * 3.0001e-3;
  if (!strcmp(influence, "inverse_distance")) return 1.0 / r;
  if (!strcmp(influence, "gaussian")) return exp(-r * r / (sigma * sigma));
  return 1.0;
}

/* PMB micromodulus c = 18 K / (4 pi int_0^delta omega r^3 dr) in closed form: int r^3 = delta^4
 * / 4; int r^2 = delta^3 / 3; int exp(-r^2 / sigma^2) r^3 = (sigma^4 / 2) (1 - (1 + delta^2 /
 * sigma^2) exp(-delta^2 / sigma^2)). */
static double micromodulus(const char *influence, double K, double delta) {
  const double pi = acos(-1.0), sigma = delta / 2, x = delta * delta / (sigma * sigma);
  if (!strcmp(influence, "inverse_distance")) return 18 * K / (4 * pi * pow(delta, 3) / 3);
  if (!strcmp(influence, "gaussian")) return 18 * K / (4 * pi * pow(sigma, 4) / 2 * (1 - (1 + x) * exp(-x)));
  return 18 * K / (pi * pow(delta, 4));
}

static void check_pmb(const char *influence) {
  pf_sim *sim = lattice("pmb", influence);
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  pf_family *fam = (pf_family *)pf_pd_body_family(b);
  symmetrize(fam);
  const double c = micromodulus(influence, 1.0e9, 3.0001e-3);
  PF_TEST_OK(pf_pd_body_force(b, p, 0.0));
  for (pf_int i = 0; i < p->n_owned; i++) {
    double want[3] = {0, 0, 0}, e[3], r0, r, mag = 0;
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
      if (fam->broken[k]) continue;
      pf_int j = fam->neighbor[k];
      bond(p, i, j, &r0, &r, e);
      const double cw = c * omega(influence, r0);
      for (int a = 0; a < 3; a++) want[a] += cw * (r - r0) / r0 * p->vol[j] * p->vol[i] * e[a] / r;
      mag += cw * fabs(r - r0) / r0 * p->vol[j] * p->vol[i];
    }
    for (int a = 0; a < 3; a++) PF_TEST_CLOSE(p->f[3 * i + a], want[a], 0, 1e-12 * mag);
  }
  pf_sim_destroy(&sim);
}

static void check_lps(const char *influence) {
  pf_sim *sim = lattice("lps", influence);
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  pf_family *fam = (pf_family *)pf_pd_body_family(b);
  symmetrize(fam);
  const double K = 1.0e9, G = 0.6e9;
  const pf_int n = p->n_owned;
  double *m = calloc((size_t)n, sizeof *m), *th = calloc((size_t)n, sizeof *th), e[3], r0, r;
  for (pf_int i = 0; i < n; i++) { /* m over every bond (reference), theta over the intact */
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
      bond(p, i, fam->neighbor[k], &r0, &r, e);
      const double w = omega(influence, r0);
      m[i] += w * r0 * r0 * p->vol[fam->neighbor[k]];
      if (!fam->broken[k]) th[i] += w * r0 * (r - r0) * p->vol[fam->neighbor[k]];
    }
  }
  for (pf_int i = 0; i < n; i++) th[i] *= 3 / m[i];
  PF_TEST_OK(pf_pd_body_force(b, p, 0.0));
  const double *theta = pf_points_field_get(p, "dilatation");
  for (pf_int i = 0; i < n; i++) {
    PF_TEST_CLOSE(theta[i], th[i], 1e-12, 1e-12 * 2e-2);
    double want[3] = {0, 0, 0}, mag = 0;
    for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
      if (fam->broken[k]) continue;
      pf_int j = fam->neighbor[k];
      bond(p, i, j, &r0, &r, e);
      const double ext = r - r0, w = omega(influence, r0);
      const double tij = w * (3 * K * th[i] / m[i] * r0 + 15 * G / m[i] * (ext - th[i] * r0 / 3));
      const double tji = w * (3 * K * th[j] / m[j] * r0 + 15 * G / m[j] * (ext - th[j] * r0 / 3));
      for (int a = 0; a < 3; a++) want[a] += (tij + tji) * p->vol[j] * p->vol[i] * e[a] / r;
      mag += (fabs(tij) + fabs(tji)) * p->vol[j] * p->vol[i];
    }
    for (int a = 0; a < 3; a++) PF_TEST_CLOSE(p->f[3 * i + a], want[a], 0, 1e-12 * mag);
  }
  free(m), free(th);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  check_kernels();
  check_pmb("constant");
  check_pmb("inverse_distance");
  check_pmb("gaussian");
  check_lps("constant");
  check_lps("inverse_distance");
  check_lps("gaussian");
  return pf_test_finish();
}
