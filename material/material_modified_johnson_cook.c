/* Modified Johnson-Cook viscoplasticity with Johnson-Cook damage, in the finite-strain form of
 * Tupek, Rimoli & Radovitzky (2013), "An approach for incorporating classical continuum damage
 * models in state-based peridynamics", CMAME 263:20-26, sec. 2.3 (docs/theory/materials.md,
 * sec. 3). Hyperelastic (Hencky) elasticity, multiplicative J2 plasticity integrated by radial
 * return in principal logarithmic strains (Simo 1992, CMAME 99:61; Simo & Hughes 1998,
 * Computational Inelasticity, ch. 9; Eterovic & Bathe 1990, IJNME 30:1099):
 *   trial        b_e^tr = F Cp_n^-1 F^T = sum_a lambda_a^2 n_a (x) n_a,  eps_a = ln(lambda_a)
 *   Kirchhoff    tau_a = lambda_L tr(eps) + 2 G eps_a   (tau = K ln J I + 2 G dev(eps))
 *   return       q_tr = sqrt(3/2) |2 G dev(eps)|; plastic when dt > 0 and q_tr > Y(eqps_n, 0):
 *                q_tr - 3 G dgam - Y(eqps_n + dgam, dgam/dt) = 0 (pf_material_radial_return),
 *                eps_e_a = eps_a - dgam (3/2) s_a^tr / q_tr,  s_a = (1 - 3 G dgam / q_tr) s_a^tr
 *   history      b_e = sum_a exp(2 eps_e_a) n_a (x) n_a,  Cp^-1 = F^-1 b_e F^-T
 *   stress       sigma = tau / J
 *   flow stress  Y = sigma0 [1 + eqps/eps0]^n [1 + C asinh(r / (2 rate0))],
 *                eps0 = (sigma0/B)^(1/n), r = dgam/dt; asinh x = ln(x + sqrt(1 + x^2)) is the
 *                paper's rate factor (Tupek et al. 2013, sec. 2.3, the flow-stress equation)
 *   damage       D_{n+1} = min(1, D_n + dgam / eps_f) while D_n < 1 (frozen at 1),
 *                eps_f = [d1 + d2 exp(d3 sigma*)] [1 + d4 ln(r / rate0_d)], sigma* = sigma_m /
 *                sigma_e at the end of the step, in the sign convention of Johnson & Cook (1985),
 *                Eng. Fract. Mech. 21:31, eq. 2 (d3 < 0: eps_f falls with triaxiality; Tupek's
 *                Table 4 value d3 = -1.5 is this D3); the rate factor is 1 for r <= rate0_d.
 * A time step dt = 0 (the initial force evaluation) is elastic: no plastic increment.
 * The stress is not degraded by D: the damage is read by the caller (correspondence bonds).
 * State: "eqps", "damage", then Cp^-1 in Voigt order "cp_inv_xx" .. "cp_inv_xy". */
#include "material/material_impl.h"

#include <stdlib.h>

typedef struct {
  double sigma0, B, n, C, rate0; /* flow stress constants */
  double eps0;                   /* reference plastic strain (sigma0/B)^(1/n) */
  int has_damage;
  double d1, d2, d3, d4, rate0_d; /* Johnson-Cook damage constants */
} mjc;

enum { NSTATE = 8, S_EQPS = 0, S_DAMAGE = 1, S_CPINV = 2 };

const pf_key pf_material_modified_johnson_cook_keys[] = {
    {"sigma0", PF_KEY_REAL, 1, NULL, "Pa", "initial yield stress sigma0 (> 0)", NULL},
    {"B", PF_KEY_REAL, 1, NULL, "Pa",
     "hardening stress B: reference plastic strain eps0 = (sigma0/B)^(1/n) (> 0)", NULL},
    {"n", PF_KEY_REAL, 1, NULL, "", "hardening exponent n (> 0)", NULL},
    {"C", PF_KEY_REAL, 0, "0", "", "strain-rate constant C (>= 0)", NULL},
    {"reference_strain_rate", PF_KEY_REAL, 0, "1.0", "1/s",
     "reference plastic strain rate rate0 of the flow stress (> 0)", NULL},
    PF_KEY_END};

