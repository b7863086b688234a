/* The eigen-decomposition of symmetric 3x3 matrices across vector lanes
 * (material/sym3_eigen.c): against matrices built as R diag(lambda) R^T with known lambda and a
 * known rotation R (the eigenvalues to 1e-14 of the largest, the reconstruction V diag(w) V^T and
 * V^T V = I to 1e-14), a zero matrix, a diagonal one, a double eigenvalue, off-diagonal entries
 * below the cut-off, a signed zero; and the bits of each lane whatever the other lanes hold
 * (each matrix decomposed in every lane beside different neighbours), which the state digests
 * of the modified Johnson-Cook bodies rely on. */
#include "material/material_impl.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { L = PF_SYM3_LANES, NM = 8 };

/* R = rotation by angle t about the unit axis n (Rodrigues). */
static void rotation(const double n[3], double t, double R[3][3]) {
  const double c = cos(t), s = sin(t);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[i][j] = (i == j) * c + (1 - c) * n[i] * n[j];
  R[0][1] -= s * n[2], R[1][0] += s * n[2];
  R[0][2] += s * n[1], R[2][0] -= s * n[1];
  R[1][2] -= s * n[0], R[2][1] += s * n[0];
}

static void build(const double lam[3], const double n[3], double t, double a[3][3]) {
  double R[3][3];
  rotation(n, t, R);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      a[i][j] = 0;
      for (int k = 0; k < 3; k++) a[i][j] += R[i][k] * lam[k] * R[j][k];
    }
  for (int i = 0; i < 3; i++) /* exactly symmetric, as the callers' matrices are */
    for (int j = 0; j < i; j++) a[i][j] = a[j][i];
}

/* The test matrices and, where known, their eigenvalues (NAN: not checked against a list). */
static void matrices(double m[NM][3][3], double lam[NM][3]) {
  static const double n1[3] = {0.48, 0.6, 0.64}, n2[3] = {0, 0.6, 0.8};
  const double l0[3] = {3.0, -1.0, 0.5}, l1[3] = {2e-3, 2e-3, -5e-4}, l2[3] = {1e-9, -3e-9, 2e-9},
               l7[3] = {4e3, 1e3, 2.5e3};
  memset(m, 0, sizeof(double) * NM * 9);
  build(l0, n1, 0.7, m[0]), memcpy(lam[0], l0, sizeof l0);
  build(l1, n2, 1.1, m[1]), memcpy(lam[1], l1, sizeof l1); /* a double eigenvalue */
  build(l2, n1, 2.3, m[2]), memcpy(lam[2], l2, sizeof l2); /* the size of a small strain */
  lam[3][0] = lam[3][1] = lam[3][2] = 0;                    /* zero */
  m[4][0][0] = 5, m[4][1][1] = -2, m[4][2][2] = 1;          /* diagonal */
  lam[4][0] = 5, lam[4][1] = -2, lam[4][2] = 1;
  m[5][0][0] = 1, m[5][1][1] = 2, m[5][2][2] = 3; /* off-diagonal below 1e-22 |a|: set to 0 */
  m[5][0][1] = m[5][1][0] = 1e-25, m[5][1][2] = m[5][2][1] = -2e-25;
  lam[5][0] = 1, lam[5][1] = 2, lam[5][2] = 3;
  m[6][0][0] = 1, m[6][1][1] = 1, m[6][2][2] = 2; /* a signed zero and equal diagonal entries */
  m[6][0][1] = m[6][1][0] = 0.5, m[6][0][2] = m[6][2][0] = -0.0;
  lam[6][0] = 0.5, lam[6][1] = 1.5, lam[6][2] = 2;
  build(l7, n2, -0.4, m[7]), memcpy(lam[7], l7, sizeof l7);
}

/* Decompose the matrices with matrix perm[l] in lane l. */
static void decompose(double m[NM][3][3], const int perm[L], double w[3][L], double V[3][3][L]) {
  _Alignas(64) double a[3][3][L];
  for (int l = 0; l < L; l++)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) a[i][j][l] = m[perm[l]][i][j];
  pf_sym3_eigen_lanes(a, w, V);
}

/* |got - want| <= tol, else say which matrix and entry and count a failure. */
static void check_close(double got, double want, double tol, const char *what, int k, int i, int j) {
  if (!(fabs(got - want) <= tol)) fprintf(stderr, "matrix %d, %s %d %d: %.17g, expected %.17g\n", k, what, i, j, got, want);
  PF_TEST_TRUE(fabs(got - want) <= tol);
}

/* The same bits, else say which matrix, lane and entry and count a failure. */
static void check_bits(double got, double want, const char *what, int k, int l, int a) {
  const int same = memcmp(&got, &want, sizeof got) == 0;
  if (!same) fprintf(stderr, "matrix %d in lane %d, %s %d: %.17g, alone %.17g\n", k, l, what, a, got, want);
  PF_TEST_TRUE(same);
}

static int cmp(const void *x, const void *y) {
  const double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  double m[NM][3][3], lam[NM][3];
  matrices(m, lam);
  _Alignas(64) double w[3][L], V[3][3][L], w0[3][L], V0[3][3][L];
  const int ident[L] = {0, 1, 2, 3, 4, 5, 6, 7};
  decompose(m, ident, w0, V0);
  for (int k = 0; k < NM; k++) {
    double scale = 0, got[3] = {w0[0][k], w0[1][k], w0[2][k]}, want[3];
    memcpy(want, lam[k], sizeof want);
    qsort(got, 3, sizeof(double), cmp), qsort(want, 3, sizeof(double), cmp);
    for (int a = 0; a < 3; a++) scale = fmax(scale, fabs(want[a]));
    for (int a = 0; a < 3; a++)
      check_close(got[a], want[a], 1e-14 * fmax(scale, 1e-300), "eigenvalue", k, a, a);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double r = 0, o = 0;
        for (int a = 0; a < 3; a++) r += V0[i][a][k] * w0[a][k] * V0[j][a][k], o += V0[a][i][k] * V0[a][j][k];
        check_close(r, m[k][i][j], 1e-14 * fmax(scale, 1e-300), "V diag(w) V^T", k, i, j);
        check_close(o, (double)(i == j), 1e-14, "V^T V", k, i, j);
      }
  }
  /* Each matrix in each lane, beside the others in shifted order: the same bits. */
  for (int shift = 1; shift < L; shift++) {
    int perm[L];
    for (int l = 0; l < L; l++) perm[l] = (l + shift) % NM;
    decompose(m, perm, w, V);
    for (int l = 0; l < L; l++) {
      const int k = perm[l];
      for (int a = 0; a < 3; a++) {
        check_bits(w[a][l], w0[a][k], "eigenvalue", k, l, a);
        for (int i = 0; i < 3; i++) check_bits(V[i][a][l], V0[i][a][k], "eigenvector entry", k, l, 3 * i + a);
      }
    }
  }
  /* Every lane the same matrix: the bits of the mixed run (a lane's sweeps do not depend on
   * how many its neighbours need). */
  for (int k = 0; k < NM; k++) {
    int perm[L];
    for (int l = 0; l < L; l++) perm[l] = k;
    decompose(m, perm, w, V);
    for (int a = 0; a < 3; a++)
      check_bits(w[a][L - 1], w0[a][k], "eigenvalue, every lane the same matrix", k, L - 1, a);
  }
  return pf_test_finish();
}
