/* The orthotropic model (material/material_orthotropic.c) against closed forms: its stiffness,
 * measured through the update (sigma = dt C D from zero stress), inverts to the compliance built
 * here from the engineering constants (Jones 1999, sec. 2.3); a rotation of 90 degrees about axis
 * 3 swaps E1 and E2; the off-axis modulus and shear coupling of a rotation theta about axis 3
 * follow Jones's transformed compliances (Jones 1999, sec. 2.6); the Z-X-Z Euler convention and
 * the axes form agree; isotropic constants give the isotropic stiffness and K, G; K is the Voigt
 * bulk modulus and K + 4G/3 the fastest quasi-longitudinal modulus, along the fibres of a ply and
 * along [111] of a cubic crystal; bad decks are refused naming the key. Every expected value is computed here from the engineering constants. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fem/fem.h"

/* A general orthotropic set (every constant different) near a carbon/epoxy ply. */
static const double E1 = 181e9, E2 = 10.3e9, E3 = 9.5e9, G12 = 7.17e9, G13 = 6.5e9, G23 = 3.7e9,
                    NU12 = 0.28, NU13 = 0.30, NU23 = 0.42, RHO = 1600;

/* A material mapping: density rho, c = {E1, E2, E3, G12, G13, G23, nu12, nu13, nu23}, then the
 * orientation's line (static storage, valid until the next call). */
static const char *ortho_deck(double rho, const double c[9], const char *orientation) {
  static char text[1024];
  snprintf(text, sizeof text,
           "model: orthotropic\ndensity: %g\nE1: %.17g\nE2: %.17g\nE3: %.17g\nG12: %.17g\nG13: %.17g\n"
           "G23: %.17g\nnu12: %.17g\nnu13: %.17g\nnu23: %.17g\n%s",
           rho, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], orientation);
  return text;
}

static const char *deck(const char *orientation) {
  const double c[9] = {E1, E2, E3, G12, G13, G23, NU12, NU13, NU23};
  return ortho_deck(RHO, c, orientation);
}

/* The compliance in the material axes, engineering shear strain (Jones 1999, sec. 2.3). */
static void compliance(double S[6][6]) {
  memset(S, 0, 36 * sizeof(double));
  S[0][0] = 1 / E1, S[1][1] = 1 / E2, S[2][2] = 1 / E3;
  S[0][1] = S[1][0] = -NU12 / E1, S[0][2] = S[2][0] = -NU13 / E1, S[1][2] = S[2][1] = -NU23 / E2;
  S[3][3] = 1 / G23, S[4][4] = 1 / G13, S[5][5] = 1 / G12;
}

/* The material's engineering stiffness in global axes, column b from one update with the
 * engineering strain increment 1e-3 e_b (D_b = 1e-3 / dt, halved for a shear: tensor shear). */
static void stiffness_of(const pf_material *m, double C[6][6]) {
  const double dt = 1e-6, g = 1e-3;
  for (int b = 0; b < 6; b++) {
    pf_test_point p;
    pf_test_point_init(m, &p);
    p.D[b] = g / dt / (b < 3 ? 1.0 : 2.0);
    pf_test_point_step(m, dt, &p);
    for (int a = 0; a < 6; a++) C[a][b] = p.sig[a] / g;
  }
}

/* Gauss-Jordan inverse with partial pivoting of a 6 x 6 matrix. */
static void inverse6(double A[6][6], double X[6][6]) {
  double M[6][12];
  for (int r = 0; r < 6; r++)
    for (int c = 0; c < 12; c++) M[r][c] = c < 6 ? A[r][c] : (c - 6 == r);
  for (int c = 0; c < 6; c++) {
    int piv = c;
    for (int r = c + 1; r < 6; r++)
      if (fabs(M[r][c]) > fabs(M[piv][c])) piv = r;
    for (int k = 0; k < 12; k++) {
      const double t = M[c][k];
      M[c][k] = M[piv][k], M[piv][k] = t;
    }
    const double d = M[c][c];
    for (int k = 0; k < 12; k++) M[c][k] /= d;
    for (int r = 0; r < 6; r++)
      if (r != c) {
        const double f = M[r][c];
        for (int k = 0; k < 12; k++) M[r][k] -= f * M[c][k];
      }
  }
  for (int r = 0; r < 6; r++)
    for (int c = 0; c < 6; c++) X[r][c] = M[r][c + 6];
}

