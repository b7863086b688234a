/* The constitutive library: the deck keys of FE materials, the list of models (material/materials.h),
 * reading the common parameters (density, elastic constants), and the calls that dispatch to a
 * model's ops table. Theory: docs/theory/fem_materials.md. */
#include "material/material_impl.h"

#include <stdlib.h>
#include <string.h>

static const pf_material_ops *const model_list[] = {
#define PF_MATERIAL(id) &pf_material_##id,
#include "material/materials.h"
#undef PF_MATERIAL
};
enum { NMODELS = sizeof model_list / sizeof model_list[0] };

/* "elastic, neo_hookean, ..." at compile time: each entry contributes ", id". */
static const char model_names[] = ""
#define PF_MATERIAL(id) ", " #id
#include "material/materials.h"
#undef PF_MATERIAL
    ;

/* The keys every model reads (material_read, read_elastic), after `model` and `density`. */
static const pf_key elastic_keys[] = {
    {"youngs_modulus", PF_KEY_REAL, 0, NULL, "Pa",
     "Young's modulus E (give E and poissons_ratio, or bulk_modulus and shear_modulus)", NULL},
    {"poissons_ratio", PF_KEY_REAL, 0, NULL, "", "Poisson's ratio nu, 0 <= nu < 0.5", NULL},
    {"bulk_modulus", PF_KEY_REAL, 0, NULL, "Pa",
     "bulk modulus K (with shear_modulus, instead of youngs_modulus and poissons_ratio)", NULL},
    {"shear_modulus", PF_KEY_REAL, 0, NULL, "Pa", "shear modulus G", NULL},
    PF_KEY_END};

/* pf_material_keys: `model` (naming the list), `density`, the elastic constants, then each
 * model's own rows (pf_material_ops.keys) in list order, assembled at first use. */
const pf_key *pf_material_key_table(void) {
  enum { MAX_KEYS = 64 };
  static pf_key rows[MAX_KEYS + 1];
  static char text[4096], model[256];
  if (rows[0].name) return rows;
  snprintf(model, sizeof model, "constitutive model: ");
  for (int k = 0; k < NMODELS; k++) strcat(strcat(model, k ? " | " : ""), model_list[k]->name);
  pf_key_table t = {rows, MAX_KEYS, 2, text, sizeof text, 0};
  rows[0] = (pf_key){"model", PF_KEY_STRING, 1, NULL, "", model, NULL};
  rows[1] = (pf_key){"density", PF_KEY_REAL, 1, NULL, "kg/m^3", "reference mass density rho0 (> 0)", NULL};
  int ierr = pf_key_table_add(&t, elastic_keys);
  for (int k = 0; k < NMODELS && !ierr; k++) ierr = pf_key_table_add(&t, model_list[k]->keys);
  return rows;
}

static const pf_material_ops *find_model(const char *model) {
  for (int k = 0; k < NMODELS; k++)
    if (model && !strcmp(model_list[k]->name, model)) return model_list[k];
  return NULL;
}

int pf_material_known(const char *model) { return find_model(model) != NULL; }

const char *pf_material_names(void) { return model_names + 2; }

/* Every key of the mapping must be one the model reads (a key that would be
 * silently ignored is an error naming it; the isotropic constants for a model with its own). */
static int check_keys(const pf_deck *d, const pf_node *mat, const pf_material_ops *ops) {
  for (int i = 0; i < pf_node_count(mat); i++) {
    const char *key = NULL;
    const pf_node *v = pf_node_map_item(mat, i, &key);
    if (!strcmp(key, "model") || !strcmp(key, "density")) continue;
    int used = 0;
    for (const pf_key *k = elastic_keys; k->name && !used && !ops->own_elastic; k++) used = !strcmp(k->name, key);
    for (const pf_key *k = ops->keys; k && k->name && !used; k++) used = !strcmp(k->name, key);
    if (used) continue;
    char list[512] = "model, density";
    for (const pf_key *k = elastic_keys; k->name && !ops->own_elastic; k++) strcat(strcat(list, ", "), k->name);
    for (const pf_key *k = ops->keys; k && k->name; k++)
      if (strlen(list) + strlen(k->name) + 3 < sizeof list) strcat(strcat(list, ", "), k->name);
    return pf_deck_error(d, v, key, "not used by model '%s' (its keys: %s)", ops->name, list);
  }
  return 0;
}

