/* Small 3x3 tensor helpers shared by the FE elements and the correspondence PD points: inverse,
 * cross product, the Hughes-Winget incremental rotation, and symmetric tensors in Voigt order
 * (xx, yy, zz, yz, xz, xy) with tensor (not engineering) shear components. */
#include "core/core.h"

#include <math.h>

const int pf_voigt_i[6] = {0, 1, 2, 1, 0, 0}, pf_voigt_j[6] = {0, 1, 2, 2, 2, 1};

double pf_mat3_inverse(double A[3][3], double inv[3][3]) {
  double c00 = A[1][1] * A[2][2] - A[1][2] * A[2][1], c01 = A[1][2] * A[2][0] - A[1][0] * A[2][2],
         c02 = A[1][0] * A[2][1] - A[1][1] * A[2][0];
  double det = A[0][0] * c00 + A[0][1] * c01 + A[0][2] * c02, r = 1.0 / det;
  inv[0][0] = c00 * r;
  inv[1][0] = c01 * r;
  inv[2][0] = c02 * r;
  inv[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) * r;
  inv[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) * r;
  inv[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) * r;
  inv[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) * r;
  inv[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) * r;
  inv[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) * r;
  return det;
}

void pf_vec3_cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* R = (I - h W)^-1 (I + h W), h = dt/2, W = skew L (Hughes & Winget 1980, eq. 34). */
void pf_mat3_hughes_winget(double L[3][3], double dt, double R[3][3]) {
  double Am[3][3], Ap[3][3], inv[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double w = 0.5 * (L[i][j] - L[j][i]) * 0.5 * dt;
      Am[i][j] = (i == j) - w;
      Ap[i][j] = (i == j) + w;
    }
  pf_mat3_inverse(Am, inv);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[i][j] = inv[i][0] * Ap[0][j] + inv[i][1] * Ap[1][j] + inv[i][2] * Ap[2][j];
}

void pf_sym6_to_mat(const double s[6], double S[3][3]) {
  for (int k = 0; k < 6; k++) S[pf_voigt_i[k]][pf_voigt_j[k]] = S[pf_voigt_j[k]][pf_voigt_i[k]] = s[k];
}

void pf_sym6_rotate(double R[3][3], double s[6]) {
  double S[3][3], T[3][3];
  pf_sym6_to_mat(s, S);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[i][j] = S[i][0] * R[j][0] + S[i][1] * R[j][1] + S[i][2] * R[j][2];
  for (int k = 0; k < 6; k++) {
    int i = pf_voigt_i[k], j = pf_voigt_j[k];
    s[k] = R[i][0] * T[0][j] + R[i][1] * T[1][j] + R[i][2] * T[2][j];
  }
}

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
