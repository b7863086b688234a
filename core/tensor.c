/* Small symmetric-tensor eigenvalue helpers shared by the correspondence PD points and their
 * stable step (the inverse, cross product, Hughes-Winget rotation and Voigt helpers that the
 * element and bond loops call are inline, in core/tensor.h). */
#include "core/core.h"

#include <math.h>

/* The smallest eigenvalue of a symmetric 3x3 matrix, by the trigonometric solution of the
 * characteristic cubic (Smith 1961, Commun. ACM 4:168): with q = tr A / 3, B = (A - q I) / p,
 * p = sqrt(tr (A - qI)^2 / 6), the eigenvalues are q + 2 p cos(phi + 2 pi k / 3),
 * phi = acos(det B / 2) / 3; the smallest is k = 1. */
double pf_sym3_min_eigenvalue(double A[3][3]) {
  const double q = (A[0][0] + A[1][1] + A[2][2]) / 3.0;
  const double off = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2];
  const double a = A[0][0] - q, b = A[1][1] - q, c = A[2][2] - q;
  const double p2 = (a * a + b * b + c * c + 2.0 * off) / 6.0;
  if (!(p2 > 1e-30 * q * q)) return q; /* a multiple of I */
  const double p = sqrt(p2);
  const double det = (a * (b * c - A[1][2] * A[1][2]) - A[0][1] * (A[0][1] * c - A[1][2] * A[0][2]) +
                      A[0][2] * (A[0][1] * A[1][2] - b * A[0][2])) / (p2 * p);
  const double phi = acos(fmax(-1.0, fmin(1.0, 0.5 * det))) / 3.0;
  return q + 2.0 * p * cos(phi + 2.0 * PF_PI / 3.0);
}

/* The smallest lambda of A v = lambda B v for symmetric A and positive definite B, i.e. min_n
 * (n.A n)/(n.B n): the smallest eigenvalue of L^-1 A L^-T with B = L L^T (Cholesky; Golub & Van
 * Loan 2013, sec. 8.7.2). 0 when B is not positive definite. */
double pf_sym3_min_relative_eigenvalue(double A[3][3], double B[3][3]) {
  double L[3][3] = {{0}}, Li[3][3] = {{0}}, T[3][3], M[3][3];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c <= r; c++) {
      double v = B[r][c];
      for (int q = 0; q < c; q++) v -= L[r][q] * L[c][q];
      if (r == c) {
        if (!(v > 0)) return 0.0;
        L[r][r] = sqrt(v);
      } else L[r][c] = v / L[c][c];
    }
  for (int c = 0; c < 3; c++) /* Li = L^-1, lower triangular */
    for (int r = c; r < 3; r++) {
      double v = r == c ? 1.0 : 0.0;
      for (int q = c; q < r; q++) v -= L[r][q] * Li[q][c];
      Li[r][c] = v / L[r][r];
    }
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) T[r][c] = Li[r][0] * A[0][c] + Li[r][1] * A[1][c] + Li[r][2] * A[2][c];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) M[r][c] = T[r][0] * Li[c][0] + T[r][1] * Li[c][1] + T[r][2] * Li[c][2];
  return pf_sym3_min_eigenvalue(M);
}
