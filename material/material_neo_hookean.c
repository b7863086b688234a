/* Compressible neo-Hookean hyperelasticity (the ln J form, often attributed to Simo & Pister
 * 1984 / Ciarlet; Bonet & Wood 2008, Nonlinear Continuum Mechanics for Finite Element Analysis,
 * 2nd ed., sec. 6.4.3):
 *   Psi(C) = G/2 (tr C - 3) - G ln J + lambda/2 (ln J)^2,
 *   sigma  = (G / J) (b - I) + (lambda ln J / J) I,   b = F F^T, J = det F.
 * The stress is a function of F alone; the incoming sigma is ignored (an objective rate is not
 * needed). lambda and G are the small-strain Lame constants, so the model agrees with linear
 * elasticity to first order in the strain. */
#include "material/material_impl.h"

static int nh_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  (void)d, (void)mat, (void)m;
  return 0;
}

/* sigma = (G/J)(b - I) + (lambda ln J / J) I, with b - I = H + H^T + H H^T, H = F - I, so that
 * small strains do not lose digits to the cancellation in b - I. */
static void nh_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                      const double *restrict D, double *restrict sigma, double *restrict state) {
  (void)dt, (void)D, (void)state;
  const double G = m->G, lam = m->lambda;
  static const int vi[6] = {0, 1, 2, 1, 0, 0}, vj[6] = {0, 1, 2, 2, 2, 1};
  for (pf_int p = 0; p < n; p++) {
    const double *restrict f = F + 9 * p;
    double H[9];
    for (int k = 0; k < 9; k++) H[k] = f[k] - (k % 4 == 0 ? 1.0 : 0.0);
    const double J = pf_det3(f);
    const double pres = lam * log(J) / J, g = G / J;
    for (int v = 0; v < 6; v++) {
      const int i = vi[v], j = vj[v];
      const double bm = H[3 * i + j] + H[3 * j + i] + H[3 * i] * H[3 * j] +
                        H[3 * i + 1] * H[3 * j + 1] + H[3 * i + 2] * H[3 * j + 2];
      sigma[6 * p + v] = g * bm + (v < 3 ? pres : 0.0);
    }
  }
}

/* Wave speed from the spatial elasticity tensor of this model, c = lambda/J I (x) I +
 * 2 (G - lambda ln J)/J I_sym (Bonet & Wood 2008, sec. 6.4.3): the longitudinal modulus is
 * M = (lambda + 2G - 2 lambda ln J) / J, plus the geometric (initial-stress) term, bounded above
 * by the largest Gershgorin bound of sigma when positive. M is never taken below the
 * small-strain lambda + 2G, so the estimate does not drop in tension. c = sqrt(M J / rho0). */
static void nh_wave_speed(const pf_material *m, pf_int n, const double *restrict F,
                          const double *restrict sigma, const double *restrict state,
                          double *restrict c) {
  (void)state;
  const double G = m->G, lam = m->lambda, rho0 = m->density, M0 = lam + 2.0 * G;
  for (pf_int p = 0; p < n; p++) {
    const double J = pf_det3(F + 9 * p);
    const double *s = sigma + 6 * p;
    const double g0 = s[0] + fabs(s[5]) + fabs(s[4]), g1 = s[1] + fabs(s[5]) + fabs(s[3]),
                 g2 = s[2] + fabs(s[4]) + fabs(s[3]);
    const double smax = fmax(0.0, fmax(g0, fmax(g1, g2)));
    const double M = fmax(M0, (lam + 2.0 * G - 2.0 * lam * log(J)) / J + smax);
    c[p] = sqrt(M * J / rho0);
  }
}

const pf_material_ops pf_material_neo_hookean = {
    .name = "neo_hookean",
    .nstate = 0,
    .create = nh_create,
    .update = nh_update,
    .wave_speed = nh_wave_speed,
};
