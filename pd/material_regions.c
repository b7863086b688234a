/* Several materials in one peridynamic body (docs/theory/interfaces.md): the body's
 * `material_regions` give regions of its points their own material of the body's model; each
 * point keeps its part's constants (pd/pd_impl.h, pf_pd_K, pf_pd_G, pf_pd_density). A state-based
 * point keeps its own material's state across an interface, as the theory allows (each end's
 * force state is its own material's, Silling et al. 2007, eq. 94); a bond-based bond between two
 * materials takes the interface rule's micromodulus (pf_pd_bond_stiffness). */
#include "pd/pd_impl.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pf_pd_part_read_constants(const pf_deck *d, const pf_node *mat, const char *name, const pf_pd_body *b,
                              pf_pd_part *part) {
  const char *model = "";
  PF_CALL(pf_deck_string(d, mat, "model", &model));
  if (strcmp(model, b->ops->name))
    return pf_deck_error(d, pf_node_get(part->node, "material"), "material", "material '%s' is model '%s', body "
                         "'%s''s material '%s' is '%s': the materials of one body share a model", name, model, b->name,
                         b->material, b->ops->name);
  PF_CALL(pf_deck_real(d, mat, "density", &part->density));
  PF_CALL(pf_deck_real(d, mat, "bulk_modulus", &part->K));
  return pf_deck_real(d, mat, "shear_modulus", &part->G);
}

/* The constants of the material named by entry's `material` into part: its model must be the
 * body's, its density and bulk modulus positive, and its shear modulus given when the body's
 * material gives one (lps). */
static int read_part(const pf_deck *d, const pf_node *entry, const pf_node *materials, pf_pd_body *b, int q) {
  pf_pd_part *part = &b->parts[q];
  const char *name = "";
  PF_CALL(pf_deck_string(d, entry, "material", &name));
  const pf_node *key = pf_node_get(entry, "material"), *mat = pf_node_get(materials, name);
  if (!mat) return pf_deck_error(d, key, "material", "no material named '%s' under materials:", name);
  snprintf(part->material, sizeof part->material, "%s", name);
  part->density = part->K = part->G = 0;
  part->node = entry;
  if (b->ops->read_part) PF_CALL(b->ops->read_part(d, mat, name, b, q, part)); /* (the material's own keys) */
  else PF_CALL(pf_pd_part_read_constants(d, mat, name, b, part));
  if (!(part->density > 0) || !(part->K > 0))
    return pf_deck_error(d, key, "material", "material '%s' needs a positive density and bulk_modulus", name);
  if (b->shear_modulus > 0 && !(part->G > 0))
    return pf_deck_error(d, key, "material", "material '%s' needs a positive shear_modulus, as body '%s''s "
                         "material '%s' gives", name, b->name, b->material);
  const double M0 = b->bulk_modulus + 4 * b->shear_modulus / 3, M = part->K + 4 * part->G / 3;
  part->kscale = part->K / b->bulk_modulus;
  part->mscale = fmax(part->kscale, M / M0); /* (safe for the step whichever modulus sets it) */
  return 0;
}

/* What several materials do not take yet, refused by name. */
static int check_body(const pf_deck *d, const pf_node *list, const pf_pd_body *b) {
  if (!b->ops->several_materials)
    return pf_deck_error(d, list, "material_regions", "body '%s' has model '%s'; several materials in one body "
                         "take %s and the continuum models (correspondence)", b->name, b->ops->name,
                         pf_pd_material_names_with(offsetof(pf_pd_material_ops, several_materials)));
  if (b->hz_expr)
    return pf_deck_error(d, list, "material_regions", "body '%s': several materials take a constant horizon "
                         "(one material in a variable-horizon body, coupled or not)", b->name);
  const pf_node *dmg = pf_node_get(b->node, "damage"); /* (coupled: the peridynamic: map's) */
  if (pf_pd_energy_limited(b) || (dmg && pf_node_get(dmg, "energy_release_rate")))
    return pf_deck_error(d, dmg, "damage", "body '%s' has several materials: a critical stretch from an energy "
                         "release rate, or an energy limit, would be one material's; give critical_stretch",
                         b->name);
  return 0;
}

