/* Johnson-Cook viscoplasticity (Johnson & Cook 1983, Proc. 7th Int. Symp. Ballistics, The Hague,
 * 541-547, eq. 1) with hypoelastic deviatoric response and radial return, optional adiabatic
 * heating, and the pressure either hypoelastic or from a Mie-Gruneisen equation of state.
 *   flow stress  sigma_y = (A + B eqps^n) (1 + C ln(max(rate / rate0, 1))) (1 - T*^m),
 *                T* = (T - T_ref) / (T_melt - T_ref) clamped to [0, 1],
 *                rate = dgam / dt (the step's mean equivalent plastic strain rate)
 *   deviator     s_tr = dev(sigma_n^R) + 2 G dt dev(D); radial return on q_tr (Simo & Hughes
 *                1998, sec. 3.3) with the consistency equation
 *                q_tr - 3 G dgam - sigma_y(eqps_n + dgam, dgam/dt, T_n) = 0 solved by bracketed
 *                Newton (pf_material_radial_return), the rate term included;
 *   temperature  T_{n+1} = T_n + beta sigma_y dgam / (rho c_p), rho = rho0 / J (Taylor-Quinney
 *                coefficient beta; 0 = isothermal); sigma_y uses T_n (explicit in T);
 *   pressure     no eos: p_{n+1} = p_n - K dt tr(D);
 *                eos:    p_{n+1} = f(mu_{n+1}) + Gamma(mu_{n+1}) E_{n+1} (eos_mie_gruneisen.c);
 *   energy       E per unit reference volume, dE/dt = J sigma : D (docs/theory/fem_materials.md):
 *                J_h = J_{n+1} exp(-dt tr(D) / 2) (mid-step J, exact when F and D agree),
 *                E_{n+1} = E_n + dt J_h [ (s_n + s_{n+1})/2 : D - (p_n + p_{n+1})/2 tr(D) ];
 *                with the eos p_{n+1} is linear in E_{n+1}, so this trapezoidal equation is
 *                solved exactly (the converged predictor-corrector):
 *                E_{n+1} = (E_n + W_s - h (p_n + f)) / (1 + h Gamma),  h = dt J_h tr(D) / 2.
 * State: "eqps", "temperature" (K), "energy" (J/m^3 of reference volume). */
#include "material/material_impl.h"

#include <stdlib.h>

typedef struct {
  double A, B, C, n, m; /* Johnson-Cook constants */
  double rate0;         /* reference strain rate, 1/s */
  double Tref, Tmelt, T0;
  double cp, beta; /* specific heat J/(kg K), Taylor-Quinney coefficient */
  double K_el;     /* bulk modulus of the elastic constants (pressure without an eos) */
  int has_eos;
  pf_material_eos_mg eos;
} jc;

const pf_key pf_material_johnson_cook_keys[] = {
    {"A", PF_KEY_REAL, 1, NULL, "Pa", "yield stress A (reference rate and temperature, > 0)", NULL},
    {"B", PF_KEY_REAL, 1, NULL, "Pa", "hardening constant B (>= 0)", NULL},
    {"C", PF_KEY_REAL, 0, "0", "", "strain-rate constant C (>= 0)", NULL},
    {"n", PF_KEY_REAL, 1, NULL, "", "hardening exponent n (> 0)", NULL},
    {"m", PF_KEY_REAL, 1, NULL, "", "thermal-softening exponent m (> 0)", NULL},
    {"reference_strain_rate", PF_KEY_REAL, 0, "1.0", "1/s", "reference strain rate rate0 (> 0)", NULL},
    {"reference_temperature", PF_KEY_REAL, 1, NULL, "K", "reference (room) temperature T_ref", NULL},
    {"melt_temperature", PF_KEY_REAL, 1, NULL, "K", "melting temperature T_melt (> T_ref)", NULL},
    PF_KEY_END};

static const pf_key jc_keys[] = {
    {"johnson_cook", PF_KEY_MAP, 0, NULL, "",
     "johnson_cook: flow stress (A + B eqps^n)(1 + C ln(rate*))(1 - T*^m) parameters",
     pf_material_johnson_cook_keys},
    {"initial_temperature", PF_KEY_REAL, 0, "reference_temperature", "K",
     "johnson_cook: temperature at t = 0", NULL},
    {"specific_heat", PF_KEY_REAL, 0, NULL, "J/(kg K)",
     "johnson_cook: specific heat c_p (needed when taylor_quinney > 0)", NULL},
    {"taylor_quinney", PF_KEY_REAL, 0, "0", "",
     "johnson_cook: fraction beta of plastic work turned into heat (0 = isothermal, <= 1)", NULL},
    {"eos", PF_KEY_MAP, 0, NULL, "",
     "johnson_cook: equation of state for the pressure (else hypoelastic with the bulk modulus)",
     pf_material_eos_keys},
    PF_KEY_END};
static const char *const jc_state[] = {"eqps", "temperature", "energy"};

