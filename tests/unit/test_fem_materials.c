/* The FE constitutive library (material/, material/eos_mie_gruneisen.c) against closed forms:
 * a conformance loop over every registered model (zero strain, rigid rotation, small-strain
 * Lame response, batching), then each model's own closed forms, the Mie-Gruneisen equation of
 * state against the Rankine-Hugoniot jump conditions, the Lexan deck of the expanding-tube
 * problem, and bad decks. Every expected value is derived here, in the comments, from the
 * model's defining equations (docs/theory/fem_materials.md), not taken from the code. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fem/fem.h"

/* ---- decks ------------------------------------------------------------------------------- */
#define ELASTIC_DECK "model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
#define NH_DECK "model: neo_hookean\ndensity: 1100\nbulk_modulus: 2.0e9\nshear_modulus: 0.6e9\n"
/* Taylor-bar copper (inputs/taylor_impact.yaml): E = 117 GPa, nu = 0.35, 400 MPa, H = 100 MPa. */
#define J2_DECK                                                                                    \
  "model: j2\ndensity: 8930\nyoungs_modulus: 117e9\npoissons_ratio: 0.35\n"                       \
  "yield_stress: 400e6\nhardening_modulus: 100e6\n"
#define J2_POWER_DECK                                                                              \
  "model: j2\ndensity: 8930\nyoungs_modulus: 117e9\npoissons_ratio: 0.35\n"                       \
  "yield_stress: 400e6\nhardening_modulus: 500e6\nhardening_exponent: 0.5\n"
/* OFHC copper, Johnson & Cook (1983) constants, with adiabatic heating. */
#define JC_DECK                                                                                    \
  "model: johnson_cook\ndensity: 8960\nyoungs_modulus: 124e9\npoissons_ratio: 0.34\n"             \
  "specific_heat: 383\ntaylor_quinney: 0.9\n"                                                      \
  "johnson_cook:\n  A: 90e6\n  B: 292e6\n  C: 0.025\n  n: 0.31\n  m: 1.09\n"                      \
  "  reference_strain_rate: 1.0\n  reference_temperature: 298\n  melt_temperature: 1356\n"
/* Lexan of the expanding-tube experiment (Littlewood 2014, back-up slides): 70 F =
 * 294.26 K, 500 F = 533.15 K. */
#define LEXAN_DECK                                                                                 \
  "model: johnson_cook\ndensity: 1190\nyoungs_modulus: 2.54e9\npoissons_ratio: 0.344\n"           \
  "johnson_cook:\n  A: 75.8e6\n  B: 68.9e6\n  C: 0.0\n  n: 1.0\n  m: 1.85\n"                      \
  "  reference_temperature: 294.26\n  melt_temperature: 533.15\n"                                  \
  "eos:\n  type: mie_gruneisen\n  c0: 1933\n  s1: 3.49\n  s2: -8.2\n  s3: 9.6\n  gamma0: 0.61\n"

/* 6061-T6, Tupek, Rimoli & Radovitzky (2013), Tables 3 and 4. */
#define MJC_DECK                                                                                   \
  "model: modified_johnson_cook\ndensity: 2700\nyoungs_modulus: 72e9\npoissons_ratio: 0.343\n"     \
  "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04, C: 0.002, reference_strain_rate: 1}\n" \
  "damage: {d1: 0.875, d2: 0.13, d3: -1.5, d4: 0, reference_strain_rate: 1}\n"

/* The orthotropic model with isotropic constants (E = 200 GPa, nu = 0.3, G = E / 2.6) at a general
 * orientation: its stiffness, K and G are the isotropic ones (tests/unit/test_orthotropic.c), so
 * the conformance loop's Lame closed forms hold. */
#define ORTHO_ISO_DECK                                                                             \
  "model: orthotropic\ndensity: 7800\nE1: 200e9\nE2: 200e9\nE3: 200e9\nG12: 76.923076923076923e9\n"  \
  "G13: 76.923076923076923e9\nG23: 76.923076923076923e9\nnu12: 0.3\nnu13: 0.3\nnu23: 0.3\n"        \
  "angles: [20, 35, 50]\n"

static pf_material *must_load(const char *text) { return pf_test_material_must_load(text, "test"); }

/* ---- conformance suite over every registered model -------------------------------------- */
typedef struct {
  const char *model, *deck;
  int hyper;  /* stress from F alone (ignores the incoming stress) */
  int linear; /* exactly linear in the strain increment (hypoelastic with a constant K) */
} conf_case;

static const conf_case cases[] = {
    {"elastic", ELASTIC_DECK, 0, 1},      {"neo_hookean", NH_DECK, 1, 0},
    {"j2", J2_DECK, 0, 1},                {"j2", J2_POWER_DECK, 0, 1},
    {"johnson_cook", JC_DECK, 0, 1},      {"johnson_cook", LEXAN_DECK, 0, 0},
    {"modified_johnson_cook", MJC_DECK, 1, 0}, {"orthotropic", ORTHO_ISO_DECK, 0, 1},
};
enum { NCASES = sizeof cases / sizeof cases[0] };