/* Elastic constants from (E, nu) or (K, G); a key of the other pair, when also given, must agree
 * to 1e-6 relative. K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)); E = 9KG / (3K + G),
 * nu = (3K - 2G) / (2 (3K + G)). */
static int read_elastic(const pf_deck *d, const pf_node *mat, pf_material *m) {
  const char *key[4] = {"youngs_modulus", "poissons_ratio", "bulk_modulus", "shear_modulus"};
  double v[4] = {0, 0, 0, 0};
  int has[4];
  for (int k = 0; k < 4; k++) {
    has[k] = pf_node_get(mat, key[k]) != NULL;
    PF_CALL(pf_deck_real(d, mat, key[k], &v[k]));
  }
  if (has[0] && has[1]) {
    if (!(v[0] > 0)) return pf_deck_error(d, pf_node_get(mat, key[0]), key[0], "must be positive (got %g)", v[0]);
    if (!(v[1] >= 0 && v[1] < 0.5))
      return pf_deck_error(d, pf_node_get(mat, key[1]), key[1], "must satisfy 0 <= nu < 0.5 (got %g)", v[1]);
    m->E = v[0], m->nu = v[1];
    m->K = m->E / (3.0 * (1.0 - 2.0 * m->nu));
    m->G = m->E / (2.0 * (1.0 + m->nu));
  } else if (has[2] && has[3]) {
    for (int k = 2; k < 4; k++)
      if (!(v[k] > 0)) return pf_deck_error(d, pf_node_get(mat, key[k]), key[k], "must be positive (got %g)", v[k]);
    m->K = v[2], m->G = v[3];
    m->E = 9.0 * m->K * m->G / (3.0 * m->K + m->G);
    m->nu = (3.0 * m->K - 2.0 * m->G) / (2.0 * (3.0 * m->K + m->G));
  } else {
    return pf_deck_error(d, mat, "youngs_modulus",
                         "model '%s' needs youngs_modulus and poissons_ratio, or bulk_modulus and "
                         "shear_modulus", m->ops->name);
  }
  const double derived[4] = {m->E, m->nu, m->K, m->G};
  for (int k = 0; k < 4; k++)
    if (has[k] && !(fabs(v[k] - derived[k]) <= 1e-6 * fabs(derived[k]) + (k == 1 ? 1e-9 : 0)))
      return pf_deck_error(d, pf_node_get(mat, key[k]), key[k],
                           "%g is inconsistent with the other elastic constants, which give %g",
                           v[k], derived[k]);
  m->lambda = m->K - 2.0 * m->G / 3.0;
  return 0;
}

static int material_read(const pf_deck *d, const pf_node *mat, const char *name,
                         const pf_material_ops *ops, pf_material *m) {
  snprintf(m->name, sizeof m->name, "%s", name ? name : "");
  m->ops = ops;
  PF_CALL(check_keys(d, mat, ops));
  if (!pf_node_get(mat, "density"))
    return pf_deck_error(d, mat, "density", "material '%s' needs 'density' (kg/m^3)", m->name);
  PF_CALL(pf_deck_real(d, mat, "density", &m->density));
  if (!(m->density > 0))
    return pf_deck_error(d, pf_node_get(mat, "density"), "density", "must be positive (got %g)", m->density);
  if (!ops->own_elastic) PF_CALL(read_elastic(d, mat, m));
  PF_CALL(ops->create(d, mat, m));
  return 0;
}

