/* Small 3x3 tensor helpers called inside the FE element and correspondence PD loops: the
 * determinant and inverse, the cross product, the Hughes-Winget incremental rotation, and
 * symmetric tensors in Voigt order (xx, yy, zz, yz, xz, xy) with tensor (not engineering) shear
 * components. They are defined here, static inline, so that they inline into those loops: called
 * across files they made the FE step 9 % slower (bench/calculix, 80,000 elements). Included by
 * core/core.h. */
#ifndef PF_CORE_TENSOR_H
#define PF_CORE_TENSOR_H

/* Voigt order: component k of a symmetric tensor is (pf_voigt_i[k], pf_voigt_j[k]). */
static const int pf_voigt_i[6] = {0, 1, 2, 1, 0, 0}, pf_voigt_j[6] = {0, 1, 2, 2, 2, 1};

/* det F of a row-major F[9], by the first row's cofactors. */
static inline double pf_det3(const double *restrict F) {
  return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
         F[2] * (F[3] * F[7] - F[4] * F[6]);
}

/* det A. */
static inline double pf_mat3_det(double A[3][3]) { return pf_det3(&A[0][0]); }

/* inv = A^-1; returns det A (inv is not finite when det A = 0). */
static inline double pf_mat3_inverse(double A[3][3], double inv[3][3]) {
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

static inline void pf_vec3_cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The incremental rotation over dt of the spin W = skew L: R = (I - h W)^-1 (I + h W), h = dt/2
 * (Hughes & Winget 1980, eq. 34). */
static inline void pf_mat3_hughes_winget(double L[3][3], double dt, double R[3][3]) {
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

static inline void pf_sym6_to_mat(const double s[6], double S[3][3]) {
  for (int k = 0; k < 6; k++) S[pf_voigt_i[k]][pf_voigt_j[k]] = S[pf_voigt_j[k]][pf_voigt_i[k]] = s[k];
}

/* s <- R s R^T */
static inline void pf_sym6_rotate(double R[3][3], double s[6]) {
  double S[3][3], T[3][3];
  pf_sym6_to_mat(s, S);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[i][j] = S[i][0] * R[j][0] + S[i][1] * R[j][1] + S[i][2] * R[j][2];
  for (int k = 0; k < 6; k++) {
    int i = pf_voigt_i[k], j = pf_voigt_j[k];
    s[k] = R[i][0] * T[0][j] + R[i][1] * T[1][j] + R[i][2] * T[2][j];
  }
}

/* ---- the same across vector lanes: lane l of each array is one tensor's, and each lane's bits
 * are those of the one-tensor functions above (the same operations in the same order; the
 * element kernels of fem/ run PF_TENSOR_LANES elements at once through them). */
#define PF_TENSOR_LANES 8

/* det A lane by lane, as pf_mat3_det. */
static inline void pf_mat3_det_lanes(double F[3][3][PF_TENSOR_LANES], double det[PF_TENSOR_LANES]) {
#pragma omp simd
  for (int l = 0; l < PF_TENSOR_LANES; l++)
    det[l] = F[0][0][l] * (F[1][1][l] * F[2][2][l] - F[1][2][l] * F[2][1][l]) -
             F[0][1][l] * (F[1][0][l] * F[2][2][l] - F[1][2][l] * F[2][0][l]) +
             F[0][2][l] * (F[1][0][l] * F[2][1][l] - F[1][1][l] * F[2][0][l]);
}

/* inv = A^-1 and det = det A lane by lane, as pf_mat3_inverse. */
static inline void pf_mat3_inverse_lanes(double A[3][3][PF_TENSOR_LANES], double inv[3][3][PF_TENSOR_LANES],
                                         double det_out[PF_TENSOR_LANES]) {
#pragma omp simd
  for (int l = 0; l < PF_TENSOR_LANES; l++) {
    double c00 = A[1][1][l] * A[2][2][l] - A[1][2][l] * A[2][1][l], c01 = A[1][2][l] * A[2][0][l] - A[1][0][l] * A[2][2][l],
           c02 = A[1][0][l] * A[2][1][l] - A[1][1][l] * A[2][0][l];
    double det = A[0][0][l] * c00 + A[0][1][l] * c01 + A[0][2][l] * c02, r = 1.0 / det;
    det_out[l] = det;
    inv[0][0][l] = c00 * r;
    inv[1][0][l] = c01 * r;
    inv[2][0][l] = c02 * r;
    inv[0][1][l] = (A[0][2][l] * A[2][1][l] - A[0][1][l] * A[2][2][l]) * r;
    inv[1][1][l] = (A[0][0][l] * A[2][2][l] - A[0][2][l] * A[2][0][l]) * r;
    inv[2][1][l] = (A[0][1][l] * A[2][0][l] - A[0][0][l] * A[2][1][l]) * r;
    inv[0][2][l] = (A[0][1][l] * A[1][2][l] - A[0][2][l] * A[1][1][l]) * r;
    inv[1][2][l] = (A[0][2][l] * A[1][0][l] - A[0][0][l] * A[1][2][l]) * r;
    inv[2][2][l] = (A[0][0][l] * A[1][1][l] - A[0][1][l] * A[1][0][l]) * r;
  }
}

/* R lane by lane, as pf_mat3_hughes_winget. */
static inline void pf_mat3_hughes_winget_lanes(double L[3][3][PF_TENSOR_LANES], double dt,
                                               double R[3][3][PF_TENSOR_LANES]) {
  _Alignas(64) double Am[3][3][PF_TENSOR_LANES], Ap[3][3][PF_TENSOR_LANES], inv[3][3][PF_TENSOR_LANES], det[PF_TENSOR_LANES];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
#pragma omp simd
      for (int l = 0; l < PF_TENSOR_LANES; l++) {
        double w = 0.5 * (L[i][j][l] - L[j][i][l]) * 0.5 * dt;
        Am[i][j][l] = (i == j) - w;
        Ap[i][j][l] = (i == j) + w;
      }
  pf_mat3_inverse_lanes(Am, inv, det);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
#pragma omp simd
      for (int l = 0; l < PF_TENSOR_LANES; l++)
        R[i][j][l] = inv[i][0][l] * Ap[0][j][l] + inv[i][1][l] * Ap[1][j][l] + inv[i][2][l] * Ap[2][j][l];
}

/* s <- R s R^T lane by lane, as pf_sym6_rotate. */
static inline void pf_sym6_rotate_lanes(double R[3][3][PF_TENSOR_LANES], double s[6][PF_TENSOR_LANES]) {
  _Alignas(64) double S[3][3][PF_TENSOR_LANES], T[3][3][PF_TENSOR_LANES];
  for (int k = 0; k < 6; k++)
#pragma omp simd
    for (int l = 0; l < PF_TENSOR_LANES; l++) S[pf_voigt_i[k]][pf_voigt_j[k]][l] = S[pf_voigt_j[k]][pf_voigt_i[k]][l] = s[k][l];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
#pragma omp simd
      for (int l = 0; l < PF_TENSOR_LANES; l++)
        T[i][j][l] = S[i][0][l] * R[j][0][l] + S[i][1][l] * R[j][1][l] + S[i][2][l] * R[j][2][l];
  for (int k = 0; k < 6; k++) {
    int i = pf_voigt_i[k], j = pf_voigt_j[k];
#pragma omp simd
    for (int l = 0; l < PF_TENSOR_LANES; l++) s[k][l] = R[i][0][l] * T[0][j][l] + R[i][1][l] * T[1][j][l] + R[i][2][l] * T[2][j][l];
  }
}

#endif