const pf_key pf_material_jc_damage_keys[] = {
    {"d1", PF_KEY_REAL, 1, NULL, "", "Johnson-Cook D1 (>= 0)", NULL},
    {"d2", PF_KEY_REAL, 1, NULL, "", "Johnson-Cook D2 (>= 0; d1 + d2 > 0)", NULL},
    {"d3", PF_KEY_REAL, 1, NULL, "",
     "Johnson-Cook D3 in exp(d3 sigma_m/sigma_e) (negative: failure strain falls with "
     "triaxiality; Tupek et al. 2013 Table 4: -1.5)", NULL},
    {"d4", PF_KEY_REAL, 0, "0", "", "Johnson-Cook D4, rate factor 1 + d4 ln(rate/rate0) (>= 0)", NULL},
    {"reference_strain_rate", PF_KEY_REAL, 0, "1.0", "1/s",
     "reference strain rate of the damage rate factor (> 0; factor 1 below it)", NULL},
    PF_KEY_END};

static const pf_key mjc_keys[] = {
    {"modified_johnson_cook", PF_KEY_MAP, 0, NULL, "",
     "modified_johnson_cook: flow stress sigma0 (1 + eqps/eps0)^n (1 + C asinh(rate/(2 rate0))) "
     "parameters (Tupek et al. 2013)", pf_material_modified_johnson_cook_keys},
    {"damage", PF_KEY_MAP, 0, NULL, "",
     "modified_johnson_cook: Johnson-Cook damage, eps_f = (d1 + d2 exp(d3 sigma_m/sigma_e)) "
     "(1 + d4 ln(rate/rate0)) (absent: no damage)", pf_material_jc_damage_keys},
    PF_KEY_END};
static const char *const mjc_state[NSTATE] = {"eqps",      "damage",    "cp_inv_xx", "cp_inv_yy",
                                              "cp_inv_zz", "cp_inv_yz", "cp_inv_xz", "cp_inv_xy"};

static int mjc_check(const pf_deck *d, const pf_node *map, const char *key, int ok, double v,
                     const char *rule) {
  return ok ? 0 : pf_deck_error(d, pf_node_get(map, key) ? pf_node_get(map, key) : map, key,
                                "must be %s (got %g)", rule, v);
}

static int mjc_require(const pf_deck *d, const pf_node *map, const char *mapname,
                       const char *const *req, int nreq) {
  for (int k = 0; k < nreq; k++)
    if (!pf_node_get(map, req[k]))
      return pf_deck_error(d, map, req[k], "the %s mapping needs '%s'", mapname, req[k]);
  return 0;
}