/* The global compliance of the material loaded from deck(orientation). */
static int global_compliance(const char *orientation, double S[6][6]) {
  pf_material *m = pf_test_material_must_load(deck(orientation), "ply");
  if (!m) return 1;
  double C[6][6];
  stiffness_of(m, C);
  inverse6(C, S);
  pf_material_destroy(&m);
  return 0;
}

/* 1. Material axes = global axes: C S = I to 1e-12 (S from the constants). */
static void inverts_to_compliance(void) {
  pf_material *m = pf_test_material_must_load(deck(""), "ply");
  if (!m) return;
  double C[6][6], S[6][6], err = 0;
  stiffness_of(m, C);
  compliance(S);
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) {
      double s = 0;
      for (int k = 0; k < 6; k++) s += C[i][k] * S[k][j];
      err = fmax(err, fabs(s - (i == j)));
    }
  printf("C S - I: largest entry %.3g\n", err);
  PF_TEST_TRUE(err < 1e-12);
  pf_material_destroy(&m);
}

/* 2. 90 degrees about axis 3: axis 1 = Rz(90) e1 = e2 and axis 2 = -e1, so global y is material 1,
 * x is material 2 (reversed, which no entry below sees), z is 3; so S_xx = 1/E2, S_yy = 1/E1, S_xy = -nu12/E1, S_zz = 1/E3, the yz
 * shear is the 1-3 plane (1/G13), xz the 2-3 plane (1/G23), xy the 1-2 plane (1/G12); no
 * normal-shear coupling. */
static void swap_90(void) {
  double S[6][6];
  if (global_compliance("angles: [90, 0, 0]\n", S)) return;
  PF_TEST_CLOSE(1 / S[0][0], E2, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[1][1], E1, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[2][2], E3, 1e-12, 0);
  PF_TEST_CLOSE(S[0][1], -NU12 / E1, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[3][3], G13, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[4][4], G23, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[5][5], G12, 1e-12, 0);
  for (int a = 0; a < 3; a++)
    for (int b = 3; b < 6; b++) PF_TEST_CLOSE(S[a][b], 0.0, 0, 1e-12 / E2);
}

/* 3. Axis 1 at theta from x in the x-y plane (angles [theta, 0, 0]), m = cos, n = sin (Jones 1999,
 * sec. 2.6):
 *   1/E_x = m^4/E1 + (1/G12 - 2 nu12/E1) m^2 n^2 + n^4/E2,
 *   S16 = (2 S11 - 2 S12 - S66) m^3 n - (2 S22 - 2 S12 - S66) m n^3   (gamma_xy = S16 sigma_x),
 *   S12 = (S11 + S22 - S66) m^2 n^2 + S12 (m^4 + n^4)                (eps_y = S12 sigma_x). */
static void off_axis(void) {
  const double s11 = 1 / E1, s22 = 1 / E2, s12 = -NU12 / E1, s66 = 1 / G12;
  for (int deg = 0; deg <= 90; deg += 15) {
    char o[64];
    snprintf(o, sizeof o, "angles: [%d, 0, 0]\n", deg);
    double S[6][6];
    if (global_compliance(o, S)) return;
    const double t = deg * PF_PI / 180, m = cos(t), n = sin(t);
    const double Ex = 1 / (pow(m, 4) / E1 + (1 / G12 - 2 * NU12 / E1) * m * m * n * n + pow(n, 4) / E2);
    const double S16 = (2 * s11 - 2 * s12 - s66) * m * m * m * n - (2 * s22 - 2 * s12 - s66) * m * n * n * n;
    const double S12 = (s11 + s22 - s66) * m * m * n * n + s12 * (pow(m, 4) + pow(n, 4));
    printf("theta %2d: E_x %.6e Pa (closed form %.6e), gamma_xy/eps_x %.6f (closed form %.6f)\n", deg,
           1 / S[0][0], Ex, S[5][0] / S[0][0], S16 * Ex);
    PF_TEST_CLOSE(1 / S[0][0], Ex, 1e-12, 0);
    PF_TEST_CLOSE(S[5][0], S16, 1e-11, 1e-12 * s66);
    PF_TEST_CLOSE(S[1][0], S12, 1e-11, 1e-12 * s11);
  }
}

/* 4. Euler Z-X-Z: [90, 90, 0] takes axis 1 to y, 2 to z, 3 to x (rotate about z by 90, then
 * about the new x, which is y, by 90); the same axes as rows give the same stiffness. */
