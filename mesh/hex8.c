/* Geometry of the 8-node trilinear hexahedron: shape-function gradients, the exact volume, the
 * mean (uniform) gradient of Flanagan & Belytschko (1981), the characteristic length for the
 * stable step, and the quadrature-exact lumped mass. Node order is Exodus HEX8: nodes 0-3 the
 * face zeta = -1 counter-clockwise seen from +zeta, nodes 4-7 above them. */
#include "mesh/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Parent coordinates (xi, eta, zeta) of the nodes. */
const double pf_hex8_node_sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                        {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

/* Gauss points of the 2x2x2 rule (weights 1): the node signs over sqrt(3). */
void pf_hex8_gauss_point(int g, double xi[3]) {
  for (int k = 0; k < 3; k++) xi[k] = pf_hex8_node_sign[g][k] / sqrt(3.0);
}

/* N_I(xi) = (1 + xi xi_I)(1 + eta eta_I)(1 + zeta zeta_I) / 8 (Hughes 2000, eq. 3.5.2) and its
 * parent derivatives dN_I/dxi_k. */
static void parent_derivatives(const double xi[3], double dN[8][3]) {
  for (int I = 0; I < 8; I++) {
    const double *s = pf_hex8_node_sign[I];
    double a = 1 + xi[0] * s[0], b = 1 + xi[1] * s[1], c = 1 + xi[2] * s[2];
    dN[I][0] = 0.125 * s[0] * b * c;
    dN[I][1] = 0.125 * a * s[1] * c;
    dN[I][2] = 0.125 * a * b * s[2];
  }
}

double pf_hex8_gradients(double x[8][3], const double xi[3], double grad[8][3]) {
  double dN[8][3], J[3][3] = {{0}};
  parent_derivatives(xi, dN);
  /* J_ik = dx_i / dxi_k = sum_I x_iI dN_I/dxi_k */
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) J[i][k] += x[I][i] * dN[I][k];
  double inv[3][3], det = pf_mat3_inverse(J, inv);
  /* dN_I/dx_i = dN_I/dxi_k (J^-1)_ki */
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      grad[I][i] = dN[I][0] * inv[0][i] + dN[I][1] * inv[1][i] + dN[I][2] * inv[2][i];
  return det;
}

/* Mean gradient B_iI = (1/V) int_V dN_I/dx_i dV and volume V (Flanagan & Belytschko 1981,
 * eqs. 14-16): B_I = (1/V) dV/dx_I. With x_xi = sum_I x_I dN_I/dxi etc.,
 *     V = int det J = sum_IJK x_I . (x_J x x_K) C_IJK,   C_IJK = int N_I,xi N_J,eta N_K,zeta,
 * and the triple product's cyclic symmetry gives
 *     dV/dx_I = sum_{J<K} (x_J x x_K) W_IJK,   W_IJK = S_IJK - S_IKJ,   S = C_IJK + C_JKI + C_KIJ.
 * The integrands are quadratic in each parent coordinate, so the 2x2x2 Gauss rule gives C
 * exactly; W is computed once and kept as its nonzero entries. V = (1/3) sum_I x_I . dV/dx_I
 * (V is homogeneous of degree 3 in x). Every node has the same number of nonzero W_IJK (nine,
 * by the element's symmetry), kept per node in (J, K) order. The nodes are taken relative to
 * their centroid (B and V do not change under translation), so that the cross products do not
 * cancel for elements far from the origin. */
enum { PER_NODE = 9 };
typedef struct {
  int8_t J, K;
  double w;
} pair_weight;
static pair_weight wtab[8][PER_NODE];
static double gauss_dN[8][3][PF_HEX8_LANES]; /* dN_I/dxi_k at Gauss point g in lane g */
static int built = 0;

static void build_triples(void) {
  static double C[8][8][8];
  for (int g = 0; g < 8; g++) {
    double xi[3], dN[8][3];
    pf_hex8_gauss_point(g, xi);
    parent_derivatives(xi, dN);
    for (int I = 0; I < 8; I++)
      for (int k = 0; k < 3; k++) gauss_dN[I][k][g] = dN[I][k];
    for (int I = 0; I < 8; I++)
      for (int J = 0; J < 8; J++)
        for (int K = 0; K < 8; K++) C[I][J][K] += dN[I][0] * dN[J][1] * dN[K][2];
  }
  for (int I = 0; I < 8; I++) {
    int n = 0;
    for (int J = 0; J < 8; J++)
      for (int K = J + 1; K < 8; K++) {
        double w = (C[I][J][K] + C[J][K][I] + C[K][I][J]) - (C[I][K][J] + C[K][J][I] + C[J][I][K]);
        if (fabs(w) > 1e-12 && n < PER_NODE) wtab[I][n] = (pair_weight){(int8_t)J, (int8_t)K, w};
        n += fabs(w) > 1e-12;
      }
    if (n != PER_NODE) abort(); /* the trilinear hexahedron has nine per node */
  }
  built = 1;
}