static int mjc_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  const pf_node *j = pf_node_get(mat, "modified_johnson_cook");
  if (!j)
    return pf_deck_error(d, mat, "modified_johnson_cook",
                         "model 'modified_johnson_cook' needs a 'modified_johnson_cook' mapping "
                         "(sigma0, B, n, C, reference_strain_rate)");
  mjc *p;
  PF_MALLOC(p, 1);
  m->data = p;
  const char *const req[] = {"sigma0", "B", "n"};
  PF_CALL(mjc_require(d, j, "modified_johnson_cook", req, 3));
  p->C = 0.0, p->rate0 = 1.0;
  PF_CALL(pf_deck_real(d, j, "sigma0", &p->sigma0));
  PF_CALL(pf_deck_real(d, j, "B", &p->B));
  PF_CALL(pf_deck_real(d, j, "n", &p->n));
  PF_CALL(pf_deck_real(d, j, "C", &p->C));
  PF_CALL(pf_deck_real(d, j, "reference_strain_rate", &p->rate0));
  PF_CALL(mjc_check(d, j, "sigma0", p->sigma0 > 0, p->sigma0, "positive"));
  PF_CALL(mjc_check(d, j, "B", p->B > 0, p->B, "positive"));
  PF_CALL(mjc_check(d, j, "n", p->n > 0, p->n, "positive"));
  PF_CALL(mjc_check(d, j, "C", p->C >= 0, p->C, ">= 0"));
  PF_CALL(mjc_check(d, j, "reference_strain_rate", p->rate0 > 0, p->rate0, "positive"));
  p->eps0 = pow(p->sigma0 / p->B, 1.0 / p->n);
  if (!(p->eps0 > 0 && isfinite(p->eps0)))
    return pf_deck_error(d, pf_node_get(j, "n"), "n",
                         "gives the reference plastic strain (sigma0/B)^(1/n) = %g, which must be "
                         "positive and finite", p->eps0);

  const pf_node *dm = pf_node_get(mat, "damage");
  p->has_damage = dm != NULL;
  p->d1 = p->d2 = p->d3 = p->d4 = 0.0, p->rate0_d = 1.0;
  if (dm) {
    const char *const dreq[] = {"d1", "d2", "d3"};
    PF_CALL(mjc_require(d, dm, "damage", dreq, 3));
    PF_CALL(pf_deck_real(d, dm, "d1", &p->d1));
    PF_CALL(pf_deck_real(d, dm, "d2", &p->d2));
    PF_CALL(pf_deck_real(d, dm, "d3", &p->d3));
    PF_CALL(pf_deck_real(d, dm, "d4", &p->d4));
    PF_CALL(pf_deck_real(d, dm, "reference_strain_rate", &p->rate0_d));
    PF_CALL(mjc_check(d, dm, "d1", p->d1 >= 0, p->d1, ">= 0"));
    PF_CALL(mjc_check(d, dm, "d2", p->d2 >= 0, p->d2, ">= 0"));
    PF_CALL(mjc_check(d, dm, "d2", p->d1 + p->d2 > 0, p->d2, "positive when d1 = 0"));
    PF_CALL(mjc_check(d, dm, "d3", isfinite(p->d3), p->d3, "finite"));
    PF_CALL(mjc_check(d, dm, "d4", p->d4 >= 0, p->d4, ">= 0"));
    PF_CALL(mjc_check(d, dm, "reference_strain_rate", p->rate0_d > 0, p->rate0_d, "positive"));
  }
  return 0;
}

/* Cp^-1 = I, eqps = D = 0 (Tupek et al. 2013: the virgin, undamaged state). */
static void mjc_init(const pf_material *m, pf_int n, double *restrict state) {
  (void)m;
  for (pf_int i = 0; i < n; i++) {
    double *st = state + (int64_t)NSTATE * i;
    for (int k = 0; k < NSTATE; k++) st[k] = k >= S_CPINV && k < S_CPINV + 3 ? 1.0 : 0.0;
  }
}

typedef struct {
  double eqps, sigma0, eps0, n, C, xs; /* xs = 1 / (2 rate0 dt) */
} mjc_flow_ctx;

/* Tupek et al. (2013), sec. 2.3: Y(dgam) = sigma0 h^n R, h = 1 + (eqps_n + dgam)/eps0,
 * R = 1 + C asinh(x), x = dgam / (2 rate0 dt); dY/ddgam = sigma0 [n h^(n-1) R / eps0 +
 * h^n C xs / sqrt(1 + x^2)], finite at eqps = 0 and at zero rate. */
static double mjc_flow(const void *ctx, double dgam, double *dflow) {
  const mjc_flow_ctx *c = ctx;
  const double h = 1.0 + (c->eqps + dgam) / c->eps0, hn = pow(h, c->n);
  const double x = dgam * c->xs, R = 1.0 + c->C * asinh(x);
  *dflow = c->sigma0 * (c->n * hn / h * R / c->eps0 + hn * c->C * c->xs / hypot(1.0, x));
  return c->sigma0 * hn * R;
}

/* Johnson & Cook (1985), eq. 2 (in the form of Tupek et al. 2013, sec. 2.3, with D3 = d3):
 * eps_f = [d1 + d2 exp(d3 sigma*)] [1 + d4 ln(r / rate0_d)], the rate factor 1 for
 * r <= rate0_d (LS-DYNA *MAT_JOHNSON_COOK practice: no rate effect below the reference). The
 * exponent is capped at 700 so that d2 = 0 never meets exp overflow (0 * inf). */