static void conformance_case(const conf_case *cc) {
  pf_material *m = must_load(cc->deck);
  if (!m) return;
  const double K = pf_material_bulk_modulus(m), G = pf_material_shear_modulus(m);
  const double rho0 = pf_material_density(m), lam = K - 2.0 * G / 3.0;
  const int ns = pf_material_nstate(m);
  PF_TEST_TRUE(ns >= 0 && ns <= 8);
  for (int k = 0; k < ns; k++) PF_TEST_TRUE(pf_material_state_name(m, k) != NULL);

  /* 1. F = I, D = 0, sigma = 0: the stress stays exactly zero, the history does not move, and
   * the wave speed is at least the small-strain dilatational speed sqrt((K + 4G/3)/rho0). */
  pf_test_point p, p0;
  pf_test_point_init(m, &p);
  p0 = p;
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 0);
  for (int k = 0; k < ns; k++) PF_TEST_CLOSE(p.st[k], p0.st[k], 0, 0);
  PF_TEST_TRUE(p.c >= sqrt((K + 4 * G / 3) / rho0) * (1 - 1e-14));

  /* 2. Rigid rotation F = R, D = 0. From zero stress: zero (hyperelastic: sigma(R) = (G/J)(R R^T
   * - I) + ... = 0; hypoelastic: zero rate). From a deviatoric stress S0 already rotated by the
   * element: S0 unchanged (hypoelastic: zero rate, and S0 is inside every yield surface here)
   * or zero (hyperelastic). Round-off scale: 1e-14 K. */
  const double axis[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  pf_test_point_init(m, &p);
  pf_test_rotation(axis, 0.7, p.F);
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-14 * K);
  const double S0[6] = {1.0e-4 * G, -0.4e-4 * G, -0.6e-4 * G, 0.3e-4 * G, -0.2e-4 * G, 0.5e-4 * G};
  pf_test_point_init(m, &p);
  pf_test_rotation(axis, 0.7, p.F);
  memcpy(p.sig, S0, sizeof S0);
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++) PF_TEST_CLOSE(p.sig[k], cc->hyper ? 0.0 : S0[k], 1e-13, 1e-14 * K);

  /* 3. Uniaxial strain increment eps along x (D_xx = eps/dt, F = diag(1 + eps, 1, 1)):
   * linear elasticity gives sigma_xx = (lambda + 2G) eps, sigma_yy = sigma_zz = lambda eps,
   * no shear. Hypoelastic models with constant K: exact (1e-10). The others (neo-Hookean, the
   * Mie-Gruneisen pressure) differ at second order: for neo-Hookean sigma_xx = (lambda + 2G)eps
   * - (G + 3 lambda/2) eps^2 + O(eps^3) and sigma_yy = lambda (eps - 3/2 eps^2) (expand
   * (G/J)(J^2 - 1) + lambda ln J / J at J = 1 + eps), so a relative 1.5 eps; the eos pressure
   * rho0 C0^2 mu with mu = 1/J - 1 = -eps + eps^2 ... plus Gamma0 E = O(eps^2) likewise stays
   * below 3 eps relative. Tolerance 5 eps, with eps = 1e-7 (round-off in 1/J - 1 ~ 1e-9). */
  const double eps = 1e-7, dt = 1e-6;
  pf_test_point_init(m, &p);
  p.F[0] = 1 + eps;
  p.D[0] = eps / dt;
  pf_test_point_step(m, dt, &p);
  const double tol = cc->linear ? 1e-10 : 5 * eps;
  PF_TEST_CLOSE(p.sig[0], (lam + 2 * G) * eps, tol, 0);
  PF_TEST_CLOSE(p.sig[1], lam * eps, tol, 0);
  PF_TEST_CLOSE(p.sig[2], lam * eps, tol, 0);
  for (int k = 3; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-12 * G * eps);

  /* 4. Batching: three different points in one call give bitwise what three calls give
   * (history point-major, state[i * nstate + k]). */
  pf_test_point q[3];
  double F3[27], D3[18], s3[18], st3[24], c3[3];
  for (int i = 0; i < 3; i++) {
    pf_test_point_init(m, &q[i]);
    q[i].F[0] = 1 + 1e-3 * (i + 1), q[i].F[1] = 2e-3 * i;
    q[i].D[0] = 1e3 * (i + 1), q[i].D[5] = 2e3 * (i + 2), q[i].D[1] = -3e2 * i;
    q[i].sig[3] = 1e-5 * G * i;
    memcpy(F3 + 9 * i, q[i].F, sizeof q[i].F);
    memcpy(D3 + 6 * i, q[i].D, sizeof q[i].D);
    memcpy(s3 + 6 * i, q[i].sig, sizeof q[i].sig);
    for (int k = 0; k < ns; k++) st3[ns * i + k] = q[i].st[k];
  }
  pf_material_update(m, 3, 1e-6, F3, D3, s3, st3, c3);
  for (int i = 0; i < 3; i++) {
    pf_test_point_step(m, 1e-6, &q[i]);
    for (int k = 0; k < 6; k++) PF_TEST_TRUE(s3[6 * i + k] == q[i].sig[k]);
    for (int k = 0; k < ns; k++) PF_TEST_TRUE(st3[ns * i + k] == q[i].st[k]);
    PF_TEST_TRUE(c3[i] == q[i].c);
  }
  pf_material_destroy(&m);
  PF_TEST_TRUE(m == NULL);
}

static void conformance(void) {
  /* Every registered model must have at least one conformance case. */
  char names[256];
  snprintf(names, sizeof names, "%s", pf_material_names());
  int nmodels = 0;
  for (char *tok = strtok(names, ", "); tok; tok = strtok(NULL, ", ")) {
    nmodels++;
    PF_TEST_TRUE(pf_material_known(tok));
    int found = 0;
    for (int c = 0; c < NCASES; c++) found |= !strcmp(cases[c].model, tok);
    if (!found) fprintf(stderr, "model '%s' has no conformance case\n", tok), pf_test_failures++;
  }
  PF_TEST_TRUE(nmodels >= 4);
  for (int c = 0; c < NCASES; c++) conformance_case(&cases[c]);
}

