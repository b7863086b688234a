/* Bond failure by critical energy (Foster, Silling & Chen 2011, Int. J. Multiscale Comput.
 * Eng. 9:675): a bond in tension fails for good once its energy per unit volume squared
 * exceeds
 *   w_c = 4 G0 / (pi delta^4)                                       [J/m^6]
 * G0 is the energy of the bonds crossing a unit area of a plane: with a bond energy w_c that
 * does not depend on the bond length,
 *   G0 = int_0^delta dz int_0^2pi dtheta int_z^delta dxi int_0^acos(z/xi) w_c xi^2 sin(phi) dphi
 *      = 2 pi w_c int_0^delta dz int_z^delta (xi^2 - z xi) dxi = 2 pi w_c int_0^delta xi^3/2 dxi
 *      = pi w_c delta^4 / 4
 * (docs/theory/bond_failure.md). The bond energy is the material's, evaluated in its
 * force kernel where the critical-stretch test sits:
 *   PMB: w = (1/2) c omega s^2 |xi|       (the pair micropotential; pmb_energy gives each end half)
 *   LPS: w = (1/2) (t_ij + t_ji) e        (lps_energy = sum_i V_i sum_j (1/2) t_ij e V_j exactly)
 * Both ends compute the same w from the same operands, so they take the same decision.
 *
 * calibration: family (docs/theory/bond_failure.md §7). w_c above counts the continuum's whole
 * family; a point near a free face, or on a lattice whose cells straddle the horizon, has fewer
 * bonds across a plane, and a crack there takes less than G0 (down to 0.69 G0 in the double
 * cantilever beam, docs/examples/dcb.md). With the family's directional moment
 *   mu_i(n) = sum_j ((xi . n)^2 / |xi|) V_j,     continuum: pi delta^4 / 3 for every n,
 * each bond i-j of direction n gets
 *   w_c,ij = (4 G0 / 3) / ((mu_i(n) + mu_j(n)) / 2) = 8 G0 / (3 (mu_i(n) + mu_j(n))),
 * which is w_c for a whole family and larger where the family lacks bonds in the bond's
 * direction. No horizon enters, so a variable horizon needs nothing more. */
#include "pd/pd_impl.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

double pf_pd_critical_energy(double G0, double delta) {
  return 4.0 * G0 / (PF_PI * delta * delta * delta * delta);
}

static const pf_key keys[] = {
    {"energy_release_rate", PF_KEY_REAL, 0, NULL, "J/m^2",
     "critical_energy: G0, converted to the critical bond energy w_c = 4 G0 / (pi delta^4)", NULL},
    {"calibration", PF_KEY_STRING, 0, "continuum", "",
     "critical_energy: continuum (w_c of a whole family for every bond) | family (each bond's w_c from "
     "its two ends' families, so that a crack takes G0 near free faces and on a coarse lattice too)", NULL},
    PF_KEY_END};

typedef struct {
  double G0;
  int family; /* calibration: family */
} critical_energy;

static int read_critical_energy(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  if (!b->ops->bond_energy) /* (the force kernel evaluates the bond energy) */
    return pf_deck_error(d, pf_node_get(map, "law"), "law",
                         "law 'critical_energy' needs the bond energy from the material's force "
                         "kernel; material model '%s' does not provide it (it does: %s)",
                         b->ops->name, pf_pd_material_names_with(offsetof(pf_pd_material_ops, bond_energy)));
  if (!pf_node_get(map, "energy_release_rate"))
    return pf_deck_error(d, map, "energy_release_rate",
                         "law 'critical_energy' needs 'energy_release_rate' (G0, J/m^2)");
  critical_energy *p;
  PF_MALLOC(p, 1);
  b->damage_data = p;
  PF_CALL(pf_deck_positive(d, map, "energy_release_rate", &p->G0));
  const char *cal = "continuum";
  PF_CALL(pf_deck_string(d, map, "calibration", &cal));
  if (strcmp(cal, "continuum") && strcmp(cal, "family"))
    return pf_deck_error(d, pf_node_get(map, "calibration"), "calibration",
                         "unknown calibration '%s' (known: continuum, family)", cal);
  p->family = !strcmp(cal, "family");
  b->critical_energy = pf_pd_critical_energy(p->G0, b->horizon);
  b->s0_init = INFINITY; /* no stretch limit */
  return 0;
}

