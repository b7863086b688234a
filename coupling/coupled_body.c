/* An FE body coupled to peridynamics by blending on its own nodes (docs/theory/coupling.md §3):
 * the nodes are also the points of a peridynamic operator (correspondence, the body's own
 * material; variable horizon and the transition forms of pd/), with beta(x) in [0, 1] from the
 * deck. With material_regions each element has its entry's material and each node, a point of
 * the operator, the latest entry's among its elements (mass rho V, constants and model its own:
 * docs/theory/interfaces.md §8). Elements whose eight nodes all have beta = 1 are not evaluated (the PD region, where
 * bonds may break). Two forms (the key `overlap`):
 * - force, a statics and patch-test tool (Seleson, Beneddine & Prudhomme 2013, force-based blending; D'Elia et al. 2021, §4):
 *     f_i = beta_i f_i^PD + (1 - beta_i) f_i^FE.
 *   Both operators give zero force under a linear displacement and the exact div sigma under a
 *   quadratic one at interior nodes, so the blend does too; it conserves neither momentum nor
 *   energy where beta varies.
 * - energy, the default: the forces of E = sum_i beta_i W_i V_i + sum_e (1 - beta_e) W_e V_e
 *   (beta_e the mean of element e's nodes), the energy the run books in both forms: each PD
 *   point's force state and each element's forces carry their weight (§3.4). Momentum and energy
 *   are conserved by construction; under a uniform stress and a linear beta the two operators'
 *   ghost forces, +sigma grad beta V_i from PD and -sigma grad beta V_i from the elements,
 *   cancel, and where they do not (beta's kinks) the consistent form (the default formulation)
 *   corrects the PD points' gradient weights once at set-up, taking the elements' part of the
 *   uniform-stress vector (fe_vector) into its targets. */
#include "coupling/coupling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct pf_coupled_body {
  char name[64];
  const pf_deck *deck;
  pf_fem_body *fe;       /* the elements */
  pf_pd_body *pd;        /* the PD operator over the same nodes */
  pf_expr *beta_expr;    /* blending weight beta(x) */
  pf_nearest *fe_region; /* the nodes where the elements act (beta < 1), for the horizon's d_fe */
  double rho;            /* the material's density, kg/m^3 */
  uint8_t *node_part;    /* [mesh nodes] material_regions: each node's part (the latest entry among
                            its elements, 0 the body's material), or NULL with one material */
  pf_int first, n;       /* owned nodes [first, first + n) of the store */
  double *beta;          /* field "blending_weight" [store] */
  double *fsave;         /* [3n] scratch of the blended force */
  int energy_form;       /* overlap: energy */
};

static double fe_distance(const void *region, const double x[3]) {
  return region ? pf_nearest_distance(region, x) : INFINITY;
}

/* The elements' part of the consistent form's targets at owned store node i (energy form). */
static void fe_vector(const void *ctx, pf_int i, double out[3]) {
  const pf_coupled_body *c = ctx;
  pf_fem_body_node_blend_vector(c->fe, i - c->first, c->beta[i], out);
}

static double beta_at(const void *ctx, const double x[3]) {
  const pf_coupled_body *c = ctx;
  return pf_expr_eval(c->beta_expr, x[0], x[1], x[2], 0.0);
}

/* The FE keys with `peridynamic:` where the FE body's table had it, before `erosion`. */
const pf_key *pf_coupled_body_keys(void) {
  static pf_key keys[40];
  if (keys[0].name) return keys;
  int n = 0;
  for (const pf_key *k = pf_fem_body_keys; k->name && n < 38; k++) {
    if (!strcmp(k->name, "erosion"))
      keys[n++] = (pf_key){"peridynamic", PF_KEY_MAP, 0, NULL, "",
                           "couple a peridynamic operator on the nodes by force blending (docs/theory/coupling.md §3)",
                           pf_pd_coupled_keys};
    keys[n++] = *k;
  }
  return keys;
}

int pf_coupled_body_requested(const pf_node *body) { return pf_node_get(body, "peridynamic") != NULL; }

