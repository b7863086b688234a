/* Private to material/: the constitutive-library plug-in table, the material
 * object, small tensor helpers shared by the models, the radial-return scalar solver and the
 * Mie-Gruneisen equation of state. Theory: docs/theory/fem_materials.md.
 *
 * Conventions of every kernel: n points, batched; F [9n] row-major F_iJ; D [6n] and sigma [6n]
 * in Voigt order (xx, yy, zz, yz, xz, xy) with tensor (not engineering) shear components;
 * state [n * nstate] point-major (point i's history is state[i * nstate + k]), like a point-store
 * field with nstate components. */
#ifndef PF_MATERIAL_IMPL_H
#define PF_MATERIAL_IMPL_H

#include "material/material.h"

#include <math.h>

typedef struct pf_material_ops pf_material_ops;

struct pf_material {
  char name[64]; /* the material's name under materials: */
  const pf_material_ops *ops;
  double density;   /* reference density rho0, kg/m^3 */
  double E, nu;     /* Young's modulus (Pa) and Poisson's ratio, from the deck */
  double K, G;      /* small-strain bulk and shear moduli, Pa (K = rho0 C0^2 with an EOS) */
  double lambda;    /* Lame's first parameter K - 2G/3, Pa */
  void *data;       /* the model's own parameters (freed by destroy, or free() when NULL) */
};

/* A model: one file material/material_<id>.c defining pf_material_<id>, and one line in
 * material/materials.h. Required: name, create, update. Optional: keys (NULL: the elastic
 * constants only), state_names (nstate = 0),
 * init (NULL: state zero), wave_speed (NULL: the hypoelastic estimate
 * pf_material_hypo_wave_speed with the small-strain K and G), destroy (NULL: free(data)).
 * Before create is called, material.c has read density and the elastic constants into the
 * material (every model is elastic at small strain) and rejected any other key not in keys;
 * for a model with own_elastic it reads density only, refuses the isotropic constants, and the
 * model's create sets E, nu, K, G and lambda (an anisotropic model: K and G are then the pair
 * that hourglass control, bulk viscosity, contact and the stable step read, which the model
 * documents). */
struct pf_material_ops {
  const char *name; /* the deck's `model:` name */
  int own_elastic;  /* 1: its keys hold its elastic constants (no youngs_modulus, ...) */
  int nstate;
  const char *const *state_names; /* [nstate] output names */
  /* Its own rows of the material mapping besides model, density and the elastic constants
   * (PF_KEY_END-ended, or NULL; each description starts "<id>: "), assembled into
   * pf_material_keys in list order: the model reads these and no other key. */
  const pf_key *keys;
  int (*create)(const pf_deck *d, const pf_node *mat, pf_material *m);
  void (*init)(const pf_material *m, pf_int n, double *restrict state);
  /* Advance n points over dt: see pf_material_update (the wave speed is done separately). */
  void (*update)(const pf_material *m, pf_int n, double dt, const double *restrict F,
                 const double *restrict D, double *restrict sigma, double *restrict state);
  /* c [n]: dilatational wave speed after the update (F end-of-step, sigma new stress). */
  void (*wave_speed)(const pf_material *m, pf_int n, const double *restrict F,
                     const double *restrict sigma, const double *restrict state,
                     double *restrict c);
  /* Optional (NULL: the model's stress depends on F only through D, nothing to do): the
   * deformation-gradient estimate of n points changed from F_from to F_to while the material
   * did not move (a correspondence point that lost bonds, pd/material_correspondence.c); keep
   * the elastic state that the next update computes the stress from. */
  void (*rereference)(const pf_material *m, pf_int n, const double *restrict F_from,
                      const double *restrict F_to, double *restrict state);
  void (*destroy)(pf_material *m);
};

#define PF_MATERIAL(id) extern const pf_material_ops pf_material_##id;
#include "material/materials.h"
#undef PF_MATERIAL

/* ---- small tensor helpers (Voigt order xx, yy, zz, yz, xz, xy) ---------------------------- */
static inline double pf_material_trace(const double *restrict a) { return a[0] + a[1] + a[2]; }
/* a : b of two symmetric tensors in Voigt form with tensor shear components. */
static inline double pf_material_ddot(const double *restrict a, const double *restrict b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}
/* The deviator s = a - tr(a)/3 I. */
static inline void pf_material_deviator(const double *restrict a, double *restrict s) {
  const double m = pf_material_trace(a) / 3.0;
  s[0] = a[0] - m, s[1] = a[1] - m, s[2] = a[2] - m;
  s[3] = a[3], s[4] = a[4], s[5] = a[5];
}
/* von Mises equivalent stress q = sqrt(3/2 s:s) of a deviator s. */
static inline double pf_material_mises(const double *restrict s) { return sqrt(1.5 * pf_material_ddot(s, s)); }

