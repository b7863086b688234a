/* Hypoelastic isotropic linear elasticity: the objective stress rate is linear in the rate of
 * deformation, sigma^o = lambda tr(D) I + 2 G D (Truesdell 1955 hypoelasticity; Belytschko,
 * Liu, Moran & Elkhodary 2014, ch. 5, hypoelastic materials; Wilkins 1964 for the explicit
 * update). The element has already rotated sigma_n by its objective rate, so one step is
 *   sigma_{n+1} = sigma_n^R + dt (lambda tr(D_{n+1/2}) I + 2 G D_{n+1/2}). */
#include "material/material_impl.h"

static int elastic_create(const pf_deck *d, const pf_node *mat, pf_material *m) {
  (void)d, (void)mat, (void)m; /* the elastic constants were read by material.c */
  return 0;
}

/* sigma += dt (lambda tr(D) I + 2 G D), Voigt (xx, yy, zz, yz, xz, xy), tensor shear. */
static void elastic_update(const pf_material *m, pf_int n, double dt, const double *restrict F,
                           const double *restrict D, double *restrict sigma,
                           double *restrict state) {
  (void)F, (void)state;
  const double lam = m->lambda, G2 = 2.0 * m->G;
#pragma omp simd
  for (pf_int i = 0; i < n; i++) {
    const double *restrict d = D + 6 * i;
    double *restrict s = sigma + 6 * i;
    const double ltr = lam * (d[0] + d[1] + d[2]);
    s[0] += dt * (ltr + G2 * d[0]);
    s[1] += dt * (ltr + G2 * d[1]);
    s[2] += dt * (ltr + G2 * d[2]);
    s[3] += dt * G2 * d[3];
    s[4] += dt * G2 * d[4];
    s[5] += dt * G2 * d[5];
  }
}

const pf_material_ops pf_material_elastic = {
    .name = "elastic",
    .nstate = 0,
    .create = elastic_create,
    .update = elastic_update,
};