/* ---- elastic --------------------------------------------------------------------------- */
static void elastic(void) {
  pf_material *m = must_load(ELASTIC_DECK);
  if (!m) return;
  /* K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)). */
  const double E = 200e9, nu = 0.3, lam = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  PF_TEST_CLOSE(pf_material_bulk_modulus(m), E / (3 * (1 - 2 * nu)), 1e-15, 0);
  PF_TEST_CLOSE(pf_material_shear_modulus(m), G, 1e-15, 0);
  PF_TEST_CLOSE(pf_material_density(m), 7800, 0, 0);
  PF_TEST_TRUE(!strcmp(pf_material_name(m), "test"));
  PF_TEST_TRUE(pf_material_nstate(m) == 0);
  /* Uniaxial strain in N steps of d eps: sigma_xx = (lambda + 2G) eps, sigma_yy = lambda eps;
   * c = sqrt((lambda + 2G) J / rho0) with J = 1 + eps. */
  pf_test_point p;
  pf_test_point_init(m, &p);
  const int N = 100;
  const double de = 1e-5, dt = 1e-7;
  for (int k = 1; k <= N; k++) {
    p.D[0] = de / dt;
    p.F[0] = 1 + k * de;
    pf_test_point_step(m, dt, &p);
  }
  const double e = N * de;
  PF_TEST_CLOSE(p.sig[0], (lam + 2 * G) * e, 1e-12, 0);
  PF_TEST_CLOSE(p.sig[1], lam * e, 1e-12, 0);
  PF_TEST_CLOSE(p.sig[2], lam * e, 1e-12, 0);
  PF_TEST_CLOSE(p.c, sqrt((lam + 2 * G) * (1 + e) / 7800), 1e-14, 0);
  /* A general rate D with every component: sigma = dt (lambda tr(D) I + 2 G D) componentwise,
   * added to the incoming stress. */
  const double Dg[6] = {300.0, -120.0, 50.0, 70.0, -210.0, 160.0}, s0[6] = {1e6, 2e6, -3e6, 4e6, -5e6, 6e6};
  pf_test_point_init(m, &p);
  memcpy(p.D, Dg, sizeof Dg);
  memcpy(p.sig, s0, sizeof s0);
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++)
    PF_TEST_CLOSE(p.sig[k], s0[k] + 1e-6 * ((k < 3 ? lam * (300.0 - 120.0 + 50.0) : 0) + 2 * G * Dg[k]), 1e-14, 0);
  pf_material_destroy(&m);
  /* The (K, G) pair and both pairs given consistently give the same constants. */
  m = must_load("model: elastic\ndensity: 7800\nbulk_modulus: 160e9\nshear_modulus: 80e9\n");
  if (m) {
    PF_TEST_CLOSE(pf_material_bulk_modulus(m), 160e9, 0, 0);
    PF_TEST_CLOSE(pf_material_shear_modulus(m), 80e9, 0, 0);
    pf_material_destroy(&m);
  }
  /* E = 9KG/(3K + G) = 9*160*80/560 GPa = 205.714285.. GPa, nu = (3K - 2G)/(2(3K + G)) = 320/1120. */
  m = must_load("model: elastic\ndensity: 7800\nbulk_modulus: 160e9\nshear_modulus: 80e9\n"
                "youngs_modulus: 205.7142857142857e9\npoissons_ratio: 0.2857142857142857\n");
  pf_material_destroy(&m);
}

/* ---- neo-Hookean ----------------------------------------------------------------------- */
/* sigma = (G/J)(b - I) + (lambda ln J / J) I, b = F F^T (Bonet & Wood 2008, sec. 6.4.3),
 * written out here for the diagonal and simple-shear F used below. */
