/* Flanagan-Belytschko (1981) hourglass control for the one-point hexahedron. The hourglass
 * base vectors Gamma_a (a = 1..4) are the node-sign products xi eta, eta zeta, zeta xi and
 * xi eta zeta (FB eq. 28). Projecting out the linear fields gives the stabilization vectors
 * (FB eq. 57)
 *     gamma_aI = Gamma_aI - B_iI sum_J Gamma_aJ x_iJ,
 * orthogonal to every linear velocity field (sum_I gamma_aI x_jI = 0, sum_I gamma_aI = 0), so
 * the hourglass forces vanish for rigid motion and uniform strain: the patch test holds. */
#include "fem/fem_impl.h"

void pf_hex8_hourglass_vectors(double x[8][3], double B[8][3], double gamma[4][8]) {
  for (int a = 0; a < 4; a++) {
    double G[8], gx[3] = {0, 0, 0};
    for (int I = 0; I < 8; I++) {
      const double *s = pf_hex8_node_sign[I];
      G[I] = a == 0 ? s[0] * s[1] : a == 1 ? s[1] * s[2] : a == 2 ? s[2] * s[0] : s[0] * s[1] * s[2];
      for (int i = 0; i < 3; i++) gx[i] += G[I] * x[I][i];
    }
    for (int I = 0; I < 8; I++) gamma[a][I] = G[I] - (B[I][0] * gx[0] + B[I][1] * gx[1] + B[I][2] * gx[2]);
  }
}
