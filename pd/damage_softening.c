/* Bonds that soften (docs/theory/bond_failure.md §8): each bond is linear to s0 = s_c / sqrt(r),
 * then its force falls linearly to zero at s1 = s_c sqrt(r), and it unloads along its secant
 * (damage d of its largest stretch, weight 1 - d): the bilinear cohesive law put on each bond, a
 * nonlocal cohesive law in the sense of Lipton (2016), of the same energy to failure as the brittle
 * bond at s_c (s0 s1 = s_c^2). The bonds fail for good at s1; the kernels are pd/softening.c and
 * the weighted passes of pd/material_pmb.c and pd/material_lps.c. */
#include "pd/pd_impl.h"

#include <stdlib.h>
#include <string.h>

static const pf_key keys[] = {
    {"critical_stretch", PF_KEY_REAL, 0, NULL, "",
     "softening: s_c, the stretch at which a brittle bond of the same energy fails (s0 s1 = s_c^2)", NULL},
    {"energy_release_rate", PF_KEY_REAL, 0, NULL, "J/m^2",
     "softening: G0, converted to s_c by the material's closed form", NULL},
    {"softening_ratio", PF_KEY_REAL, 0, "2", "",
     "softening: r = s1 / s0 > 1; the bond is linear to s0 = s_c / sqrt(r), its force falls linearly to zero "
     "at s1 = s_c sqrt(r), where it fails (materials pmb and lps)", NULL},
    {"no_fail", PF_KEY_LIST, 0, NULL, "", "softening: regions whose points' bonds neither soften nor fail",
     pf_region_keys},
    PF_KEY_END};

/* s_c as the critical-stretch law reads it, r, and the body's stretch limit s1 = s_c sqrt(r). */
static int read_softening(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  const pf_node *law = pf_node_get(map, "law");
  if (strcmp(b->ops->name, "pmb") && strcmp(b->ops->name, "lps"))
    return pf_deck_error(d, law, "law", "law 'softening' is built for the materials pmb and lps (body '%s' has %s)",
                         b->name, b->ops->name);
  if (b->hz_expr || b->coupled)
    return pf_deck_error(d, law, "law", "law 'softening' needs a PD body of one horizon, not coupled to elements "
                         "(body '%s')", b->name);
  PF_CALL(pf_pd_damage_read_stretch(d, map, b));
  double r = 2;
  PF_CALL(pf_deck_real(d, map, "softening_ratio", &r));
  if (!(r > 1) || !isfinite(r))
    return pf_deck_error(d, pf_node_get(map, "softening_ratio"), "softening_ratio",
                         "must be a number above 1 (s1 / s0; got %g)", r);
  b->soft_ratio = r;
  b->s0_init *= sqrt(r); /* the stretch limit is s1 */
  b->fam.nstate = 2;     /* (s_max, d) per bond */
  return 0;
}

/* The points' s1 (the no-fail regions follow in pd/damage.c); the scratch of the LPS weighted
 * volume the softening takes. A body of several materials or with transition points is an input
 * error (their kernels take no weights). Collective. */
static int attach_softening(pf_pd_body *b, pf_points *pts, int fresh) {
  (void)pts;
  for (pf_int i = b->first; fresh && i < b->first + b->n; i++) b->s0[i] = b->s0_init;
  double special = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) special += b->region[i] != 0;
  if (b->nparts > 1 || b->interface_law || pf_sum_all(special) > 0)
    return pf_deck_error(b->deck, pf_node_get(pf_node_get(b->node, "damage"), "law"), "law",
                         "law 'softening' needs a body of one material whose points all take the standard "
                         "force (body '%s' has %s)", b->name,
                         b->nparts > 1 ? "material_regions" : "transition or overlap points");
  free(b->soft_lost);
  b->soft_lost = calloc((size_t)b->n + 1, sizeof *b->soft_lost);
  PF_CHECK(b->soft_lost, PF_ERR_MEMORY, "out of memory");
  return 0;
}

const pf_pd_damage_ops pf_pd_damage_softening = {
    .name = "softening",
    .keys = keys,
    .read = read_softening,
    .attach = attach_softening,
};
