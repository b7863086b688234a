/* Material values that look like a unit slip, warned about with the deck's file, line and key
 * (the run goes on: an unusual material may mean them). Every material of these models is a
 * solid: a density below 100 kg/m^3 (lighter than any solid but foams and aerogels; g/cm^3
 * typed for kg/m^3 gives 0.5-23: 7.8 for steel, which a bound of 1 kg/m^3 would miss) or above
 * 1e5 kg/m^3 (denser than any solid: 22 600 kg/m^3 for osmium), and a modulus below 1 MPa (MPa or
 * GPa typed for Pa: 200 for steel) or above 1e13 Pa (stiffer than any solid: 1.2e12 Pa for
 * diamond's Young's modulus). */
#include "sim/sim_impl.h"

#define PF_DENSITY_LOW 100.0  /* kg/m^3 */
#define PF_DENSITY_HIGH 1e5   /* kg/m^3 */
#define PF_MODULUS_LOW 1e6    /* Pa */
#define PF_MODULUS_HIGH 1e13  /* Pa */

static const char *const modulus_keys[] = {"youngs_modulus", "bulk_modulus", "shear_modulus"};

/* One material's key against [lo, hi]; what: the quantity and its usual slip. */
static void check_value(const pf_deck *d, const pf_node *mat, const char *name, const char *key, double lo,
                        double hi, const char *unit, const char *slip) {
  const pf_node *n = pf_node_get(mat, key);
  double v = 0;
  if (!n || pf_deck_real(d, mat, key, &v) || !(v > 0)) return; /* (a bad value is the model's error) */
  if (v < lo)
    pf_deck_warn(d, n, key, "material '%s': %g %s is below %g %s, lighter or softer than a solid (%s; units are SI)", name,
                 v, unit, lo, unit, slip);
  else if (v > hi)
    pf_deck_warn(d, n, key, "material '%s': %g %s is above %g %s, beyond any solid (units are SI)", name, v, unit,
                 hi, unit);
}

void pf_sim_warn_unit_slips(const pf_deck *d, const pf_node *materials) {
  for (int k = 0; k < pf_node_count(materials); k++) {
    const char *name;
    const pf_node *mat = pf_node_map_item(materials, k, &name);
    check_value(d, mat, name, "density", PF_DENSITY_LOW, PF_DENSITY_HIGH, "kg/m^3",
                "g/cm^3 typed for kg/m^3? steel is 7850 kg/m^3");
    for (size_t j = 0; j < sizeof modulus_keys / sizeof *modulus_keys; j++)
      check_value(d, mat, name, modulus_keys[j], PF_MODULUS_LOW, PF_MODULUS_HIGH, "Pa",
                  "MPa or GPa typed for Pa? steel's Young's modulus is 2e11 Pa");
  }
}