static void euler_and_axes(void) {
  double S[6][6], Sa[6][6];
  if (global_compliance("angles: [90, 90, 0]\n", S)) return;
  PF_TEST_CLOSE(1 / S[0][0], E3, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[1][1], E1, 1e-12, 0);
  PF_TEST_CLOSE(1 / S[2][2], E2, 1e-12, 0);
  if (global_compliance("axes: [[0, 1, 0], [0, 0, 1], [1, 0, 0]]\n", Sa)) return;
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++) PF_TEST_CLOSE(Sa[a][b], S[a][b], 1e-12, 1e-12 / E1);
  /* Axis 1 at 30 degrees in the x-y plane given as axes equals angles [30, 0, 0]. */
  const double c = cos(PF_PI / 6), s = sin(PF_PI / 6);
  char o[160];
  snprintf(o, sizeof o, "axes: [[%.17g, %.17g, 0], [%.17g, %.17g, 0], [0, 0, 1]]\n", c, s, -s, c);
  if (global_compliance(o, Sa) || global_compliance("angles: [30, 0, 0]\n", S)) return;
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++) PF_TEST_CLOSE(Sa[a][b], S[a][b], 1e-12, 1e-12 / E1);
}

/* 5. Isotropic constants (E, nu, G = E / 2(1 + nu)) at any orientation: C = lambda I(x)I + 2 mu
 * I_sym to round-off, K = E / 3(1 - 2nu) and G = mu (the fastest wave is lambda + 2 mu in every
 * direction). */
static void isotropic(void) {
  const double E = 200e9, nu = 0.3, mu = E / (2 * (1 + nu)), lam = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double c[9] = {E, E, E, mu, mu, mu, nu, nu, nu};
  pf_material *m = pf_test_material_must_load(ortho_deck(7800, c, "angles: [20, 35, 50]\n"), "iso");
  if (!m) return;
  double C[6][6];
  stiffness_of(m, C);
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++) {
      const double want = (a < 3 && b < 3 ? lam : 0) + (a == b ? (a < 3 ? 2 * mu : mu) : 0);
      PF_TEST_CLOSE(C[a][b], want, 0, 1e-12 * E);
    }
  PF_TEST_CLOSE(pf_material_bulk_modulus(m), E / (3 * (1 - 2 * nu)), 1e-12, 0);
  PF_TEST_CLOSE(pf_material_shear_modulus(m), mu, 1e-12, 0);
  pf_material_destroy(&m);
}

/* 6. K and G of the ply: K = the Voigt bulk modulus (C11 + C22 + C33 + 2(C12 + C13 + C23))/9
 * of the stiffness inverted here from S; K + 4G/3 = M, the fastest quasi-longitudinal modulus.
 * Whatever the constants, M >= C11, C22, C33 (the P waves along the axes, whose Christoffel
 * tensors are diag(C11, C66, C55) etc.); for this ply the fibre P wave is the fastest (a search
 * over directions outside this test, 1-degree grid, found none faster): M = C11. The wave speed
 * at F = I is sqrt(M / rho). The same at another orientation (both are invariants). */
static void moduli(void) {
  double S[6][6], C[6][6];
  compliance(S);
  inverse6(S, C);
  const double KV = (C[0][0] + C[1][1] + C[2][2] + 2 * (C[0][1] + C[0][2] + C[1][2])) / 9;
  for (int k = 0; k < 2; k++) {
    pf_material *m = pf_test_material_must_load(deck(k ? "angles: [30, 40, 50]\n" : ""), "ply");
    if (!m) return;
    const double K = pf_material_bulk_modulus(m), M = K + 4 * pf_material_shear_modulus(m) / 3;
    printf("K %.6e Pa (Voigt %.6e), K + 4G/3 %.6e Pa (C11 %.6e)\n", K, KV, M, C[0][0]);
    PF_TEST_CLOSE(K, KV, 1e-12, 0);
    PF_TEST_CLOSE(M, C[0][0], 1e-12, 0);
    PF_TEST_TRUE(M >= fmax(C[1][1], C[2][2]));
    pf_test_point p;
    pf_test_point_init(m, &p);
    pf_test_point_step(m, 1e-6, &p);
    PF_TEST_CLOSE(p.c, sqrt(C[0][0] / RHO), 1e-12, 0);
    pf_material_destroy(&m);
  }
}

