/* An FE body coupled to peridynamics by force blending on its own nodes (docs/theory/coupling.md
 * §3; Seleson, Beneddine & Prudhomme 2013, force-based blending; D'Elia et al. 2021, §4): the
 * nodes are also the points of a peridynamic operator (correspondence, the body's own material;
 * variable horizon and the partial-stress form of pd/partial_stress.c), and each node's force is
 *   f_i = beta_i f_i^PD + (1 - beta_i) f_i^FE,
 * with beta(x) in [0, 1] from the deck. Elements whose eight nodes all have beta = 1 are not
 * evaluated (the PD region, where bonds may break); the PD operator acts everywhere else too,
 * its forces weighted by beta. Both operators give zero force under a linear displacement and
 * the exact div sigma under a quadratic one at interior nodes, so the blend does too. */
#include "fem/fem_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double fe_distance(const void *region, const double x[3]) {
  return region ? pf_nearest_distance(region, x) : INFINITY;
}

int pf_fem_body_coupling_read(pf_fem_body *b, const pf_node *body, const pf_node *materials) {
  const pf_node *map = pf_node_get(body, "peridynamic");
  if (!map) return 0;
  PF_CALL(pf_pd_body_create_coupled(b->deck, body, map, materials, &b->pd));
  const pf_node *bn = pf_node_get(map, "blending");
  PF_CALL(pf_expr_create(pf_node_text(bn), b->deck, bn, "blending", &b->beta_expr));
  int pd_region = 0;
  pf_int nfe = 0;
  double *fe;
  PF_MALLOC(fe, 3 * (size_t)b->mesh.nnodes + 1);
  for (pf_int k = 0; k < b->mesh.nnodes; k++) { /* every rank checks the whole mesh alike */
    const double *x = &b->mesh.X[3 * (size_t)k], w = pf_expr_eval(b->beta_expr, x[0], x[1], x[2], 0.0);
    if (!(w >= 0 && w <= 1)) {
      free(fe);
      return pf_deck_error(b->deck, bn, "blending", "body '%s': beta is %g at node %" PF_INT_FMT
                           " (%g, %g, %g); it must lie in [0, 1]", b->name, w, k + 1, x[0], x[1], x[2]);
    }
    pd_region |= w == 1;
    if (w < 1) memcpy(&fe[3 * (size_t)nfe++], x, 3 * sizeof(double));
  }
  int ierr = nfe > 0 && pf_pd_body_uses_fe_distance(b->pd) ? pf_nearest_create(fe, nfe, &b->fe_region) : 0;
  free(fe);
  PF_CALL(ierr);
  pf_pd_body_set_fe_distance(b->pd, fe_distance, b->fe_region); /* the horizon's d_fe */
  const pf_node *dmg = pf_node_get(map, "damage");
  const char *law = "none";
  PF_CALL(pf_deck_string(b->deck, dmg, "law", &law));
  if (strcmp(law, "none") && !pd_region)
    return pf_deck_error(b->deck, dmg, "damage", "body '%s' has no node with blending weight 1: damage acts only "
                         "in the peridynamic region, never in the transition, overlap or elements", b->name);
  return 0;
}

double pf_fem_body_beta(const pf_fem_body *b, const double x[3]) {
  return b->beta_expr ? pf_expr_eval(b->beta_expr, x[0], x[1], x[2], 0.0) : 0.0;
}

/* Is element e of the mesh left to peridynamics (all its nodes at beta = 1)? */
int pf_fem_body_element_is_pd(const pf_fem_body *b, pf_int e) {
  if (!b->pd) return 0;
  for (int I = 0; I < 8; I++)
    if (pf_fem_body_beta(b, &b->mesh.X[3 * (size_t)b->mesh.conn[8 * (size_t)e + I]]) < 1) return 0;
  return 1;
}

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

int pf_fem_body_coupled_rows(const pf_fem_body *b, const pf_bond_rows *pd, const pf_bond_rows *elem,
                             pf_bond_rows *rows) {
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
  (void)b;
  return ierr;
}

int pf_fem_body_coupling_attach(pf_fem_body *b, pf_points *pts) {
  if (!b->pd) return 0;
  int idx;
  PF_CALL(pf_points_field_register(pts, "blending_weight", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT, &idx));
  b->beta = pts->fields[idx].data;
  for (pf_int i = b->first; i < b->first + b->n; i++) b->beta[i] = pf_fem_body_beta(b, &pts->X[3 * (size_t)i]);
  PF_CALL(pf_points_exchange(pts, b->beta, 1));
  pf_pd_body_set_blending(b->pd, b->beta);
  for (pf_int i = b->first; i < b->first + b->n; i++) pts->m[i] = b->rho * pts->vol[i]; /* all nodes */
  free(b->fsave);
  PF_MALLOC(b->fsave, 3 * (size_t)b->n + 1);
  return 0;
}

/* f = beta f_PD + (1 - beta) f_FE on the owned nodes, added to what pts->f already holds. */
int pf_fem_body_coupled_force(pf_fem_body *b, pf_points *pts, double dt) {
  double *f = &pts->f[3 * (size_t)b->first], *keep = b->fsave;
  const size_t n3 = 3 * (size_t)b->n;
  memcpy(keep, f, n3 * sizeof(double));
  memset(f, 0, n3 * sizeof(double));
  PF_CALL(pf_pd_body_force(b->pd, pts, dt));
  for (size_t k = 0; k < n3; k++) keep[k] += b->beta[b->first + k / 3] * f[k], f[k] = 0.0;
  PF_CALL(pf_fem_elements_evaluate(b, pts, dt));
  for (pf_int i = 0; i < b->n; i++) {
    double fe[3];
    pf_fem_node_force(b, i, fe);
    const double w = 1.0 - b->beta[b->first + i];
    for (int a = 0; a < 3; a++) f[3 * (size_t)i + a] = keep[3 * (size_t)i + a] + w * fe[a];
  }
  b->stable_dt = fmin(b->stable_dt, pf_pd_body_stable_dt(b->pd, pts));
  return 0;
}

int pf_fem_body_coupling_ready(pf_fem_body *b, pf_points *pts) {
  if (b->pd) b->stable_dt = fmin(b->stable_dt, pf_pd_body_stable_dt(b->pd, pts));
  return 0;
}