/* Hypoelastic dilatational wave speed c = sqrt((K + 4G/3) / rho), rho = rho0 / J the current
 * density (Belytschko, Liu, Moran & Elkhodary 2014, ch. 6, element stable step). */
static inline double pf_material_hypo_wave_speed(double K, double G, double rho0, double J) {
  return sqrt((K + 4.0 * G / 3.0) * J / rho0);
}

/* ---- eigen-decomposition of symmetric 3x3 matrices across vector lanes (material/sym3_eigen.c) -- *
 * Lane l of each array is one matrix: a (destroyed) = V diag(w) V^T, the columns of V orthonormal
 * eigenvectors, each lane's bits those of the matrix decomposed alone (cyclic Jacobi). */
#define PF_SYM3_LANES 8
void pf_sym3_eigen_lanes(double a[3][3][PF_SYM3_LANES], double w[3][PF_SYM3_LANES],
                         double V[3][3][PF_SYM3_LANES]);

/* ---- radial return (material/material.c) ------------------------------------------------------- *
 * The consistency equation of J2 radial return with a flow stress that depends on the
 * increment dgam of equivalent plastic strain (hardening, rate):
 *   g(dgam) = q_trial - 3 G dgam - sigma_y(dgam) = 0
 * (Simo & Hughes 1998, sec. 3.3, Box 3.2 radial return; the rate-dependent form is the same
 * scalar equation with sigma_y depending on dgam / dt). sigma_y must be non-decreasing in dgam,
 * so g decreases and the root lies in [0, (q_trial - sigma_y(0)) / (3G)]; it is found by Newton
 * safeguarded by bisection (Press et al., Numerical Recipes, 3rd ed., sec. 9.4, rtsafe), which
 * copes with an infinite slope at dgam = 0 (power law with exponent < 1 at eqps = 0).
 * flow(ctx, dgam, &dflow) returns sigma_y and its derivative (which may be infinite). */
typedef double (*pf_material_flow_fn)(const void *ctx, double dgam, double *dflow);
double pf_material_radial_return(double q_trial, double G3, double dgam_max, pf_material_flow_fn flow,
                            const void *ctx);

/* Keys of the `johnson_cook:` mapping (material/material_johnson_cook.c). */
extern const pf_key pf_material_johnson_cook_keys[];
/* Keys of the `modified_johnson_cook:` and `damage:` mappings (material/material_modified_johnson_cook.c). */
extern const pf_key pf_material_modified_johnson_cook_keys[];
extern const pf_key pf_material_jc_damage_keys[];

/* ---- Mie-Gruneisen equation of state (material/eos_mie_gruneisen.c) --------------------------- */
typedef struct {
  double rho0;             /* reference density, kg/m^3 */
  double c0;               /* bulk sound speed (Us-up intercept), m/s */
  double s1, s2, s3;       /* Us-up slope coefficients */
  double gamma0, a;        /* Gruneisen gamma and its first-order volume correction */
} pf_material_eos_mg;

/* Keys of the `eos:` mapping. */
extern const pf_key pf_material_eos_keys[];
/* Read the `eos:` mapping (type must be mie_gruneisen); errors name the key. */
int pf_material_eos_mg_read(const pf_deck *d, const pf_node *eos, double rho0, pf_material_eos_mg *e);
/* The pressure is linear in E: p(mu, E) = f(mu) + Gamma(mu) E, with E the internal energy per
 * unit reference volume (J/m^3) and mu = rho/rho0 - 1 = 1/J - 1. f(mu) returns the E = 0 part
 * and, when dfdmu is not NULL, its derivative. */
double pf_material_eos_mg_f(const pf_material_eos_mg *e, double mu, double *dfdmu);
static inline double pf_material_eos_mg_gamma(const pf_material_eos_mg *e, double mu) { return e->gamma0 + e->a * mu; }
double pf_material_eos_mg_pressure(const pf_material_eos_mg *e, double mu, double E);
/* Isentropic bulk modulus K_s = -J dp/dJ along dE = -p dJ, at (J, E): K_s = (f'(mu) + a E)/J +
 * Gamma(mu) p J; equals rho0 C0^2 at the reference state. */
double pf_material_eos_mg_bulk_modulus(const pf_material_eos_mg *e, double J, double E);

#endif