/* The mean gradients of PF_HEX8_LANES elements at once, lane l of every array one element's: the
 * loops over the elements are the vector loops, and each lane's result does not depend on the
 * others (the same bits in any lane, pf_hex8_mean_gradient). */
void pf_hex8_mean_gradient_lanes(double x[8][3][PF_HEX8_LANES], double B[8][3][PF_HEX8_LANES],
                                 double V[PF_HEX8_LANES]) {
  enum { W = PF_HEX8_LANES };
  if (!built) build_triples();
  _Alignas(64) double c[8][3][W], o[3][W], cr[8][8][3][W], v[W];
  for (int i = 0; i < 3; i++) {
#pragma omp simd
    for (int l = 0; l < W; l++) o[i][l] = 0;
    for (int I = 0; I < 8; I++)
#pragma omp simd
      for (int l = 0; l < W; l++) o[i][l] += 0.125 * x[I][i][l];
  }
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
#pragma omp simd
      for (int l = 0; l < W; l++) c[I][i][l] = x[I][i][l] - o[i][l];
  for (int J = 0; J < 8; J++)
    for (int K = J + 1; K < 8; K++) {
      double(*a)[W] = c[J], (*b)[W] = c[K];
      double(*r)[W] = cr[J][K];
#pragma omp simd
      for (int l = 0; l < W; l++) {
        r[0][l] = a[1][l] * b[2][l] - a[2][l] * b[1][l];
        r[1][l] = a[2][l] * b[0][l] - a[0][l] * b[2][l];
        r[2][l] = a[0][l] * b[1][l] - a[1][l] * b[0][l];
      }
    }
  for (int I = 0; I < 8; I++) {
    _Alignas(64) double b[3][W] = {{0}};
#pragma GCC unroll 9 /* (each t its vector loop: unrolled and jammed, the loop over l went scalar) */
    for (int t = 0; t < PER_NODE; t++) {
      const double w = wtab[I][t].w, (*r)[W] = (const double(*)[W])cr[wtab[I][t].J][wtab[I][t].K];
#pragma omp simd
      for (int l = 0; l < W; l++) b[0][l] += w * r[0][l], b[1][l] += w * r[1][l], b[2][l] += w * r[2][l];
    }
    memcpy(B[I], b, sizeof b);
  }
#pragma omp simd
  for (int l = 0; l < W; l++) {
    double s = 0;
    for (int I = 0; I < 8; I++) s += c[I][0][l] * B[I][0][l] + c[I][1][l] * B[I][1][l] + c[I][2][l] * B[I][2][l];
    v[l] = s / 3.0;
  }
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
#pragma omp simd
      for (int l = 0; l < W; l++) B[I][i][l] /= v[l];
#pragma omp simd
  for (int l = 0; l < W; l++) V[l] = v[l];
}

/* pf_hex8_gradients at the eight Gauss points of one element at once, lane g Gauss point g
 * (pf_hex8_gauss_point): the same operations lane by lane, so the same bits. */
void pf_hex8_gauss_gradients_lanes(double x[8][3], double grad[8][3][PF_HEX8_LANES], double det[PF_HEX8_LANES]) {
  enum { W = PF_HEX8_LANES };
  _Static_assert(PF_HEX8_LANES == 8 && PF_TENSOR_LANES == 8, "a lane for each of the 8 Gauss points");
  if (!built) build_triples();
  _Alignas(64) double J[3][3][W], inv[3][3][W];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
#pragma omp simd
      for (int l = 0; l < W; l++) J[i][k][l] = 0;
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++)
#pragma omp simd
        for (int l = 0; l < W; l++) J[i][k][l] += x[I][i] * gauss_dN[I][k][l];
  pf_mat3_inverse_lanes(J, inv, det);
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
#pragma omp simd
      for (int l = 0; l < W; l++)
        grad[I][i][l] = gauss_dN[I][0][l] * inv[0][i][l] + gauss_dN[I][1][l] * inv[1][i][l] + gauss_dN[I][2][l] * inv[2][i][l];
}

