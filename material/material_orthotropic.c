/* Orthotropic linear elasticity, hypoelastic (docs/theory/fem_materials.md §8).
 * Material axes 1, 2, 3; engineering constants E_i, G_ij, nu_ij (nu_ij = -eps_j / eps_i under
 * a stress along i, nu_ji = nu_ij E_j / E_i). The compliance in the material axes, Voigt order
 * (11, 22, 33, 23, 13, 12) with engineering shear strains (Jones 1999, Mechanics of Composite
 * Materials, 2nd ed., sec. 2.3):
 *   S = [1/E1 -nu21/E2 -nu31/E3; -nu12/E1 1/E2 -nu32/E3; -nu13/E1 -nu23/E2 1/E3] (+) diag(1/G23,
 *       1/G13, 1/G12),
 * positive definite iff E_i, G_ij > 0, |nu_ij| < sqrt(E_i / E_j) and
 *   Delta = 1 - nu12 nu21 - nu23 nu32 - nu31 nu13 - 2 nu21 nu32 nu13 > 0
 * (Jones 1999, sec. 2.4, restrictions on the engineering constants; Lempriere 1968). Its inverse,
 * the stiffness, in closed form (Jones 1999, sec. 2.3):
 *   C11 = E1 (1 - nu23 nu32) / Delta,  C22 = E2 (1 - nu13 nu31) / Delta,  C33 = E3 (1 - nu12 nu21) / Delta,
 *   C12 = E1 (nu21 + nu31 nu23) / Delta, C13 = E1 (nu31 + nu21 nu32) / Delta,
 *   C23 = E2 (nu32 + nu12 nu31) / Delta, C44 = G23, C55 = G13, C66 = G12.
 * The stiffness tensor is rotated to the global axes once, at create, as a fourth-order tensor,
 * C_pqrs = A_ip A_jq A_kr A_ls C'_ijkl with A's rows the material axes in global coordinates
 * (Ting 1996, Anisotropic Elasticity, sec. 2.6; the same as the Bond matrix, Jones 1999 sec. 2.6),
 * so that no Voigt factor of 2 enters the rotation. The update is hypoelastic as the isotropic
 * model (Belytschko, Liu, Moran & Elkhodary 2014, ch. 5): sigma_{n+1} = sigma_n^R + dt C : D, the
 * element having rotated sigma_n by its objective rate; the material axes stay the ones given in
 * the reference configuration (a small-rotation model, see the theory page).
 * K and G: the Voigt bulk modulus K_V and the G for which K + 4G/3 is M, the largest
 * quasi-longitudinal wave modulus rho c^2 over directions (the Christoffel equation; Auld 1973,
 * Acoustic Fields and Waves in Solids, ch. 7): so the wave speed sqrt(M J / rho0) of the default
 * hypoelastic estimate, and every element or point step from K + 4G/3, bound the fastest wave. */
#include "material/material_impl.h"

#include <string.h>

typedef struct {
  double C[6][6]; /* global stiffness acting on tensor-shear D: dsigma_a = dt sum_b C[a][b] D_b */
} ortho;

