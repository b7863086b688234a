/* Bond failure by critical energy (Foster, Silling & Chen 2011, Int. J. Multiscale Comput.
 * Eng. 9:675): a bond in tension fails for good once its energy per unit volume squared
 * exceeds
 *   w_c = 4 G0 / (pi delta^4)                                       [J/m^6]
 * G0 is the energy of the bonds crossing a unit area of a plane: with a bond energy w_c that
 * does not depend on the bond length,
 *   G0 = int_0^delta dz int_0^2pi dtheta int_z^delta dxi int_0^acos(z/xi) w_c xi^2 sin(phi) dphi
 *      = 2 pi w_c int_0^delta dz int_z^delta (xi^2 - z xi) dxi = 2 pi w_c int_0^delta xi^3/2 dxi
 *      = pi w_c delta^4 / 4
 * (docs/theory/materials.md, section 4). The bond energy is the material's, evaluated in its
 * force kernel where the critical-stretch test sits:
 *   PMB: w = (1/2) c omega s^2 |xi|       (the pair micropotential; pmb_energy gives each end half)
 *   LPS: w = (1/2) (t_ij + t_ji) e        (lps_energy = sum_i V_i sum_j (1/2) t_ij e V_j exactly)
 * Both ends compute the same w from the same operands, so they take the same decision. */
#include "pd/pd_impl.h"

#include <stddef.h>

double pf_pd_critical_energy(double G0, double delta) {
  return 4.0 * G0 / (PF_PI * delta * delta * delta * delta);
}

static const char *const keys[] = {"energy_release_rate", NULL};

static int read_critical_energy(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  if (!b->ops->bond_energy) /* (the force kernel evaluates the bond energy) */
    return pf_deck_error(d, pf_node_get(map, "law"), "law",
                         "law 'critical_energy' needs the bond energy from the material's force "
                         "kernel; material model '%s' does not provide it (it does: %s)",
                         b->ops->name, pf_pd_material_names_with(offsetof(pf_pd_material_ops, bond_energy)));
  if (!pf_node_get(map, "energy_release_rate"))
    return pf_deck_error(d, map, "energy_release_rate",
                         "law 'critical_energy' needs 'energy_release_rate' (G0, J/m^2)");
  double G0;
  PF_CALL(pf_deck_positive(d, map, "energy_release_rate", &G0));
  b->critical_energy = pf_pd_critical_energy(G0, b->horizon);
  b->s0_init = INFINITY; /* no stretch limit */
  return 0;
}

const pf_pd_damage_ops pf_pd_damage_critical_energy = {
    .name = "critical_energy",
    .keys = keys,
    .read = read_critical_energy,
    .fails_on_energy = 1,
};
