/* The state of an FE body's elements as rows of a global table (one row per mesh element):
 * stress and material history at each quadrature point, the hourglass forces and the
 * bulk-viscosity pressure of the last evaluation, the element energies and whether the element
 * is deleted (fem/erosion.c). Checkpoints write
 * it, a restart or a re-partition gives it back. */
#include "fem/fem_impl.h"

#include <string.h>

int pf_fem_body_state_ncomp(const pf_fem_body *b) { return b->nqp * (6 + b->nstate) + 12 + 1 + 3 + 1; }

static void pack(const pf_fem_body *b, pf_int e, double *row) {
  const size_t nq = (size_t)b->nqp;
  memcpy(row, &b->sigma[6 * nq * e], sizeof(double) * 6 * nq);
  row += 6 * nq;
  memcpy(row, &b->state[(size_t)b->nstate * nq * e], sizeof(double) * b->nstate * nq);
  row += (size_t)b->nstate * nq;
  memcpy(row, &b->hgq[12 * (size_t)e], sizeof(double) * 12);
  row[12] = b->bvq[e];
  memcpy(row + 13, &b->energy[3 * (size_t)e], sizeof(double) * 3);
  row[16] = pf_fem_element_eroded(b, e);
}

static void unpack(pf_fem_body *b, pf_int e, const double *row) {
  const size_t nq = (size_t)b->nqp;
  memcpy(&b->sigma[6 * nq * e], row, sizeof(double) * 6 * nq);
  row += 6 * nq;
  memcpy(&b->state[(size_t)b->nstate * nq * e], row, sizeof(double) * b->nstate * nq);
  row += (size_t)b->nstate * nq;
  memcpy(&b->hgq[12 * (size_t)e], row, sizeof(double) * 12);
  b->bvq[e] = row[12];
  memcpy(&b->energy[3 * (size_t)e], row + 13, sizeof(double) * 3);
}

pf_int pf_fem_body_state_get(const pf_fem_body *b, pf_gid *ids, double *data) {
  const int nc = pf_fem_body_state_ncomp(b);
  pf_int k = 0;
  for (pf_int e = 0; e < b->nel; e++)
    if (b->own[e]) {
      ids[k] = b->eid[e];
      pack(b, e, &data[(size_t)nc * k++]);
    }
  return k;
}

void pf_fem_body_state_set(pf_fem_body *b, const double *full) {
  const int nc = pf_fem_body_state_ncomp(b);
  for (pf_int e = 0; e < b->nel; e++) unpack(b, e, &full[(size_t)nc * b->eid[e]]);
  if (!b->erosion) return;
  b->n_eroded = 0;
  for (pf_int e = 0; e < b->mesh.nelem; e++) {
    b->mesh_eroded[e] = full[(size_t)nc * e + nc - 1] != 0;
    b->n_eroded += b->mesh_eroded[e];
    if (b->convert) b->mesh_converted[e] = b->mesh_eroded[e]; /* (a deleted element is converted at its step's end) */
  }
  if (b->convert) pf_fem_lumped_masses(b, b->pts);
}

int pf_fem_body_history(pf_fem_body *b, int restore) {
  const size_t nc = (size_t)pf_fem_body_state_ncomp(b);
  if (restore) {
    PF_CHECK(b->committed && b->committed_nel == b->nel, PF_ERR_RUN,
             "FE body '%s': no committed history for its %" PF_INT_FMT " elements", b->name, b->nel);
    for (pf_int e = 0; e < b->nel; e++) unpack(b, e, &b->committed[nc * e]);
    return 0;
  }
  if (b->committed_nel != b->nel || !b->committed) {
    free(b->committed);
    b->committed_nel = 0;
    PF_MALLOC(b->committed, nc * (size_t)b->nel);
    b->committed_nel = b->nel;
  }
  for (pf_int e = 0; e < b->nel; e++) pack(b, e, &b->committed[nc * e]);
  return 0;
}

pf_int pf_fem_body_nlocal(const pf_fem_body *b) { return b->nel; }

void pf_fem_body_set_stable_dt(pf_fem_body *b, double dt) { b->stable_dt = dt; }