/* The interface's own damage law: critical_stretch (its stretch limit) or critical_energy (its
 * energy limit w_c = 4 G0 / (pi delta^4) from its G0, Foster, Silling & Chen 2011, as the body
 * law's: docs/theory/bond_failure.md §3). */
static int read_interface_damage(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  const char *law = "";
  PF_CALL(pf_deck_string(d, map, "law", &law));
  const int stretch = !strcmp(law, "critical_stretch"), energy = !strcmp(law, "critical_energy");
  if (!stretch && !energy)
    return pf_deck_error(d, pf_node_get(map, "law"), "law",
                         "unknown interface law '%s' (known: critical_stretch, critical_energy)", law);
  const char *need = stretch ? "critical_stretch" : "energy_release_rate", *other = stretch ? "energy_release_rate" : "critical_stretch";
  if (!pf_node_get(map, need) || pf_node_get(map, other))
    return pf_deck_error(d, map, need, "interface law '%s' takes '%s' (and not '%s')", law, need, other);
  double v;
  PF_CALL(pf_deck_positive(d, map, need, &v));
  b->interface_law = 1;
  b->interface_s0 = stretch ? v : INFINITY;
  b->interface_wc = energy ? pf_pd_critical_energy(v, b->horizon) : INFINITY;
  return 0;
}

static int read_interface(const pf_deck *d, const pf_node *body, pf_pd_body *b) {
  const pf_node *map = pf_node_get(body, "interface");
  const char *rule = "series";
  b->interface = PF_PD_INTERFACE_SERIES;
  b->interface_s0 = b->interface_wc = INFINITY;
  if (!map) return 0;
  PF_CALL(pf_deck_string(d, map, "micromodulus", &rule));
  if (!strcmp(rule, "mean")) b->interface = PF_PD_INTERFACE_MEAN;
  else if (strcmp(rule, "series"))
    return pf_deck_error(d, pf_node_get(map, "micromodulus"), "micromodulus",
                         "unknown interface rule '%s' (known: series, mean)", rule);
  const pf_node *dmg = pf_node_get(map, "damage");
  return dmg ? read_interface_damage(d, dmg, b) : 0;
}

/* The interface's energy limit on the bonds between two materials, none on the others
 * (b->wc_bond, with the rows' slack, which the batched loops read). */
static int fill_interface_energy(pf_pd_body *b) {
  const pf_family *fam = &b->fam;
  const int64_t nb = pf_pd_family_nbonds(fam);
  free(b->wc_bond);
  PF_MALLOC(b->wc_bond, nb + PF_FAMILY_SLACK);
  for (int64_t k = 0; k < nb + PF_FAMILY_SLACK; k++) b->wc_bond[k] = INFINITY;
  for (pf_int i = b->first; i < b->first + b->n; i++)
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      if (b->part[fam->neighbor[k]] != b->part[i]) b->wc_bond[k] = b->interface_wc;
  return 0;
}

