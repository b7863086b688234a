/* FE bodies: a hexahedral mesh whose nodes live in the point store beside the PD points, its
 * material, the element options, and the owner-computes assembly (docs/architecture.md §2): every
 * rank evaluates each element that has one of its owned nodes (elements on a partition boundary are
 * evaluated by both ranks, identically, from the same ghosted node data), and each owned node sums
 * its elements' forces in ascending global element order. No reverse communication, and the same
 * bits on any number of ranks. */
#include "fem/fem_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const pf_key hourglass_keys[] = {
    {"type", PF_KEY_STRING, 0, "viscous", "", "viscous | stiffness | none (Flanagan-Belytschko 1981)", NULL},
    {"coefficient", PF_KEY_REAL, 0, "0.1", "",
     "q_hv (viscous) or q_hs (stiffness: the fraction of a fully integrated element's stiffness)", NULL},
    PF_KEY_END};

static const pf_key bulk_viscosity_keys[] = {
    {"linear", PF_KEY_REAL, 0, "0.06", "", "C_l in q = rho l (C_q l trD^2 - C_l c trD)", NULL},
    {"quadratic", PF_KEY_REAL, 0, "1.5", "", "C_q (von Neumann-Richtmyer)", NULL},
    PF_KEY_END};

const pf_key pf_fem_body_keys[] = {
    {"name", PF_KEY_STRING, 1, NULL, "", "body name (the Exodus block name)", NULL},
    {"type", PF_KEY_STRING, 1, NULL, "", "finite_element", NULL},
    {"material", PF_KEY_STRING, 1, NULL, "", "a name under materials: (an FE model)", NULL},
    {"material_regions", PF_KEY_LIST, 0, NULL, "",
     "other materials on some elements: each entry a material and a block or region (later entries take precedence); "
     "with a peridynamic: operator, of one continuum model and a constant horizon, each node taking the latest entry "
     "among its elements (docs/theory/interfaces.md §8)", pf_fem_material_region_keys},
    {"mesh", PF_KEY_MAP, 1, NULL, "", "the hexahedral mesh", pf_mesh_keys},
    {"element", PF_KEY_STRING, 0, "reduced", "",
     "reduced (one point, hourglass control) | bbar (2x2x2 selective-reduced)", NULL},
    {"hourglass", PF_KEY_MAP, 0, NULL, "", "hourglass control of reduced elements", hourglass_keys},
    {"bulk_viscosity", PF_KEY_MAP, 0, NULL, "", "artificial bulk viscosity", bulk_viscosity_keys},
    {"initial_velocity", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m/s", "expressions in x, y, z", NULL},
    {"erosion", PF_KEY_MAP, 0, NULL, "", "delete elements that pass these limits (fem/erosion.c)", pf_fem_erosion_keys},
    {"initial_displacement", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m", "expressions in x, y, z; the stress follows it in hyperelastic and PD models (rate-form models start unstressed)", NULL},
    PF_KEY_END};

static int read_options(const pf_deck *d, const pf_node *body, pf_fem_body *b) {
  const char *element = "reduced", *hg = "viscous";
  PF_CALL(pf_deck_string(d, body, "element", &element));
  if (strcmp(element, "reduced") && strcmp(element, "bbar"))
    return pf_deck_error(d, pf_node_get(body, "element"), "element", "unknown element '%s' (known: reduced, bbar)", element);
  b->bbar = !strcmp(element, "bbar");
  b->nqp = b->bbar ? 8 : 1;
  const pf_node *h = pf_node_get(body, "hourglass"), *bv = pf_node_get(body, "bulk_viscosity");
  b->hg_coef = 0.1;
  PF_CALL(pf_deck_string(d, h, "type", &hg));
  PF_CALL(pf_deck_real(d, h, "coefficient", &b->hg_coef));
  if (!strcmp(hg, "stiffness")) b->hg = PF_HG_STIFFNESS;
  else if (!strcmp(hg, "viscous")) b->hg = PF_HG_VISCOUS;
  else if (!strcmp(hg, "none")) b->hg = PF_HG_NONE;
  else return pf_deck_error(d, pf_node_get(h, "type"), "type", "unknown hourglass control '%s' (known: stiffness, viscous, none)", hg);
  if (!(b->hg_coef >= 0 && b->hg_coef <= 1))
    return pf_deck_error(d, pf_node_get(h, "coefficient"), "coefficient", "must be in [0, 1] (got %g)", b->hg_coef);
  if (b->bbar) b->hg = PF_HG_NONE; /* fully integrated: no hourglass modes */
  b->bv_linear = 0.06, b->bv_quadratic = 1.5;
  PF_CALL(pf_deck_real(d, bv, "linear", &b->bv_linear));
  PF_CALL(pf_deck_real(d, bv, "quadratic", &b->bv_quadratic));
  if (!(b->bv_linear >= 0)) return pf_deck_error(d, pf_node_get(bv, "linear"), "linear", "must not be negative");
  if (!(b->bv_quadratic >= 0)) return pf_deck_error(d, pf_node_get(bv, "quadratic"), "quadratic", "must not be negative");
  return 0;
}

static void gather_reference(const pf_mesh *m, pf_int e, double x[8][3]) {
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) x[I][i] = m->X[3 * (size_t)m->conn[8 * (size_t)e + I] + i];
}

/* Lumped nodal volumes int N_I dV of the whole mesh (the points' volumes). */
static int nodal_volumes(pf_fem_body *b) {
  const pf_mesh *m = &b->mesh;
  PF_MALLOC(b->node_volume, m->nnodes);
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3], w[8];
    gather_reference(m, e, x);
    pf_hex8_lumped_mass(x, 1.0, w);
    for (int I = 0; I < 8; I++) b->node_volume[m->conn[8 * (size_t)e + I]] += w[I];
  }
  return 0;
}