/* Several materials: each node, a PD point, takes the material of the latest material_regions entry
 * among its elements (docs/theory/interfaces.md §8), which the PD operator's part q (the q-th
 * entry's) carries. */
static int node_parts(pf_coupled_body *c) {
  const pf_mesh *mesh = pf_fem_body_mesh(c->fe);
  PF_MALLOC(c->node_part, mesh->nnodes + 1);
  if (pf_fem_body_node_entries(c->fe, c->node_part)) return pf_pd_body_set_node_parts(c->pd, c->node_part, mesh->nnodes);
  PF_FREE(c->node_part);
  return 0;
}

/* The `peridynamic:` map: the PD operator, beta (checked at every mesh node), d_fe. */
static int read_coupling(pf_coupled_body *c, const pf_node *body, const pf_node *materials) {
  const pf_node *map = pf_node_get(body, "peridynamic");
  const pf_mesh *mesh = pf_fem_body_mesh(c->fe);
  PF_CALL(pf_pd_body_create_coupled(c->deck, body, map, materials, &c->pd));
  const pf_node *bn = pf_node_get(map, "blending");
  PF_CALL(pf_expr_create(pf_node_text(bn), c->deck, bn, "blending", &c->beta_expr));
  int pd_region = 0;
  pf_int nfe = 0;
  double *fe;
  PF_MALLOC(fe, 3 * (size_t)mesh->nnodes + 1);
  for (pf_int k = 0; k < mesh->nnodes; k++) { /* every rank checks the whole mesh alike */
    const double *x = &mesh->X[3 * (size_t)k], w = beta_at(c, x);
    if (!(w >= 0 && w <= 1)) {
      free(fe);
      return pf_deck_error(c->deck, bn, "blending", "body '%s': beta is %g at node %" PF_INT_FMT
                           " (%g, %g, %g); it must lie in [0, 1]", c->name, w, k + 1, x[0], x[1], x[2]);
    }
    pd_region |= w == 1;
    if (w < 1) memcpy(&fe[3 * (size_t)nfe++], x, 3 * sizeof(double));
  }
  int ierr = nfe > 0 && pf_pd_body_uses_fe_distance(c->pd) ? pf_nearest_create(fe, nfe, &c->fe_region) : 0;
  free(fe);
  PF_CALL(ierr);
  pf_pd_body_set_fe_distance(c->pd, fe_distance, c->fe_region); /* the horizon's d_fe */
  PF_CALL(node_parts(c));
  const pf_node *dmg = pf_node_get(map, "damage");
  const char *law = "none";
  PF_CALL(pf_deck_string(c->deck, dmg, "law", &law));
  if (strcmp(law, "none") && !pd_region)
    return pf_deck_error(c->deck, dmg, "damage", "body '%s' has no node with blending weight 1: damage acts only "
                         "in the peridynamic region, never in the transition, overlap or elements", c->name);
  pf_fem_body_set_blending(c->fe, beta_at, c);
  const char *form = "energy";
  PF_CALL(pf_deck_string(c->deck, map, "overlap", &form));
  if (strcmp(form, "force") && strcmp(form, "energy"))
    return pf_deck_error(c->deck, pf_node_get(map, "overlap"), "overlap",
                         "body '%s': unknown overlap form '%s' (known: force, energy)", c->name, form);
  c->energy_form = !strcmp(form, "energy");
  return 0;
}

int pf_coupled_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials, pf_coupled_body **out) {
  *out = NULL;
  pf_coupled_body *c;
  PF_MALLOC(c, 1);
  const char *name = "";
  int ierr = pf_deck_string(d, body, "name", &name);
  snprintf(c->name, sizeof c->name, "%s", name);
  c->deck = d;
  if (!ierr) ierr = pf_fem_body_create(d, body, materials, &c->fe);
  if (!ierr) c->rho = pf_material_density(pf_fem_body_material(c->fe));
  if (!ierr) ierr = read_coupling(c, body, materials);
  if (ierr) {
    pf_coupled_body_destroy(&c);
    return ierr;
  }
  *out = c;
  return 0;
}