int pf_pd_parts_read(const pf_deck *d, const pf_node *body, const pf_node *materials, pf_pd_body *b) {
  pf_pd_part *p0 = &b->parts[0];
  snprintf(p0->material, sizeof p0->material, "%s", b->material);
  p0->density = b->density, p0->K = b->bulk_modulus, p0->G = b->shear_modulus;
  p0->kscale = p0->mscale = 1.0;
  p0->node = pf_node_get(body, "material");
  b->nparts = 1;
  const pf_node *list = pf_node_get(body, "material_regions");
  if (!list && pf_node_get(body, "interface"))
    return pf_deck_error(d, pf_node_get(body, "interface"), "interface", "an interface rule needs "
                         "material_regions (body '%s' has one material)", b->name);
  if (!list) return 0;
  const int n = pf_node_count(list);
  if (n < 1 || n >= PF_PD_MAX_PARTS)
    return pf_deck_error(d, list, "material_regions", "give 1 to %d entries (got %d)", PF_PD_MAX_PARTS - 1, n);
  PF_CALL(check_body(d, list, b));
  for (int q = 1; q <= n; q++) {
    const pf_node *entry = pf_node_item(list, q - 1), *rn = pf_node_get(entry, "region"), *bn = pf_node_get(entry, "block");
    if (!rn == !bn)
      return pf_deck_error(d, bn ? bn : entry, bn ? "block" : "region", "body '%s': an entry of material_regions "
                           "gives %s of block and region (give exactly one)", b->name, bn ? "both" : "neither");
    PF_CALL(read_part(d, entry, materials, b, q));
    b->parts[q].block = bn;
    if (rn) PF_CALL(pf_region_from_deck(d, rn, NULL, -1, &b->parts[q].region));
  }
  b->nparts = n + 1;
  return read_interface(d, body, b);
}

/* A region or block that claims no point of the body is an error naming its entry (collective). */
static int check_claims(const pf_pd_body *b) {
  double count[PF_PD_MAX_PARTS] = {0};
  for (pf_int i = b->first; i < b->first + b->n; i++) count[(int)b->part[i]] += 1;
  for (int q = 1; q < b->nparts; q++) {
    const char *key = b->parts[q].block ? "block" : "region";
    if (pf_sum_all(count[q]) == 0)
      return pf_deck_error(b->deck, b->parts[q].node, key, "body '%s': the %s of material '%s' holds none of its "
                           "points (or later entries claim them all)", b->name, key, b->parts[q].material);
  }
  return 0;
}

/* The body's first global id (its points are numbered from it in cloud order; collective). */
static pf_gid first_gid(const pf_pd_body *b, const pf_points *pts) {
  double least = INFINITY;
  for (pf_int i = b->first; i < b->first + b->n; i++) least = fmin(least, (double)pts->gid[i]);
  return (pf_gid)pf_min_all(least);
}

int pf_pd_parts_attach(pf_pd_body *b, pf_points *pts, int fresh) {
  b->part = NULL;
  if (b->nparts < 2) return 0;
  int idx;
  PF_CALL(pf_points_field_register(pts, "material", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT | PF_FIELD_CONSTANT, &idx));
  double *part = pts->fields[idx].data;
  const pf_gid g0 = b->block_part ? first_gid(b, pts) : 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) { /* (from reference positions and global ids: the same
                                                           on any partition) */
    const pf_gid j = pts->gid[i] - g0;
    PF_CHECK(!b->block_part || (j >= 0 && j < b->nblock_part), PF_ERR_INPUT, "body '%s': point %" PF_GID_FMT
             " is not in its cloud of %" PF_GID_FMT " points", b->name, pts->gid[i], b->nblock_part);
    part[i] = b->block_part ? b->block_part[j] : 0; /* (the last block entry that claims it; coupled: the
                                                       last entry among the node's elements) */
    for (int q = 1; q < b->nparts && !b->coupled; q++) /* (later entries over earlier) */
      if (!b->parts[q].block && q > part[i] && pf_region_selects(&b->parts[q].region, pts, i)) part[i] = q;
  }
  PF_CALL(pf_points_exchange(pts, part, 1));
  b->part = part;
  if (isfinite(b->interface_wc)) PF_CALL(fill_interface_energy(b));
  return fresh ? check_claims(b) : 0;
}

int pf_pd_body_set_node_parts(pf_pd_body *b, const uint8_t *entry, pf_gid nnodes) {
  pf_pd_parts_free(b);
  if (b->nparts < 2) return 0;
  PF_MALLOC(b->block_part, nnodes + 1);
  for (pf_gid k = 0; k < nnodes; k++) {
    PF_CHECK(entry[k] < b->nparts, PF_ERR_INPUT, "body '%s': node %" PF_GID_FMT " has part %d of %d", b->name,
             k + 1, (int)entry[k], b->nparts);
    b->block_part[k] = entry[k];
  }
  b->nblock_part = nnodes;
  return 0;
}