static double mjc_failure_strain(const mjc *p, double triax, double rate) {
  const double f = p->d1 + p->d2 * exp(fmin(p->d3 * triax, 700.0));
  return rate > p->rate0_d ? f * (1.0 + p->d4 * log(rate / p->rate0_d)) : f;
}

static const int vi[6] = {0, 1, 2, 1, 0, 0}, vj[6] = {0, 1, 2, 2, 2, 1};

/* Fi = F^-1 = adj(F) / det F, F row-major [9]. */
static void inverse3(const double *restrict f, double Fi[3][3]) {
  const double J = pf_det3(f);
  Fi[0][0] = (f[4] * f[8] - f[5] * f[7]) / J, Fi[0][1] = (f[2] * f[7] - f[1] * f[8]) / J;
  Fi[0][2] = (f[1] * f[5] - f[2] * f[4]) / J, Fi[1][0] = (f[5] * f[6] - f[3] * f[8]) / J;
  Fi[1][1] = (f[0] * f[8] - f[2] * f[6]) / J, Fi[1][2] = (f[2] * f[3] - f[0] * f[5]) / J;
  Fi[2][0] = (f[3] * f[7] - f[4] * f[6]) / J, Fi[2][1] = (f[1] * f[6] - f[0] * f[7]) / J;
  Fi[2][2] = (f[0] * f[4] - f[1] * f[3]) / J;
}

/* b_e^tr - I = F A F^T + H + H^T + H H^T, A = Cp^-1 - I, H = F - I: no cancellation at small
 * strain (the stored Cp^-1 is I exactly until the first plastic step). Lane l of B. */
static void trial_b_minus_identity(const double *restrict f, const double *restrict st, int l,
                                   double B[3][3][PF_SYM3_LANES]) {
  double A[3][3], Hm[3][3], FA[3][3];
  for (int v = 0; v < 6; v++)
    A[vi[v]][vj[v]] = A[vj[v]][vi[v]] = st[S_CPINV + v] - (v < 3 ? 1.0 : 0.0);
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) Hm[r][c] = f[3 * r + c] - (r == c ? 1.0 : 0.0);
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++)
      FA[r][c] = f[3 * r] * A[0][c] + f[3 * r + 1] * A[1][c] + f[3 * r + 2] * A[2][c];
  for (int r = 0; r < 3; r++)
    for (int c = r; c < 3; c++) {
      double b = Hm[r][c] + Hm[c][r];
      for (int k = 0; k < 3; k++) b += FA[r][k] * f[3 * c + k] + Hm[r][k] * Hm[c][k];
      B[r][c][l] = B[c][r][l] = b;
    }
}

/* The rest of one point's step from the eigenvalues mu_a of b_e^tr - I and their vectors V
 * (columns): principal logarithmic strains, the trial Kirchhoff stress, the radial return,
 * Cp^-1, eqps and D, sigma (see the file comment). */
