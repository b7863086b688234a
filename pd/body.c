/* A peridynamic body: its deck keys, material lookup by name, family, and the per-step entry
 * points that dispatch to the material's ops table. */
#include "pd/pd_impl.h"
#include "material/material.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const pf_pd_material_ops *const material_list[] = {
#define PF_PD_MATERIAL(id) &pf_pd_material_##id,
#include "pd/materials.h"
#undef PF_PD_MATERIAL
};
enum { NMATERIALS = sizeof material_list / sizeof material_list[0] };

/* pf_pd_material_keys: `model` (naming the list), the keys every PD material reads
 * (read_material), then each material's own rows (pf_pd_material_ops.keys) in list order,
 * assembled at first use. */
static const pf_key common_material_keys[] = {
    {"density", PF_KEY_REAL, 1, NULL, "kg/m^3", "mass density", NULL},
    {"bulk_modulus", PF_KEY_REAL, 0, NULL, "Pa", "bulk modulus K", NULL},
    {"shear_modulus", PF_KEY_REAL, 0, NULL, "Pa", "shear modulus G (lps, elastic_plastic)", NULL},
    PF_KEY_END};

const pf_key *pf_pd_material_key_table(void) {
  enum { MAX_KEYS = 32 };
  static pf_key rows[MAX_KEYS + 1];
  static char text[1024], model[256] = "peridynamic material: ";
  if (rows[0].name) return rows;
  for (int k = 0; k < NMATERIALS; k++)
    strcat(strcat(model, k ? " | " : ""), material_list[k]->name);
  pf_key_table t = {rows, MAX_KEYS, 1, text, sizeof text, 0};
  rows[0] = (pf_key){"model", PF_KEY_STRING, 1, NULL, "", model, NULL};
  int ierr = pf_key_table_add(&t, common_material_keys);
  for (int k = 0; k < NMATERIALS && !ierr; k++) ierr = pf_key_table_add(&t, material_list[k]->keys);
  return rows;
}

static const pf_key crack_keys[] = {
    {"shape", PF_KEY_STRING, 1, NULL, "", "rectangle | disk", NULL},
    {"corner", PF_KEY_VEC3, 0, NULL, "m", "rectangle: one corner p0", NULL},
    {"edge_a", PF_KEY_VEC3, 0, NULL, "m", "rectangle: first edge vector from the corner", NULL},
    {"edge_b", PF_KEY_VEC3, 0, NULL, "m", "rectangle: second edge vector from the corner", NULL},
    {"center", PF_KEY_VEC3, 0, NULL, "m", "disk: centre", NULL},
    {"normal", PF_KEY_VEC3, 0, NULL, "", "disk: normal", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "disk: radius", NULL},
    PF_KEY_END};

static const pf_key part_keys[] = {
    {"material", PF_KEY_STRING, 1, NULL, "", "a name under materials:, of the body material's model (a continuum model: its constants, an "
     "orthotropic one its axes, may differ)", NULL},
    {"region", PF_KEY_MAP, 0, NULL, "", "the points (reference positions) that take it (give region or block)",
     pf_region_keys},
    {"block", PF_KEY_STRING, 0, NULL, "",
     "the points of this block of the body's discretization that take it: a points_file's block id, an exodus "
     "SPHERE, HEX8 or TET4 block's name or id (give region or block)", NULL},
    PF_KEY_END};

static const pf_key interface_damage_keys[] = {
    {"law", PF_KEY_STRING, 1, NULL, "", "critical_stretch | critical_energy", NULL},
    {"critical_stretch", PF_KEY_REAL, 0, NULL, "", "critical_stretch: the stretch limit of the interface's bonds",
     NULL},
    {"energy_release_rate", PF_KEY_REAL, 0, NULL, "J/m^2",
     "critical_energy: the interface's G0, its bonds' energy limit w_c = 4 G0 / (pi delta^4)", NULL},
    PF_KEY_END};

static const pf_key interface_keys[] = {
    {"micromodulus", PF_KEY_STRING, 0, "series", "",
     "pmb: a bond between two materials takes series (2 c_i c_j / (c_i + c_j), its two halves as springs in "
     "series) | mean ((c_i + c_j) / 2)", NULL},
    {"damage", PF_KEY_MAP, 0, NULL, "",
     "the interface's own failure law: the bonds between two materials take it instead of the body's",
     interface_damage_keys},
    PF_KEY_END};

