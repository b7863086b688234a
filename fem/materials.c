/* The materials of an FE body: the body's `material`, and per element the one its
 * `material_regions` give (a mesh block, or a region holding the element's reference centroid;
 * later entries take precedence, unclaimed elements keep `material`). Every element reads its
 * own material's density, moduli and constitutive update (docs/theory/fem.md §9c).
 * The material state of an element is stored with one stride for the whole body, the largest of
 * its materials' state counts: an element uses the first nstate slots of its material, the rest
 * are zero. The output has one field per state name of any of the materials (the union), zero
 * on the elements whose material has no such variable. */
#include "fem/fem_impl.h"

#include <stdlib.h>
#include <string.h>

const pf_key pf_fem_material_region_keys[] = {
    {"material", PF_KEY_STRING, 1, NULL, "", "a name under materials: (an FE model) for the elements this entry selects", NULL},
    {"block", PF_KEY_STRING, 0, NULL, "",
     "the elements of this mesh block (gmsh physical group, Exodus element block, Pamgen block_N); give block or region",
     NULL},
    {"region", PF_KEY_MAP, 0, NULL, "",
     "the elements whose reference centroid is inside this region (a shape, not a set); give block or region",
     pf_region_keys},
    PF_KEY_END};

/* The body's index of the material named mname (the value of `key` at node `at`), created and
 * appended when the body has not got it yet. */
static int material_index(pf_fem_body *b, const pf_deck *d, const pf_node *at, const char *key, const char *mname,
                          const pf_node *materials, int *idx) {
  for (int m = 0; m < b->nmat; m++)
    if (!strcmp(pf_material_name(b->mats[m].mat), mname)) return *idx = m, 0;
  const pf_node *node = pf_node_get(materials, mname);
  if (!node) return pf_deck_error(d, at, key, "no material named '%s' under materials:", mname);
  const char *model = "";
  PF_CALL(pf_deck_string(d, node, "model", &model));
  if (!pf_material_known(model))
    return pf_deck_error(d, at, key, "material '%s' has model '%s', which is not a finite-element model (known: %s)",
                         mname, model, pf_material_names());
  if (b->nmat == PF_FEM_MAX_MATERIALS)
    return pf_deck_error(d, at, key, "body '%s': more than %d materials", b->name, PF_FEM_MAX_MATERIALS);
  pf_fem_material *fm = &b->mats[b->nmat];
  PF_CALL(pf_material_create(d, node, mname, &fm->mat));
  b->nmat++;
  fm->rho = pf_material_density(fm->mat);
  fm->K = pf_material_bulk_modulus(fm->mat);
  fm->G = pf_material_shear_modulus(fm->mat);
  fm->nstate = pf_material_nstate(fm->mat);
  fm->eqps = -1;
  for (int k = 0; k < fm->nstate; k++)
    if (!strcmp(pf_material_state_name(fm->mat, k), "eqps")) fm->eqps = k;
  if (fm->nstate > b->nstate) b->nstate = fm->nstate;
  *idx = b->nmat - 1;
  return 0;
}

int pf_fem_materials_read(pf_fem_body *b, const pf_deck *d, const pf_node *body, const pf_node *materials) {
  const char *mname = NULL;
  int m;
  PF_CALL(pf_deck_string(d, body, "material", &mname));
  return material_index(b, d, pf_node_get(body, "material"), "material", mname, materials, &m);
}

void pf_fem_materials_destroy(pf_fem_body *b) {
  for (int m = 0; m < b->nmat; m++) pf_material_destroy(&b->mats[m].mat);
  free(b->mesh_entry);
  b->mesh_entry = NULL, b->nmat = 0;
}

static int known_block(const pf_fem_body *b, const pf_deck *d, const pf_node *at, const char *name, int *blk) {
  char known[512] = "";
  for (int k = 0; k < b->mesh.nblocks; k++) {
    if (!strcmp(b->mesh.block_name[k], name)) return *blk = k, 0;
    size_t len = strlen(known);
    snprintf(known + len, sizeof known - len, "%s%s", k ? ", " : "", b->mesh.block_name[k]);
  }
  return pf_deck_error(d, at, "block", "body '%s': its mesh has no block '%s' (known: %s)", b->name, name, known);
}

static int centroid_inside(const pf_mesh *m, pf_int e, const pf_region *r) {
  double c[3] = {0, 0, 0};
  for (int I = 0; I < 8; I++)
    for (int a = 0; a < 3; a++) c[a] += m->X[3 * (size_t)m->conn[8 * (size_t)e + I] + a] / 8.0;
  return pf_region_contains(r, c);
}

/* One entry of `material_regions`: its material on the elements it selects. */
static int read_entry(pf_fem_body *b, const pf_deck *d, const pf_node *item, int entry, const pf_node *materials) {
  const pf_node *bn = pf_node_get(item, "block"), *rn = pf_node_get(item, "region");
  if (!bn == !rn)
    return pf_deck_error(d, item, "material_regions", "body '%s': an entry gives %s of block and region (give exactly one)",
                         b->name, bn ? "both" : "neither");
  const char *mname = NULL, *block = NULL;
  int m, blk = -1;
  pf_region r;
  PF_CALL(pf_deck_string(d, item, "material", &mname));
  PF_CALL(material_index(b, d, pf_node_get(item, "material"), "material", mname, materials, &m));
  if (bn) {
    PF_CALL(pf_deck_string(d, item, "block", &block));
    PF_CALL(known_block(b, d, bn, block, &blk));
  } else
    PF_CALL(pf_region_from_deck(d, rn, NULL, -1, &r));
  pf_int count = 0;
  b->entry_mat[entry] = (uint8_t)m;
  for (pf_int e = 0; e < b->mesh.nelem; e++)
    if (bn ? b->mesh.block[e] == blk : centroid_inside(&b->mesh, e, &r))
      b->mesh_entry[e] = (uint8_t)entry, count++;
  if (!count)
    return pf_deck_error(d, bn ? bn : rn, bn ? "block" : "region",
                         "body '%s': this entry of material_regions selects no element", b->name);
  return 0;
}