static void point_update(const mjc *p, double K, double G, double dt, const double *restrict f,
                         double *restrict st, double *restrict sg, const double mu[3], double V[3][3]) {
  double eps[3], s[3];
  for (int a = 0; a < 3; a++) eps[a] = 0.5 * log1p(mu[a]);
  const double tr = eps[0] + eps[1] + eps[2], tau_m = K * tr;
  for (int a = 0; a < 3; a++) s[a] = 2.0 * G * (eps[a] - tr / 3.0);
  const double q = sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
  const double eqps = st[S_EQPS];
  /* (pow(1, n) is 1 exactly: the virgin points, most of a body, skip the call) */
  const double Y0 = eqps == 0.0 ? p->sigma0 : p->sigma0 * pow(1.0 + eqps / p->eps0, p->n);
  if (dt > 0 && q > Y0) {
    const mjc_flow_ctx ctx = {eqps, p->sigma0, p->eps0, p->n, p->C, 0.5 / (p->rate0 * dt)};
    const double dgam = pf_material_radial_return(q, 3.0 * G, (q - Y0) / (3.0 * G), mjc_flow, &ctx);
    const double scale = 1.0 - 3.0 * G * dgam / q;
    double be[3]; /* exp(2 eps_e) - 1 */
    for (int a = 0; a < 3; a++) {
      be[a] = expm1(2.0 * (eps[a] - 1.5 * dgam * s[a] / q));
      s[a] *= scale;
    }
    /* Cp^-1 = F^-1 b_e F^-T with b_e = I + V diag(be) V^T, F^-1 = adj(F) / det F. */
    double Fi[3][3], W[3][3];
    inverse3(f, Fi);
    for (int r = 0; r < 3; r++) /* W = F^-1 V */
      for (int c = 0; c < 3; c++) W[r][c] = Fi[r][0] * V[0][c] + Fi[r][1] * V[1][c] + Fi[r][2] * V[2][c];
    for (int v = 0; v < 6; v++) {
      const int r = vi[v], c = vj[v];
      double x = Fi[r][0] * Fi[c][0] + Fi[r][1] * Fi[c][1] + Fi[r][2] * Fi[c][2];
      for (int a = 0; a < 3; a++) x += W[r][a] * be[a] * W[c][a];
      st[S_CPINV + v] = x;
    }
    st[S_EQPS] = eqps + dgam;
    /* Damage at the end-of-step triaxiality tau_m / q_{n+1} (= sigma_m / sigma_e). */
    const double qn = scale * q;
    if (p->has_damage && st[S_DAMAGE] < 1.0 && dgam > 0 && qn > 0) {
      const double ef = mjc_failure_strain(p, tau_m / qn, dgam / dt);
      st[S_DAMAGE] = fmin(1.0, st[S_DAMAGE] + dgam / ef);
    }
  }
  /* sigma = V diag(tau_a / J) V^T. */
  const double J = pf_det3(f);
  double t[3];
  for (int a = 0; a < 3; a++) t[a] = (tau_m + s[a]) / J;
  for (int v = 0; v < 6; v++) {
    const int r = vi[v], c = vj[v];
    sg[v] = V[r][0] * t[0] * V[c][0] + V[r][1] * t[1] * V[c][1] + V[r][2] * t[2] * V[c][2];
  }
}

/* One step per point (Simo 1992, box 1 / Simo & Hughes 1998, ch. 9, in principal logarithmic
 * strains; Tupek et al. 2013, sec. 2.3): b_e^tr = F Cp^-1 F^T -> eps_a = 1/2 ln(lambda_a^2) ->
 * tau_a = K tr(eps) + 2G dev(eps)_a -> radial return on q_tr with Y(eqps_n + dgam, dgam/dt) ->
 * eps_e, Cp^-1 = F^-1 exp(2 eps_e) F^-T, eqps, D -> sigma = tau / J (see the file comment). The
 * eigen-decomposition of b_e^tr - I, most of the work, runs PF_SYM3_LANES points at a time across
 * the vector lanes (material/sym3_eigen.c; lanes past n repeat the block's first point). The
 * incoming sigma and D are not used (hyperelastic). */
static void mjc_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                       const double *restrict D, double *restrict sigma, double *restrict state) {
  (void)D;
  const mjc *p = m->data;
  for (pf_int i0 = 0; i0 < n; i0 += PF_SYM3_LANES) {
    const int nl = n - i0 < PF_SYM3_LANES ? (int)(n - i0) : PF_SYM3_LANES;
    _Alignas(64) double B[3][3][PF_SYM3_LANES], mu[3][PF_SYM3_LANES], V[3][3][PF_SYM3_LANES];
    for (int l = 0; l < PF_SYM3_LANES; l++) {
      const pf_int i = i0 + (l < nl ? l : 0);
      trial_b_minus_identity(F + 9 * (int64_t)i, state + (int64_t)NSTATE * i, l, B);
    }
    pf_sym3_eigen_lanes(B, mu, V);
    for (int l = 0; l < nl; l++) {
      const pf_int i = i0 + l;
      double mul[3], Vl[3][3];
      for (int a = 0; a < 3; a++) {
        mul[a] = mu[a][l];
        for (int c = 0; c < 3; c++) Vl[a][c] = V[a][c][l];
      }
      point_update(p, m->K, m->G, dt, F + 9 * (int64_t)i, state + (int64_t)NSTATE * i, sigma + 6 * (int64_t)i, mul, Vl);
    }
  }
}

