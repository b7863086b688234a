/* The modified Johnson-Cook model (material/material_modified_johnson_cook.c; Tupek, Rimoli &
 * Radovitzky 2013, CMAME 263:20, sec. 2.3) against closed forms derived here, in the comments:
 * the flow stress, the Johnson-Cook failure strain, Hencky elasticity, objectivity, the
 * uniaxial-stress plastic path (in logarithmic strain it is the 1-D small-strain problem), the
 * damage integral, and bad decks. Parameters: 6061-T6 of Tupek et al. (2013), Tables 3 and 4.
 * Every expected value is computed here from the model's defining equations, never taken from
 * the code. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fem/fem.h"

/* ---- decks and constants ------------------------------------------------------------------ */
#define AL_ELASTIC                                                                                 \
  "model: modified_johnson_cook\ndensity: 2700\nyoungs_modulus: 72e9\npoissons_ratio: 0.343\n"
#define TUPEK_FLOW                                                                                 \
  "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04, C: 0.002, reference_strain_rate: 1}\n"
#define TUPEK_DAMAGE "damage: {d1: 0.875, d2: 0.13, d3: -1.5, d4: 0, reference_strain_rate: 1}\n"
/* Tables 3 and 4 of Tupek et al. (2013). */
#define TUPEK_DECK AL_ELASTIC TUPEK_FLOW TUPEK_DAMAGE
/* The same without the rate term (C = 0) and without damage. */
#define RI_DECK AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04}\n"

static const double E = 72e9, NU = 0.343, RHO0 = 2700;
static const double SIG0 = 250e6, BH = 365e6, NH = 0.04, RATE0 = 1.0;
static const double D1 = 0.875, D2 = 0.13, D3 = -1.5;
#define GMOD (E / (2 * (1 + NU)))
#define KMOD (E / (3 * (1 - 2 * NU)))
#define LAME (KMOD - 2 * GMOD / 3)

/* Tupek et al. (2013), sec. 2.3, written as printed:
 * Y = sigma0 [1 + eqps/eps0]^n [1 + C log(r/(2 rate0) + sqrt(1 + (r/(2 rate0))^2))],
 * eps0 = (sigma0/B)^(1/n). */
static double flow_stress(double eqps, double rate, double C) {
  const double eps0 = pow(SIG0 / BH, 1.0 / NH), x = rate / (2 * RATE0);
  return SIG0 * pow(1 + eqps / eps0, NH) * (1 + C * log(x + sqrt(1 + x * x)));
}
/* Johnson & Cook (1985), eq. 2, d4 = 0: eps_f = d1 + d2 exp(d3 sigma*). */
static double failure_strain(double triax) { return D1 + D2 * exp(D3 * triax); }