static void neo_hookean(void) {
  pf_material *m = must_load(NH_DECK);
  if (!m) return;
  const double K = 2.0e9, G = 0.6e9, lam = K - 2 * G / 3, rho0 = 1100;
  pf_test_point p;
  /* Uniaxial stretch F = diag(s, 1, 1): J = s, b = diag(s^2, 1, 1):
   * sigma_xx = G (s^2 - 1)/s + lambda ln s / s, sigma_yy = sigma_zz = lambda ln s / s. */
  const double stretch[2] = {1.5, 0.7};
  for (int t = 0; t < 2; t++) {
    const double s = stretch[t];
    pf_test_point_init(m, &p);
    p.F[0] = s;
    p.sig[0] = 1e9; /* ignored: hyperelastic */
    pf_test_point_step(m, 1e-6, &p);
    PF_TEST_CLOSE(p.sig[0], G * (s * s - 1) / s + lam * log(s) / s, 1e-13, 0);
    PF_TEST_CLOSE(p.sig[1], lam * log(s) / s, 1e-13, 0);
    PF_TEST_CLOSE(p.sig[2], lam * log(s) / s, 1e-13, 0);
    for (int k = 3; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-6);
  }
  /* Wave speed in compression s = 0.7: the longitudinal modulus of the model's spatial
   * elasticity tensor lambda/J + 2 (G - lambda ln J)/J (the stress is compressive, so no
   * initial-stress term), c^2 = M / rho = M J / rho0 = (lambda + 2G - 2 lambda ln J) / rho0. */
  PF_TEST_CLOSE(p.c, sqrt((lam + 2 * G - 2 * lam * log(0.7)) / rho0), 1e-13, 0);
  /* Simple shear F = I + g e_x (x) e_y: J = 1, b = [[1 + g^2, g, 0], [g, 1, 0], [0, 0, 1]]:
   * sigma_xx = G g^2, sigma_xy = G g, the rest zero. */
  const double g = 0.8;
  pf_test_point_init(m, &p);
  p.F[1] = g;
  pf_test_point_step(m, 1e-6, &p);
  PF_TEST_CLOSE(p.sig[0], G * g * g, 1e-14, 0);
  PF_TEST_CLOSE(p.sig[5], G * g, 1e-14, 0);
  for (int k = 1; k < 5; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-5);
  /* Objectivity: F = R U gives sigma(R U) = R sigma(U) R^T with sigma(U) from the diagonal
   * closed form above (U = diag(u0, u1, u2), J = u0 u1 u2). */
  const double u[3] = {1.2, 0.9, 1.1}, J = u[0] * u[1] * u[2];
  double R[9], sU[3];
  for (int a = 0; a < 3; a++) sU[a] = G / J * (u[a] * u[a] - 1) + lam * log(J) / J;
  const double ax[3] = {0.6, 0.0, 0.8};
  pf_test_rotation(ax, 1.1, R);
  pf_test_point_init(m, &p);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) p.F[3 * i + j] = R[3 * i + j] * u[j];
  pf_test_point_step(m, 1e-6, &p);
  static const int vi[6] = {0, 1, 2, 1, 0, 0}, vj[6] = {0, 1, 2, 2, 2, 1};
  for (int v = 0; v < 6; v++) {
    double want = 0;
    for (int a = 0; a < 3; a++) want += R[3 * vi[v] + a] * sU[a] * R[3 * vj[v] + a];
    PF_TEST_CLOSE(p.sig[v], want, 0, 1e-12 * G);
  }
  pf_material_destroy(&m);
}

/* ---- J2 -------------------------------------------------------------------------------- */
/* One step of uniaxial stress: D = diag(d, dl, dl) with the lateral rate dl found by the secant
 * method so that sigma_yy = sigma_zz = 0 (to 1e-13 of the yield stress). */
static void uniaxial_stress_step(const pf_material *m, double dt, double d, double *dl, pf_test_point *p,
                                 double tol) {
  const pf_test_point start = *p;
  pf_test_point a = start, b = start;
  double xa = *dl, xb = *dl + 0.05 * d;
  a.D[0] = d, a.D[1] = a.D[2] = xa;
  pf_test_point_step(m, dt, &a);
  for (int it = 0; it < 60; it++) {
    b = start;
    b.D[0] = d, b.D[1] = b.D[2] = xb;
    pf_test_point_step(m, dt, &b);
    if (fabs(b.sig[1]) <= tol) {
      *p = b, *dl = xb;
      return;
    }
    const double xn = xb - b.sig[1] * (xb - xa) / (b.sig[1] - a.sig[1]);
    a = b, xa = xb, xb = xn;
  }
  fprintf(stderr, "uniaxial stress: lateral iteration did not converge\n");
  pf_test_failures++;
  *p = b;
}