static const pf_key body_keys[] = {
    {"name", PF_KEY_STRING, 1, NULL, "", "body name (the Exodus block name)", NULL},
    {"type", PF_KEY_STRING, 0, "peridynamic", "", "peridynamic", NULL},
    {"material", PF_KEY_STRING, 1, NULL, "", "a name under materials:", NULL},
    {"geometry", PF_KEY_MAP, 1, NULL, "", "where the points are", pf_geometry_keys},
    {"material_regions", PF_KEY_LIST, 0, NULL, "",
     "several materials in one body (pmb, lps, elastic_plastic, and one continuum model as correspondence; constant "
     "horizon): "
     "each entry's region, or block of the discretization, takes its material, later entries over earlier ones; "
     "the other points keep `material` "
     "(docs/theory/interfaces.md)",
     part_keys},
    {"interface", PF_KEY_MAP, 0, "micromodulus: series", "", "how a bond between two materials is formed",
     interface_keys},
    {"horizon", PF_KEY_EXPR, 1, NULL, "m",
     "horizon delta (bonds with |xi| <= delta): a number, or an expression in x, y, z (a variable "
     "horizon; lps and correspondence materials)", NULL},
    {"formulation", PF_KEY_STRING, 0, "consistent (correspondence), standard (lps)", "",
     "auto (partial stress at interior points whose family reaches another horizon, standard elsewhere) | "
     "standard | partial_stress (lps and correspondence materials) | corrected (the standard force less "
     "its uniform-stress ghost force where the horizon varies; correspondence) | consistent (the "
     "standard energy form with ghost-force-free gradient weights where the horizon varies; "
     "correspondence)", NULL},
    {"allow_in_dynamics", PF_KEY_BOOL, 0, "false", "",
     "true: run the statics forms auto, partial_stress and corrected in an explicit run that takes steps, "
     "which they do not conserve energy in (refused otherwise; docs/theory/coupling.md §2.2); no effect on "
     "the standard and consistent forms", NULL},
    {"influence", PF_KEY_STRING, 0, "constant", "", "constant | inverse_distance | gaussian", NULL},
    {"influence_length", PF_KEY_REAL, 0, "horizon/2", "m", "gaussian: sigma in exp(-r^2/sigma^2)", NULL},
    {"partial_volumes", PF_KEY_BOOL, 0, "false", "",
     "weigh neighbours by the fraction of their cell inside the horizon", NULL},
    {"damage", PF_KEY_MAP, 0, "law: none", "", "bond failure law", pf_pd_damage_key_rows},
    {"precracks", PF_KEY_LIST, 0, NULL, "", "planar cracks: bonds crossing them are not created", crack_keys},
    {"initial_velocity", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m/s", "expressions in x, y, z", NULL},
    {"initial_velocity_set", PF_KEY_STRING, 0, NULL, "",
     "the initial velocity on this node set of the body only (as Peridigm's Initial Velocity on a node set); "
     "its other points start at rest", NULL},
    {"initial_displacement", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m", "expressions in x, y, z; the stress follows it in hyperelastic and PD models (rate-form models start unstressed)", NULL},
    {"hourglass", PF_KEY_MAP, 0, "type: stiffness, coefficient: 0.05", "",
     "correspondence (material with a continuum model): zero-energy-mode control", pf_pd_hourglass_keys},
    {"critical_damage", PF_KEY_REAL, 0, "0.99", "",
     "correspondence with a damage model: a bond fails once either end's damage exceeds it", NULL},
    {"bond_loss", PF_KEY_STRING, 0, "keep_stress", "",
     "correspondence: keep_stress (a point that loses bonds keeps its elastic state) | jump (its "
     "stress follows the new Fbar at once, as Tupek et al. 2013)", NULL},
    PF_KEY_END};

/* The body tables nest the damage table: it is assembled first. */
const pf_key *pf_pd_body_key_table(void) {
  pf_pd_damage_key_table();
  return body_keys;
}

double pf_pd_pmb_micromodulus(double K, const pf_influence *w, double delta) {
  return 18.0 * K / pf_pd_influence_moment(w, delta, 3);
}

double pf_pd_pmb_critical_stretch(double G0, double K, double delta) {
  return sqrt(5.0 * G0 / (9.0 * K * delta));
}

int pf_pd_material_known(const char *model) {
  for (int k = 0; k < NMATERIALS; k++)
    if (!strcmp(material_list[k]->name, model)) return 1;
  return 0;
}

/* The registered materials whose int flag at byte offset `flag` is set (every one: flag < 0). */
static const char *names_with(long flag) {
  static char known[256];
  known[0] = '\0';
  for (int k = 0; k < NMATERIALS; k++) {
    if (flag >= 0 && !*(const int *)((const char *)material_list[k] + flag)) continue;
    strcat(known, known[0] ? ", " : "");
    strcat(known, material_list[k]->name);
  }
  return known;
}

const char *pf_pd_material_names(void) { return names_with(-1); }
const char *pf_pd_material_names_with(size_t flag) { return names_with((long)flag); }

int pf_pd_material_reads_key(const pf_pd_material_ops *m, const char *key) {
  for (const char *const *k = m->body_keys; k && *k; k++)
    if (!strcmp(*k, key)) return 1;
  return 0;
}

static int find_material(const pf_deck *d, const pf_node *mat, const char *model,
                         const pf_pd_material_ops **ops) {
  for (int k = 0; k < NMATERIALS; k++)
    if (!strcmp(material_list[k]->name, model)) {
      *ops = material_list[k];
      return 0;
    }
  return pf_deck_error(d, pf_node_get(mat, "model"), "model",
                       "'%s' is not a peridynamic material (known: %s)", model, pf_pd_material_names());
}

static int read_cracks(const pf_deck *d, const pf_node *list, int *n, pf_precrack **out) {
  *n = pf_node_count(list);
  PF_MALLOC(*out, *n);
  for (int q = 0; q < *n; q++) {
    const pf_node *c = pf_node_item(list, q);
    pf_precrack *pc = &(*out)[q];
    const char *shape = "";
    PF_CALL(pf_deck_string(d, c, "shape", &shape));
    if (!strcmp(shape, "rectangle")) {
      pc->kind = PF_CRACK_RECTANGLE;
      if (!pf_node_get(c, "corner") || !pf_node_get(c, "edge_a") || !pf_node_get(c, "edge_b"))
        return pf_deck_error(d, c, "corner", "a rectangle needs corner, edge_a and edge_b");
      PF_CALL(pf_deck_vec3(d, c, "corner", pc->p0));
      PF_CALL(pf_deck_vec3(d, c, "edge_a", pc->a));
      PF_CALL(pf_deck_vec3(d, c, "edge_b", pc->b));
      const double an[3] = {pc->a[1] * pc->b[2] - pc->a[2] * pc->b[1], pc->a[2] * pc->b[0] - pc->a[0] * pc->b[2],
                           pc->a[0] * pc->b[1] - pc->a[1] * pc->b[0]};
      const double area = sqrt(an[0] * an[0] + an[1] * an[1] + an[2] * an[2]);
      const double la = sqrt(pc->a[0] * pc->a[0] + pc->a[1] * pc->a[1] + pc->a[2] * pc->a[2]);
      const double lb = sqrt(pc->b[0] * pc->b[0] + pc->b[1] * pc->b[1] + pc->b[2] * pc->b[2]);
      if (!(area > 1e-12 * la * lb)) /* (a crack that cuts no bond would pass without a word) */
        return pf_deck_error(d, pf_node_get(c, "edge_b"), "edge_b",
                             "the rectangle has no area: edge_a and edge_b are zero or parallel (|edge_a x edge_b| = "
                             "%g m^2)",
                             area);
    } else if (!strcmp(shape, "disk")) {
      pc->kind = PF_CRACK_DISK;
      if (!pf_node_get(c, "center") || !pf_node_get(c, "normal") || !pf_node_get(c, "radius"))
        return pf_deck_error(d, c, "center", "a disk needs center, normal and radius");
      PF_CALL(pf_deck_vec3(d, c, "center", pc->center));
      PF_CALL(pf_deck_vec3(d, c, "normal", pc->normal));
      const double nn = pc->normal[0] * pc->normal[0] + pc->normal[1] * pc->normal[1] + pc->normal[2] * pc->normal[2];
      if (!(nn > 0)) return pf_deck_error(d, pf_node_get(c, "normal"), "normal", "must not be zero");
      PF_CALL(pf_deck_positive(d, c, "radius", &pc->radius)); /* (a crack that cuts no bond would pass without a word) */
    } else {
      return pf_deck_error(d, pf_node_get(c, "shape"), "shape",
                           "unknown pre-crack shape '%s' (known: rectangle, disk)", shape);
    }
  }
  return 0;
}

/* Material name -> its mapping under materials:, model, and elastic constants. */
static int read_material(const pf_deck *d, const pf_node *body, const pf_node *materials,
                         pf_pd_body *b, const pf_node **mat) {
  const char *mname = NULL, *model = NULL;
  PF_CALL(pf_deck_string(d, body, "material", &mname));
  snprintf(b->material, sizeof b->material, "%s", mname);
  *mat = pf_node_get(materials, mname);
  if (!*mat)
    return pf_deck_error(d, pf_node_get(body, "material"), "material",
                         "no material named '%s' under materials:", mname);
  PF_CALL(pf_deck_string(d, *mat, "model", &model));
  if (pf_material_known(model)) b->ops = &pf_pd_material_correspondence; /* K, G from it */
  else PF_CALL(find_material(d, *mat, model, &b->ops));
  PF_CALL(pf_deck_real(d, *mat, "density", &b->density));
  PF_CALL(pf_deck_real(d, *mat, "bulk_modulus", &b->bulk_modulus));
  PF_CALL(pf_deck_real(d, *mat, "shear_modulus", &b->shear_modulus));
  const char *keys[] = {"density", "bulk_modulus", "shear_modulus"};
  const double vals[] = {b->density, b->bulk_modulus, b->shear_modulus};
  for (int k = 0; k < 3; k++)
    if (pf_node_get(*mat, keys[k]) && !(vals[k] > 0))
      return pf_deck_error(d, pf_node_get(*mat, keys[k]), keys[k], "must be positive (got %g)", vals[k]);
  return 0;
}

static int read_influence(const pf_deck *d, const pf_node *body, pf_pd_body *b) {
  const char *name = "constant";
  PF_CALL(pf_deck_string(d, body, "influence", &name));
  if (pf_pd_influence_by_name(name, &b->influence.kind))
    return pf_deck_error(d, pf_node_get(body, "influence"), "influence",
                         "unknown influence function '%s' (known: %s)", name, pf_pd_influence_names());
  b->influence.length = 0.5 * b->horizon; /* (a variable horizon refuses the gaussian) */
  PF_CALL(pf_deck_real(d, body, "influence_length", &b->influence.length));
  if (!(b->influence.length > 0) && (!b->hz_expr || pf_node_get(body, "influence_length")))
    return pf_deck_error(d, pf_node_get(body, "influence_length"), "influence_length", "must be positive");
  return 0;
}

/* The horizon: a positive number, or an expression of position (its largest value over the
 * body's points is known once they are: pf_pd_body_find_bonds). */
static int read_horizon(const pf_deck *d, const pf_node *body, pf_pd_body *b) {
  const pf_node *h = pf_node_get(body, "horizon");
  const char *text = pf_node_text(h);
  char *end = NULL;
  b->horizon = strtod(text, &end);
  if (end != text && *end == '\0') {
    if (!(b->horizon > 0)) return pf_deck_error(d, h, "horizon", "must be positive (got %g)", b->horizon);
    return 0;
  }
  b->horizon = 0; /* until the points are known */
  b->one_sided = 1;
  if (!b->coupled && strstr(text, "d_fe"))
    return pf_deck_error(d, h, "horizon", "d_fe (the distance to the elements) is known only in the "
                         "peridynamic: map of a finite_element body; here give the horizon in x, y, z");
  if (!b->coupled) return pf_expr_create(text, d, h, "horizon", &b->hz_expr);
  const char *vars[] = {"d_fe"}; /* the distance to the nearest node where the elements act */
  b->uses_dfe = strstr(text, "d_fe") != NULL;
  return pf_expr_create_vars(text, d, h, "horizon", vars, 1, &b->hz_expr);
}

/* The default is a form for dynamics: the consistent form when the material has a deformation
 * gradient (correspondence), the standard form otherwise (lps: the gradient of its energy,
 * stable and conservative, with the ghost forces of a varying horizon; the partial stress of
 * auto is a strong form that conserves nothing and grows unstable in long runs,
 * docs/theory/coupling.md §2.4). After the material is read. */
static int read_formulation(const pf_deck *d, const pf_node *body, pf_pd_body *b) {
  const char *names[] = {"auto", "standard", "partial_stress", "corrected", "consistent"};
  const char *name = b->ops->gradient_forms ? "consistent" : "standard";
  PF_CALL(pf_deck_string(d, body, "formulation", &name));
  for (int k = 0; k < 5; k++)
    if (!strcmp(name, names[k])) {
      b->form = (pf_pd_formulation)k;
      return 0;
    }
  return pf_deck_error(d, pf_node_get(body, "formulation"), "formulation",
                       "unknown formulation '%s' (known: auto, standard, partial_stress, corrected, consistent)", name);
}

/* What a variable horizon and the partial-stress form need (docs/theory/coupling.md §1). */
static int check_variable_horizon(const pf_deck *d, const pf_node *body, const pf_pd_body *b) {
  const pf_node *h = pf_node_get(body, "horizon"), *f = pf_node_get(body, "formulation");
  const pf_node *dmg = pf_node_get(body, "damage");
  if ((b->form == PF_PD_CORRECTED || b->form == PF_PD_CONSISTENT) && !b->ops->gradient_forms)
    return pf_deck_error(d, f, "formulation", "the %s form needs a correspondence material (body '%s' has %s)",
                         b->form == PF_PD_CORRECTED ? "corrected" : "consistent", b->name, b->ops->name);
  if ((b->hz_expr || b->form == PF_PD_PARTIAL_STRESS) && !b->ops->partial_stress)
    return pf_deck_error(d, b->hz_expr ? h : f, b->hz_expr ? "horizon" : "formulation",
                         "a variable horizon and the partial-stress form need lps or a correspondence "
                         "material (body '%s' has %s)", b->name, b->ops->name);
  if (b->form == PF_PD_PARTIAL_STRESS && (pf_pd_stretch_limited(b) || pf_pd_energy_limited(b)))
    return pf_deck_error(d, dmg, "damage", "body '%s' is all partial stress (a transition region), which "
                         "carries no damage; use formulation: auto to keep damage where the horizon is "
                         "constant", b->name);
  if (!b->hz_expr) return 0;
  if (b->partial)
    return pf_deck_error(d, pf_node_get(body, "partial_volumes"), "partial_volumes",
                         "not with a variable horizon (each end would need its own fractions)");
  if (b->influence.kind == PF_INFLUENCE_GAUSSIAN)
    return pf_deck_error(d, pf_node_get(body, "influence"), "influence",
                         "the gaussian influence scales with the horizon; with a variable horizon use "
                         "constant or inverse_distance");
  if (pf_pd_energy_limited(b) || (dmg && pf_node_get(dmg, "energy_release_rate")))
    return pf_deck_error(d, dmg, "damage", "the energy-based laws depend on the horizon; with a variable "
                         "horizon give a critical_stretch");
  return 0;
}

/* owner: the body mapping with the name and the material; body: the mapping of the PD keys (the
 * same node, or an FE body's `peridynamic:` map). */
static int body_read(const pf_deck *d, const pf_node *owner, const pf_node *body, const pf_node *materials,
                     pf_pd_body *b) {
  const char *name = "";
  b->deck = d;
  b->node = body;
  PF_CALL(pf_deck_string(d, owner, "name", &name));
  snprintf(b->name, sizeof b->name, "%s", name);
  PF_CALL(read_horizon(d, body, b));
  const pf_node *mat = NULL;
  PF_CALL(read_material(d, owner, materials, b, &mat));
  PF_CALL(read_formulation(d, body, b));
  PF_CALL(read_influence(d, body, b));
  const char *corr_keys[] = {"hourglass", "critical_damage", "bond_loss"};
  for (int k = 0; k < 3; k++)
    if (pf_node_get(body, corr_keys[k]) && !pf_pd_material_reads_key(b->ops, corr_keys[k]))
      return pf_deck_error(d, pf_node_get(body, corr_keys[k]), corr_keys[k],
                           "only for correspondence bodies (a material whose model is one of %s)",
                           pf_material_names());
  PF_CALL(b->ops->create(d, mat, b));
  PF_CALL(pf_deck_bool(d, body, "partial_volumes", &b->partial));
  PF_CALL(read_cracks(d, pf_node_get(body, "precracks"), &b->ncracks, &b->cracks));
  PF_CALL(pf_pd_damage_read(d, pf_node_get(body, "damage"), b));
  PF_CALL(check_variable_horizon(d, body, b));
  return pf_pd_parts_read(d, b->coupled ? owner : body, materials, b); /* (coupled: the FE body's entries) */
}

static int create(const pf_deck *d, const pf_node *owner, const pf_node *map, const pf_node *materials,
                  int coupled, pf_pd_body **out) {
  *out = NULL;
  pf_pd_body *b;
  PF_MALLOC(b, 1);
  b->one_sided = b->coupled = coupled; /* a coupled body's rows also hold each node's element neighbours */
  int ierr = body_read(d, owner, map, materials, b);
  if (ierr) {
    pf_pd_body_destroy(&b);
    return ierr;
  }
  *out = b;
  return 0;
}

int pf_pd_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials,
                      pf_pd_body **out) {
  return create(d, body, body, materials, 0, out);
}

/* delta(x) at a point (coupled: with d_fe, its distance to the nearest node where the elements
 * act, infinite when there is none); a value that is not positive and finite is an input error
 * naming it. */
static int horizon_at(const pf_pd_body *b, const double *x, pf_gid gid, double *h) {
  const double d_fe = b->uses_dfe && b->fe_distance ? b->fe_distance(b->fe_ctx, x) : INFINITY;
  *h = pf_expr_eval_vars(b->hz_expr, x[0], x[1], x[2], 0.0, &d_fe);
  if (*h > 0 && isfinite(*h)) return 0;
  return pf_deck_error(b->deck, pf_node_get(b->node, "horizon"), "horizon",
                       "body '%s': the horizon is %g at point %" PF_GID_FMT " (%g, %g, %g); it must be "
                       "positive", b->name, *h, gid, x[0], x[1], x[2]);
}

static const pf_key coupled_keys[] = {
    {"horizon", PF_KEY_EXPR, 1, NULL, "m",
     "horizon at the nodes: a number or an expression in x, y, z and d_fe (the distance to the nearest node "
     "where the elements act, blending < 1)", NULL},
    {"blending", PF_KEY_EXPR, 1, NULL, "",
     "blending weight beta(x, y, z) in [0, 1]: 1 peridynamics only, 0 elements only", NULL},
    {"overlap", PF_KEY_STRING, 0, "energy", "",
     "energy (the forces of beta W_PD + (1 - beta) W_FE: conserves momentum and energy; with the consistent "
     "formulation free of ghost forces; docs/theory/coupling.md §3.4) | force (f = beta f_PD + (1 - beta) f_FE "
     "at each node: a statics tool, conserves neither)", NULL},
    {"formulation", PF_KEY_STRING, 0, "consistent", "",
     "consistent (for dynamics) | auto | partial_stress | corrected (statics and patch-test tools) | "
     "standard (no correction; docs/theory/coupling.md §2.2)", NULL},
    {"allow_in_dynamics", PF_KEY_BOOL, 0, "false", "",
     "true: run the statics forms auto, partial_stress and corrected in an explicit run that takes steps, "
     "which they do not conserve energy in (refused otherwise; docs/theory/coupling.md §2.2); no effect on "
     "the standard and consistent forms", NULL},
    {"influence", PF_KEY_STRING, 0, "constant", "", "constant | inverse_distance", NULL},
    {"hourglass", PF_KEY_MAP, 0, "type: stiffness, coefficient: 0.05", "", "zero-energy-mode control",
     pf_pd_hourglass_keys},
    {"critical_damage", PF_KEY_REAL, 0, "0.99", "", "a bond fails once either end's damage exceeds it", NULL},
    {"bond_loss", PF_KEY_STRING, 0, "keep_stress", "",
     "keep_stress (a point that loses bonds keeps its elastic state) | jump (its stress follows the "
     "new Fbar at once, as Tupek et al. 2013)", NULL},
    {"damage", PF_KEY_MAP, 0, "law: none", "", "bond failure law (acts where beta = 1 only)", pf_pd_damage_key_rows},
    {"precracks", PF_KEY_LIST, 0, NULL, "", "planar cracks", crack_keys},
    PF_KEY_END};

const pf_key *pf_pd_coupled_key_table(void) {
  pf_pd_damage_key_table();
  return coupled_keys;
}

int pf_pd_body_create_coupled(const pf_deck *d, const pf_node *owner, const pf_node *map,
                              const pf_node *materials, pf_pd_body **out) {
  return create(d, owner, map, materials, 1, out);
}

void pf_pd_body_set_blending(pf_pd_body *b, const double *beta, int weight_states) {
  b->blend = beta, b->blend_states = weight_states;
}

void pf_pd_body_set_fe_distance(pf_pd_body *b, pf_pd_distance_fn distance, const void *ctx) {
  b->fe_distance = distance, b->fe_ctx = ctx;
}

int pf_pd_body_uses_fe_distance(const pf_pd_body *b) { return b->uses_dfe; }

void pf_pd_body_set_fe_vector(pf_pd_body *b, pf_pd_fe_vector_fn vector, const void *ctx) {
  b->fe_vector = vector, b->fe_vector_ctx = ctx;
}

int pf_pd_body_find_bonds(pf_pd_body *b, const pf_pd_cloud *cloud, const pf_points *pts,
                          pf_int first, pf_int n, pf_bond_rows *rows) {
  if (!b->hz_expr)
    return pf_pd_family_build(cloud, pts, first, n, b->horizon, NULL, b->partial, b->ncracks, b->cracks, rows);
  double *hz;
  PF_MALLOC(hz, cloud->n);
  int ierr = 0;
  b->horizon = 0;
  for (pf_int j = 0; j < cloud->n && !ierr; j++) {
    ierr = horizon_at(b, &cloud->X[3 * j], cloud->gid0 + j, &hz[j]);
    b->horizon = fmax(b->horizon, hz[j]);
  }
  if (!ierr)
    ierr = pf_pd_family_build(cloud, pts, first, n, b->horizon, hz, 0, b->ncracks, b->cracks, rows);
  free(hz);
  return ierr;
}

/* Is point i's own family complete (no free surface within its horizon)? Its first moment
 * sum_j V_j xi vanishes on a symmetric family; a surface point's is a sizeable fraction of
 * sum_j V_j |xi|. (Declared in pd/pd_impl.h.) */
int pf_pd_family_complete(const pf_pd_body *b, const pf_points *pts, pf_int i, double S[3]) {
  const pf_family *fam = &b->fam;
  double m1[3] = {0, 0, 0}, m0 = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    const pf_int j = fam->neighbor[k];
    double xi[3], r02 = 0;
    for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r02 += xi[a] * xi[a];
    const double r0 = sqrt(r02), v = pf_pd_bond_volume(fam, pts->vol, k, j);
    if (!pf_pd_in_family(b, i, r0)) continue;
    for (int a = 0; a < 3; a++) m1[a] += v * xi[a];
    m0 += v * r0;
  }
  if (S) S[0] = m1[0], S[1] = m1[1], S[2] = m1[2];
  return sqrt(m1[0] * m1[0] + m1[1] * m1[1] + m1[2] * m1[2]) <= 0.01 * m0;
}