/* The estimate of F changed from Fa to Fb with the material at rest (a correspondence point
 * that lost bonds): keep b_e = F Cp^-1 F^T, so Cp^-1 <- Fb^-1 Fa Cp^-1 Fa^T Fb^-T = M Cp^-1 M^T
 * with M = Fb^-1 Fa (docs/theory/materials.md §2.7). eqps and D do not change. */
static void mjc_rereference(const pf_material *m, pf_int n, const double *restrict Fa,
                            const double *restrict Fb, double *restrict state) {
  (void)m;
  for (pf_int i = 0; i < n; i++) {
    const double *a = Fa + 9 * (int64_t)i, *f = Fb + 9 * (int64_t)i;
    double *restrict st = state + (int64_t)NSTATE * i;
    double Fi[3][3], M[3][3], C[3][3], MC[3][3];
    inverse3(f, Fi);
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) M[r][c] = Fi[r][0] * a[c] + Fi[r][1] * a[3 + c] + Fi[r][2] * a[6 + c];
    for (int v = 0; v < 6; v++) C[vi[v]][vj[v]] = C[vj[v]][vi[v]] = st[S_CPINV + v];
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) MC[r][c] = M[r][0] * C[0][c] + M[r][1] * C[1][c] + M[r][2] * C[2][c];
    for (int v = 0; v < 6; v++) {
      const int r = vi[v], c = vj[v];
      st[S_CPINV + v] = MC[r][0] * M[c][0] + MC[r][1] * M[c][1] + MC[r][2] * M[c][2];
    }
  }
}

/* Longitudinal wave speed of Hencky elasticity (the plastic tangent is never stiffer): along a
 * principal direction a, the acoustic modulus of tau = K ln J I + 2 G dev(eps) is
 * rho c^2 = (lambda + 2G - tau_a) / J (Truesdell tangent lambda + 2G - 2 tau_a plus the
 * initial-stress term tau_a, over J), so c^2 = (lambda + 2G - tau_a) / rho0 with rho = rho0/J.
 * The estimate takes c^2 = (lambda + 2G + J g) / rho0, g the largest Gershgorin bound of |sigma|
 * (>= max_a |tau_a| / J): exact at zero stress, an upper bound along principal directions, and a
 * margin of the same order for the stress-dependent terms in other directions. The default
 * hypoelastic estimate sqrt((K + 4G/3) J / rho0) would fall below it in compression (J < 1,
 * -tau_a > 0). */
static void mjc_wave_speed(const pf_material *m, pf_int n, const double *restrict F,
                           const double *restrict sigma, const double *restrict state,
                           double *restrict c) {
  (void)state;
  const double M0 = m->lambda + 2.0 * m->G, rho0 = m->density;
  for (pf_int i = 0; i < n; i++) {
    const double *s = sigma + 6 * (int64_t)i;
    const double g0 = fabs(s[0]) + fabs(s[5]) + fabs(s[4]), g1 = fabs(s[1]) + fabs(s[5]) + fabs(s[3]),
                 g2 = fabs(s[2]) + fabs(s[4]) + fabs(s[3]);
    const double J = pf_det3(F + 9 * (int64_t)i);
    c[i] = sqrt((M0 + J * fmax(g0, fmax(g1, g2))) / rho0);
  }
}

const pf_material_ops pf_material_modified_johnson_cook = {
    .name = "modified_johnson_cook",
    .nstate = NSTATE,
    .state_names = mjc_state,
    .keys = mjc_keys,
    .create = mjc_create,
    .init = mjc_init,
    .update = mjc_update,
    .wave_speed = mjc_wave_speed,
    .rereference = mjc_rereference,
};
