/* Mie-Gruneisen equation of state in the form of LS-DYNA's *EOS_GRUNEISEN (EOS type 4; LS-DYNA
 * Keyword User's Manual, vol. I/II, and Theory Manual), which fits the shock velocity to the
 * particle velocity by Us = C0 + S1 up + S2 up^2/Us + S3 up^3/Us^2 and takes the Hugoniot as the
 * reference curve with Gamma rho = Gamma0 rho0 (Meyers 1994, Dynamic Behavior of Materials,
 * ch. 4-5; Steinberg 1996, Equation of State and Strength Properties of Selected Materials,
 * UCRL-MA-106439). With mu = rho/rho0 - 1 = 1/J - 1 and E the internal energy per unit
 * reference volume:
 *   compression (mu > 0):
 *     p = rho0 C0^2 mu [1 + (1 - Gamma0/2) mu - (a/2) mu^2]
 *         / [1 - (S1 - 1) mu - S2 mu^2/(mu + 1) - S3 mu^3/(mu + 1)^2]^2  +  (Gamma0 + a mu) E
 *   tension (mu <= 0):
 *     p = rho0 C0^2 mu + (Gamma0 + a mu) E.
 * S2 = S3 = 0 is the linear Us-up form. */
#include "material/material_impl.h"

#include <string.h>

const pf_key pf_material_eos_keys[] = {
    {"type", PF_KEY_STRING, 1, NULL, "", "equation of state: mie_gruneisen", NULL},
    {"c0", PF_KEY_REAL, 1, NULL, "m/s", "bulk sound speed C0 (intercept of the Us-up fit, > 0)", NULL},
    {"s1", PF_KEY_REAL, 1, NULL, "", "first Us-up slope coefficient S1", NULL},
    {"s2", PF_KEY_REAL, 0, "0", "", "second Us-up coefficient S2 (0 for the linear fit)", NULL},
    {"s3", PF_KEY_REAL, 0, "0", "", "third Us-up coefficient S3 (0 for the linear fit)", NULL},
    {"gamma0", PF_KEY_REAL, 1, NULL, "", "Gruneisen gamma at the reference state (>= 0)", NULL},
    {"a", PF_KEY_REAL, 0, "0", "", "first-order volume correction a in Gamma = Gamma0 + a mu", NULL},
    PF_KEY_END};

int pf_material_eos_mg_read(const pf_deck *d, const pf_node *eos, double rho0, pf_material_eos_mg *e) {
  const char *type = NULL;
  PF_CALL(pf_deck_string(d, eos, "type", &type));
  if (!type) return pf_deck_error(d, eos, "type", "the eos mapping needs 'type' (known: mie_gruneisen)");
  if (strcmp(type, "mie_gruneisen"))
    return pf_deck_error(d, pf_node_get(eos, "type"), "type",
                         "unknown equation of state '%s' (known: mie_gruneisen)", type);
  const char *required[] = {"c0", "s1", "gamma0"};
  for (int k = 0; k < 3; k++)
    if (!pf_node_get(eos, required[k]))
      return pf_deck_error(d, eos, required[k], "the mie_gruneisen eos needs '%s'", required[k]);
  *e = (pf_material_eos_mg){.rho0 = rho0};
  PF_CALL(pf_deck_real(d, eos, "c0", &e->c0));
  PF_CALL(pf_deck_real(d, eos, "s1", &e->s1));
  PF_CALL(pf_deck_real(d, eos, "s2", &e->s2));
  PF_CALL(pf_deck_real(d, eos, "s3", &e->s3));
  PF_CALL(pf_deck_real(d, eos, "gamma0", &e->gamma0));
  PF_CALL(pf_deck_real(d, eos, "a", &e->a));
  if (!(e->c0 > 0)) return pf_deck_error(d, pf_node_get(eos, "c0"), "c0", "must be positive (got %g)", e->c0);
  if (!(e->gamma0 >= 0))
    return pf_deck_error(d, pf_node_get(eos, "gamma0"), "gamma0", "must be >= 0 (got %g)", e->gamma0);
  return 0;
}

/* The E = 0 part f(mu) (formula above) and df/dmu. In compression f = rho0 C0^2 mu N / Q^2 with
 *   N = 1 + (1 - Gamma0/2) mu - (a/2) mu^2,             N' = (1 - Gamma0/2) - a mu,
 *   Q = 1 - (S1-1) mu - S2 mu^2/(mu+1) - S3 mu^3/(mu+1)^2,
 *   Q' = -(S1-1) - S2 mu (mu+2)/(mu+1)^2 - S3 mu^2 (mu+3)/(mu+1)^3,
 *   f' = rho0 C0^2 [(N + mu N') Q - 2 mu N Q'] / Q^3.  In tension f = rho0 C0^2 mu. */
double pf_material_eos_mg_f(const pf_material_eos_mg *e, double mu, double *dfdmu) {
  const double k = e->rho0 * e->c0 * e->c0;
  if (mu <= 0) {
    if (dfdmu) *dfdmu = k;
    return k * mu;
  }
  const double mp1 = mu + 1.0;
  const double N = 1.0 + (1.0 - 0.5 * e->gamma0) * mu - 0.5 * e->a * mu * mu;
  const double Q = 1.0 - (e->s1 - 1.0) * mu - e->s2 * mu * mu / mp1 - e->s3 * mu * mu * mu / (mp1 * mp1);
  if (dfdmu) {
    const double dN = (1.0 - 0.5 * e->gamma0) - e->a * mu;
    const double dQ = -(e->s1 - 1.0) - e->s2 * mu * (mu + 2.0) / (mp1 * mp1) -
                      e->s3 * mu * mu * (mu + 3.0) / (mp1 * mp1 * mp1);
    *dfdmu = k * ((N + mu * dN) * Q - 2.0 * mu * N * dQ) / (Q * Q * Q);
  }
  return k * mu * N / (Q * Q);
}

double pf_material_eos_mg_pressure(const pf_material_eos_mg *e, double mu, double E) {
  return pf_material_eos_mg_f(e, mu, NULL) + pf_material_eos_mg_gamma(e, mu) * E;
}

/* K_s = -J dp/dJ|_s with dE = -p dJ and dmu/dJ = -1/J^2:  K_s = (f' + a E)/J + Gamma p J. */
double pf_material_eos_mg_bulk_modulus(const pf_material_eos_mg *e, double J, double E) {
  const double mu = 1.0 / J - 1.0;
  double df;
  const double p = pf_material_eos_mg_f(e, mu, &df) + pf_material_eos_mg_gamma(e, mu) * E;
  return (df + e->a * E) / J + pf_material_eos_mg_gamma(e, mu) * p * J;
}