double pf_pd_body_part_density(const pf_pd_body *b, int q) { return b->parts[q].density; }

void pf_pd_parts_free(pf_pd_body *b) {
  free(b->block_part);
  b->block_part = NULL, b->nblock_part = 0;
}

/* "'left' (id 1), 'right' (id 2)" for an Exodus cloud; "1, 2" for a point file (its first 32 ids). */
static void cloud_blocks(const pf_point_cloud *pc, char *out, size_t len) {
  int32_t seen[32];
  int nseen = 0;
  out[0] = '\0';
  for (int k = 0; k < pc->nnamed; k++) {
    size_t used = strlen(out);
    snprintf(out + used, len - used, "%s'%s' (id %d)", k ? ", " : "", pc->named[k], (int)pc->named_id[k]);
  }
  for (pf_int i = 0; !pc->nnamed && i < pc->n && nseen < 32; i++) {
    int k = 0;
    while (k < nseen && seen[k] != pc->block[i]) k++;
    if (k < nseen) continue;
    seen[nseen++] = pc->block[i];
    size_t used = strlen(out);
    snprintf(out + used, len - used, "%s%d", k ? ", " : "", (int)pc->block[i]);
  }
}

/* The block id an entry's `block` names in the cloud: an Exodus block's name, else an integer id
 * that some point of the cloud has; otherwise an error listing the cloud's blocks. */
static int entry_block(const pf_pd_body *b, const pf_point_cloud *pc, const pf_node *key, int32_t *id) {
  const char *want = pf_node_text(key);
  for (int k = 0; want && k < pc->nnamed; k++)
    if (!strcmp(pc->named[k], want)) return *id = pc->named_id[k], 0;
  char *end = NULL;
  const long v = want ? strtol(want, &end, 10) : 0;
  pf_int count = 0;
  if (want && end != want && *end == '\0' && v >= INT32_MIN && v <= INT32_MAX)
    for (pf_int i = 0; i < pc->n; i++) count += pc->block[i] == v;
  if (count) return *id = (int32_t)v, 0;
  char known[1024];
  cloud_blocks(pc, known, sizeof known);
  return pf_deck_error(b->deck, key, "block", "body '%s': its geometry holds no block '%s' (its blocks: %s)", b->name,
                       want ? want : "", known);
}

int pf_pd_body_take_blocks(pf_pd_body *b, const pf_point_cloud *pc) {
  pf_pd_parts_free(b);
  int any = 0;
  for (int q = 1; q < b->nparts; q++) any |= b->parts[q].block != NULL;
  if (!any) return 0;
  const pf_node *g = pf_node_get(b->node, "geometry");
  const char *shape = pf_node_text(pf_node_get(g, "shape"));
  for (int q = 1; q < b->nparts; q++)
    if (b->parts[q].block && !(shape && (!strcmp(shape, "points_file") || !strcmp(shape, "exodus"))))
      return pf_deck_error(b->deck, b->parts[q].block, "block", "body '%s': a block is one of a discretization's "
                           "(geometry shape points_file or exodus); its shape is '%s'", b->name, shape ? shape : "");
  PF_MALLOC(b->block_part, pc->n + 1);
  memset(b->block_part, 0, (size_t)pc->n + 1);
  b->nblock_part = pc->n;
  for (int q = 1; q < b->nparts; q++) {
    int32_t id;
    if (!b->parts[q].block) continue;
    PF_CALL(entry_block(b, pc, b->parts[q].block, &id));
    for (pf_int j = 0; j < pc->n; j++)
      if (pc->block[j] == id) b->block_part[j] = (uint8_t)q;
  }
  return 0;
}