int pf_fem_body_node_entries(const pf_fem_body *b, uint8_t *entry) {
  const pf_mesh *m = &b->mesh;
  for (pf_int k = 0; k < m->nnodes; k++) {
    entry[k] = 0;
    for (int64_t q = b->mesh_node_off[k]; q < b->mesh_node_off[k + 1] && b->mesh_entry; q++)
      if (b->mesh_entry[b->mesh_node_item[q]] > entry[k]) entry[k] = b->mesh_entry[b->mesh_node_item[q]];
  }
  return b->mesh_entry != NULL;
}

/* The union of the materials' state names, and where each material keeps each. */
static int state_names(pf_fem_body *b) {
  b->nnames = 0;
  for (int m = 0; m < b->nmat; m++) {
    for (int k = 0; k < PF_FEM_MAX_STATE_NAMES; k++) b->slot[m][k] = -1;
    for (int k = 0; k < b->mats[m].nstate; k++) {
      const char *name = pf_material_state_name(b->mats[m].mat, k);
      int u = 0;
      while (u < b->nnames && strcmp(b->names[u], name)) u++;
      PF_CHECK(u < PF_FEM_MAX_STATE_NAMES, PF_ERR_INPUT, "body '%s': its materials have more than %d state variables",
               b->name, PF_FEM_MAX_STATE_NAMES);
      if (u == b->nnames) b->names[b->nnames++] = name;
      b->slot[m][u] = (int8_t)k;
    }
  }
  return 0;
}

int pf_fem_materials_regions(pf_fem_body *b, const pf_deck *d, const pf_node *body, const pf_node *materials) {
  const pf_node *list = pf_node_get(body, "material_regions");
  if (list && !pf_node_count(list))
    return pf_deck_error(d, list, "material_regions", "body '%s': an empty list (leave the key out)", b->name);
  if (list && pf_node_count(list) > UINT8_MAX)
    return pf_deck_error(d, list, "material_regions", "body '%s': more than %d entries", b->name, UINT8_MAX);
  b->entry_mat[0] = 0;
  if (list) PF_MALLOC(b->mesh_entry, b->mesh.nelem);
  for (int i = 0; list && i < pf_node_count(list); i++)
    PF_CALL(read_entry(b, d, pf_node_item(list, i), i + 1, materials));
  return state_names(b);
}

int pf_fem_materials_init(pf_fem_body *b) {
  const pf_int nq = b->nqp;
  if (!b->mesh_entry) {
    pf_material_init(b->mats[0].mat, nq * b->nel, b->state);
    return 0;
  }
  double *one;
  PF_MALLOC(one, (size_t)nq * b->nstate);
  for (pf_int e = 0; e < b->nel; e++) {
    const pf_fem_material *fm = pf_fem_element_material(b, e);
    double *st = &b->state[(size_t)b->nstate * nq * e];
    pf_material_init(fm->mat, nq, one);
    for (pf_int g = 0; g < nq; g++)
      for (int k = 0; k < b->nstate; k++) st[b->nstate * g + k] = k < fm->nstate ? one[fm->nstate * g + k] : 0.0;
  }
  free(one);
  return 0;
}

/* Copy n points' states between the body's stride `wide` and a material's `narrow` (<= wide). */
static void restride(pf_int n, int narrow, int wide, const double *from, double *to, int to_narrow) {
  for (pf_int p = 0; p < n; p++)
    for (int k = 0; k < narrow; k++)
      if (to_narrow) to[(size_t)narrow * p + k] = from[(size_t)wide * p + k];
      else to[(size_t)wide * p + k] = from[(size_t)narrow * p + k];
}

void pf_fem_materials_update(pf_fem_body *b, pf_int e0, pf_int ne, double dt, const double *F, const double *D,
                             double *c, double *scratch) {
  const pf_int nq = b->nqp;
  const int ns = b->nstate;
  for (pf_int k0 = 0, k1; k0 < ne; k0 = k1) { /* one call per run of elements of one material */
    const pf_fem_material *fm = pf_fem_element_material(b, e0 + k0);
    for (k1 = k0 + 1; k1 < ne && pf_fem_element_material(b, e0 + k1) == fm; k1++) {
    }
    const pf_int n = (k1 - k0) * nq;
    double *sig = &b->sigma[6 * (size_t)nq * (e0 + k0)], *st = &b->state[(size_t)ns * nq * (e0 + k0)];
    const double *Fk = &F[9 * (size_t)nq * k0], *Dk = &D[6 * (size_t)nq * k0];
    if (fm->nstate == ns) {
      pf_material_update(fm->mat, n, dt, Fk, Dk, sig, st, &c[(size_t)nq * k0]);
      continue;
    }
    restride(n, fm->nstate, ns, st, scratch, 1);
    pf_material_update(fm->mat, n, dt, Fk, Dk, sig, scratch, &c[(size_t)nq * k0]);
    restride(n, fm->nstate, ns, scratch, st, 0);
  }
}

void pf_fem_body_material_bounds(const pf_fem_body *b, double *density, double *bulk_modulus) {
  *density = b->mats[0].rho, *bulk_modulus = b->mats[0].K;
  for (int m = 1; m < b->nmat; m++) {
    if (b->mats[m].rho < *density) *density = b->mats[m].rho;
    if (b->mats[m].K > *bulk_modulus) *bulk_modulus = b->mats[m].K;
  }
}