/* One element: every lane the same element (the same bits as its lane of a batch). */
double pf_hex8_mean_gradient(double x[8][3], double B[8][3]) {
  _Alignas(64) double xl[8][3][PF_HEX8_LANES], Bl[8][3][PF_HEX8_LANES], V[PF_HEX8_LANES];
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      for (int l = 0; l < PF_HEX8_LANES; l++) xl[I][i][l] = x[I][i];
  pf_hex8_mean_gradient_lanes(xl, Bl, V);
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) B[I][i] = Bl[I][i][0];
  return V[0];
}

/* Row-sum lumped mass: m_I = rho int N_I dV, exact with 2x2x2 Gauss (N_I det J is cubic in each
 * parent coordinate). */
void pf_hex8_lumped_mass(double x[8][3], double rho, double m[8]) {
  double xi[3], grad[8][3];
  for (int I = 0; I < 8; I++) m[I] = 0;
  for (int g = 0; g < 8; g++) {
    pf_hex8_gauss_point(g, xi);
    double det = pf_hex8_gradients(x, xi, grad);
    for (int I = 0; I < 8; I++) {
      const double *s = pf_hex8_node_sign[I];
      double N = 0.125 * (1 + xi[0] * s[0]) * (1 + xi[1] * s[1]) * (1 + xi[2] * s[2]);
      m[I] += rho * N * det;
    }
  }
}

/* Faces of the hexahedron (Exodus side order), outward when the element has positive volume. */
const int pf_hex8_face[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}};

/* Characteristic length l = V / A_max, A_max the largest face area (the LS-DYNA / DYNA3D choice,
 * Hallquist 2006, LS-DYNA Theory Manual eq. 20.4); for a cube of edge h, l = h. The face area of
 * a bilinear quadrilateral is taken as half the norm of its diagonals' cross product (exact for
 * planar faces). */
void pf_hex8_char_length_lanes(double x[8][3][PF_HEX8_LANES], const double V[PF_HEX8_LANES],
                               double len[PF_HEX8_LANES]) {
  enum { W = PF_HEX8_LANES };
  _Alignas(64) double amax[W] = {0};
  for (int f = 0; f < 6; f++) {
    const int *q = pf_hex8_face[f];
#pragma omp simd
    for (int l = 0; l < W; l++) {
      double d1[3], d2[3];
      for (int i = 0; i < 3; i++) d1[i] = x[q[2]][i][l] - x[q[0]][i][l], d2[i] = x[q[3]][i][l] - x[q[1]][i][l];
      const double n0 = d1[1] * d2[2] - d1[2] * d2[1], n1 = d1[2] * d2[0] - d1[0] * d2[2],
                   n2 = d1[0] * d2[1] - d1[1] * d2[0], a = 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
      amax[l] = a > amax[l] ? a : amax[l]; /* (fmax for every area that is a number) */
    }
  }
#pragma omp simd
  for (int l = 0; l < W; l++) len[l] = V[l] / amax[l];
}

double pf_hex8_char_length(double x[8][3], double V) {
  _Alignas(64) double xl[8][3][PF_HEX8_LANES], Vl[PF_HEX8_LANES], len[PF_HEX8_LANES];
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      for (int l = 0; l < PF_HEX8_LANES; l++) xl[I][i][l] = x[I][i];
  for (int l = 0; l < PF_HEX8_LANES; l++) Vl[l] = V;
  pf_hex8_char_length_lanes(xl, Vl, len);
  return len[0];
}

/* The smallest Jacobian determinant det(dx/dxi) over the eight corners. At corner I the trilinear
 * map's derivative along each parent axis is exact from the edge to the neighbour n_k that differs
 * in that coordinate only: dx/dxi_k = (x_I - x_{n_k}) / (2 s_k), s_k = node_sign[I][k]. A one-point
 * element checks det J at its centre only; a corner below zero means the map folds over itself
 * there (the element is tangled, its surface self-intersecting) while the centre may look sound
 * (the corner Jacobians of Knupp 2000 for hexahedral mesh quality). */
double pf_hex8_min_corner_jacobian(double x[8][3]) {
  static const int edge_neighbour[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                           {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
  double jmin = INFINITY;
  for (int I = 0; I < 8; I++) {
    double d[3][3], c[3];
    for (int k = 0; k < 3; k++)
      for (int i = 0; i < 3; i++)
        d[k][i] = (x[I][i] - x[edge_neighbour[I][k]][i]) / (2.0 * pf_hex8_node_sign[I][k]);
    pf_vec3_cross(d[0], d[1], c);
    jmin = fmin(jmin, c[0] * d[2][0] + c[1] * d[2][1] + c[2] * d[2][2]);
  }
  return jmin;
}
