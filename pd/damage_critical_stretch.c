/* Bond failure by critical stretch (Silling & Askari 2005): a bond fails for good when its
 * stretch exceeds min(s0_i, s0_j), with s0 constant: given, or from the energy release rate G0
 * through the material's closed form (e.g. PMB s0 = sqrt(5 G0 / (9 K delta)), eq. 9). The
 * evolving s0 of Silling and Askari is pd/damage_silling_askari.c. Points of the deck's
 * no_fail region start with s0 = INFINITY (pd/damage.c): the no-fail zone along loaded edges
 * of Ha & Bobaru (2010). */
#include "pd/pd_impl.h"

static const pf_key keys[] = {
    {"critical_stretch", PF_KEY_REAL, 0, NULL, "", "critical_stretch: s0", NULL},
    {"energy_release_rate", PF_KEY_REAL, 0, NULL, "J/m^2",
     "critical_stretch: G0, converted to s0 by the material's closed form", NULL},
    {"no_fail", PF_KEY_LIST, 0, NULL, "",
     "critical_stretch: regions (reference positions, at most 8) whose points have no stretch limit (s0 = "
     "infinity); a bond fails at the smaller s0 of its ends, so the bonds with both ends inside never fail",
     pf_region_keys}, /* (read by pd/damage.c for the laws that list it) */
    PF_KEY_END};

/* Constant s0, given or from G0 through the material's closed form. */
int pf_pd_damage_read_stretch(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  double s0 = INFINITY;
  int has_s0 = pf_node_get(map, "critical_stretch") != NULL;
  int has_g0 = pf_node_get(map, "energy_release_rate") != NULL;
  if (has_s0 == has_g0)
    return pf_deck_error(d, map, "critical_stretch",
                         "give exactly one of 'critical_stretch' and 'energy_release_rate'");
  if (has_s0) PF_CALL(pf_pd_damage_read_required(d, map, "critical_stretch", &s0));
  else {
    double G0;
    PF_CALL(pf_pd_damage_read_required(d, map, "energy_release_rate", &G0));
    s0 = b->ops->critical_stretch ? b->ops->critical_stretch(b, G0) : NAN;
    if (!isfinite(s0))
      return pf_deck_error(d, pf_node_get(map, "energy_release_rate"), "energy_release_rate",
                           "no closed form s0(G0) for material '%s' with this influence "
                           "function; give 'critical_stretch'", b->ops->name);
  }
  b->s0_init = s0;
  return 0;
}

const pf_pd_damage_ops pf_pd_damage_critical_stretch = {
    .name = "critical_stretch",
    .keys = keys,
    .read = pf_pd_damage_read_stretch,
};