static void j2(void) {
  pf_material *m = must_load(J2_DECK);
  if (!m) return;
  PF_TEST_TRUE(pf_material_nstate(m) == 1 && !strcmp(pf_material_state_name(m, 0), "eqps"));
  PF_TEST_TRUE(pf_material_state_name(m, 1) == NULL);
  const double E = 117e9, nu = 0.35, Y = 400e6, H = 100e6, G = E / (2 * (1 + nu));
  /* Uniaxial stress, strain eps along x. Elastic: sigma = E eps while E eps < Y. Plastic, with
   * linear hardening on this proportional path (where backward-Euler radial return is exact):
   * sigma = Y + H eqps (consistency; the plastic strain along x is eqps because the plastic
   * flow is along (1, -1/2, -1/2)), eps = sigma/E + eqps (additivity), hence
   * sigma = Y + E_t (eps - Y/E), E_t = E H/(E + H); the deviator norm
   * |s| = sqrt(2/3) sigma (s = sigma (2/3, -1/3, -1/3)). */
  pf_test_point p;
  pf_test_point_init(m, &p);
  double dl = -nu * 1e3;
  const double de = 1e-4, dt = 1e-7, Et = E * H / (E + H);
  int nplastic = 0;
  for (int k = 1; k <= 100; k++) {
    uniaxial_stress_step(m, dt, de / dt, &dl, &p, 1e-13 * Y);
    const double e = k * de;
    if (E * e < Y) {
      PF_TEST_CLOSE(p.sig[0], E * e, 1e-12, 0);
      PF_TEST_CLOSE(p.st[0], 0.0, 0, 0);
    } else {
      nplastic++;
      PF_TEST_CLOSE(p.sig[0], Y + H * p.st[0], 1e-12, 0);
      PF_TEST_CLOSE(p.sig[0], Y + Et * (e - Y / E), 1e-10, 0);
      double s[6], mean = (p.sig[0] + p.sig[1] + p.sig[2]) / 3;
      for (int c = 0; c < 6; c++) s[c] = p.sig[c] - (c < 3 ? mean : 0);
      const double snorm = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                                2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
      PF_TEST_CLOSE(snorm, sqrt(2.0 / 3.0) * (Y + H * p.st[0]), 1e-12, 0);
    }
  }
  PF_TEST_TRUE(nplastic > 50);
  /* Slope of stress against plastic strain between two plastic states: exactly H. */
  {
    const double s1 = p.sig[0], e1 = p.st[0];
    uniaxial_stress_step(m, dt, de / dt, &dl, &p, 1e-13 * Y);
    PF_TEST_CLOSE((p.sig[0] - s1) / (p.st[0] - e1), H, 1e-6, 0);
  }
  /* Pure shear (D_xy = gdot/2; engineering shear g): elastic tau = G g while sqrt(3) tau < Y;
   * plastic: sqrt(3) tau = Y + H eqps (von Mises q = sqrt(3) tau) and g = tau/G + sqrt(3) eqps
   * (the plastic engineering shear is sqrt(3) eqps), so tau = (Y/sqrt(3) + H g/3)/(1 + H/(3G)).
   * Normal stresses stay zero. */
  pf_test_point_init(m, &p);
  const double dg = 2e-4;
  nplastic = 0;
  for (int k = 1; k <= 100; k++) {
    p.D[5] = 0.5 * dg / dt;
    pf_test_point_step(m, dt, &p);
    const double g = k * dg;
    const double tau = sqrt(3) * G * g < Y ? G * g : (Y / sqrt(3) + H * g / 3) / (1 + H / (3 * G));
    nplastic += sqrt(3) * G * g >= Y;
    PF_TEST_CLOSE(p.sig[5], tau, 1e-10, 0);
    PF_TEST_CLOSE(p.st[0], (g - p.sig[5] / G) / sqrt(3), 1e-9, 1e-15);
    for (int c = 0; c < 5; c++) PF_TEST_CLOSE(p.sig[c], 0.0, 0, 1e-6);
  }
  PF_TEST_TRUE(nplastic > 50);
  pf_material_destroy(&m);

  /* Power law sigma_y = Y + H eqps^0.5, pure shear. At every plastic step the converged state
   * satisfies consistency sqrt(3) tau = Y + H eqps^0.5 and the flow rule g = tau/G + sqrt(3)
   * eqps; these two equations fix (tau, eqps) uniquely, since the first is increasing and the
   * second decreasing in eqps. The first plastic step starts at eqps = 0, where the slope is
   * infinite. A single large step from the virgin state is checked the same way. */
  m = must_load(J2_POWER_DECK);
  if (!m) return;
  const double Hp = 500e6;
  pf_test_point_init(m, &p);
  nplastic = 0;
  for (int k = 1; k <= 100; k++) {
    p.D[5] = 0.5 * dg / dt;
    pf_test_point_step(m, dt, &p);
    const double g = k * dg;
    if (p.st[0] > 0) {
      nplastic++;
      PF_TEST_CLOSE(sqrt(3) * p.sig[5], Y + Hp * sqrt(p.st[0]), 1e-10, 0);
      PF_TEST_CLOSE(g, p.sig[5] / G + sqrt(3) * p.st[0], 1e-10, 0);
    } else {
      PF_TEST_CLOSE(p.sig[5], G * g, 1e-12, 0);
      PF_TEST_TRUE(sqrt(3) * G * g <= Y);
    }
  }
  PF_TEST_TRUE(nplastic > 50);
  pf_test_point_init(m, &p);
  p.D[5] = 0.5 * 0.05 / dt;
  pf_test_point_step(m, dt, &p);
  PF_TEST_TRUE(p.st[0] > 0);
  PF_TEST_CLOSE(sqrt(3) * p.sig[5], Y + Hp * sqrt(p.st[0]), 1e-10, 0);
  PF_TEST_CLOSE(0.05, p.sig[5] / G + sqrt(3) * p.st[0], 1e-10, 0);
  pf_material_destroy(&m);
}

/* ---- Johnson-Cook ---------------------------------------------------------------------- */
/* The Johnson & Cook (1983) flow stress, written out independently of the code. */
static double jc_flow_stress(double eqps, double rate, double T) {
  const double A = 90e6, B = 292e6, C = 0.025, n = 0.31, mm = 1.09, r0 = 1.0, Tr = 298, Tm = 1356;
  double Ts = (T - Tr) / (Tm - Tr);
  Ts = Ts < 0 ? 0 : Ts > 1 ? 1 : Ts;
  return (A + B * pow(eqps, n)) * (1 + C * log(rate / r0 > 1 ? rate / r0 : 1)) * (1 - pow(Ts, mm));
}

/* One pure-shear step of engineering shear g over dt from (eqps0, T0) and zero stress. The
 * converged step must satisfy: consistency sqrt(3) tau = sigma_y(eqps, deqps/dt, T0); the flow
 * rule g = tau/G + sqrt(3) deqps; adiabatic heating rho c dT = beta sigma_y deqps (J = 1 in
 * shear, so rho = rho0); and the energy E = dt (0 + tau)/2 * 2 D_xy = tau g / 2 (trapezoidal
 * stress power from zero stress, sigma : D = 2 sigma_xy D_xy). Returns deqps / dt. */
