/* Hexahedron kernels against closed forms: the mean gradient reproduces linear fields exactly
 * (sum_I x_jI B_iI = delta_ij, sum_I B_iI = 0) and gives the exact volume of a distorted element
 * (checked against a 6x6x6 Gauss rule of det J, exact for any trilinear hexahedron); the
 * Flanagan-Belytschko stabilization vectors are orthogonal to linear fields; the lumped masses
 * add up to rho V; the characteristic length of a cube is its edge; an element far from the
 * origin keeps its volume and gradient. */
#include "fem/fem_impl.h"
#include "test_common.h"

#include <math.h>
#include <string.h>

static const double gl6_x[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
static const double gl6_w[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                0.4679139345726910, 0.3607615730481386, 0.1713244923791704};

/* Volume by a 6-point Gauss-Legendre rule in each direction of det J (from a finite difference
 * free evaluation: J from the trilinear map written out here independently). */
static double volume_gl6(double x[8][3]) {
  double V = 0;
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++)
      for (int c = 0; c < 6; c++) {
        double xi[3] = {gl6_x[a], gl6_x[b], gl6_x[c]}, J[3][3] = {{0}};
        for (int I = 0; I < 8; I++) {
          const double *s = pf_hex8_node_sign[I];
          double d[3] = {s[0] * (1 + s[1] * xi[1]) * (1 + s[2] * xi[2]) / 8,
                         s[1] * (1 + s[0] * xi[0]) * (1 + s[2] * xi[2]) / 8,
                         s[2] * (1 + s[0] * xi[0]) * (1 + s[1] * xi[1]) / 8};
          for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) J[i][k] += x[I][i] * d[k];
        }
        double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                     J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                     J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
        V += gl6_w[a] * gl6_w[b] * gl6_w[c] * det;
      }
  return V;
}

static void distorted(double x[8][3]) {
  static const double jitter[8][3] = {{0.02, -0.01, 0.03}, {0.05, 0.02, -0.04}, {-0.03, 0.06, 0.01},
                                      {0.01, -0.05, 0.02}, {-0.04, 0.03, -0.02}, {0.03, 0.01, 0.05},
                                      {0.06, -0.02, -0.03}, {-0.02, -0.04, 0.04}};
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) x[I][i] = 1e-3 * (0.5 * (1 + pf_hex8_node_sign[I][i]) * (1 + i * 0.3) + jitter[I][i]);
}

static void test_mean_gradient(void) {
  double x[8][3], B[8][3];
  distorted(x);
  double V = pf_hex8_mean_gradient(x, B), ref = volume_gl6(x);
  PF_TEST_CLOSE(V, ref, 1e-13, 0);
  pf_test_measure("volume_error", fabs(V / ref - 1), "1");
  double worst = 0; /* the largest error of sum_I x_jI B_iI = delta_ij */
  for (int i = 0; i < 3; i++) {
    double s = 0;
    for (int I = 0; I < 8; I++) s += B[I][i];
    PF_TEST_CLOSE(s, 0.0, 0, 1e-9 / 1e-3);
    for (int j = 0; j < 3; j++) {
      double t = 0;
      for (int I = 0; I < 8; I++) t += x[I][j] * B[I][i];
      PF_TEST_CLOSE(t, i == j ? 1.0 : 0.0, 0, 1e-13);
      worst = fmax(worst, fabs(t - (i == j ? 1.0 : 0.0)));
    }
  }
  pf_test_measure("identity_error", worst, "1");
  /* a parallelepiped: V = |det(edges)| */
  double e[3][3] = {{2e-3, 0.3e-3, 0}, {0.1e-3, 1e-3, 0.2e-3}, {0, -0.4e-3, 1.5e-3}}, p[8][3];
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) {
      p[I][i] = 0;
      for (int k = 0; k < 3; k++) p[I][i] += 0.5 * (1 + pf_hex8_node_sign[I][k]) * e[k][i];
    }
  double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  PF_TEST_CLOSE(pf_hex8_mean_gradient(p, B), fabs(det), 1e-13, 0);
}

/* An element 10 m from the origin (10^4 element sizes) has the same volume and gradient as
 * the same element at the origin: translation invariance, to round-off of the element's size. */
static void test_far_from_origin(void) {
  double x[8][3], y[8][3], B[8][3], C[8][3];
  distorted(x);
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) y[I][i] = x[I][i] + 10.0;
  double V = pf_hex8_mean_gradient(x, B), W = pf_hex8_mean_gradient(y, C);
  PF_TEST_CLOSE(W, V, 1e-11, 0);
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) PF_TEST_CLOSE(C[I][i], B[I][i], 0, 1e-10 / 1e-3);
}

/* Lane l: the distorted element scaled by 1 + l / 4 and moved by l mm along x. */
static void lanes_of_elements(double x[8][3][PF_HEX8_LANES], double one[PF_HEX8_LANES][8][3]) {
  double d[8][3];
  distorted(d);
  for (int l = 0; l < PF_HEX8_LANES; l++)
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) one[l][I][i] = x[I][i][l] = d[I][i] * (1 + 0.25 * l) + (i == 0) * 1e-3 * l;
}