int pf_material_create(const pf_deck *d, const pf_node *mat, const char *name,
                           pf_material **out) {
  *out = NULL;
  const char *model = NULL;
  PF_CALL(pf_deck_string(d, mat, "model", &model));
  if (!model)
    return pf_deck_error(d, mat, "model", "material '%s' needs 'model' (known: %s)", name ? name : "",
                         pf_material_names());
  const pf_material_ops *ops = find_model(model);
  if (!ops)
    return pf_deck_error(d, pf_node_get(mat, "model"), "model",
                         "unknown FE material model '%s' (known: %s)", model, pf_material_names());
  pf_material *m;
  PF_MALLOC(m, 1);
  int ierr = material_read(d, mat, name, ops, m);
  if (ierr) {
    pf_material_destroy(&m);
    return ierr;
  }
  *out = m;
  return 0;
}

int pf_material_destroy(pf_material **m) {
  if (!*m) return 0;
  if ((*m)->ops && (*m)->ops->destroy) (*m)->ops->destroy(*m);
  else free((*m)->data);
  PF_FREE(*m);
  return 0;
}

const char *pf_material_name(const pf_material *m) { return m->name; }
double pf_material_density(const pf_material *m) { return m->density; }
double pf_material_bulk_modulus(const pf_material *m) { return m->K; }
double pf_material_shear_modulus(const pf_material *m) { return m->G; }
int pf_material_nstate(const pf_material *m) { return m->ops->nstate; }

const char *pf_material_state_name(const pf_material *m, int k) {
  return k >= 0 && k < m->ops->nstate ? m->ops->state_names[k] : NULL;
}

void pf_material_init(const pf_material *m, pf_int n, double *state) {
  if (m->ops->init) m->ops->init(m, n, state);
  else
    for (int64_t k = 0; k < (int64_t)n * m->ops->nstate; k++) state[k] = 0.0;
}

void pf_material_rereference(const pf_material *m, pf_int n, const double *F_from,
                                 const double *F_to, double *state) {
  if (m->ops->rereference) m->ops->rereference(m, n, F_from, F_to, state);
}

void pf_material_update(const pf_material *m, pf_int n, double dt,
                            const double *restrict F, const double *restrict D,
                            double *restrict sigma, double *restrict state, double *restrict c) {
  m->ops->update(m, n, dt, F, D, sigma, state);
  if (!c) return;
  if (m->ops->wave_speed) {
    m->ops->wave_speed(m, n, F, sigma, state, c);
    return;
  }
  const double K = m->K, G = m->G, rho0 = m->density;
#pragma omp simd
  for (pf_int i = 0; i < n; i++) c[i] = pf_material_hypo_wave_speed(K, G, rho0, pf_det3(F + 9 * i));
}

/* Safeguarded Newton on g(x) = q - G3 x - sigma_y(x) over the bracket [0, x_max] where g(0) > 0
 * >= g(x_max) (Press et al., Numerical Recipes 3rd ed., sec. 9.4 "rtsafe"): a Newton step that
 * leaves the current bracket, or a non-finite slope, is replaced by bisection. */
double pf_material_radial_return(double q, double G3, double x_max, pf_material_flow_fn flow, const void *ctx) {
  double lo = 0.0, hi = x_max, x = 0.5 * x_max;
  for (int it = 0; it < 200; it++) {
    double dfl = 0.0;
    const double g = q - G3 * x - flow(ctx, x, &dfl);
    if (fabs(g) <= 1e-15 * q) return x;
    if (g > 0) lo = x;
    else hi = x;
    double xn = isfinite(dfl) ? x - g / (-G3 - dfl) : NAN;
    if (!(xn >= lo && xn <= hi)) xn = 0.5 * (lo + hi); /* also when NaN */
    if (fabs(xn - x) <= 1e-15 * x_max) return xn;
    x = xn;
  }
  return x;
}