/* Node -> element CSR of the whole mesh, elements ascending. */
static int mesh_node_elements(const pf_mesh *m, int64_t **off, pf_int **item) {
  PF_MALLOC(*off, m->nnodes + 1);
  PF_MALLOC(*item, 8 * (size_t)m->nelem);
  int64_t *o = *off;
  for (size_t k = 0; k < 8 * (size_t)m->nelem; k++) o[m->conn[k] + 1]++;
  for (pf_int k = 0; k < m->nnodes; k++) o[k + 1] += o[k];
  int64_t *fill = malloc(sizeof(int64_t) * ((size_t)m->nnodes + 1));
  PF_CHECK(fill, PF_ERR_MEMORY, "out of memory");
  memcpy(fill, o, sizeof(int64_t) * ((size_t)m->nnodes + 1));
  for (pf_int e = 0; e < m->nelem; e++)
    for (int I = 0; I < 8; I++) (*item)[fill[m->conn[8 * (size_t)e + I]]++] = e;
  free(fill);
  return 0;
}

int pf_fem_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials, pf_fem_body **out) {
  *out = NULL;
  pf_fem_body *b;
  PF_MALLOC(b, 1);
  const char *name = "";
  int ierr = pf_deck_string(d, body, "name", &name);
  snprintf(b->name, sizeof b->name, "%s", name);
  b->deck = d, b->node = body;
  if (!ierr) ierr = read_options(d, body, b);
  if (!ierr) ierr = pf_fem_materials_read(b, d, body, materials);
  if (!ierr) ierr = pf_mesh_read(d, pf_node_get(body, "mesh"), &b->mesh);
  if (!ierr) ierr = pf_fem_materials_regions(b, d, body, materials);
  if (!ierr) ierr = pf_fem_erosion_read(b, d, body);
  if (!ierr) ierr = nodal_volumes(b);
  if (!ierr) ierr = mesh_node_elements(&b->mesh, &b->mesh_node_off, &b->mesh_node_item);
  if (ierr) {
    pf_fem_body_destroy(&b);
    return ierr;
  }
  *out = b;
  return 0;
}

