/* perifem constitutive library: elastic, neo-Hookean, J2, Johnson-Cook, modified Johnson-Cook
 * and orthotropic elastic models with a Mie-Gruneisen equation of state, shared by the hexahedral elements
 * (fem/) and correspondence peridynamics (pd/). Depends on core/ only. */
#ifndef PF_MATERIAL_H
#define PF_MATERIAL_H

#include "core/core.h"

#ifndef PF_USES_MATERIAL
#error "material/material.h is included by a module below material/ (docs/architecture.md: the module layers)"
#endif

/* ---- constitutive library (material/) ---------------------------------------------
 * One library for FE elements and correspondence PD points. A model advances the Cauchy stress
 * of n material points over one step, batched. Stress and rate of deformation are symmetric
 * tensors in Voigt order (xx, yy, zz, yz, xz, xy), tensor (not engineering) shear components. */
typedef struct pf_material pf_material;
/* Keys of a material under `materials:` whose model is an FE model: assembled at first use from
 * the list material/materials.h, each model giving its own rows (pf_material_ops.keys), so that
 * adding a model edits no table here. The name reads as the table. */
const pf_key *pf_material_key_table(void);
#define pf_material_keys (pf_material_key_table())
/* 1 when model names an FE/continuum model (elastic, neo_hookean, j2, johnson_cook, ...). */
int pf_material_known(const char *model);
/* The known model names, comma separated (for error messages). */
const char *pf_material_names(void);
/* Read the material mapping `mat` (named `name` under materials:); errors name the key. */
int pf_material_create(const pf_deck *d, const pf_node *mat, const char *name,
                           pf_material **m);
int pf_material_destroy(pf_material **m);
const char *pf_material_name(const pf_material *m);
double pf_material_density(const pf_material *m);       /* reference density, kg/m^3 */
double pf_material_bulk_modulus(const pf_material *m);  /* small-strain K, Pa */
double pf_material_shear_modulus(const pf_material *m); /* small-strain G, Pa */
/* History variables per material point and their names (output fields). A model with an
 * equivalent plastic strain names it "eqps". */
int pf_material_nstate(const pf_material *m);
const char *pf_material_state_name(const pf_material *m, int k);
/* Initial state of n points: state [n * nstate] (e.g. temperature = initial temperature). */
void pf_material_init(const pf_material *m, pf_int n, double *state);
/* Advance n material points over dt (s):
 *   F     [9n] deformation gradient at the end of the step, row-major F_iJ = dx_i/dX_J
 *   D     [6n] rate of deformation at mid-step, 1/s
 *   sigma [6n] in: the previous Cauchy stress already rotated to the end configuration
 *              (the element applies the objective rate); out: the new Cauchy stress, Pa.
 *              Hyperelastic models compute it from F alone.
 *   state [n * nstate] history variables, updated
 *   c     [n] out: the current dilatational wave speed, m/s (for the stable step) */
void pf_material_update(const pf_material *m, pf_int n, double dt,
                            const double *restrict F, const double *restrict D,
                            double *restrict sigma, double *restrict state, double *restrict c);

/* The deformation-gradient estimate of n points changed from F_from [9n] to F_to [9n] without
 * the material moving (a correspondence point that lost bonds): the model re-expresses its
 * history so that its elastic state, and so its stress, stays what it was (docs/theory/
 * materials.md §2.7). A model whose stress follows F only through D needs nothing. */
void pf_material_rereference(const pf_material *m, pf_int n, const double *F_from,
                                 const double *F_to, double *state);

#endif
