/* Hypoelastic J2 (von Mises) plasticity with isotropic hardening, integrated by the radial
 * return of Wilkins (1964) in the form of Simo & Hughes (1998), Computational Inelasticity,
 * sec. 3.3, Boxes 3.1-3.2 (small-strain algorithm applied to the rotated stress and the rate of
 * deformation, as hypoelastic explicit codes do):
 *   trial:   sigma_tr = sigma_n^R + dt (lambda tr(D) I + 2 G D),  s_tr = dev sigma_tr,
 *            q_tr = sqrt(3/2 s_tr : s_tr)
 *   yield:   f = q_tr - sigma_y(eqps_n) <= 0  ->  elastic step
 *   return:  solve q_tr - 3 G dgam - sigma_y(eqps_n + dgam) = 0,
 *            s_{n+1} = (1 - 3 G dgam / q_tr) s_tr,  eqps_{n+1} = eqps_n + dgam,
 *            pressure unchanged by the return.
 * Hardening: sigma_y(eqps) = sigma_y0 + H eqps^n_h. Linear (n_h = 1): dgam = f / (3G + H) in
 * closed form. Power law: bracketed Newton (pf_material_radial_return), which stays safe where the
 * slope H n_h eqps^(n_h - 1) is infinite (eqps = 0, n_h < 1). State: "eqps". */
#include "material/material_impl.h"

#include <stdlib.h>

typedef struct {
  double sy0, H, nh; /* sigma_y = sy0 + H eqps^nh */
} j2;

static const pf_key j2_keys[] = {
    {"yield_stress", PF_KEY_REAL, 0, NULL, "Pa", "j2: initial yield stress sigma_y0 (> 0)", NULL},
    {"hardening_modulus", PF_KEY_REAL, 0, "0", "Pa",
     "j2: isotropic hardening H in sigma_y = sigma_y0 + H eqps^hardening_exponent (>= 0)", NULL},
    {"hardening_exponent", PF_KEY_REAL, 0, "1", "",
     "j2: exponent of the hardening law (1 = linear hardening, > 0)", NULL},
    PF_KEY_END};
static const char *const j2_state[] = {"eqps"};

static int j2_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  if (!pf_node_get(mat, "yield_stress"))
    return pf_deck_error(d, mat, "yield_stress", "model 'j2' needs 'yield_stress' (Pa)");
  j2 *p;
  PF_MALLOC(p, 1);
  m->data = p;
  p->H = 0.0, p->nh = 1.0;
  PF_CALL(pf_deck_real(d, mat, "yield_stress", &p->sy0));
  PF_CALL(pf_deck_real(d, mat, "hardening_modulus", &p->H));
  PF_CALL(pf_deck_real(d, mat, "hardening_exponent", &p->nh));
  if (!(p->sy0 > 0))
    return pf_deck_error(d, pf_node_get(mat, "yield_stress"), "yield_stress", "must be positive (got %g)", p->sy0);
  if (!(p->H >= 0))
    return pf_deck_error(d, pf_node_get(mat, "hardening_modulus"), "hardening_modulus",
                         "must be >= 0 (got %g)", p->H);
  if (!(p->nh > 0))
    return pf_deck_error(d, pf_node_get(mat, "hardening_exponent"), "hardening_exponent",
                         "must be positive (got %g)", p->nh);
  return 0;
}

typedef struct {
  double eps, sy0, H, nh;
} j2_flow_ctx;

/* sigma_y(eqps_n + dgam) = sy0 + H (eqps_n + dgam)^nh and its slope (infinite at 0 if nh < 1). */
static double j2_flow(const void *ctx, double dgam, double *dflow) {
  const j2_flow_ctx *c = ctx;
  const double e = c->eps + dgam;
  *dflow = e > 0 ? c->H * c->nh * pow(e, c->nh - 1.0) : (c->nh < 1 ? INFINITY : c->nh == 1 ? c->H : 0.0);
  return c->sy0 + c->H * pow(e, c->nh);
}

static void j2_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                      const double *restrict D, double *restrict sigma, double *restrict state) {
  (void)F;
  const j2 *p = m->data;
  const double K = m->K, G2 = 2.0 * m->G, G3 = 3.0 * m->G;
  for (pf_int i = 0; i < n; i++) {
    const double *restrict d = D + 6 * i;
    double *restrict sg = sigma + 6 * i;
    double s[6], dd[6];
    pf_material_deviator(sg, s);
    pf_material_deviator(d, dd);
    const double mean = pf_material_trace(sg) / 3.0 + dt * K * pf_material_trace(d);
    for (int k = 0; k < 6; k++) s[k] += dt * G2 * dd[k];
    const double q = pf_material_mises(s), eps = state[i];
    const double sy = p->sy0 + p->H * pow(eps, p->nh);
    double scale = 1.0;
    if (q > sy) {
      double dgam;
      if (p->nh == 1.0) {
        dgam = (q - sy) / (G3 + p->H);
      } else {
        const j2_flow_ctx ctx = {eps, p->sy0, p->H, p->nh};
        dgam = pf_material_radial_return(q, G3, (q - sy) / G3, j2_flow, &ctx);
      }
      scale = 1.0 - G3 * dgam / q;
      state[i] = eps + dgam;
    }
    for (int k = 0; k < 6; k++) sg[k] = scale * s[k] + (k < 3 ? mean : 0.0);
  }
}

const pf_material_ops pf_material_j2 = {
    .name = "j2",
    .nstate = 1,
    .state_names = j2_state,
    .keys = j2_keys,
    .create = j2_create,
    .update = j2_update,
};