static const pf_key ortho_keys[] = {
    {"E1", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: Young's modulus along material axis 1", NULL},
    {"E2", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: Young's modulus along material axis 2", NULL},
    {"E3", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: Young's modulus along material axis 3", NULL},
    {"G12", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: shear modulus in the 1-2 plane", NULL},
    {"G13", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: shear modulus in the 1-3 plane", NULL},
    {"G23", PF_KEY_REAL, 0, NULL, "Pa", "orthotropic: shear modulus in the 2-3 plane", NULL},
    {"nu12", PF_KEY_REAL, 0, NULL, "", "orthotropic: Poisson's ratio -eps2/eps1 under stress along 1", NULL},
    {"nu13", PF_KEY_REAL, 0, NULL, "", "orthotropic: Poisson's ratio -eps3/eps1 under stress along 1", NULL},
    {"nu23", PF_KEY_REAL, 0, NULL, "", "orthotropic: Poisson's ratio -eps3/eps2 under stress along 2", NULL},
    {"angles", PF_KEY_VEC3, 0, "[0, 0, 0]", "deg",
     "orthotropic: material axes as intrinsic Z-X-Z Euler angles [a, b, c] (rotate the global axes "
     "about z by a, about the new x by b, about the new z by c); or axes", NULL},
    {"axes", PF_KEY_MAT3, 0, NULL, "",
     "orthotropic: material axes 1, 2, 3 as the rows, in global coordinates (a rotation); or angles", NULL},
    PF_KEY_END};

enum { NCONST = 9 }; /* the first nine rows of ortho_keys: E1 E2 E3 G12 G13 G23 nu12 nu13 nu23 */
static const char *const_key(int k) { return ortho_keys[k].name; }

/* The nine constants, each required; moduli positive, |nu_ij| < sqrt(E_i / E_j), Delta > 0. */
static int read_constants(const pf_deck *d, const pf_node *mat, double v[NCONST]) {
  for (int k = 0; k < NCONST; k++) {
    const pf_node *n = pf_node_get(mat, const_key(k));
    if (!n) return pf_deck_error(d, mat, const_key(k), "model 'orthotropic' needs '%s' (E1, E2, E3, G12, G13, "
                                 "G23 in Pa; nu12, nu13, nu23)", const_key(k));
    PF_CALL(pf_deck_real(d, mat, const_key(k), &v[k]));
    if (k < 6 && !(v[k] > 0)) return pf_deck_error(d, n, const_key(k), "must be positive (got %g)", v[k]);
  }
  static const int ei[3] = {0, 0, 1}, ej[3] = {1, 2, 2}; /* nu12, nu13, nu23: E_i, E_j */
  for (int k = 0; k < 3; k++) {
    const double lim = sqrt(v[ei[k]] / v[ej[k]]);
    if (!(fabs(v[6 + k]) < lim))
      return pf_deck_error(d, pf_node_get(mat, const_key(6 + k)), const_key(6 + k),
                           "|%s| = %g must be below sqrt(E%d/E%d) = %g (a positive-definite compliance)",
                           const_key(6 + k), fabs(v[6 + k]), ei[k] + 1, ej[k] + 1, lim);
  }
  const double n21 = v[6] * v[1] / v[0], n31 = v[7] * v[2] / v[0], n32 = v[8] * v[2] / v[1];
  const double delta = 1.0 - v[6] * n21 - v[8] * n32 - n31 * v[7] - 2.0 * n21 * n32 * v[7];
  if (!(delta > 0))
    return pf_deck_error(d, pf_node_get(mat, "nu12"), "nu12",
                         "nu12, nu13, nu23 give 1 - nu12 nu21 - nu23 nu32 - nu31 nu13 - 2 nu21 nu32 nu13 "
                         "= %g, not positive: the compliance is not positive definite", delta);
  return 0;
}

/* The stiffness in the material axes (closed form above), Voigt, engineering shear strain. */
static void material_stiffness(const double v[NCONST], double C[6][6]) {
  const double E1 = v[0], E2 = v[1], E3 = v[2], n12 = v[6], n13 = v[7], n23 = v[8];
  const double n21 = n12 * E2 / E1, n31 = n13 * E3 / E1, n32 = n23 * E3 / E2;
  const double dl = 1.0 - n12 * n21 - n23 * n32 - n31 * n13 - 2.0 * n21 * n32 * n13;
  memset(C, 0, 36 * sizeof(double));
  C[0][0] = E1 * (1.0 - n23 * n32) / dl, C[1][1] = E2 * (1.0 - n13 * n31) / dl;
  C[2][2] = E3 * (1.0 - n12 * n21) / dl;
  C[0][1] = C[1][0] = E1 * (n21 + n31 * n23) / dl;
  C[0][2] = C[2][0] = E1 * (n31 + n21 * n32) / dl;
  C[1][2] = C[2][1] = E2 * (n32 + n12 * n31) / dl;
  C[3][3] = v[5], C[4][4] = v[4], C[5][5] = v[3];
}

/* Voigt index of the tensor pair (i, j): 11 22 33 23 13 12. */
static int voigt(int i, int j) { return i == j ? i : 6 - i - j; }

/* C_pqrs = A_ip A_jq A_kr A_ls C'_ijkl, one index at a time; in and out as Voigt matrices with
 * engineering shear strain (C_ijkl = Cv[voigt(i,j)][voigt(k,l)]). */
static void rotate_stiffness(double A[3][3], double Cm[6][6], double Cg[6][6]) {
  double T[81], U[81];
  for (int q = 0; q < 81; q++) T[q] = Cm[voigt(q / 27, q / 9 % 3)][voigt(q / 3 % 3, q % 3)];
  for (int pass = 0; pass < 4; pass++) { /* the index rotated moves last: after 4 passes, in place */
    for (int q = 0; q < 81; q++) {
      const int p = q % 3, rest = q / 3; /* U[rest, p] = sum_i A_ip T[i, rest] */
      U[q] = A[0][p] * T[rest] + A[1][p] * T[27 + rest] + A[2][p] * T[54 + rest];
    }
    memcpy(T, U, sizeof T);
  }
  static const int pi[6] = {0, 1, 2, 1, 0, 0}, pj[6] = {0, 1, 2, 2, 2, 1};
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++) Cg[a][b] = T[27 * pi[a] + 9 * pj[a] + 3 * pi[b] + pj[b]];
}

/* The material axes as the rows of A: from axes (checked to be a rotation) or the Euler angles
 * R = Rz(a) Rx(b) Rz(c), whose columns are the axes, A = R^T. */
static int read_axes(const pf_deck *d, const pf_node *mat, double A[3][3]) {
  const pf_node *na = pf_node_get(mat, "angles"), *nx = pf_node_get(mat, "axes");
  if (na && nx) return pf_deck_error(d, nx, "axes", "give the material axes as angles or as axes, not both");
  if (nx) {
    PF_CALL(pf_deck_mat3(d, mat, "axes", A));
    double err = fabs(pf_mat3_det(A) - 1.0);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        err = fmax(err, fabs(A[i][0] * A[j][0] + A[i][1] * A[j][1] + A[i][2] * A[j][2] - (i == j)));
    if (!(err <= 1e-9))
      return pf_deck_error(d, nx, "axes", "the rows are not a rotation (orthonormal, determinant +1): off by %g", err);
    return 0;
  }
  double ang[3] = {0, 0, 0};
  PF_CALL(pf_deck_vec3(d, mat, "angles", ang));
  const double a = ang[0] * PF_PI / 180, b = ang[1] * PF_PI / 180, c = ang[2] * PF_PI / 180;
  const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cc = cos(c), sc = sin(c);
  const double R[3][3] = {{ca * cc - sa * cb * sc, -ca * sc - sa * cb * cc, sa * sb},
                          {sa * cc + ca * cb * sc, -sa * sc + ca * cb * cc, -ca * sb},
                          {sb * sc, sb * cc, cb}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) A[i][j] = R[j][i];
  return 0;
}

/* The quasi-longitudinal modulus of direction n: the largest eigenvalue of the Christoffel
 * tensor Gamma_ik = C_ijkl n_j n_l (Auld 1973, ch. 7), as -lambda_min(-Gamma). */
static double christoffel_max(double Cv[6][6], const double n[3], double G[3][3]) {
  double M[3][3];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      double s = 0;
      for (int j = 0; j < 3; j++)
        for (int l = 0; l < 3; l++) s += Cv[voigt(i, j)][voigt(k, l)] * n[j] * n[l];
      G[i][k] = s, M[i][k] = -s;
    }
  return -pf_sym3_min_eigenvalue(M);
}

/* M = max over unit n, a of a_i n_j a_k n_l C_ijkl: the best direction of a 3-degree grid of the
 * half sphere, then alternating power steps a <- Gamma(n) a, n <- P(a) n (P_jl = a_i a_k C_ijkl),
 * each of which does not lower a.Gamma(n).a, both matrices being positive definite. */
static double wave_modulus(double Cv[6][6]) {
  double best = -1, n[3] = {1, 0, 0}, G[3][3];
  for (int it = 0; it <= 30; it++)
    for (int ip = 0; ip < 120; ip++) {
      const double t = it * PF_PI / 60, p = ip * PF_PI / 60;
      const double m[3] = {sin(t) * cos(p), sin(t) * sin(p), cos(t)};
      const double f = christoffel_max(Cv, m, G);
      if (f > best) best = f, memcpy(n, m, sizeof n);
    }
  double a[3] = {n[0], n[1], n[2]};
  for (int k = 0; k < 500; k++) {
    double na[3], nn[3], P[3][3];
    christoffel_max(Cv, n, G);
    for (int i = 0; i < 3; i++) na[i] = G[i][0] * a[0] + G[i][1] * a[1] + G[i][2] * a[2];
    christoffel_max(Cv, na, P); /* P(a) = Gamma with the roles of the index pairs exchanged */
    for (int i = 0; i < 3; i++) nn[i] = P[i][0] * n[0] + P[i][1] * n[1] + P[i][2] * n[2];
    const double la = sqrt(na[0] * na[0] + na[1] * na[1] + na[2] * na[2]);
    const double ln = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    for (int i = 0; i < 3; i++) a[i] = na[i] / la, n[i] = nn[i] / ln;
  }
  return fmax(best, christoffel_max(Cv, n, G));
}

static int ortho_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  double v[NCONST], A[3][3], Cm[6][6];
  ortho *o;
  PF_CALL(read_constants(d, mat, v));
  PF_CALL(read_axes(d, mat, A));
  PF_MALLOC(o, 1);
  m->data = o;
  material_stiffness(v, Cm);
  rotate_stiffness(A, Cm, o->C);
  /* K_V = (C11 + C22 + C33 + 2 (C12 + C13 + C23)) / 9 (Voigt 1928), rotation invariant. */
  m->K = (Cm[0][0] + Cm[1][1] + Cm[2][2] + 2.0 * (Cm[0][1] + Cm[0][2] + Cm[1][2])) / 9.0;
  m->G = 0.75 * (wave_modulus(Cm) - m->K);
  m->lambda = m->K - 2.0 * m->G / 3.0;
  m->E = 9.0 * m->K * m->G / (3.0 * m->K + m->G);
  m->nu = (3.0 * m->K - 2.0 * m->G) / (2.0 * (3.0 * m->K + m->G));
  for (int a = 0; a < 6; a++)
    for (int b = 3; b < 6; b++) o->C[a][b] *= 2.0; /* engineering shear strain = 2 D_b */
  return 0;
}

/* sigma += dt C D, Voigt (xx, yy, zz, yz, xz, xy), tensor shear D (the 2 folded into C). */
static void ortho_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                         const double *restrict D, double *restrict sigma, double *restrict state) {
  (void)F, (void)state;
  const ortho *o = m->data;
  for (pf_int i = 0; i < n; i++) {
    const double *restrict dd = D + 6 * i;
    double *restrict s = sigma + 6 * i;
    for (int a = 0; a < 6; a++) {
      const double *c = o->C[a];
      s[a] += dt * (c[0] * dd[0] + c[1] * dd[1] + c[2] * dd[2] + c[3] * dd[3] + c[4] * dd[4] + c[5] * dd[5]);
    }
  }
}

const pf_material_ops pf_material_orthotropic = {
    .name = "orthotropic",
    .own_elastic = 1,
    .keys = ortho_keys,
    .create = ortho_create,
    .update = ortho_update,
};
