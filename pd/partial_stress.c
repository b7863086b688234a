/* The partial-stress form of a state-based material (Silling & Seleson 2013; Littlewood 2014,
 * "Partial stress formulation" and "Application of partial stress"), for a variable
 * horizon without ghost forces. Theory: docs/theory/coupling.md §2.
 *   nu_i   = sum_j T_i<xi> (x) xi V_j                                (partial stress)
 *   L_i    = div nu = tr( [sum_j w (nu_j - nu_i) (x) xi V_j] K_i^-1 )  (nonlocal divergence)
 *   f_i    = V_i L_i,  i.e. f_i,a = V_i sum_j w V_j (nu_j - nu_i)_ab (K_i^-1 xi)_b
 * with the sums over i's own family (j within delta_i) and K_i = sum_j w xi (x) xi V_j. A linear
 * displacement gives the same nu at every point (the same F, any horizon), hence f = 0 to
 * round-off even at a free surface; a quadratic one gives the constant div sigma wherever the
 * family is symmetric (the nonlocal gradient is exact for linear fields). */
#include "pd/pd_impl.h"

#include <string.h>

double pf_pd_shape_tensor_inverse(const pf_pd_body *b, const pf_points *pts, pf_int i, double Ki[9]) {
  const pf_family *fam = &b->fam;
  double K[3][3] = {{0}}, inv[3][3];
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    double xi[3], r0, w;
    if (!pf_pd_own_bond(b, pts, i, k, xi, &r0, &w)) continue;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[r][c] += w * xi[r] * xi[c];
  }
  const double det = pf_mat3_inverse(K, inv), tr = (K[0][0] + K[1][1] + K[2][2]) / 3.0;
  if (!(det > 1e-6 * tr * tr * tr)) { /* too few bonds for a gradient: no force */
    memset(Ki, 0, 9 * sizeof(double));
    return 0.0;
  }
  memcpy(Ki, inv, 9 * sizeof(double));
  return det;
}

void pf_pd_partial_stress_force(const pf_pd_body *b, pf_points *pts, pf_int i, const double *nu,
                                int stride, const double Ki[9]) {
  const pf_family *fam = &b->fam;
  const double *ni = &nu[(size_t)stride * i];
  double L[3] = {0, 0, 0}; /* sum_j w V_j (nu_j - nu_i) K_i^-1 xi */
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    double xi[3], r0, w;
    if (!pf_pd_own_bond(b, pts, i, k, xi, &r0, &w)) continue;
    const double *nj = &nu[(size_t)stride * fam->neighbor[k]];
    double kx[3];
    for (int q = 0; q < 3; q++) kx[q] = Ki[3 * q] * xi[0] + Ki[3 * q + 1] * xi[1] + Ki[3 * q + 2] * xi[2];
    for (int a = 0; a < 3; a++)
      for (int q = 0; q < 3; q++) L[a] += w * (nj[3 * a + q] - ni[3 * a + q]) * kx[q];
  }
  for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * L[a];
}