int pf_coupled_body_destroy(pf_coupled_body **pc) {
  pf_coupled_body *c = *pc;
  if (!c) return 0;
  pf_fem_body_destroy(&c->fe);
  pf_pd_body_destroy(&c->pd);
  pf_expr_destroy(&c->beta_expr);
  pf_nearest_destroy(&c->fe_region);
  free(c->fsave), free(c->node_part);
  PF_FREE(*pc);
  return 0;
}

pf_fem_body *pf_coupled_body_fem(const pf_coupled_body *c) { return c->fe; }
pf_pd_body *pf_coupled_body_pd(const pf_coupled_body *c) { return c->pd; }

/* Sorted union of the ascending gid list of row r of pd and the list e into out; from[k] is the
 * bond of pd whose fields bond k takes (-1: an element neighbour only, intact). */
static pf_int merge(const pf_bond_rows *pd, pf_int r, const pf_gid *e, pf_int ne, pf_gid *out, int64_t *from) {
  const int64_t o = pd->offset[r];
  const pf_int na = (pf_int)(pd->offset[r + 1] - o);
  const pf_gid *a = &pd->gid[o];
  pf_int i = 0, j = 0, n = 0;
  while (i < na || j < ne) {
    const int from_pd = j >= ne || (i < na && a[i] <= e[j]);
    if (from_pd && j < ne && a[i] == e[j]) j++;
    from[n] = from_pd ? o + i : -1;
    out[n++] = from_pd ? a[i++] : e[j++];
  }
  return n;
}

static int merged_rows(const pf_bond_rows *pd, const pf_bond_rows *elem, pf_bond_rows *rows) {
  int ierr = pf_bond_rows_fields_copy(rows, pd);
  for (pf_int r = 0; r < pd->n && !ierr; r++) {
    const int64_t oe = elem->offset[r];
    const pf_int na = (pf_int)(pd->offset[r + 1] - pd->offset[r]), ne = (pf_int)(elem->offset[r + 1] - oe);
    pf_gid *g = malloc(sizeof(pf_gid) * ((size_t)(na + ne) + 1));
    int64_t *from = malloc(sizeof(int64_t) * ((size_t)(na + ne) + 1));
    if (!g || !from) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    else ierr = pf_bond_rows_append_from(rows, merge(pd, r, &elem->gid[oe], ne, g, from), g, pd, from);
    free(g), free(from);
  }
  return ierr;
}

int pf_coupled_body_rows(const pf_coupled_body *c, const pf_points *pts, pf_int first, pf_int n, pf_gid gid0,
                         pf_bond_rows *rows) {
  pf_bond_rows pd, el;
  PF_CALL(pf_bond_rows_init(&pd));
  PF_CALL(pf_bond_rows_init(&el));
  int ierr = pf_fem_body_node_rows(c->fe, pts, first, n, gid0, &el);
  if (!ierr && pf_pd_body_family(c->pd)->offset) ierr = pf_pd_body_bond_rows(c->pd, pts, &pd);
  else if (!ierr) {
    const pf_mesh *mesh = pf_fem_body_mesh(c->fe);
    const double *volume = pf_fem_body_node_volumes(c->fe);
    double *cell = malloc(sizeof(double) * ((size_t)mesh->nnodes + 1));
    if (!cell) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    for (pf_int k = 0; !ierr && k < mesh->nnodes; k++) cell[k] = cbrt(volume[k]);
    pf_pd_cloud cloud = {mesh->X, cell, mesh->nnodes, gid0};
    if (!ierr) ierr = pf_pd_body_find_bonds(c->pd, &cloud, pts, first, n, &pd);
    free(cell);
  }
  if (!ierr) ierr = merged_rows(&pd, &el, rows);
  pf_bond_rows_free(&pd), pf_bond_rows_free(&el);
  return ierr;
}

/* The blending field and the masses: every node carries rho V (the PD operator's mass; several
 * materials: its part's rho). */