/* Point i's moment tensor sum_j (xi (x) xi / |xi|) V_j over its own family, every bond the
 * family was built with (broken or not: a reference quantity, the same after a restart), into
 * t[6] (xx, yy, zz, xy, yz, zx). */
static void family_moment(const pf_pd_body *b, const pf_points *pts, pf_int i, double t[6]) {
  const pf_family *fam = &b->fam;
  for (int a = 0; a < 6; a++) t[a] = 0;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    const pf_int j = fam->neighbor[k];
    double xi[3], r2 = 0;
    for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r2 += xi[a] * xi[a];
    const double r0 = sqrt(r2);
    if (!pf_pd_in_family(b, i, r0)) continue;
    const double w = pf_pd_bond_volume(fam, pts->vol, k, j) / r0;
    t[0] += w * xi[0] * xi[0], t[1] += w * xi[1] * xi[1], t[2] += w * xi[2] * xi[2];
    t[3] += w * xi[0] * xi[1], t[4] += w * xi[1] * xi[2], t[5] += w * xi[2] * xi[0];
  }
}

/* n . T n for the unit vector n. */
static double along(const double *t, const double n[3]) {
  return t[0] * n[0] * n[0] + t[1] * n[1] * n[1] + t[2] * n[2] * n[2] +
         2.0 * (t[3] * n[0] * n[1] + t[4] * n[1] * n[2] + t[5] * n[2] * n[0]);
}

/* Each bond's w_c,ij (calibration: family) into b->wc_bond, from the moments of both ends
 * (ghosts included). Both ends form n . T n from n and -n: the same bits, so the same w_c. */
static int family_thresholds(pf_pd_body *b, pf_points *pts) {
  const critical_energy *p = b->damage_data;
  int idx;
  PF_CALL(pf_points_field_register(pts, "family_moment", 6, PF_FIELD_GHOST, &idx));
  double *T = pts->fields[idx].data;
  for (pf_int i = b->first; i < b->first + b->n; i++) family_moment(b, pts, i, &T[6 * (size_t)i]);
  PF_CALL(pf_points_exchange(pts, T, 6));
  const pf_family *fam = &b->fam;
  const int64_t nb = pf_pd_family_nbonds(fam);
  free(b->wc_bond);
  PF_MALLOC(b->wc_bond, nb + PF_FAMILY_SLACK); /* (the batched loops read the slack) */
  for (pf_int i = b->first; i < b->first + b->n; i++)
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      const pf_int j = fam->neighbor[k];
      double n[3], r2 = 0;
      for (int a = 0; a < 3; a++) n[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r2 += n[a] * n[a];
      const double r0 = sqrt(r2);
      for (int a = 0; a < 3; a++) n[a] /= r0;
      const double mu = along(&T[6 * (size_t)i], n) + along(&T[6 * (size_t)j], n);
      PF_CHECK(mu > 0, PF_ERR_INPUT, "body '%s': the bond from point %" PF_GID_FMT " at (%g, %g, %g) has no "
               "family moment along it (calibration: family)", b->name, pts->gid[i], pts->X[3 * i],
               pts->X[3 * i + 1], pts->X[3 * i + 2]);
      b->wc_bond[k] = 8.0 * p->G0 / (3.0 * mu);
    }
  return 0;
}

static int attach_critical_energy(pf_pd_body *b, pf_points *pts, int fresh) {
  for (pf_int i = b->first; fresh && i < b->first + b->n; i++) b->s0[i] = b->s0_init;
  const critical_energy *p = b->damage_data;
  return p->family ? family_thresholds(b, pts) : 0;
}

const pf_pd_damage_ops pf_pd_damage_critical_energy = {
    .name = "critical_energy",
    .keys = keys,
    .read = read_critical_energy,
    .attach = attach_critical_energy,
};