/* Coupled in the energy form: the partial-stress and corrected forms are written for unweighted
 * force states, so a point whose row reaches beta < 1 takes the standard form, whose force states
 * carry the weights. The consistent form takes the weights into its corrections instead
 * (docs/theory/coupling.md §3.4): a point with beta > 0 whose row reaches another beta (the
 * overlap and its kinks) or another horizon gets corrected gradient weights (bit 8). */
static void standard_in_overlap(const pf_pd_body *b) {
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n && b->blend && b->blend_states; i++) {
    int inside = b->blend[i] == 1, same = 1;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      inside &= b->blend[fam->neighbor[k]] == 1, same &= b->blend[fam->neighbor[k]] == b->blend[i];
    if (inside) continue;
    const int corrected = b->form == PF_PD_CONSISTENT && b->blend[i] > 0 && (!same || ((int)b->region[i] & 8));
    b->region[i] = 2 * (b->blend[i] < 1) + 8 * corrected;
  }
}

/* Each point's horizon (ghosts too) and its force form: with auto, partial stress where its row
 * reaches a point of another horizon and its own family is complete; standard at free surfaces,
 * where the strong form has no traction-free condition and is unstable (docs/theory/coupling.md
 * §2.4). */
static int set_regions(pf_pd_body *b, pf_points *pts) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "horizon", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT | PF_FIELD_CONSTANT, &idx));
  b->hz = pts->fields[idx].data;
  PF_CALL(pf_points_field_register(pts, "region", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT | PF_FIELD_CONSTANT, &idx));
  b->region = pts->fields[idx].data;
  double hmax = b->horizon;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    if (b->hz_expr) PF_CALL(horizon_at(b, &pts->X[3 * i], pts->gid[i], &b->hz[i]));
    else b->hz[i] = b->horizon;
    hmax = fmax(hmax, b->hz[i]);
  }
  b->horizon = pf_max_all(hmax); /* (after a restart the clouds were not searched) */
  PF_CALL(pf_points_exchange(pts, b->hz, 1));
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    int varies = 0, ps = b->form == PF_PD_PARTIAL_STRESS;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      varies |= b->hz[fam->neighbor[k]] != b->hz[i];
    ps |= b->form == PF_PD_AUTO && varies && pf_pd_family_complete(b, pts, i, NULL);
    b->region[i] = ps + 2 * (b->blend && b->blend[i] < 1) + 4 * (b->form == PF_PD_CORRECTED && varies) +
                   8 * (b->form == PF_PD_CONSISTENT && varies);
  }
  standard_in_overlap(b);
  free(b->idle);
  b->idle = NULL;
  if (b->blend) {
    PF_MALLOC(b->idle, b->n + 1);
    for (pf_int i = b->first; i < b->first + b->n; i++) {
      int idle = b->blend[i] == 0;
      for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1] && idle; k++)
        idle = b->blend[fam->neighbor[k]] == 0;
      b->idle[i - b->first] = (uint8_t)idle;
    }
  }
  return pf_points_exchange(pts, b->region, 1);
}

