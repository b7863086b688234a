/* What a re-partition or a checkpoint must carry besides the points: every body's bond rows
 * (PD families, FE node adjacency), and the bodies' per-element state as whole tables. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

pf_body_span pf_sim_span(const pf_sim *sim, int b) {
  return (pf_body_span){b, sim->gid0[b], sim->body_start[b], sim->body_start[b + 1] - sim->body_start[b]};
}

int pf_sim_bond_rows(const pf_sim *sim, pf_bond_rows *rows) {
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body_span s = pf_sim_span(sim, b);
    PF_CALL(sim->body[b].ops->rows(sim->body[b].data, sim->pts, &s, rows));
  }
  return 0;
}

int pf_sim_bond_fields(const pf_sim *sim, pf_bond_rows *rows) {
  for (int b = 0; b < sim->nbodies; b++)
    PF_CALL(pf_body_bond_fields(&sim->body[b], rows));
  return 0;
}

int pf_sim_table_shape(const pf_sim *sim, int b, pf_table *t, pf_int *nlocal) {
  const pf_body *body = &sim->body[b];
  memset(t, 0, sizeof *t);
  *nlocal = 0;
  if (!pf_body_table_shape(body, &t->total, &t->ncomp, nlocal)) return 0;
  snprintf(t->name, sizeof t->name, "fem_%s", sim->body_name[b]);
  return 1;
}

int pf_sim_body_tables(const pf_sim *sim, pf_table *t, int *n) {
  *n = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    pf_table *tb = &t[*n];
    pf_int nlocal;
    if (!pf_sim_table_shape(sim, b, tb, &nlocal)) continue;
    (*n)++;
    pf_gid *id;
    double *data;
    PF_MALLOC(id, nlocal);
    PF_MALLOC(data, (size_t)nlocal * tb->ncomp);
    tb->id = id, tb->data = data;
    tb->n = sim->body[b].ops->table_get(sim->body[b].data, id, data);
  }
  return 0;
}

void pf_sim_body_tables_free(pf_table *t, int n) {
  for (int k = 0; k < n; k++) free((void *)t[k].id), free((void *)t[k].data);
}