/* Root of a decreasing function g on [lo, hi] (g(lo) >= 0 >= g(hi)) by bisection to round-off. */
static double bisect(double (*g)(double, const double *), const double *par, double lo, double hi) {
  for (int it = 0; it < 200 && hi - lo > 1e-17 * fabs(hi); it++) {
    const double mid = 0.5 * (lo + hi);
    if (g(mid, par) > 0) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

static pf_material *must_load(const char *text) { return pf_test_material_must_load(text, "al6061"); }

static void set_diag(pf_test_point *p, double a, double b, double c) {
  memset(p->F, 0, sizeof p->F);
  p->F[0] = a, p->F[4] = b, p->F[8] = c;
}

static const int vi[6] = {0, 1, 2, 1, 0, 0}, vj[6] = {0, 1, 2, 2, 2, 1};

/* ---- registration, state, interface basics ------------------------------------------------ */
static void basics(void) {
  PF_TEST_TRUE(pf_material_known("modified_johnson_cook"));
  PF_TEST_TRUE(strstr(pf_material_names(), "modified_johnson_cook") != NULL);
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  static const char *names[8] = {"eqps",      "damage",    "cp_inv_xx", "cp_inv_yy",
                                 "cp_inv_zz", "cp_inv_yz", "cp_inv_xz", "cp_inv_xy"};
  PF_TEST_TRUE(pf_material_nstate(m) == 8);
  for (int k = 0; k < 8; k++) {
    const char *nm = pf_material_state_name(m, k);
    PF_TEST_TRUE(nm && !strcmp(nm, names[k]));
  }
  PF_TEST_CLOSE(pf_material_shear_modulus(m), GMOD, 1e-15, 0);
  PF_TEST_CLOSE(pf_material_bulk_modulus(m), KMOD, 1e-15, 0);
  /* init: eqps = D = 0, Cp^-1 = I. */
  double st[16];
  for (int k = 0; k < 16; k++) st[k] = -7.0;
  pf_material_init(m, 2, st);
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 8; k++) PF_TEST_CLOSE(st[8 * i + k], k >= 2 && k <= 4 ? 1.0 : 0.0, 0, 0);

  /* F = I: zero stress exactly, history unchanged; wave speed sqrt((lambda + 2G)/rho0). The
   * incoming stress is ignored (hyperelastic). */
  pf_test_point p, p0;
  pf_test_point_init(m, &p);
  p.sig[0] = 1e8, p.sig[5] = -3e7;
  p0 = p;
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 0);
  for (int k = 0; k < 8; k++) PF_TEST_CLOSE(p.st[k], p0.st[k], 0, 0);
  PF_TEST_CLOSE(p.c, sqrt((LAME + 2 * GMOD) / RHO0), 1e-14, 0);
  /* F = R: b_e = R R^T = I, zero stress to round-off (1e-14 K). */
  const double ax[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  pf_test_point_init(m, &p);
  pf_test_rotation(ax, 0.7, p.F);
  pf_test_point_step(m, 1e-6, &p);
  for (int k = 0; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-14 * KMOD);
  PF_TEST_CLOSE(p.st[0], 0.0, 0, 0);

  /* Batching: three points (one plastic) in one call give bitwise what three calls give. */
  pf_test_point q[3];
  double F3[27], D3[18], s3[18], st3[24], c3[3];
  for (int i = 0; i < 3; i++) {
    pf_test_point_init(m, &q[i]);
    q[i].F[0] = 1 + 1e-2 * (i + 1), q[i].F[1] = 3e-3 * i, q[i].F[4] = 1 - 4e-3 * i;
    q[i].st[0] = 0.1 * i;
    memcpy(F3 + 9 * i, q[i].F, sizeof q[i].F);
    memcpy(D3 + 6 * i, q[i].D, sizeof q[i].D);
    memcpy(s3 + 6 * i, q[i].sig, sizeof q[i].sig);
    memcpy(st3 + 8 * i, q[i].st, sizeof q[i].st);
  }
  pf_material_update(m, 3, 1e-5, F3, D3, s3, st3, c3);
  for (int i = 0; i < 3; i++) {
    pf_test_point_step(m, 1e-5, &q[i]);
    for (int k = 0; k < 6; k++) PF_TEST_TRUE(s3[6 * i + k] == q[i].sig[k]);
    for (int k = 0; k < 8; k++) PF_TEST_TRUE(st3[8 * i + k] == q[i].st[k]);
    PF_TEST_TRUE(c3[i] == q[i].c);
  }
  PF_TEST_TRUE(q[2].st[0] > 0.2);
  pf_material_destroy(&m);
  PF_TEST_TRUE(m == NULL);
}

/* ---- 1. flow stress ------------------------------------------------------------------------ */
/* Isochoric principal stretch F = diag(e^a, e^-a, 1) from Cp^-1 = I and eqps0: the trial log
 * strain is (a, -a, 0) (deviatoric, J = 1), s_tr = 2G (a, -a, 0), q_tr = 2 sqrt(3) G a. The
 * return keeps the direction, so tau_xx = -tau_yy = 2 G a - sqrt(3) G dgam, tau_zz = 0, and
 * dgam solves 2 sqrt(3) G a - 3 G dgam = Y(eqps0 + dgam, dgam/dt) (found here by bisection). */
static double shear_residual(double x, const double *par) {
  /* par: a, eqps0, dt, C */
  return 2 * sqrt(3) * GMOD * par[0] - 3 * GMOD * x - flow_stress(par[1] + x, x / par[2], par[3]);
}

static void shear_step(const pf_material *m, double C, double eqps0, double a, double dt) {
  const double par[4] = {a, eqps0, dt, C};
  const double hi = (2 * sqrt(3) * GMOD * a - flow_stress(eqps0, 0, C)) / (3 * GMOD);
  PF_TEST_TRUE(hi > 0);
  const double dgam = bisect(shear_residual, par, 0, hi);
  pf_test_point p;
  pf_test_point_init(m, &p);
  p.st[0] = eqps0;
  set_diag(&p, exp(a), exp(-a), 1.0);
  pf_test_point_step(m, dt, &p);
  const double txx = 2 * GMOD * a - sqrt(3) * GMOD * dgam;
  PF_TEST_CLOSE(p.st[0] - eqps0, dgam, 1e-9, 0);
  PF_TEST_CLOSE(p.sig[0], txx, 1e-11, 0);
  PF_TEST_CLOSE(p.sig[1], -txx, 1e-11, 0);
  for (int k = 2; k < 6; k++) PF_TEST_CLOSE(p.sig[k], 0.0, 0, 1e-13 * fabs(txx));
  /* Consistency with the printed formula at the code's own end state. */
  PF_TEST_CLOSE(sqrt(3) * p.sig[0], flow_stress(p.st[0], (p.st[0] - eqps0) / dt, C), 1e-11, 0);
  PF_TEST_TRUE(isfinite(p.sig[0]) && isfinite(p.st[0]));
}

static void flow(void) {
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  /* The reference strain by hand: eps0 = (250/365)^25 = exp(25 ln 0.684932) = 7.7836e-5. At
   * eqps = 1 and zero rate Y = sigma0 ((1 + eps0)/eps0)^n = B (1 + eps0)^n (as eps0^n =
   * sigma0/B): the classical B eqps^n at large strain. */
  const double eps0 = pow(SIG0 / BH, 1 / NH);
  PF_TEST_CLOSE(eps0, 7.7836e-5, 1e-4, 0);
  PF_TEST_CLOSE(flow_stress(1.0, 0, 0.002), 365e6 * pow(1 + eps0, NH), 1e-14, 0);
  /* High rate (r ~ 1e3 .. 1e4 1/s), moderate rate, and near-zero rate (dt = 1e3 s). */
  shear_step(m, 0.002, 0.0, 0.01, 1e-6);
  shear_step(m, 0.002, 0.1, 0.01, 1e-6);
  shear_step(m, 0.002, 0.3, 0.02, 1e-3);
  shear_step(m, 0.002, 0.05, 0.01, 1e3);
  shear_step(m, 0.002, 0.0, 0.2, 1e-7);
  pf_material_destroy(&m);

  m = must_load(RI_DECK);
  if (!m) return;
  shear_step(m, 0.0, 0.0, 0.01, 1e-6);
  shear_step(m, 0.0, 0.2, 0.03, 1e-6);
  /* Finite slope at eqps = 0: dY/deqps = sigma0 n / eps0 (about 1.29e11 Pa; the classical JC
   * B n eqps^(n-1) is infinite there). A step just above yield (q_tr - sigma0 = 2.5e-6 sigma0)
   * gives dgam ~ 1e-9 and a measured slope (sqrt(3) tau_xx - sigma0) / dgam within
   * |Y''| dgam / Y' = (1 - n) dgam / eps0 ~ 2e-5 of it. */
  {
    const double H0 = SIG0 * NH / pow(SIG0 / BH, 1 / NH);
    const double a = SIG0 / (2 * sqrt(3) * GMOD) * (1 + 2.5e-6);
    pf_test_point p;
    pf_test_point_init(m, &p);
    set_diag(&p, exp(a), exp(-a), 1.0);
    pf_test_point_step(m, 1e-6, &p);
    const double dgam = p.st[0], slope = (sqrt(3) * p.sig[0] - SIG0) / dgam;
    PF_TEST_TRUE(dgam > 0 && dgam < 1e-8);
    PF_TEST_CLOSE(slope, H0, 1e-4, 0);
    PF_TEST_CLOSE(dgam, (2 * sqrt(3) * GMOD * a - SIG0) / (3 * GMOD + H0), 1e-4, 0);
  }
  pf_material_destroy(&m);

  /* Finite value at zero rate: with C > 0 and dt = 1e6 s (r ~ 1e-8 1/s) the flow stress is the
   * rate-independent one to 1e-10 (C asinh(x) ~ C x ~ 1e-11). */
  m = must_load(TUPEK_DECK);
  if (!m) return;
  {
    pf_test_point p;
    pf_test_point_init(m, &p);
    p.st[0] = 0.1;
    set_diag(&p, exp(0.01), exp(-0.01), 1.0);
    pf_test_point_step(m, 1e6, &p);
    PF_TEST_TRUE(p.st[0] > 0.1 && isfinite(p.sig[0]));
    PF_TEST_CLOSE(sqrt(3) * p.sig[0], flow_stress(p.st[0], 0.0, 0.0), 1e-10, 0);
  }
  /* dt = 0 (initial forces): elastic even above yield, history untouched. */
  {
    pf_test_point p;
    pf_test_point_init(m, &p);
    set_diag(&p, exp(0.02), exp(-0.02), 1.0);
    pf_test_point_step(m, 0.0, &p);
    PF_TEST_CLOSE(p.sig[0], 2 * GMOD * 0.02, 1e-12, 0);
    PF_TEST_TRUE(p.st[0] == 0 && p.st[1] == 0 && p.st[2] == 1 && p.st[5] == 0);
  }
  pf_material_destroy(&m);
}

/* ---- 2. failure strain -------------------------------------------------------------------- */
/* One plastic step from the virgin state under F = diag(e^0.02, e^x, e^x): axisymmetric, so
 * sigma* = sigma_m / sigma_e = (s_xx + 2 s_yy)/3 / |s_xx - s_yy| of the output stress and
 * D = dgam / eps_f(sigma*) with d4 = 0, i.e. eps_f = eqps / D. Raising x raises the mean stress
 * at nearly the same deviator, so sigma* sweeps from about -0.9 to 2. */
static void failure(void) {
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  const double xs[7] = {-0.03, -0.015, -0.005, 0.0, 0.003, 0.006, 0.009};
  double prev_t = -INFINITY, prev_ef = INFINITY;
  for (int k = 0; k < 7; k++) {
    pf_test_point p;
    pf_test_point_init(m, &p);
    set_diag(&p, exp(0.02), exp(xs[k]), exp(xs[k]));
    pf_test_point_step(m, 1e-3, &p);
    const double triax = (p.sig[0] + 2 * p.sig[1]) / 3 / fabs(p.sig[0] - p.sig[1]);
    PF_TEST_TRUE(p.st[0] > 0 && p.st[1] > 0);
    const double ef = p.st[0] / p.st[1];
    PF_TEST_CLOSE(ef, failure_strain(triax), 1e-12, 0);
    PF_TEST_TRUE(triax > prev_t); /* the sweep is in increasing triaxiality ... */
    PF_TEST_TRUE(ef < prev_ef);   /* ... and eps_f falls strictly (d3 < 0) */
    prev_t = triax, prev_ef = ef;
    if (k == 0) PF_TEST_TRUE(triax < -0.5);
    if (k == 6) PF_TEST_TRUE(triax > 1.5);
  }
  /* eps_f(1/3) = d1 + d2 exp(-0.5) = 0.875 + 0.13 * 0.60653066 = 0.95384899 (the Johnson-Cook
   * convention exp(D3 sigma*), D3 = -1.5); the uniaxial-stress path of test 6 measures it. */
  PF_TEST_CLOSE(failure_strain(1.0 / 3), 0.875 + 0.13 * exp(-0.5), 1e-15, 0);
  PF_TEST_CLOSE(failure_strain(1.0 / 3), 0.95384899, 1e-8, 0);
  pf_material_destroy(&m);

  /* The rate factor: d4 = 0.1, reference 1 1/s. Below the reference rate the factor is 1;
   * above, 1 + d4 ln(r). Pure shear F = diag(e^a, e^-a, 1): sigma* = 0, eps_f = (d1 + d2) f_r. */
  m = must_load(AL_ELASTIC TUPEK_FLOW "damage: {d1: 0.875, d2: 0.13, d3: -1.5, d4: 0.1}\n");
  if (!m) return;
  const double dts[2] = {1e-6, 1e3};
  for (int k = 0; k < 2; k++) {
    pf_test_point p;
    pf_test_point_init(m, &p);
    set_diag(&p, exp(0.01), exp(-0.01), 1.0);
    pf_test_point_step(m, dts[k], &p);
    const double r = p.st[0] / dts[k];
    PF_TEST_TRUE(k == 0 ? r > 100 : r < 1);
    const double fr = r > 1 ? 1 + 0.1 * log(r) : 1.0;
    PF_TEST_CLOSE(p.st[0] / p.st[1], (D1 + D2) * fr, 1e-12, 0);
  }
  pf_material_destroy(&m);
  /* Without a damage mapping the damage stays zero. */
  m = must_load(RI_DECK);
  if (m) {
    pf_test_point p;
    pf_test_point_init(m, &p);
    set_diag(&p, exp(0.05), exp(-0.05), 1.0);
    pf_test_point_step(m, 1e-5, &p);
    PF_TEST_TRUE(p.st[0] > 0 && p.st[1] == 0);
    pf_material_destroy(&m);
  }
}

/* ---- 3. elasticity ------------------------------------------------------------------------- */
static void elasticity(void) {
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  pf_test_point p;
  /* Uniaxial stress in Hencky elasticity: F = diag(l, l^-nu, l^-nu) gives log strains
   * (e, -nu e, -nu e), e = ln l, tau_xx = lambda (1 - 2nu) e + 2 G e = E e and
   * tau_yy = lambda (1 - 2nu) e - 2 G nu e = 0; sigma = tau / J, J = l^(1 - 2 nu). Small strain:
   * sigma_xx = E eps (1 + O(eps)). */
  const double ls[3] = {1 + 1e-6, 1.003, 1 / 1.003};
  for (int k = 0; k < 3; k++) {
    const double l = ls[k], lt = pow(l, -NU), J = l * lt * lt;
    pf_test_point_init(m, &p);
    set_diag(&p, l, lt, lt);
    pf_test_point_step(m, 1e-6, &p);
    PF_TEST_CLOSE(p.sig[0], E * log(l) / J, 1e-10, 0);
    if (k == 0) PF_TEST_CLOSE(p.sig[0], E * 1e-6, 1e-6, 0);
    for (int c = 1; c < 6; c++) PF_TEST_CLOSE(p.sig[c], 0.0, 0, 1e-9 * fabs(p.sig[0]));
    PF_TEST_TRUE(p.st[0] == 0);
  }
  /* Hydrostatic stretch F = a I: eps = ln a (1, 1, 1), tau = K ln J I, J = a^3, so
   * sigma = K ln(a^3) / a^3 I exactly; no deviator, so no plastic flow at any a. Wave speed:
   * along a principal direction rho c^2 = (lambda + 2G - tau_a)/J, c^2 = (lambda + 2G - tau)/rho0,
   * the code's estimate must not be below it. */
  const double as[4] = {0.8, 0.9, 1.1, 1.25};
  for (int k = 0; k < 4; k++) {
    const double a = as[k], J = a * a * a;
    pf_test_point_init(m, &p);
    set_diag(&p, a, a, a);
    pf_test_point_step(m, 1e-6, &p);
    for (int c = 0; c < 3; c++) PF_TEST_CLOSE(p.sig[c], KMOD * log(J) / J, 1e-13, 0);
    for (int c = 3; c < 6; c++) PF_TEST_CLOSE(p.sig[c], 0.0, 0, 0);
    PF_TEST_TRUE(p.st[0] == 0);
    PF_TEST_TRUE(p.c >= sqrt((LAME + 2 * GMOD - KMOD * log(J)) / RHO0) * (1 - 1e-14));
  }
  /* Simple shear F = I + g e_x (x) e_y, elastic (g = 2e-3): to first order sigma_xy = G g;
   * the log strain of the principal stretches is exact, so check isochoric J = 1 gives zero
   * mean stress: tr sigma = 3 K ln J = 0 to round-off. */
  pf_test_point_init(m, &p);
  p.F[1] = 2e-3;
  pf_test_point_step(m, 1e-6, &p);
  PF_TEST_CLOSE(p.sig[5], GMOD * 2e-3, 1e-6, 0);
  PF_TEST_CLOSE(p.sig[0] + p.sig[1] + p.sig[2], 0.0, 0, 1e-10 * GMOD * 2e-3);
  PF_TEST_TRUE(p.st[0] == 0);
  pf_material_destroy(&m);
}

/* ---- 4. objectivity ------------------------------------------------------------------------ */
/* Simple shear to g = 0.3 with a small stretch, plastic, driven once by F_k and once by
 * R_k F_k with a rotation R_k that changes every step. Tau = K ln J I + 2G dev(eps_e) depends on
 * F only through b_e = F Cp^-1 F^T, and Cp^-1 is a reference-frame tensor, so: the history is
 * the same, and sigma(R F) = R sigma(F) R^T (its invariants the same). */
static void objectivity(void) {
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  pf_test_point a, b;
  pf_test_point_init(m, &a);
  pf_test_point_init(m, &b);
  const double ax[3] = {0.6, 0.0, 0.8}, dt = 1e-5;
  const int N = 60;
  for (int k = 1; k <= N; k++) {
    const double g = 0.3 * k / N;
    set_diag(&a, 1 + 0.1 * g, 1.0, 1 - 0.05 * g);
    a.F[1] = g, a.F[2] = 0.2 * g;
    double R[9];
    pf_test_rotation(ax, 0.37 * k, R);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        b.F[3 * i + j] = R[3 * i] * a.F[j] + R[3 * i + 1] * a.F[3 + j] + R[3 * i + 2] * a.F[6 + j];
    pf_test_point_step(m, dt, &a);
    pf_test_point_step(m, dt, &b);
    const double scale = sqrt(a.sig[0] * a.sig[0] + a.sig[1] * a.sig[1] + a.sig[2] * a.sig[2] +
                              2 * (a.sig[3] * a.sig[3] + a.sig[4] * a.sig[4] + a.sig[5] * a.sig[5]));
    double S[3][3], T[3][3];
    for (int v = 0; v < 6; v++) {
      S[vi[v]][vj[v]] = S[vj[v]][vi[v]] = a.sig[v];
      T[vi[v]][vj[v]] = T[vj[v]][vi[v]] = b.sig[v];
    }
    for (int v = 0; v < 6; v++) {
      double want = 0;
      for (int p = 0; p < 3; p++)
        for (int q = 0; q < 3; q++) want += R[3 * vi[v] + p] * S[p][q] * R[3 * vj[v] + q];
      PF_TEST_CLOSE(b.sig[v], want, 0, 1e-11 * scale);
    }
    /* invariants: trace, S:S, det */
    double ss = 0, tt = 0;
    for (int p = 0; p < 3; p++)
      for (int q = 0; q < 3; q++) ss += S[p][q] * S[p][q], tt += T[p][q] * T[p][q];
    const double detS = S[0][0] * (S[1][1] * S[2][2] - S[1][2] * S[2][1]) -
                        S[0][1] * (S[1][0] * S[2][2] - S[1][2] * S[2][0]) +
                        S[0][2] * (S[1][0] * S[2][1] - S[1][1] * S[2][0]);
    const double detT = T[0][0] * (T[1][1] * T[2][2] - T[1][2] * T[2][1]) -
                        T[0][1] * (T[1][0] * T[2][2] - T[1][2] * T[2][0]) +
                        T[0][2] * (T[1][0] * T[2][1] - T[1][1] * T[2][0]);
    PF_TEST_CLOSE(T[0][0] + T[1][1] + T[2][2], S[0][0] + S[1][1] + S[2][2], 0, 1e-11 * scale);
    PF_TEST_CLOSE(tt, ss, 1e-10, 0);
    PF_TEST_CLOSE(detT, detS, 0, 1e-10 * scale * scale * scale);
    PF_TEST_CLOSE(b.st[0], a.st[0], 1e-11, 1e-15);
    PF_TEST_CLOSE(b.st[1], a.st[1], 1e-11, 1e-15);
    for (int c = 2; c < 8; c++) PF_TEST_CLOSE(b.st[c], a.st[c], 0, 1e-11);
  }
  PF_TEST_TRUE(a.st[0] > 0.1);
  pf_material_destroy(&m);
}

/* ---- 5 and 6. uniaxial stress ------------------------------------------------------------- */
/* One step to F = diag(l, lt, lt) with ln lt found by the secant method so that
 * sigma_yy = sigma_zz = 0 to tol. The step always starts from the same history. */
static void uniaxial_step(const pf_material *m, double dt, double l, double *llt, pf_test_point *p,
                          double tol) {
  const pf_test_point start = *p;
  pf_test_point a = start, b = start;
  double xa = *llt, xb = *llt - 1e-4;
  set_diag(&a, l, exp(xa), exp(xa));
  pf_test_point_step(m, dt, &a);
  for (int it = 0; it < 80; it++) {
    b = start;
    set_diag(&b, l, exp(xb), exp(xb));
    pf_test_point_step(m, dt, &b);
    if (fabs(b.sig[1]) <= tol) {
      *p = b, *llt = xb;
      return;
    }
    const double xn = xb - b.sig[1] * (xb - xa) / (b.sig[1] - a.sig[1]);
    a = b, xa = xb, xb = xn;
  }
  fprintf(stderr, "uniaxial stress: lateral iteration did not converge (sigma_yy %g)\n", b.sig[1]);
  pf_test_failures++;
  *p = b;
}

/* Uniaxial stress in logarithmic strain (C = 0): the plastic flow is along (1, -1/2, -1/2) at
 * every step (the deviator of diag(tau, 0, 0)), so the axial plastic log strain is eqps, and
 * Hencky elasticity gives the axial elastic log strain tau/E (test 3). Hence, exactly and for
 * any step size on a monotonic path (backward Euler on a fixed flow direction):
 *   tau = Y(eqps),  ln l = tau/E + eqps,  ln lt = -nu tau/E - eqps/2.
 * Reference eqps: the root of ln l - e - Y(e)/E (decreasing in e). */
static double uni_residual(double e, const double *par) {
  return par[0] - e - flow_stress(e, e / par[1], par[2]) / E;
}

static void uniaxial(void) {
  pf_material *m = must_load(RI_DECK);
  if (!m) return;
  pf_test_point p;
  pf_test_point_init(m, &p);
  double llt = 0;
  int nplastic = 0;
  const double dt = 1e-4;
  for (int k = 1; k <= 150; k++) {
    const double el = 0.002 * k, l = exp(el);
    uniaxial_step(m, dt, l, &llt, &p, 1e-12 * SIG0);
    const double J = l * exp(2 * llt), tau = J * p.sig[0];
    if (E * el <= SIG0) {
      PF_TEST_CLOSE(tau, E * el, 1e-10, 0);
      PF_TEST_TRUE(p.st[0] == 0);
    } else {
      nplastic++;
      const double par[3] = {el, INFINITY, 0.0};
      const double e = bisect(uni_residual, par, 0, el);
      PF_TEST_CLOSE(tau, flow_stress(e, 0, 0), 1e-8, 0);
      PF_TEST_CLOSE(p.st[0], e, 1e-8, 0);
      PF_TEST_CLOSE(llt, -NU * tau / E - e / 2, 1e-8, 0);
    }
  }
  PF_TEST_TRUE(nplastic > 100);
  pf_material_destroy(&m);

  /* With the rate term (C = 0.002): one step from the virgin state to ln l = 0.02 in dt: the same
   * relations with Y(dgam, dgam/dt): ln l = Y/E + dgam. */
  m = must_load(TUPEK_DECK);
  if (!m) return;
  const double dts[2] = {1e-6, 1e-2};
  for (int k = 0; k < 2; k++) {
    pf_test_point_init(m, &p);
    llt = -0.01;
    uniaxial_step(m, dts[k], exp(0.02), &llt, &p, 1e-12 * SIG0);
    const double par[3] = {0.02, dts[k], 0.002};
    const double e = bisect(uni_residual, par, 0, 0.02);
    PF_TEST_CLOSE(exp(0.02 + 2 * llt) * p.sig[0], flow_stress(e, e / dts[k], 0.002), 1e-8, 0);
    PF_TEST_CLOSE(p.st[0], e, 1e-8, 0);
  }
  pf_material_destroy(&m);
}

/* Damage on the monotonic uniaxial-stress path: sigma* = 1/3 at every step and d4 = 0, so
 * eps_f is the constant d1 + d2 exp(-0.5) and D = sum dgam / eps_f = eqps / eps_f while D < 1;
 * once D reaches 1 it stays there while eqps keeps growing. */
static void damage(void) {
  pf_material *m = must_load(TUPEK_DECK);
  if (!m) return;
  const double ef = D1 + D2 * exp(-0.5);
  pf_test_point p;
  pf_test_point_init(m, &p);
  double llt = 0;
  int ndamaged = 0, nfull = 0;
  double D_prev = 0;
  for (int k = 1; k <= 250; k++) {
    const double l = exp(0.005 * k);
    uniaxial_step(m, 1e-3, l, &llt, &p, 1e-12 * SIG0);
    const double D = p.st[1];
    if (D_prev < 1) {
      if (p.st[0] / ef < 1) {
        PF_TEST_CLOSE(D, p.st[0] / ef, 1e-10, 0);
        ndamaged += p.st[0] > 0;
      } else {
        PF_TEST_TRUE(D >= 1); /* the step that reaches eps_f */
      }
    } else {
      nfull++;
      PF_TEST_TRUE(D == D_prev); /* frozen */
    }
    D_prev = D;
  }
  PF_TEST_TRUE(ndamaged > 100 && nfull > 20);
  PF_TEST_TRUE(p.st[0] > 1.1 && p.st[1] >= 1);
  pf_material_destroy(&m);
}

/* ---- 7. bad decks -------------------------------------------------------------------------- */
static void bad(const char *text, int validate, const char *must_mention) {
  pf_test_material_bad(text, "al6061", validate, must_mention);
}

static void bad_inputs(void) {
  pf_error_set_quiet(1);
  for (int validate = 0; validate < 2; validate++) {
    bad(AL_ELASTIC "modified_johnson_cook: {B: 365e6, n: 0.04}\n", validate, "sigma0");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: -0.04}\n", validate, "'n'");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0}\n", validate, "'n'");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: -250e6, B: 365e6, n: 0.04}\n", validate, "sigma0");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, n: 0.04}\n", validate, "'B'");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 0, n: 0.04}\n", validate, "'B'");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04, C: -1}\n", validate, "'C'");
    bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04, reference_strain_rate: 0}\n",
        validate, "reference_strain_rate");
    bad(AL_ELASTIC, validate, "modified_johnson_cook");
    bad(AL_ELASTIC TUPEK_FLOW "damage: {d1: 0.875, d2: 0.13}\n", validate, "d3");
    bad(AL_ELASTIC TUPEK_FLOW "damage: {d1: -0.1, d2: 0.13, d3: -1.5}\n", validate, "d1");
    bad(AL_ELASTIC TUPEK_FLOW "damage: {d1: 0, d2: 0, d3: -1.5}\n", validate, "d2");
    bad(AL_ELASTIC TUPEK_FLOW "damage: {d1: 0.8, d2: 0.1, d3: -1.5, d4: -0.01}\n", validate, "d4");
    bad(AL_ELASTIC TUPEK_FLOW "damage: {d1: 0.8, d2: 0.1, d3: -1.5, reference_strain_rate: -1}\n",
        validate, "reference_strain_rate");
    /* keys of other models are rejected, by name */
    bad(TUPEK_DECK "yield_stress: 1e8\n", validate, "yield_stress");
    bad(TUPEK_DECK "taylor_quinney: 0.9\n", validate, "taylor_quinney");
    bad(AL_ELASTIC TUPEK_FLOW "johnson_cook: {A: 1e8, B: 1e8, n: 0.5, m: 1, reference_temperature: 300, "
        "melt_temperature: 900}\n", validate, "not used");
    /* no elastic constants */
    bad("model: modified_johnson_cook\ndensity: 2700\n" TUPEK_FLOW, validate, "youngs_modulus");
  }
  /* A key unknown inside the mapping: the schema check names it. */
  bad(AL_ELASTIC "modified_johnson_cook: {sigma0: 250e6, B: 365e6, n: 0.04, A: 1}\n", 1, "A");
  pf_error_clear();
  pf_error_set_quiet(0);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  basics();
  flow();
  failure();
  elasticity();
  objectivity();
  uniaxial();
  damage();
  bad_inputs();
  return pf_test_finish();
}