/* Masses that came with the points (a re-partition, a checkpoint) are density x volume, as the
 * fresh set-up made them, bit for bit. Collective. */
static int check_masses(const pf_pd_body *b, const pf_points *pts, pf_int first, pf_int n) {
  char msg[400] = "";
  int ok = 1;
  for (pf_int i = first; i < first + n && ok; i++)
    if (pts->m[i] != pf_pd_density(b, i) * pts->vol[i]) {
      ok = 0;
      snprintf(msg, sizeof msg, "body '%s': point %" PF_GID_FMT " carries mass %.17g kg, not density x volume = "
               "%.17g kg: the checkpoint it came from is damaged", b->name, pts->gid[i], pts->m[i],
               pf_pd_density(b, i) * pts->vol[i]);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

static int family_shortfalls(pf_pd_body *b, pf_points *pts);

int pf_pd_body_attach(pf_pd_body *b, pf_points *pts, pf_int first, pf_int n,
                      const pf_bond_rows *rows, const pf_int *local, int fresh) {
  b->first = first;
  b->n = n;
  PF_CALL(pf_pd_family_from_rows(rows, local, first, n, b->partial, &b->fam));
  if (pf_sum_all((double)pf_pd_family_nbonds(&b->fam)) == 0 && pf_sum_all(n) > 1)
    return pf_deck_error(b->deck, pf_node_get(b->node, "horizon"), "horizon",
                         "no point of body '%s' has a neighbour within the horizon %g m; the "
                         "horizon must exceed the point spacing (typically 3 spacings)", b->name, b->horizon);
  free(b->smin);
  PF_MALLOC(b->smin, n);
  free(b->lost);
  PF_MALLOC(b->lost, n);
  PF_CALL(set_regions(b, pts));
  PF_CALL(pf_pd_parts_attach(b, pts, fresh));
  if (fresh) { /* (after a re-partition or a restart the masses came with the points) */
    for (pf_int i = first; i < first + n; i++) pts->m[i] = pf_pd_density(b, i) * pts->vol[i];
    PF_CALL(pf_points_exchange(pts, pts->m, 1));
  } else {
    PF_CALL(check_masses(b, pts, first, n));
  }
  PF_CALL(pf_pd_damage_setup(b, pts, fresh));
  b->fresh = fresh;
  if (b->ops->setup) PF_CALL(b->ops->setup(b, pts));
  if (b->ops->family_stiffness) PF_CALL(family_shortfalls(b, pts));
  int idx;
  PF_CALL(pf_points_field_register(pts, "damage", 1, PF_FIELD_OUTPUT, &idx));
  return 0;
}

int pf_pd_body_bond_rows(const pf_pd_body *b, const pf_points *pts, pf_bond_rows *rows) {
  return pf_pd_family_to_rows(&b->fam, pts, rows);
}

int pf_pd_body_bond_fields(const pf_pd_body *b, pf_bond_rows *rows) {
  return pf_pd_family_register_fields(rows, b->partial, b->fam.nstate);
}

int pf_pd_body_destroy(pf_pd_body **b) {
  if (!*b) return 0;
  if ((*b)->ops && (*b)->ops->destroy && (*b)->mat) (*b)->ops->destroy(*b);
  pf_pd_body_freeze_damage(*b, NULL, 0); /* (the law's limits back, to be freed) */
  free((*b)->frozen.none_s0);
  pf_pd_family_free(&(*b)->fam);
  free((*b)->smin);
  free((*b)->lost);
  free((*b)->idle);
  free((*b)->cracks);
  free((*b)->damage_data);
  free((*b)->soft_lost);
  free((*b)->wc_bond);
  pf_pd_parts_free(*b);
  free((*b)->history.committed);
  pf_pd_body_failures_free(*b);
  pf_expr_destroy(&(*b)->hz_expr);
  PF_FREE(*b);
  return 0;
}

int pf_pd_family_free(pf_family *fam) {
  PF_FREE(fam->offset);
  PF_FREE(fam->neighbor);
  PF_FREE(fam->broken);
  PF_FREE(fam->vfrac);
  PF_FREE(fam->rest);
  PF_FREE(fam->recorded);
  PF_FREE(fam->state);
  return 0;
}

int64_t pf_pd_family_nbonds(const pf_family *fam) { return fam->offset ? fam->offset[fam->n] : 0; }
double pf_pd_body_density(const pf_pd_body *b) { return b->density; }
double pf_pd_body_horizon(const pf_pd_body *b) { return b->horizon; }
double pf_pd_body_point_horizon(const pf_pd_body *b, pf_int i) { return b->hz[i]; }
double pf_pd_body_bulk_modulus(const pf_pd_body *b) { return b->bulk_modulus; }
const pf_family *pf_pd_body_family(const pf_pd_body *b) { return &b->fam; }
int64_t pf_pd_body_nbonds(const pf_pd_body *b) { return pf_pd_family_nbonds(&b->fam); }

double pf_pd_body_point_sum(const pf_pd_body *b, const pf_points *pts, pf_pd_point_term term) {
  double *v = malloc(sizeof *v * (size_t)(b->n > 0 ? b->n : 1));
  if (!v) return NAN; /* (out of memory: shows in the balance) */
#pragma omp parallel for schedule(static)
  for (pf_int k = 0; k < b->n; k++) v[k] = term(b, pts, b->first + k);
  double sum = 0;
  for (pf_int k = 0; k < b->n; k++) sum += v[k];
  free(v);
  return sum;
}

double pf_pd_body_bond_rate(const pf_pd_body *b) { return b->ops->bond_rate > 0 ? b->ops->bond_rate : 1.5e8; }

double pf_pd_body_bytes_per_bond(const pf_pd_body *b) {
  const pf_family *f = &b->fam;
  return (double)(sizeof *f->neighbor + sizeof *f->broken + (f->vfrac ? sizeof *f->vfrac : 0) +
                  (f->rest ? sizeof *f->rest : 0) + (size_t)f->nstate * sizeof *f->state +
                  (b->wc_bond ? sizeof *b->wc_bond : 0));
}

int pf_pd_body_force(pf_pd_body *b, pf_points *pts, double dt) {
  b->dt = dt;
  return b->ops->force(b, pts);
}

int pf_pd_body_uses_velocity(const pf_pd_body *b) { return b->ops->uses_velocity; }

double pf_pd_body_energy(const pf_pd_body *b, const pf_points *pts) { return b->ops->energy(b, pts); }

double pf_pd_body_take_damage_work(pf_pd_body *b) {
  double w = b->damage_work;
  b->damage_work = 0;
  return w;
}

/* The row (owned point, from 0) that holds bond k: the last li with offset[li] <= k. */
static pf_int row_of_bond(const int64_t *offset, pf_int n, int64_t k) {
  pf_int lo = 0, hi = n; /* offset[lo] <= k < offset[hi] */
  while (hi - lo > 1) {
    pf_int mid = lo + (hi - lo) / 2;
    if (offset[mid] <= k) lo = mid;
    else hi = mid;
  }
  return lo;
}

/* Bit l of the result: byte l of the 8 bytes at p is not zero (bytes in memory order). The
 * bytes' bits are folded into bit 0 of each byte, which one multiplication gathers into the top
 * byte. */
static inline unsigned nonzero_bytes(const uint8_t *p) {
  uint64_t t;
  memcpy(&t, p, sizeof t);
  t |= t >> 4, t |= t >> 2, t |= t >> 1;
  return (unsigned)(((t & 0x0101010101010101ull) * 0x0102040810204080ull) >> 56);
}

/* The broken bonds among bonds [64 w, 64 w + 64) of nb, as bits. */
static uint64_t broken_bits(const uint8_t *broken, int64_t w, int64_t nb) {
  uint64_t m = 0;
  if (64 * w + 64 <= nb) {
    for (int q = 0; q < 8; q++) m |= (uint64_t)nonzero_bytes(&broken[64 * w + 8 * q]) << (8 * q);
  } else {
    for (int64_t k = 64 * w; k < nb; k++) m |= (uint64_t)(broken[k] != 0) << (k - 64 * w);
  }
  return m;
}

/* Bond k of owned point i takes its current length as its rest length, never above it (no force
 * at the break), and above 0 (0 means not recorded). */
static void record_rest(const pf_family *fam, const pf_points *pts, pf_int i, int64_t k) {
  const double *yi = &pts->y[3 * i], *yj = &pts->y[3 * fam->neighbor[k]];
  const double d0 = yj[0] - yi[0], d1 = yj[1] - yi[1], d2 = yj[2] - yi[2], r = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
  float rest = (float)r;
  if ((double)rest > r) rest = nextafterf(rest, 0.0f);
  fam->rest[k] = fmaxf(rest, FLT_MIN);
}

void pf_pd_body_rest_at_break(const pf_pd_body *b, const pf_points *pts, pf_int i, int64_t k) {
  const pf_family *fam = &b->fam;
  const uint64_t bit = 1ull << (k % 64);
  if (!b->rest_at_break || (__atomic_load_n(&fam->recorded[k / 64], __ATOMIC_RELAXED) & bit)) return;
  __atomic_fetch_or(&fam->recorded[k / 64], bit, __ATOMIC_RELAXED); /* (a word spans rows of two threads) */
  record_rest(fam, pts, i, k);
}

/* Each bond that broke since the last call takes its current length as its rest length. Called
 * every step when the body is in self-contact, so the scan reads only the broken flags, 64 at
 * a time, against the bits of the bonds already recorded (fam->recorded): in the fragmenting
 * cylinder, where most blocks of bonds hold a broken one, reading the rest lengths of every
 * such block to find the new ones cost 17 % of the run. PMB, LPS and elastic-plastic record
 * their failed bonds as they release them (pf_pd_body_rest_at_break): their scan runs at the
 * first call only (bonds broken before the body was in self-contact, or in a checkpoint). */
void pf_pd_body_record_breaks(pf_pd_body *b, const pf_points *pts) {
  pf_family *fam = &b->fam;
  const int64_t nbonds = fam->offset[b->n], nwords = (nbonds + 63) / 64;
  if (b->rest_at_break && b->ops->records_rest) return; /* (its releases recorded every break since) */
  b->rest_at_break = 1; /* (from the next pass on; what it did not record, the scan finds) */
#pragma omp parallel for schedule(static)
  for (int64_t w = 0; w < nwords; w++) {
    uint64_t todo = broken_bits(fam->broken, w, nbonds) & ~fam->recorded[w];
    if (!todo) continue;
    fam->recorded[w] |= todo;
    pf_int li = row_of_bond(fam->offset, b->n, 64 * w + __builtin_ctzll(todo));
    for (; todo; todo &= todo - 1) {
      const int64_t k = 64 * w + __builtin_ctzll(todo);
      while (fam->offset[li + 1] <= k) li++; /* (the word's rows, in order) */
      record_rest(fam, pts, b->first + li, k);
    }
  }
}

/* Threaded: a point writes only its own damage, and the count of broken bonds is an integer sum. */
int64_t pf_pd_body_damage(const pf_pd_body *b, pf_points *pts) {
  double *phi = pf_points_field_get(pts, "damage");
  const pf_family *fam = &b->fam;
  int64_t nbroken = 0;
#pragma omp parallel for reduction(+ : nbroken) schedule(static)
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double all = 0, intact = 0;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (b->one_sided) { /* own-family bonds only */
        double r2 = 0;
        for (int a = 0; a < 3; a++) r2 += pow(pts->X[3 * fam->neighbor[k] + a] - pts->X[3 * i + a], 2);
        if (!pf_pd_in_family(b, i, sqrt(r2))) continue;
      }
      double v = pf_pd_bond_volume(fam, pts->vol, k, fam->neighbor[k]);
      all += v;
      intact += fam->broken[k] ? 0 : v;
      nbroken += fam->broken[k];
    }
    phi[i] = all > 0 ? 1.0 - intact / all : 0.0;
  }
  return nbroken;
}