static double jc_shear_step(const pf_material *m, double eqps0, double T0, double g, double dt) {
  const double G = 124e9 / (2 * 1.34), rho0 = 8960, cp = 383, beta = 0.9;
  pf_test_point p;
  pf_test_point_init(m, &p);
  p.st[0] = eqps0, p.st[1] = T0;
  p.D[5] = 0.5 * g / dt;
  pf_test_point_step(m, dt, &p);
  const double tau = p.sig[5], deqps = p.st[0] - eqps0, sy = sqrt(3) * tau;
  PF_TEST_TRUE(deqps > 0);
  PF_TEST_CLOSE(sy, jc_flow_stress(p.st[0], deqps / dt, T0), 1e-10, 1e-6);
  PF_TEST_CLOSE(g, tau / G + sqrt(3) * deqps, 1e-11, 0);
  PF_TEST_CLOSE(rho0 * cp * (p.st[1] - T0), beta * sy * deqps, 1e-10, 1e-9);
  PF_TEST_CLOSE(p.st[2], 0.5 * tau * g, 1e-12, 1e-9);
  for (int c = 0; c < 5; c++) PF_TEST_CLOSE(p.sig[c], 0.0, 0, 1e-5);
  return deqps / dt;
}

static void johnson_cook(void) {
  pf_material *m = must_load(JC_DECK);
  if (!m) return;
  const char *names[3] = {"eqps", "temperature", "energy"};
  PF_TEST_TRUE(pf_material_nstate(m) == 3);
  for (int k = 0; k < 3; k++) PF_TEST_TRUE(!strcmp(pf_material_state_name(m, k), names[k]));
  /* The initial temperature defaults to the reference temperature. */
  double st[6];
  pf_material_init(m, 2, st);
  PF_TEST_CLOSE(st[1], 298, 0, 0);
  PF_TEST_CLOSE(st[4], 298, 0, 0);
  PF_TEST_CLOSE(st[0] + st[2] + st[3] + st[5], 0, 0, 0);
  {
    pf_material *m2 = must_load(JC_DECK "initial_temperature: 400\n");
    if (m2) {
      pf_material_init(m2, 2, st);
      PF_TEST_CLOSE(st[1], 400, 0, 0);
      PF_TEST_CLOSE(st[4], 400, 0, 0);
      pf_material_destroy(&m2);
    }
  }
  /* Rate term active (deqps/dt >> rate0), with thermal softening (T = 500 K) and hardening. */
  double rate = jc_shear_step(m, 0.1, 500, 0.01, 1e-6);
  PF_TEST_TRUE(rate > 100);
  /* Rate below the reference rate: the rate factor is 1. */
  rate = jc_shear_step(m, 0.1, 500, 0.01, 10.0);
  PF_TEST_TRUE(rate < 1.0);
  /* From the virgin state (slope of B eqps^0.31 infinite at 0), at T_ref (no softening) and
   * below T_ref (T* clamped to 0). */
  jc_shear_step(m, 0.0, 298, 0.01, 1e-6);
  jc_shear_step(m, 0.0, 250, 0.01, 1e-6);
  jc_shear_step(m, 0.3, 1000, 0.02, 1e-5);
  /* At and above the melting temperature sigma_y = 0: the deviator is returned to zero, all of
   * the shear is plastic (deqps = g / sqrt(3)). */
  for (int t = 0; t < 2; t++) {
    pf_test_point p;
    pf_test_point_init(m, &p);
    p.st[1] = t ? 1500 : 1356;
    p.D[5] = 0.5 * 0.01 / 1e-6;
    pf_test_point_step(m, 1e-6, &p);
    PF_TEST_CLOSE(p.sig[5], 0.0, 0, 1e-5);
    PF_TEST_CLOSE(p.st[0], 0.01 / sqrt(3), 1e-12, 0);
  }
  pf_material_destroy(&m);
}

/* ---- Mie-Gruneisen --------------------------------------------------------------------- */
/* The LS-DYNA *EOS_GRUNEISEN pressure, written out here (mu = 1/J - 1, E per reference volume). */
typedef struct {
  double rho0, c0, s1, s2, s3, g0, a;
} eos_par;

static double eos_f(const eos_par *e, double mu) {
  if (mu <= 0) return e->rho0 * e->c0 * e->c0 * mu;
  const double num = 1 + (1 - e->g0 / 2) * mu - e->a / 2 * mu * mu;
  const double den = 1 - (e->s1 - 1) * mu - e->s2 * mu * mu / (mu + 1) - e->s3 * pow(mu, 3) / pow(mu + 1, 2);
  return e->rho0 * e->c0 * e->c0 * mu * num / (den * den);
}
static double eos_p(const eos_par *e, double mu, double E) { return eos_f(e, mu) + (e->g0 + e->a * mu) * E; }

/* Stress of a JC+eos material at F = J^(1/3) I, D = 0, zero deviator and energy E0: no work is
 * done (D = 0) and no deviator is created, so sigma = -p(mu, E0) I. */
static void eos_state(const pf_material *m, double J, double E0, pf_test_point *p) {
  pf_test_point_init(m, p);
  p->F[0] = p->F[4] = p->F[8] = cbrt(J);
  p->st[2] = E0;
  pf_test_point_step(m, 1e-7, p);
}