/* 7. A cubic crystal (E1 = E2 = E3, one nu, one G unrelated to E / 2(1 + nu)): copper, C11 = 168.4,
 * C12 = 121.4, C44 = 75.4 GPa (Kittel 2005, ch. 3), whose anisotropy 2 C44 / (C11 - C12) = 3.2 > 1
 * makes the longitudinal wave along [111] the fastest, rho c^2 = (C11 + 2 C12 + 4 C44) / 3 = 237.6
 * GPa against C11 along the axes (Kittel 2005, ch. 3): the search must leave the axes. Engineering
 * constants of a cubic crystal: E = (C11 - C12)(C11 + 2 C12) / (C11 + C12), nu = C12 / (C11 +
 * C12), G = C44; K = (C11 + 2 C12) / 3. At two orientations. */
static void cubic(void) {
  const double c11 = 168.4e9, c12 = 121.4e9, c44 = 75.4e9;
  const double E = (c11 - c12) * (c11 + 2 * c12) / (c11 + c12), nu = c12 / (c11 + c12);
  for (int k = 0; k < 2; k++) {
    const double c[9] = {E, E, E, c44, c44, c44, nu, nu, nu};
    pf_material *m = pf_test_material_must_load(ortho_deck(8960, c, k ? "angles: [10, 20, 30]\n" : ""), "copper");
    if (!m) return;
    const double K = pf_material_bulk_modulus(m), M = K + 4 * pf_material_shear_modulus(m) / 3;
    printf("cubic: K + 4G/3 %.6e Pa ([111]: %.6e, C11 %.6e)\n", M, (c11 + 2 * c12 + 4 * c44) / 3, c11);
    PF_TEST_CLOSE(K, (c11 + 2 * c12) / 3, 1e-12, 0);
    PF_TEST_CLOSE(M, (c11 + 2 * c12 + 4 * c44) / 3, 1e-10, 0);
    pf_material_destroy(&m);
  }
}

static void bad(const char *text, const char *must_mention) { pf_test_material_bad(text, "ply", 1, must_mention); }

#define BASE "model: orthotropic\ndensity: 1600\nE1: 181e9\nE3: 10.3e9\nG12: 7.17e9\nG13: 7.17e9\nG23: 3.7e9\nnu12: 0.28\nnu13: 0.28\n"

static void bad_inputs(void) {
  pf_error_set_quiet(1);
  bad(BASE "E2: 10.3e9\n", "key 'nu23'"); /* missing */
  bad(BASE "nu23: 0.4\n", "key 'E2'");
  bad(BASE "E2: -10.3e9\nnu23: 0.4\n", "key 'E2'");
  bad(BASE "E2: 10.3e9\nnu23: 1.0\n", "key 'nu23'"); /* |nu23| < sqrt(E2/E3) = 1 */
  bad(BASE "E2: 10.3e9\nnu23: 0.4\nyoungs_modulus: 1e9\n", "key 'youngs_modulus'");
  /* All E equal, every nu 0.6 (each below 1): Delta = 1 - 3 (0.36) - 2 (0.216) < 0. */
  bad("model: orthotropic\ndensity: 1600\nE1: 1e9\nE2: 1e9\nE3: 1e9\nG12: 1e8\nG13: 1e8\nG23: 1e8\n"
      "nu12: 0.6\nnu13: 0.6\nnu23: 0.6\n", "key 'nu12'");
  bad(BASE "E2: 10.3e9\nnu23: 0.4\nangles: [0, 0, 0]\naxes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n", "key 'axes'");
  bad(BASE "E2: 10.3e9\nnu23: 0.4\naxes: [[1, 0, 0], [0, 1, 0], [0, 0, -1]]\n", "key 'axes'"); /* a reflection */
  bad(BASE "E2: 10.3e9\nnu23: 0.4\naxes: [[1, 0, 0], [0, 1, 1e-6], [0, 0, 1]]\n", "key 'axes'");
  bad(BASE "E2: 10.3e9\nnu23: 0.4\naxes: [[1, 0, 0], [0, 1, 0]]\n", "axes");
  pf_error_clear();
  pf_error_set_quiet(0);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  inverts_to_compliance();
  swap_90();
  off_axis();
  euler_and_axes();
  isotropic();
  moduli();
  cubic();
  bad_inputs();
  return pf_test_finish();
}