int pf_pd_weighted_volumes(const pf_pd_body *b, pf_points *pts, double *m) {
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double s = 0;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      pf_int j = fam->neighbor[k];
      double r2 = 0;
      for (int a = 0; a < 3; a++) r2 += pow(pts->X[3 * j + a] - pts->X[3 * i + a], 2);
      if (!pf_pd_in_family(b, i, sqrt(r2))) continue;
      s += pf_pd_omega(&b->influence, sqrt(r2)) * r2 * pf_pd_bond_volume(fam, pts->vol, k, j);
    }
    PF_CHECK(s > 0, PF_ERR_INPUT,
             "body '%s': point %" PF_GID_FMT " at (%g, %g, %g) has no neighbour within the horizon %g m",
             b->name, pts->gid[i], pts->X[3 * i], pts->X[3 * i + 1], pts->X[3 * i + 2], b->horizon);
    m[i] = s;
  }
  return pf_points_exchange(pts, m, 1); /* the ghosts' m for the force pass */
}

/* The bound's slack: a face halves a family and doubles its LPS bonds' stiffness, and the
 * quasi-static masses of the bound below relax such points at the default safety factor in every
 * shipped deck; the shortfall counts beyond that factor 2, in those masses and in the explicit
 * step (docs/theory/quasi_static.md §2, pd.md §4). */