static int attach_blending(pf_coupled_body *c, pf_points *pts, pf_gid gid0) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "blending_weight", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT | PF_FIELD_CONSTANT, &idx));
  c->beta = pts->fields[idx].data;
  for (pf_int i = c->first; i < c->first + c->n; i++) c->beta[i] = beta_at(c, &pts->X[3 * (size_t)i]);
  PF_CALL(pf_points_exchange(pts, c->beta, 1));
  pf_pd_body_set_blending(c->pd, c->beta, c->energy_form);
  PF_CALL(pf_fem_body_set_blending_field(c->fe, c->beta));
  pf_pd_body_set_fe_vector(c->pd, fe_vector, c);
  for (pf_int i = c->first; i < c->first + c->n; i++) { /* all nodes */
    const double rho = c->node_part ? pf_pd_body_part_density(c->pd, c->node_part[pts->gid[i] - gid0]) : c->rho;
    pts->m[i] = rho * pts->vol[i];
  }
  free(c->fsave);
  PF_MALLOC(c->fsave, 3 * (size_t)c->n + 1);
  return 0;
}

int pf_coupled_body_attach(pf_coupled_body *c, int body, pf_points *pts, pf_int first, pf_int n, pf_gid gid0,
                           const pf_bond_rows *rows, const pf_int *local, int fresh) {
  c->first = first, c->n = n;
  PF_CALL(pf_fem_body_attach(c->fe, body, pts, first, n, gid0));
  PF_CALL(attach_blending(c, pts, gid0));
  PF_CALL(pf_pd_body_attach(c->pd, pts, first, n, rows, local, fresh));
  pf_fem_body_set_stable_dt(c->fe, fmin(pf_fem_body_stable_dt(c->fe), pf_pd_body_stable_dt(c->pd, pts)));
  return 0;
}

/* The energy form: the PD operator weights its force states itself, the elements' shares carry
 * their weights. */
static int energy_form_force(pf_coupled_body *c, pf_points *pts, double dt, double t, long step) {
  PF_CALL(pf_pd_body_force(c->pd, pts, dt));
  PF_CALL(pf_fem_body_evaluate(c->fe, pts, dt, t, step));
  double *f = &pts->f[3 * (size_t)c->first];
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < c->n; i++) {
    double fe[3];
    pf_fem_body_node_force(c->fe, i, 1, fe);
    for (int a = 0; a < 3; a++) f[3 * (size_t)i + a] += fe[a];
  }
  pf_fem_body_set_stable_dt(c->fe, fmin(pf_fem_body_stable_dt(c->fe), pf_pd_body_stable_dt(c->pd, pts)));
  return 0;
}

/* Force form: f = beta f_PD + (1 - beta) f_FE on the owned nodes; energy form: the forces of the
 * blended energy. Added to what pts->f already holds. */
int pf_coupled_body_force(pf_coupled_body *c, pf_points *pts, double dt, double t, long step) {
  if (c->energy_form) return energy_form_force(c, pts, dt, t, step);
  double *f = &pts->f[3 * (size_t)c->first], *keep = c->fsave;
  const size_t n3 = 3 * (size_t)c->n;
  memcpy(keep, f, n3 * sizeof(double));
  memset(f, 0, n3 * sizeof(double));
  PF_CALL(pf_pd_body_force(c->pd, pts, dt));
  for (size_t k = 0; k < n3; k++) keep[k] += c->beta[c->first + k / 3] * f[k], f[k] = 0.0;
  PF_CALL(pf_fem_body_evaluate(c->fe, pts, dt, t, step));
#pragma omp parallel for schedule(static)
  for (pf_int i = 0; i < c->n; i++) {
    double fe[3];
    pf_fem_body_node_force(c->fe, i, 0, fe);
    const double w = 1.0 - c->beta[c->first + i];
    for (int a = 0; a < 3; a++) f[3 * (size_t)i + a] = keep[3 * (size_t)i + a] + w * fe[a];
  }
  pf_fem_body_set_stable_dt(c->fe, fmin(pf_fem_body_stable_dt(c->fe), pf_pd_body_stable_dt(c->pd, pts)));
  return 0;
}