static void mie_gruneisen(void) {
  const eos_par lexan = {1190, 1933, 3.49, -8.2, 9.6, 0.61, 0.0};
  pf_material *m = must_load(LEXAN_DECK);
  if (!m) return;
  const double G = 2.54e9 / (2 * 1.344), rho0 = 1190, K0 = rho0 * 1933.0 * 1933.0;
  PF_TEST_CLOSE(pf_material_bulk_modulus(m), K0, 1e-15, 0);
  PF_TEST_CLOSE(pf_material_shear_modulus(m), G, 1e-15, 0);
  pf_test_point p;
  /* E = 0 on both branches, and with energy (Gamma0 E term). */
  const double mus[4] = {0.02, 0.2, 0.4, -0.05}, Es[2] = {0.0, 3e8};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 2; k++) {
      eos_state(m, 1 / (1 + mus[i]), Es[k], &p);
      const double want = -eos_p(&lexan, mus[i], Es[k]);
      for (int c = 0; c < 3; c++) PF_TEST_CLOSE(p.sig[c], want, 1e-12, 0);
      for (int c = 3; c < 6; c++) PF_TEST_CLOSE(p.sig[c], 0.0, 0, 0);
      PF_TEST_TRUE(isfinite(p.c) && p.c > 0);
    }
  /* Tension branch: p = rho0 C0^2 mu + Gamma0 E. */
  eos_state(m, 1 / 0.95, 1e8, &p);
  PF_TEST_CLOSE(-p.sig[0], K0 * -0.05 + 0.61 * 1e8, 1e-12, 0);
  /* The Hugoniot (Rankine-Hugoniot jump conditions, independent of the mu form): for
   * compression eta = 1 - J = up/Us the fit Us = C0 + S1 up + S2 up^2/Us + S3 up^3/Us^2 reads
   * Us = C0 / (1 - S1 eta - S2 eta^2 - S3 eta^3); the shock state has p_H = rho0 Us up and
   * E_H = p_H eta / 2 per reference volume (e - e0 = p (v0 - v)/2). With a = 0 the eos must
   * return p(mu_H, E_H) = p_H. */
  const double etas[3] = {0.05, 0.15, 0.25};
  for (int i = 0; i < 3; i++) {
    const double eta = etas[i];
    const double Us = 1933 / (1 - 3.49 * eta + 8.2 * eta * eta - 9.6 * eta * eta * eta), up = eta * Us;
    const double pH = rho0 * Us * up;
    eos_state(m, 1 - eta, 0.5 * pH * eta, &p);
    PF_TEST_CLOSE(-p.sig[0], pH, 1e-12, 0);
  }
  /* Wave speed: at the reference state K_eff = rho0 C0^2 (> K of E and nu here), so
   * c = sqrt((rho0 C0^2 + 4G/3)/rho0). In compression, the isentropic K_s = -J dp/dJ|_s
   * (dE = -p dJ): K_s = (f'(mu) + a E)/J + Gamma p J, f' by central differences here. */
  PF_TEST_TRUE(K0 > 2.54e9 / (3 * (1 - 2 * 0.344)));
  eos_state(m, 1.0, 0.0, &p);
  PF_TEST_CLOSE(p.c, sqrt((K0 + 4 * G / 3) / rho0), 1e-14, 0);
  {
    const double J = 0.85, mu = 1 / J - 1, E0 = 2e7, h = 1e-6;
    eos_state(m, J, E0, &p);
    const double df = (eos_f(&lexan, mu + h) - eos_f(&lexan, mu - h)) / (2 * h);
    const double Ks = df / J + 0.61 * eos_p(&lexan, mu, E0) * J;
    PF_TEST_TRUE(Ks > K0);
    PF_TEST_CLOSE(p.c, sqrt((Ks + 4 * G / 3) * J / rho0), 1e-7, 0);
  }
  /* Energy along an isentropic compression, D = d I (no deviator): dE/dJ = -p(J, E) exactly
   * (stress power J sigma : D = -p dJ/dt). Reference: RK4 in J with 20000 steps. The material
   * is driven with N = 400 steps, F = J(t)^(1/3) I, J(t) = exp(3 d t); its trapezoidal update is
   * second order, error ~ (dJ)^2 ~ 1e-7 relative. */
  {
    const double Jend = 0.87;
    double E = 0, J = 1;
    const int M = 20000;
    const double hJ = (Jend - 1) / M;
    for (int k = 0; k < M; k++) {
      const double k1 = -eos_p(&lexan, 1 / J - 1, E);
      const double k2 = -eos_p(&lexan, 1 / (J + hJ / 2) - 1, E + hJ / 2 * k1);
      const double k3 = -eos_p(&lexan, 1 / (J + hJ / 2) - 1, E + hJ / 2 * k2);
      const double k4 = -eos_p(&lexan, 1 / (J + hJ) - 1, E + hJ * k3);
      E += hJ / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      J += hJ;
    }
    const int N = 400;
    const double dt = 1e-8, d = log(Jend) / (3 * N * dt);
    pf_test_point_init(m, &p);
    for (int k = 1; k <= N; k++) {
      p.D[0] = p.D[1] = p.D[2] = d;
      p.F[0] = p.F[4] = p.F[8] = exp(d * k * dt);
      pf_test_point_step(m, dt, &p);
    }
    PF_TEST_CLOSE(p.st[2], E, 1e-5, 0);
    PF_TEST_CLOSE(-p.sig[0], eos_p(&lexan, 1 / Jend - 1, p.st[2]), 1e-12, 0);
    PF_TEST_TRUE(p.st[0] == 0);
  }
  pf_material_destroy(&m);

  /* Linear Us-up form (S2 = S3 = 0) with a != 0, copper-like constants: the classical
   * p = rho0 C0^2 mu (1 + (1 - Gamma0/2) mu) / (1 - (S1 - 1) mu)^2 at E = 0 and a = 0 would be
   * its special case; here a = 0.5 adds -(a/2) mu^2 to the numerator and a mu E to Gamma. */
  m = must_load("model: johnson_cook\ndensity: 8930\nyoungs_modulus: 117e9\npoissons_ratio: 0.35\n"
                "johnson_cook: {A: 90e6, B: 292e6, n: 0.31, m: 1.09, reference_temperature: 298, "
                "melt_temperature: 1356}\n"
                "eos: {type: mie_gruneisen, c0: 3940, s1: 1.489, gamma0: 2.02, a: 0.5}\n");
  if (!m) return;
  const double k = 8930 * 3940.0 * 3940.0;
  for (int i = 0; i < 3; i++) {
    const double mu = 0.05 * (i + 1), E0 = 1e9 * i;
    eos_state(m, 1 / (1 + mu), E0, &p);
    const double want = k * mu * (1 + (1 - 2.02 / 2) * mu - 0.25 * mu * mu) / pow(1 - 0.489 * mu, 2) +
                        (2.02 + 0.5 * mu) * E0;
    PF_TEST_CLOSE(-p.sig[0], want, 1e-12, 0);
  }
  pf_material_destroy(&m);
  m = must_load("model: johnson_cook\ndensity: 8930\nyoungs_modulus: 117e9\npoissons_ratio: 0.35\n"
                "johnson_cook: {A: 90e6, B: 292e6, n: 0.31, m: 1.09, reference_temperature: 298, "
                "melt_temperature: 1356}\n"
                "eos: {type: mie_gruneisen, c0: 3940, s1: 1.489, gamma0: 2.02}\n");
  if (!m) return;
  for (int i = 0; i < 3; i++) {
    const double mu = 0.1 * (i + 1);
    eos_state(m, 1 / (1 + mu), 0.0, &p);
    PF_TEST_CLOSE(-p.sig[0], k * mu * (1 + (1 - 2.02 / 2) * mu) / pow(1 - 0.489 * mu, 2), 1e-12, 0);
  }
  pf_material_destroy(&m);
}

