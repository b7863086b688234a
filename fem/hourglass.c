/* Flanagan-Belytschko (1981) hourglass control for the one-point hexahedron. The hourglass
 * base vectors Gamma_a (a = 1..4) are the node-sign products xi eta, eta zeta, zeta xi and
 * xi eta zeta (FB eq. 28). Projecting out the linear fields gives the stabilization vectors
 * (FB eq. 57)
 *     gamma_aI = Gamma_aI - B_iI sum_J Gamma_aJ x_iJ,
 * orthogonal to every linear velocity field (sum_I gamma_aI x_jI = 0, sum_I gamma_aI = 0), so
 * the hourglass forces vanish for rigid motion and uniform strain: the patch test holds. Formed
 * for PF_HEX8_LANES elements at once, lane l of every array one element's. */
#include "fem/fem_impl.h"

void pf_hex8_hourglass_vectors_lanes(double x[8][3][PF_HEX8_LANES], double B[8][3][PF_HEX8_LANES],
                                     double gamma[4][8][PF_HEX8_LANES]) {
  enum { W = PF_HEX8_LANES };
  for (int a = 0; a < 4; a++) {
    _Alignas(64) double G[8], gx[3][W];
    for (int I = 0; I < 8; I++) {
      const double *s = pf_hex8_node_sign[I];
      G[I] = a == 0 ? s[0] * s[1] : a == 1 ? s[1] * s[2] : a == 2 ? s[2] * s[0] : s[0] * s[1] * s[2];
    }
    for (int i = 0; i < 3; i++) {
#pragma omp simd
      for (int l = 0; l < W; l++) gx[i][l] = 0;
      for (int I = 0; I < 8; I++)
#pragma omp simd
        for (int l = 0; l < W; l++) gx[i][l] += G[I] * x[I][i][l];
    }
    for (int I = 0; I < 8; I++)
#pragma omp simd
      for (int l = 0; l < W; l++)
        gamma[a][I][l] = G[I] - (B[I][0][l] * gx[0][l] + B[I][1][l] * gx[1][l] + B[I][2][l] * gx[2][l]);
  }
}