#define PF_PD_BOUND_SLACK 2.0

/* sum_j V_j c_ij omega / |xi| over point i's family, c_ij = c (times the parts' micromodulus
 * scale), and times max(1, (g_i + g_j) / (2 slack)) when g (the family shortfalls) is given. */
static double stiffness_row(const pf_pd_body *b, const pf_points *pts, pf_int i, double c, const double *g) {
  const pf_family *fam = &b->fam;
  double sum = 0;
  for (int64_t k = fam->offset[i - fam->first]; k < fam->offset[i - fam->first + 1]; k++) {
    pf_int j = fam->neighbor[k];
    double r2 = 0;
    for (int a = 0; a < 3; a++) r2 += pow(pts->X[3 * j + a] - pts->X[3 * i + a], 2);
    double r0 = sqrt(r2);
    if (!pf_pd_in_family(b, i, r0)) continue;
    const double cb = b->part ? c * fmax(pf_pd_part_at(b, i)->mscale, pf_pd_part_at(b, j)->mscale) : c;
    const double term = pf_pd_bond_volume(fam, pts->vol, k, j) * cb * pf_pd_omega(&b->influence, r0) / r0;
    sum += g ? term * fmax(1.0, 0.5 * (g[i] + g[j]) / PF_PD_BOUND_SLACK) : term;
  }
  return sum;
}