int pf_fem_body_destroy(pf_fem_body **pb) {
  pf_fem_body *b = *pb;
  if (!b) return 0;
  pf_mesh_free(&b->mesh);
  pf_fem_materials_destroy(b);
  free(b->node_volume), free(b->mesh_node_off), free(b->mesh_node_item), free(b->eid), free(b->conn), free(b->own), free(b->sigma), free(b->state);
  free(b->hgq), free(b->bvq), free(b->ref), free(b->share), free(b->fe), free(b->energy), free(b->node_off), free(b->node_item), free(b->buf);
  free(b->mesh_eroded), free(b->due), free(b->mesh_converted), free(b->wmass), free(b->committed);
  PF_FREE(*pb);
  return 0;
}

int pf_fem_body_cloud(const pf_fem_body *b, pf_point_cloud *pc) {
  const pf_mesh *m = &b->mesh;
  memset(pc, 0, sizeof *pc);
  pc->n = m->nnodes;
  PF_MALLOC(pc->X, 3 * (size_t)m->nnodes);
  PF_MALLOC(pc->vol, m->nnodes);
  PF_MALLOC(pc->cell, m->nnodes);
  PF_MALLOC(pc->block, m->nnodes);
  memcpy(pc->X, m->X, sizeof(double) * 3 * (size_t)m->nnodes);
  for (pf_int k = 0; k < m->nnodes; k++) pc->vol[k] = b->node_volume[k], pc->cell[k] = cbrt(b->node_volume[k]);
  return 0;
}

static int cmp_gid(const void *a, const void *b) {
  pf_gid x = *(const pf_gid *)a, y = *(const pf_gid *)b;
  return (x > y) - (x < y);
}

int pf_fem_body_node_rows(const pf_fem_body *b, const pf_points *pts, pf_int first, pf_int n, pf_gid gid0,
                          pf_bond_rows *rows) {
  const pf_mesh *m = &b->mesh;
  const int64_t *off = b->mesh_node_off;
  const pf_int *item = b->mesh_node_item;
  pf_gid row[27 * 8 + 8];
  int ierr = 0;
  for (pf_int i = first; i < first + n && !ierr; i++) {
    pf_int k = (pf_int)(pts->gid[i] - gid0), cnt = 0;
    for (int64_t q = off[k]; q < off[k + 1]; q++)
      for (int I = 0; I < 8; I++) {
        pf_int j = m->conn[8 * (size_t)item[q] + I];
        if (j == k) continue;
        int seen = 0;
        for (pf_int r = 0; r < cnt && !seen; r++) seen = row[r] == gid0 + j;
        if (!seen && cnt < (pf_int)(sizeof row / sizeof row[0])) row[cnt++] = gid0 + j;
        else if (!seen) ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                                              "body '%s': node %" PF_INT_FMT " has more than %zu neighbours",
                                              b->name, k + 1, sizeof row / sizeof row[0]);
      }
    qsort(row, (size_t)cnt, sizeof row[0], cmp_gid);
    if (!ierr) ierr = pf_bond_rows_append(rows, cnt, row, 0, NULL);
  }
  return ierr;
}

const double *pf_fem_body_node_volumes(const pf_fem_body *b) { return b->node_volume; }

void pf_fem_body_set_blending(pf_fem_body *b, pf_fem_weight_fn beta, const void *ctx) {
  b->beta_fn = beta, b->beta_ctx = ctx;
}

/* Each element's share of the blended energy, 1 - the mean beta of its eight nodes (the nodes'
 * beta is fixed for a store layout: computed here, at every attach, not every step). */
int pf_fem_body_set_blending_field(pf_fem_body *b, const double *beta) {
  free(b->share);
  PF_MALLOC(b->share, (size_t)b->nel + 1);
  for (pf_int e = 0; e < b->nel; e++) {
    double w = 1;
    for (int I = 0; I < 8; I++) w -= beta[b->conn[8 * (size_t)e + I]] / 8.0;
    b->share[e] = w;
  }
  return 0;
}