static int jc_check(const pf_deck *d, const pf_node *map, const char *key, int ok, double v,
                    const char *rule) {
  return ok ? 0 : pf_deck_error(d, pf_node_get(map, key) ? pf_node_get(map, key) : map, key,
                                "must be %s (got %g)", rule, v);
}

static int jc_read_constants(const pf_deck *d, const pf_node *j, jc *p) {
  const char *required[] = {"A", "B", "n", "m", "reference_temperature", "melt_temperature"};
  for (int k = 0; k < 6; k++)
    if (!pf_node_get(j, required[k]))
      return pf_deck_error(d, j, required[k], "the johnson_cook mapping needs '%s'", required[k]);
  p->C = 0.0, p->rate0 = 1.0;
  PF_CALL(pf_deck_real(d, j, "A", &p->A));
  PF_CALL(pf_deck_real(d, j, "B", &p->B));
  PF_CALL(pf_deck_real(d, j, "C", &p->C));
  PF_CALL(pf_deck_real(d, j, "n", &p->n));
  PF_CALL(pf_deck_real(d, j, "m", &p->m));
  PF_CALL(pf_deck_real(d, j, "reference_strain_rate", &p->rate0));
  PF_CALL(pf_deck_real(d, j, "reference_temperature", &p->Tref));
  PF_CALL(pf_deck_real(d, j, "melt_temperature", &p->Tmelt));
  PF_CALL(jc_check(d, j, "A", p->A > 0, p->A, "positive"));
  PF_CALL(jc_check(d, j, "B", p->B >= 0, p->B, ">= 0"));
  PF_CALL(jc_check(d, j, "C", p->C >= 0, p->C, ">= 0"));
  PF_CALL(jc_check(d, j, "n", p->n > 0, p->n, "positive"));
  PF_CALL(jc_check(d, j, "m", p->m > 0, p->m, "positive"));
  PF_CALL(jc_check(d, j, "reference_strain_rate", p->rate0 > 0, p->rate0, "positive"));
  PF_CALL(jc_check(d, j, "reference_temperature", p->Tref >= 0, p->Tref, ">= 0 K"));
  PF_CALL(jc_check(d, j, "melt_temperature", p->Tmelt > p->Tref, p->Tmelt,
                   "above reference_temperature"));
  return 0;
}

static int jc_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  const pf_node *j = pf_node_get(mat, "johnson_cook");
  if (!j)
    return pf_deck_error(d, mat, "johnson_cook",
                         "model 'johnson_cook' needs a 'johnson_cook' mapping (A, B, n, m, "
                         "reference_temperature, melt_temperature)");
  jc *p;
  PF_MALLOC(p, 1);
  m->data = p;
  PF_CALL(jc_read_constants(d, j, p));
  p->T0 = p->Tref, p->cp = 0.0, p->beta = 0.0;
  PF_CALL(pf_deck_real(d, mat, "initial_temperature", &p->T0));
  PF_CALL(pf_deck_real(d, mat, "specific_heat", &p->cp));
  PF_CALL(pf_deck_real(d, mat, "taylor_quinney", &p->beta));
  PF_CALL(jc_check(d, mat, "initial_temperature", p->T0 >= 0, p->T0, ">= 0 K"));
  PF_CALL(jc_check(d, mat, "taylor_quinney", p->beta >= 0 && p->beta <= 1, p->beta, "in [0, 1]"));
  if (p->beta > 0 && !pf_node_get(mat, "specific_heat"))
    return pf_deck_error(d, mat, "specific_heat", "taylor_quinney > 0 needs 'specific_heat' (J/(kg K))");
  if (pf_node_get(mat, "specific_heat"))
    PF_CALL(jc_check(d, mat, "specific_heat", p->cp > 0, p->cp, "positive"));
  p->K_el = m->K;
  const pf_node *eos = pf_node_get(mat, "eos");
  if (eos) {
    PF_CALL(pf_material_eos_mg_read(d, eos, m->density, &p->eos));
    p->has_eos = 1;
    /* The small-strain bulk modulus is now the eos's, rho0 C0^2 (K_s at the reference state). */
    m->K = m->density * p->eos.c0 * p->eos.c0;
    m->lambda = m->K - 2.0 * m->G / 3.0;
  }
  return 0;
}

static void jc_init(const pf_material *m, pf_int n, double *restrict state) {
  const jc *p = m->data;
  for (pf_int i = 0; i < n; i++) state[3 * i] = 0.0, state[3 * i + 1] = p->T0, state[3 * i + 2] = 0.0;
}

typedef struct {
  double eps, A, B, C, n, theta, rate_dt; /* rate_dt = rate0 dt (<= 0: no rate term) */
} jc_flow_ctx;

/* sigma_y(dgam) = (A + B e^n)(1 + C ln(max(dgam / (rate0 dt), 1))) theta, e = eqps_n + dgam, and
 * its derivative theta [B n e^(n-1) R + (A + B e^n) C / dgam (rate branch only)]. */