double pf_pd_stable_dt_point(const pf_pd_body *b, const pf_points *pts, pf_int i, double c) {
  const double sum = stiffness_row(b, pts, i, c, b->shortfall);
  return sum > 0 ? sqrt(2.0 * pf_pd_density(b, i) / sum) : INFINITY;
}

int pf_pd_body_step_varies(const pf_pd_body *b) { return b->ops->stable_dt != NULL; }

double pf_pd_body_stable_dt(const pf_pd_body *b, const pf_points *pts) {
  if (b->ops->stable_dt) return b->ops->stable_dt(b, pts);
  double dt = INFINITY, h = NAN, c = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    if (b->hz[i] != h) { /* the micromodulus of this point's horizon */
      h = b->hz[i];
      c = b->ops->micromodulus ? b->ops->micromodulus(b, h)
                               : pf_pd_pmb_micromodulus(b->bulk_modulus, &b->influence, h);
    }
    dt = fmin(dt, pf_pd_stable_dt_point(b, pts, i, c));
  }
  return dt;
}

/* The smallest own step of point i's family, itself included (a row of the stiffness couples i to
 * its neighbours' states: the stiffest of them bounds it). */
static double family_step(const pf_pd_body *b, const double *step, pf_int i) {
  double dt = step[i];
  for (int64_t k = b->fam.offset[i - b->first]; k < b->fam.offset[i - b->first + 1]; k++)
    dt = fmin(dt, step[b->fam.neighbor[k]]);
  return dt;
}