/* ---- the Lexan deck under a strong compression with plastic flow ------------------------ */
static void lexan(void) {
  pf_material *m = must_load(LEXAN_DECK);
  if (!m) return;
  pf_test_point p;
  pf_test_point_init(m, &p);
  PF_TEST_CLOSE(p.st[1], 294.26, 0, 0);
  /* 50 steps of uniaxial strain to J = 0.8 at 1e6 1/s. */
  const int N = 50;
  const double dt = 1e-8, d = log(0.8) / (N * dt);
  for (int k = 1; k <= N; k++) {
    p.D[0] = d;
    p.F[0] = exp(d * k * dt);
    pf_test_point_step(m, dt, &p);
  }
  for (int c = 0; c < 6; c++) PF_TEST_TRUE(isfinite(p.sig[c]));
  PF_TEST_TRUE(p.sig[0] < 0 && p.st[0] > 0 && p.st[2] > 0);
  PF_TEST_TRUE(isfinite(p.c) && p.c > 1933);
  pf_material_destroy(&m);
}

/* ---- bad decks ------------------------------------------------------------------------- */
static void bad(const char *text, const char *must_mention) { pf_test_material_bad(text, "test", 1, must_mention); }

static void bad_inputs(void) {
  pf_error_set_quiet(1);
  PF_TEST_TRUE(!pf_material_known("plastic_foo"));
  PF_TEST_TRUE(pf_material_known("j2") && pf_material_known("johnson_cook"));
  bad("model: plastic_foo\ndensity: 1000\nyoungs_modulus: 1e9\npoissons_ratio: 0.3\n", "johnson_cook");
  bad("model: j2\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n", "yield_stress");
  bad("model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.5\n", "poissons_ratio");
  bad("model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: -0.1\n", "poissons_ratio");
  bad("model: elastic\ndensity: 0\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n", "density");
  bad("model: elastic\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n", "density");
  bad("model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\n", "poissons_ratio");
  bad("model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "bulk_modulus: 100e9\n", "bulk_modulus");
  bad("model: elastic\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "yield_stress: 1e8\n", "yield_stress");
  bad("model: neo_hookean\ndensity: 7800\nbulk_modulus: 1e9\nshear_modulus: -1e9\n", "shear_modulus");
  bad("model: j2\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\nyield_stress: -1\n",
      "yield_stress");
  bad("model: j2\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\nyield_stress: 1e8\n"
      "taylor_quinney: 0.9\n", "taylor_quinney");
  bad("model: johnson_cook\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n", "johnson_cook");
  bad("model: johnson_cook\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "johnson_cook: {A: 1e8, B: 1e8, n: 0.5, m: 1, reference_temperature: 300, melt_temperature: 300}\n",
      "melt_temperature");
  bad("model: johnson_cook\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "taylor_quinney: 0.9\n"
      "johnson_cook: {A: 1e8, B: 1e8, n: 0.5, m: 1, reference_temperature: 300, melt_temperature: 1800}\n",
      "specific_heat");
  bad("model: johnson_cook\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "johnson_cook: {A: 1e8, B: 1e8, n: 0.5, m: 1, reference_temperature: 300, melt_temperature: 1800}\n"
      "eos: {type: tillotson, c0: 4000, s1: 1.5, gamma0: 2}\n", "tillotson");
  bad("model: johnson_cook\ndensity: 7800\nyoungs_modulus: 200e9\npoissons_ratio: 0.3\n"
      "johnson_cook: {A: 1e8, B: 1e8, n: 0.5, m: 1, reference_temperature: 300, melt_temperature: 1800}\n"
      "eos: {type: mie_gruneisen, c0: -4000, s1: 1.5, gamma0: 2}\n", "c0");
  pf_error_clear();
  pf_error_set_quiet(0);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  conformance();
  elastic();
  neo_hookean();
  j2();
  johnson_cook();
  mie_gruneisen();
  lexan();
  bad_inputs();
  return pf_test_finish();
}
