/* Element erosion (`erosion:` of an FE body): an element whose equivalent plastic strain or volume
 * ratio J = V / V0 passes the deck's limits is deleted, as explicit codes do for material that
 * has failed or flows through a gap (LS-DYNA *MAT_ADD_EROSION: MXEPS, and the volumetric
 * limits; Belytschko, Liu & Moran 2000, sec. 6.6 on element deletion; docs/theory/fem.md sec. 9a).
 * Deleted, it gives no force and no stable-step limit; its nodes keep their lumped masses (so
 * momentum is conserved), and a node whose elements are all deleted moves freely. The stress
 * work it took stays in the internal energy (the energy balance keeps it). Decisions are made
 * after each force evaluation from the element's state, identically on every rank that
 * evaluates it, and then exchanged so that every rank holds the mesh-wide flags (the contact
 * surfaces are rebuilt from them): the run is the same on any number of ranks. */
#include "fem/fem_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const pf_key pf_fem_erosion_keys[] = {
    {"plastic_strain", PF_KEY_REAL, 0, NULL, "", "delete an element once a quadrature point's equivalent plastic strain reaches this (models with 'eqps')", NULL},
    {"min_volume_ratio", PF_KEY_REAL, 0, NULL, "", "delete an element whose volume ratio V/V0 falls to this", NULL},
    {"max_volume_ratio", PF_KEY_REAL, 0, NULL, "", "delete an element whose volume ratio V/V0 reaches this", NULL},
    {"convert_to_particles", PF_KEY_BOOL, 0, "false", "",
     "a deleted element becomes a particle of the `type: particles` body that names this body (fem/particles.c)", NULL},
    PF_KEY_END};

int pf_fem_erosion_read(pf_fem_body *b, const pf_deck *d, const pf_node *body) {
  const pf_node *map = pf_node_get(body, "erosion");
  b->erode_eqps = b->erode_jmax = INFINITY, b->erode_jmin = -INFINITY;
  if (!map) return 0;
  if (pf_node_get(body, "peridynamic"))
    return pf_deck_error(d, map, "erosion", "body '%s': erosion of a body with a peridynamic: operator is not supported",
                         b->name);
  PF_CALL(pf_deck_real(d, map, "plastic_strain", &b->erode_eqps));
  PF_CALL(pf_deck_real(d, map, "min_volume_ratio", &b->erode_jmin));
  PF_CALL(pf_deck_real(d, map, "max_volume_ratio", &b->erode_jmax));
  if (pf_node_get(map, "plastic_strain")) { /* (an element of a material without one is not tested) */
    int some = 0;
    for (int m = 0; m < b->nmat; m++) some |= b->mats[m].eqps >= 0;
    if (!some)
      return pf_deck_error(d, pf_node_get(map, "plastic_strain"), "plastic_strain",
                           "the material of body '%s' has no equivalent plastic strain", b->name);
    if (!(b->erode_eqps > 0))
      return pf_deck_error(d, pf_node_get(map, "plastic_strain"), "plastic_strain", "must be positive (got %g)", b->erode_eqps);
  }
  if (pf_node_get(map, "min_volume_ratio") && !(b->erode_jmin > 0 && b->erode_jmin < 1))
    return pf_deck_error(d, pf_node_get(map, "min_volume_ratio"), "min_volume_ratio", "must lie in (0, 1) (got %g)",
                         b->erode_jmin);
  if (pf_node_get(map, "max_volume_ratio") && !(b->erode_jmax > 1))
    return pf_deck_error(d, pf_node_get(map, "max_volume_ratio"), "max_volume_ratio", "must exceed 1 (got %g)",
                         b->erode_jmax);
  PF_CALL(pf_deck_bool(d, map, "convert_to_particles", &b->convert));
  if (b->convert && b->mesh_entry)
    return pf_deck_error(d, pf_node_get(map, "convert_to_particles"), "convert_to_particles",
                         "body '%s': converting the elements of a body with material_regions is not supported", b->name);
  if (pf_node_count(map) == !!pf_node_get(map, "convert_to_particles"))
    return pf_deck_error(d, map, "erosion", "give at least one of plastic_strain, min_volume_ratio, max_volume_ratio");
  b->erosion = 1;
  PF_MALLOC(b->mesh_eroded, b->mesh.nelem);
  if (b->convert) PF_MALLOC(b->mesh_converted, b->mesh.nelem);
  return 0;
}

/* After element e's forces: 1 when it reached a limit (its volume ratio J at the step's end). */
int pf_fem_erosion_due(const pf_fem_body *b, pf_int e, double J) {
  if (!(J > b->erode_jmin && J < b->erode_jmax)) return 1;
  const int eqps = pf_fem_element_material(b, e)->eqps;
  for (int g = 0; g < b->nqp && eqps >= 0; g++)
    if (b->state[(size_t)b->nstate * ((size_t)b->nqp * e + g) + eqps] >= b->erode_eqps) return 1;
  return 0;
}

/* Every rank's newly due elements, merged into the mesh-wide flags. Collective (when the body
 * has erosion). */
int pf_fem_erosion_sync(pf_fem_body *b) {
  if (!b->erosion) return 0;
  int n = (int)b->n_due, R = pf_comm_size(), *cnt, *dis, total = 0;
  PF_MALLOC(cnt, 2 * R);
  dis = cnt + R;
  int ierr = MPI_Allgather(&n, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < R; r++) dis[r] = total, total += cnt[r];
  pf_gid *all = NULL;
  if (!ierr && total > 0) {
    all = malloc(sizeof *all * (size_t)total);
    if (!all) ierr = PF_ERR_MEMORY;
    if (!ierr) ierr = MPI_Allgatherv(b->due, n, PF_GID_MPI, all, cnt, dis, PF_GID_MPI, MPI_COMM_WORLD);
  }
  for (int k = 0; !ierr && k < total; k++)
    if (!b->mesh_eroded[all[k]]) b->mesh_eroded[all[k]] = 1, b->n_eroded++;
  free(all), free(cnt);
  b->n_due = 0;
  PF_CHECK(!ierr, PF_ERR_LIB, "body '%s': exchanging the eroded elements failed", b->name);
  return 0;
}

const uint8_t *pf_fem_body_eroded(const pf_fem_body *b, long *count) {
  *count = b->n_eroded;
  return b->erosion ? b->mesh_eroded : NULL;
}