int pf_pd_body_stiffness_bounds(pf_pd_body *b, pf_points *pts, pf_int first, pf_int n, double *k) {
  double *step = b->ops->point_steps ? b->ops->point_steps(b) : NULL;
  if (step) PF_CALL(pf_points_exchange(pts, step, 1)); /* (the ghosts': their last evaluation's) */
  for (pf_int i = first; i < first + n; i++) {
    const double h = b->hz[i];
    const double c = b->ops->micromodulus ? b->ops->micromodulus(b, h) : pf_pd_pmb_micromodulus(b->bulk_modulus, &b->influence, h);
    const double sum = stiffness_row(b, pts, i, c, b->shortfall);
    const double own = step ? family_step(b, step, i) : INFINITY;
    const double dt = sum > 0 ? fmin(sqrt(2.0 * pf_pd_density(b, i) / sum), own) : INFINITY;
    k[i - first] = isfinite(dt) ? 4 * pts->m[i] / (dt * dt) : 0;
  }
  return 0;
}

/* m_whole(delta) = int_0^delta omega(r) r^2 4 pi r^2 dr, the weighted volume of a whole
 * spherical family (midpoint rule, 256 intervals: only ratios at equal horizons matter). */
static double whole_family_volume(const pf_pd_body *b, double delta) {
  const int n = 256;
  double s = 0;
  for (int k = 0; k < n; k++) {
    const double r = (k + 0.5) * delta / n;
    s += pf_pd_omega(&b->influence, r) * r * r * r * r;
  }
  return 4 * PF_PI * s * delta / n;
}

/* A whole family of a cubic lattice holds 0.92-1.13 of the continuum's weighted volume at 2 to 6
 * spacings (omega = 1 and 1/r): the share that stands for a whole family in a body that has none. */
#define PF_PD_WHOLE_SHARE 0.9

/* The family shortfalls g_i of a family_stiffness material (docs/theory/quasi_static.md §2):
 * rho_i = m_i / m_whole(delta_i) the point's share of a whole family's weighted volume, g_i =
 * rho_top / rho_i with rho_top the largest over the body (every rank) or PF_PD_WHOLE_SHARE if
 * larger. Ghosts too. Collective. */
static int family_shortfalls(pf_pd_body *b, pf_points *pts) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "family_shortfall", 1, PF_FIELD_GHOST, &idx));
  double *g = b->shortfall = pts->fields[idx].data, top = 0;
  PF_CALL(pf_pd_weighted_volumes(b, pts, g));
  for (pf_int i = b->first; i < b->first + b->n; i++) top = fmax(top, g[i] /= whole_family_volume(b, b->hz[i]));
  top = fmax(pf_max_all(top), PF_PD_WHOLE_SHARE);
  for (pf_int i = b->first; i < b->first + b->n; i++) g[i] = top / g[i];
  return pf_points_exchange(pts, g, 1);
}

int pf_pd_lost_volume_fields(pf_pd_body *b, pf_points *pts, double **mom) {
  int il, im;
  PF_CALL(pf_points_field_register(pts, "lost_weighted_volume", 1, PF_FIELD_RESTART, &il));
  PF_CALL(pf_points_field_register(pts, "dilatation_moment", 1, PF_FIELD_GHOST, &im));
  b->lost_volume = pts->fields[il].data, *mom = pts->fields[im].data;
  return 0;
}