/* A lane's mean gradient, volume and characteristic length have the bits of its element alone. */
static void test_lanes_independent(void) {
  enum { W = PF_HEX8_LANES };
  double x[8][3][W], one[W][8][3], B[8][3][W], V[W], len[W];
  lanes_of_elements(x, one);
  pf_hex8_mean_gradient_lanes(x, B, V);
  pf_hex8_char_length_lanes(x, V, len);
  for (int l = 0; l < W; l++) {
    double Bl[8][3], Vl = pf_hex8_mean_gradient(one[l], Bl);
    PF_TEST_TRUE(Vl == V[l] && pf_hex8_char_length(one[l], Vl) == len[l]);
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) PF_TEST_TRUE(Bl[I][i] == B[I][i][l]);
  }
}

/* The gradients at the 8 Gauss points at once (lane g, Gauss point g): the bits of
 * pf_hex8_gradients at each point, for each of the lanes' elements; and their volumes sum to the
 * element's (2x2x2 Gauss integrates det J, a polynomial of degree 2 in each coordinate, exactly). */
static void test_gauss_lanes(void) {
  enum { W = PF_HEX8_LANES };
  double x[8][3][W], one[W][8][3], B[8][3][W], V[W];
  lanes_of_elements(x, one);
  pf_hex8_mean_gradient_lanes(x, B, V);
  for (int e = 0; e < W; e++) {
    double gr[8][3][W], det[W], sum = 0;
    pf_hex8_gauss_gradients_lanes(one[e], gr, det);
    for (int g = 0; g < 8; g++) {
      double xi[3], gg[8][3];
      pf_hex8_gauss_point(g, xi);
      PF_TEST_TRUE(pf_hex8_gradients(one[e], xi, gg) == det[g]);
      for (int I = 0; I < 8; I++)
        for (int i = 0; i < 3; i++) PF_TEST_TRUE(gg[I][i] == gr[I][i][g]);
      sum += det[g];
    }
    PF_TEST_CLOSE(sum, V[e], 1e-13, 0);
  }
}

static void test_hourglass_vectors(void) {
  enum { W = PF_HEX8_LANES };
  double x[8][3][W], one[W][8][3], B[8][3][W], V[W], g[4][8][W];
  lanes_of_elements(x, one);
  pf_hex8_mean_gradient_lanes(x, B, V);
  pf_hex8_hourglass_vectors_lanes(x, B, g);
  for (int l = 0; l < W; l++)
    for (int a = 0; a < 4; a++) {
      double s = 0, n = 0;
      for (int I = 0; I < 8; I++) s += g[a][I][l], n += g[a][I][l] * g[a][I][l];
      PF_TEST_CLOSE(s, 0.0, 0, 1e-12);
      PF_TEST_TRUE(n > 1.0); /* not degenerate: |Gamma|^2 = 8 for a parallelepiped */
      for (int j = 0; j < 3; j++) {
        double t = 0;
        for (int I = 0; I < 8; I++) t += g[a][I][l] * one[l][I][j];
        PF_TEST_CLOSE(t, 0.0, 0, 1e-15 * (1 + 2.0 * l));
      }
    }
}

static void test_mass_and_length(void) {
  double x[8][3], m[8], total = 0, B[8][3];
  distorted(x);
  pf_hex8_lumped_mass(x, 7800.0, m);
  for (int I = 0; I < 8; I++) total += m[I], PF_TEST_TRUE(m[I] > 0);
  PF_TEST_CLOSE(total, 7800.0 * volume_gl6(x), 1e-13, 0);
  double c[8][3], h = 2.5e-3;
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) c[I][i] = 0.5 * h * (1 + pf_hex8_node_sign[I][i]);
  PF_TEST_CLOSE(pf_hex8_char_length(c, pf_hex8_mean_gradient(c, B)), h, 1e-14, 0);
}

/* Corner Jacobians: a cube of edge h has det J = (h/2)^3 at every corner; a distorted element's
 * smallest equals the smallest full isoparametric det J evaluated at the corners; pushing a corner
 * node past the plane of its three neighbours (the corner folds over) makes it negative while the
 * element's volume stays positive. */
static void test_corner_jacobian(void) {
  double c[8][3], x[8][3], grad[8][3], h = 2.0e-3;
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) c[I][i] = 0.5 * h * (1 + pf_hex8_node_sign[I][i]);
  PF_TEST_CLOSE(pf_hex8_min_corner_jacobian(c), 0.125 * h * h * h, 1e-14, 0);
  distorted(x);
  double jmin = INFINITY;
  for (int I = 0; I < 8; I++) jmin = fmin(jmin, pf_hex8_gradients(x, pf_hex8_node_sign[I], grad));
  PF_TEST_CLOSE(pf_hex8_min_corner_jacobian(x), jmin, 1e-13, 0);
  /* node 6 (+1, +1, +1) of the cube: its neighbours 2, 5, 7 span the plane x + y + z = 2h; moved
   * along (-1, -1, -1) by d, it crosses the plane at d = h / sqrt(3) */
  for (int k = -1; k <= 1; k += 2) {
    double d = h / sqrt(3.0) * (1 + 0.01 * k), B[8][3];
    memcpy(x, c, sizeof x);
    for (int i = 0; i < 3; i++) x[6][i] -= d / sqrt(3.0);
    PF_TEST_TRUE((pf_hex8_min_corner_jacobian(x) < 0) == (k > 0));
    PF_TEST_TRUE(pf_hex8_mean_gradient(x, B) > 0.5 * h * h * h);
  }
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  test_corner_jacobian();
  test_mean_gradient();
  test_far_from_origin();
  test_lanes_independent();
  test_gauss_lanes();
  test_hourglass_vectors();
  test_mass_and_length();
  return pf_test_finish();
}