static double jc_flow(const void *ctx, double dgam, double *dflow) {
  const jc_flow_ctx *c = ctx;
  const double e = c->eps + dgam;
  const double hard = c->A + c->B * pow(e, c->n);
  const double dhard = e > 0 ? c->B * c->n * pow(e, c->n - 1.0) : (c->n < 1 ? INFINITY : c->n == 1 ? c->B : 0.0);
  double R = 1.0, dR = 0.0;
  if (c->rate_dt > 0 && dgam > c->rate_dt) R = 1.0 + c->C * log(dgam / c->rate_dt), dR = c->C / dgam;
  *dflow = c->theta * (dhard * R + hard * dR);
  return c->theta * hard * R;
}

/* Thermal factor 1 - T*^m, T* = (T - T_ref)/(T_melt - T_ref) clamped to [0, 1]. */
static double jc_theta(const jc *p, double T) {
  const double Ts = fmin(1.0, fmax(0.0, (T - p->Tref) / (p->Tmelt - p->Tref)));
  return 1.0 - pow(Ts, p->m);
}

static void jc_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                      const double *restrict D, double *restrict sigma, double *restrict state) {
  const jc *p = m->data;
  const double K = m->K, G2 = 2.0 * m->G, G3 = 3.0 * m->G, rho0 = m->density;
  for (pf_int i = 0; i < n; i++) {
    const double *restrict d = D + 6 * i;
    double *restrict sg = sigma + 6 * i, *restrict st = state + 3 * i;
    const double J = pf_det3(F + 9 * i), trD = pf_material_trace(d);
    const double Jh = J * exp(-0.5 * dt * trD);
    double s_n[6], s[6], dd[6];
    pf_material_deviator(sg, s_n);
    pf_material_deviator(d, dd);
    const double p_n = -pf_material_trace(sg) / 3.0;
    for (int k = 0; k < 6; k++) s[k] = s_n[k] + dt * G2 * dd[k];
    /* deviatoric return */
    const double q = pf_material_mises(s), eps = st[0], T = st[1];
    const jc_flow_ctx ctx = {eps, p->A, p->B, p->C, p->n, jc_theta(p, T), p->rate0 * dt};
    const double sy0 = ctx.theta * (p->A + p->B * pow(eps, p->n));
    if (q > sy0) {
      const double dgam = pf_material_radial_return(q, G3, (q - sy0) / G3, jc_flow, &ctx);
      const double scale = 1.0 - G3 * dgam / q;
      for (int k = 0; k < 6; k++) s[k] *= scale;
      st[0] = eps + dgam;
      if (p->beta > 0) st[1] = T + p->beta * (q - G3 * dgam) * dgam * J / (rho0 * p->cp);
    }
    /* energy and pressure (trapezoidal stress power, mid-step J) */
    double sh[6];
    for (int k = 0; k < 6; k++) sh[k] = 0.5 * (s_n[k] + s[k]);
    const double Ws = dt * Jh * pf_material_ddot(sh, d), h = 0.5 * dt * Jh * trD;
    double pres;
    if (p->has_eos) {
      const double mu = 1.0 / J - 1.0, f = pf_material_eos_mg_f(&p->eos, mu, NULL);
      const double Gam = pf_material_eos_mg_gamma(&p->eos, mu);
      st[2] = (st[2] + Ws - h * (p_n + f)) / (1.0 + h * Gam);
      pres = f + Gam * st[2];
    } else {
      pres = p_n - dt * K * trD;
      st[2] += Ws - h * (p_n + pres);
    }
    for (int k = 0; k < 6; k++) sg[k] = s[k] - (k < 3 ? pres : 0.0);
  }
}

/* With the eos: c = sqrt((K_eff + 4G/3) / rho), rho = rho0/J, K_eff = max(K_elastic, rho0 C0^2,
 * K_s(J, E)), K_s the isentropic bulk modulus of the eos (pf_material_eos_mg_bulk_modulus). rho0 C0^2
 * is K_s at the reference state, so the estimate never falls below the reference-state sound
 * speed; K_s takes over in compression, where it grows. Without the eos: hypoelastic estimate. */
static void jc_wave_speed(const pf_material *m, pf_int n, const double *restrict F,
                          const double *restrict sigma, const double *restrict state,
                          double *restrict c) {
  (void)sigma;
  const jc *p = m->data;
  const double G = m->G, rho0 = m->density;
  for (pf_int i = 0; i < n; i++) {
    const double J = pf_det3(F + 9 * i);
    double K = p->K_el;
    if (p->has_eos)
      K = fmax(K, fmax(m->K, pf_material_eos_mg_bulk_modulus(&p->eos, J, state[3 * i + 2])));
    c[i] = pf_material_hypo_wave_speed(K, G, rho0, J);
  }
}

const pf_material_ops pf_material_johnson_cook = {
    .name = "johnson_cook",
    .nstate = 3,
    .state_names = jc_state,
    .keys = jc_keys,
    .create = jc_create,
    .init = jc_init,
    .update = jc_update,
    .wave_speed = jc_wave_speed,
};
