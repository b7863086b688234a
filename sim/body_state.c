/* What a re-partition or a checkpoint must carry besides the points: every body's bond rows
 * (PD families, FE node adjacency), and the FE bodies' element state as whole tables. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_sim_bond_rows(const pf_sim *sim, pf_bond_rows *rows) {
  for (int b = 0; b < sim->nbodies; b++)
    if (sim->body[b]) PF_CALL(pf_pd_body_bond_rows(sim->body[b], sim->pts, rows));
    else
      PF_CALL(pf_fem_body_node_rows(sim->fem[b], sim->pts, sim->body_start[b],
                                    sim->body_start[b + 1] - sim->body_start[b], sim->gid0[b], rows));
  return 0;
}

int pf_sim_bond_fields(const pf_sim *sim, pf_bond_rows *rows) {
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_pd_body *pd = sim->body[b] ? sim->body[b] : pf_fem_body_pd(sim->fem[b]);
    if (pd) PF_CALL(pf_pd_body_bond_fields(pd, rows));
  }
  return 0;
}

void pf_sim_fem_table_name(const pf_sim *sim, int b, char *out, size_t len) {
  snprintf(out, len, "fem_%s", sim->body_name[b]);
}

int pf_sim_fem_tables(const pf_sim *sim, pf_table *t, int *n) {
  *n = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    if (!sim->fem[b]) continue;
    const pf_fem_body *f = sim->fem[b];
    pf_table *tb = &t[(*n)++];
    memset(tb, 0, sizeof *tb);
    pf_sim_fem_table_name(sim, b, tb->name, sizeof tb->name);
    tb->total = pf_fem_body_mesh(f)->nelem;
    tb->ncomp = pf_fem_body_state_ncomp(f);
    pf_gid *id;
    double *data;
    PF_MALLOC(id, pf_fem_body_nlocal(f));
    PF_MALLOC(data, (size_t)pf_fem_body_nlocal(f) * tb->ncomp);
    tb->id = id, tb->data = data;
    tb->n = pf_fem_body_state_get(f, id, data);
  }
  return 0;
}

void pf_sim_fem_tables_free(pf_table *t, int n) {
  for (int k = 0; k < n; k++) free((void *)t[k].id), free((void *)t[k].data);
}

/* The FE bodies' state over a re-partition: gathered whole before, set back after. */
int pf_sim_settle_keeping_fem(pf_sim *sim, pf_bond_rows *rows) {
  pf_table t[PF_MAX_BODIES];
  double *full[PF_MAX_BODIES] = {NULL}, stable[PF_MAX_BODIES];
  int n = 0, ierr = pf_sim_fem_tables(sim, t, &n);
  for (int k = 0, b = 0; b < sim->nbodies; b++) {
    stable[b] = sim->fem[b] ? pf_min_all(pf_fem_body_stable_dt(sim->fem[b])) : INFINITY;
    if (!sim->fem[b] || ierr) continue;
    if (!(full[b] = malloc(sizeof(double) * ((size_t)t[k].total * t[k].ncomp + 1))))
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    else ierr = pf_table_allgather(&t[k], full[b]);
    k++;
  }
  pf_sim_fem_tables_free(t, n);
  if (!ierr) ierr = pf_sim_settle(sim, rows, 0);
  for (int b = 0; b < sim->nbodies; b++) {
    if (sim->fem[b] && !ierr) {
      pf_fem_body_state_set(sim->fem[b], full[b]);
      pf_fem_body_set_stable_dt(sim->fem[b], stable[b]);
    }
    free(full[b]);
  }
  return ierr;
}
