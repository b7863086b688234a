/* Spreading the bodies over the MPI ranks. At set-up every rank generates the
 * bodies' points (cheap and deterministic), takes an equal slice of the global ids, finds the
 * bonds of its slice, and the slices are partitioned (Zoltan RCB or METIS, weighted by bond
 * count) and migrated to their owners with their bond rows. Ghosts are then exactly the
 * off-rank neighbours named in the rows. A re-partition at an output step reuses the same
 * migration with the full state. Global ids are the generation order, so nothing a point
 * computes depends on the partition. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const pf_key pf_parallel_keys[] = {
    {"decomposition", PF_KEY_STRING, 0, "rcb", "",
     "rcb (Zoltan recursive coordinate bisection) | metis (k-way on the bond graph)", NULL},
    {"rebalance_threshold", PF_KEY_REAL, 0, "0", "",
     "at output steps, re-partition when the ranks' work (bonds + points, and the contact "
     "candidates as a second phase balanced on its own, docs/parallel.md sec. 5) exceeds this "
     "multiple of its mean; 0: never", NULL},
    PF_KEY_END};

int pf_sim_setup_parallel(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *root = pf_deck_root(d), *par = pf_node_get(root, "parallel"), *out = pf_node_get(root, "output");
  const char *method = "rcb", *layout = "joined";
  PF_CALL(pf_deck_string(d, par, "decomposition", &method));
  if (!strcmp(method, "rcb")) sim->decomposition = PF_PARTITION_RCB;
  else if (!strcmp(method, "metis")) sim->decomposition = PF_PARTITION_METIS;
  else
    return pf_deck_error(d, pf_node_get(par, "decomposition"), "decomposition",
                         "unknown decomposition '%s' (known: rcb, metis)", method);
  PF_CALL(pf_deck_real(d, par, "rebalance_threshold", &sim->rebalance_threshold));
  if (!(sim->rebalance_threshold == 0 || sim->rebalance_threshold >= 1))
    return pf_deck_error(d, pf_node_get(par, "rebalance_threshold"), "rebalance_threshold",
                         "must be 0 (never) or at least 1 (got %g)", sim->rebalance_threshold);
  PF_CALL(pf_deck_string(d, out, "layout", &layout));
  if (strcmp(layout, "joined") && strcmp(layout, "spread"))
    return pf_deck_error(d, pf_node_get(out, "layout"), "layout", "unknown layout '%s' (known: joined, spread)", layout);
  sim->spread_output = !strcmp(layout, "spread");
  if (sim->spread_output && sim->rebalance_threshold > 0)
    return pf_deck_error(d, pf_node_get(par, "rebalance_threshold"), "rebalance_threshold",
                         "re-partitioning changes each rank's points, which a spread Exodus file "
                         "set cannot follow; use output.layout: joined");
  return 0;
}

/* This rank's equal slice of the global ids, with the points' data from the clouds. */
static int make_slice(const pf_sim *sim, const pf_point_cloud *pc, const pf_gid *gid0, pf_points **out) {
  pf_gid n = gid0[sim->nbodies];
  int rank = pf_comm_rank(), size = pf_comm_size();
  pf_gid lo = n * rank / size, hi = n * (rank + 1) / size;
  PF_CALL(pf_points_create((pf_int)(hi - lo), out));
  pf_points *p = *out;
  p->n_global = n;
  int b = 0;
  for (pf_gid g = lo; g < hi; g++) {
    while (g >= gid0[b + 1]) b++;
    pf_int i = (pf_int)(g - lo), j = (pf_int)(g - gid0[b]);
    memcpy(&p->X[3 * i], &pc[b].X[3 * j], 3 * sizeof(double));
    memcpy(&p->y[3 * i], &pc[b].X[3 * j], 3 * sizeof(double));
    p->vol[i] = pc[b].vol[j];
    p->cell[i] = pc[b].cell[j];
    p->gid[i] = g;
    p->body[i] = b;
  }
  return 0;
}

/* The work imbalance of the owned points (rows[i]: point i's bonds + 1; extra[i]: its
 * interactions' work, or NULL) once each point is on rank owner[i] (owner NULL: where it is).
 * With the bodies' force loop and the interactions as two phases that every rank passes one
 * after the other (pf_partition_phases), a step takes the sum over the phases of the largest
 * rank's work, so the imbalance is that sum over the sum of the phases' means (one phase:
 * max / mean). Collective. */
static int imbalance_of(const int *rows, const int *extra, const int *owner, pf_int n, double *imbalance) {
  const int size = pf_comm_size(), rank = pf_comm_rank(), phases = pf_partition_phases(extra, n);
  double *load = calloc((size_t)(2 * size), sizeof *load);
  PF_CHECK(load, PF_ERR_MEMORY, "out of memory");
  for (pf_int i = 0; i < n; i++) {
    const int r = owner ? owner[i] : rank;
    load[r] += rows[i];
    if (extra) load[(phases - 1) * size + r] += extra[i]; /* (one phase: all zero) */
  }
  int ierr = MPI_Allreduce(MPI_IN_PLACE, load, 2 * size, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS;
  double slowest = 0, sum = 0;
  for (int p = 0; p < 2; p++) {
    double max = 0;
    for (int r = 0; r < size; r++) max = fmax(max, load[p * size + r]), sum += load[p * size + r];
    slowest += max;
  }
  *imbalance = sum > 0 ? slowest * size / sum : 1;
  free(load);
  PF_CHECK(!ierr, PF_ERR_LIB, "MPI_Allreduce of the ranks' work failed");
  return 0;
}

/* Each owned point's bonds + 1 (pf_partition_weight without interactions) into w. */
static void row_weights(const pf_bond_rows *rows, pf_int n, int *w) {
  for (pf_int i = 0; i < n; i++) w[i] = pf_partition_weight(rows, NULL, i);
}

/* Keep the owned points' row weights and ids of a partition for the next checks (rows in the
 * points' order); on failure the checks build the rows. */
static void keep_row_work(pf_sim *sim, const pf_bond_rows *rows) {
  const pf_int n = sim->pts->n_owned;
  free(sim->row_work), free(sim->row_work_gid);
  sim->row_work = malloc(sizeof(int) * ((size_t)n + 1));
  sim->row_work_gid = malloc(sizeof(pf_gid) * ((size_t)n + 1));
  sim->row_work_n = sim->row_work && sim->row_work_gid ? n : -1;
  if (sim->row_work_n < 0) return;
  row_weights(rows, n, sim->row_work);
  memcpy(sim->row_work_gid, sim->pts->gid, sizeof(pf_gid) * (size_t)n);
}

/* The kept row weights, when the owned points are still those they were kept for (no element
 * became a particle since; an eroded element's nodes are weighed with their rows of the last
 * partition until the next). */
static const int *kept_row_work(const pf_sim *sim) {
  const pf_int n = sim->pts->n_owned;
  if (sim->row_work_n != n || (n > 0 && memcmp(sim->row_work_gid, sim->pts->gid, sizeof(pf_gid) * (size_t)n)))
    return NULL;
  return sim->row_work;
}

int pf_sim_settle(pf_sim *sim, pf_bond_rows *rows, const int *extra, int fresh, double *imbalance) {
  int *owner_of = NULL, *dest = NULL;
  pf_int *local = NULL;
  int ierr = pf_partition_compute(sim->decomposition, sim->pts, rows, extra, &owner_of);
  if (!ierr && imbalance) { /* the work each rank will have, by the partition's own weights */
    const size_t n = (size_t)sim->pts->n_owned + 1;
    int *w = malloc(sizeof(int) * n), *to = malloc(sizeof(int) * n);
    if (!w || !to) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    for (pf_int i = 0; !ierr && i < sim->pts->n_owned; i++) to[i] = owner_of[sim->pts->gid[i]];
    if (!ierr) row_weights(rows, sim->pts->n_owned, w);
    if (!ierr) ierr = imbalance_of(w, extra, to, sim->pts->n_owned, imbalance);
    free(w), free(to);
  }
  if (!ierr && !(dest = malloc(sizeof(int) * ((size_t)sim->pts->n_owned + 1))))
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (pf_int i = 0; !ierr && i < sim->pts->n_owned; i++) dest[i] = owner_of[sim->pts->gid[i]];
  if (!ierr) ierr = pf_points_migrate(sim->pts, rows, dest, sim->nbodies, sim->body_start);
  free(dest);
  if (!ierr) keep_row_work(sim, rows);
  if (!ierr && !(local = malloc(sizeof(pf_int) * ((size_t)rows->offset[rows->n] + 1))))
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  if (!ierr) ierr = pf_points_add_ghosts(sim->pts, rows, owner_of, local);
  for (int b = 0; b < sim->nbodies && !ierr; b++) {
    const pf_body_span s = pf_sim_span(sim, b);
    ierr = sim->body[b].ops->attach(sim->body[b].data, sim->pts, &s, rows, local, fresh);
  }
  free(owner_of), free(local);
  pf_bond_rows_release(rows); /* (the bodies hold their bonds now) */
  pf_memory_trim();
  if (!ierr) ierr = pf_sim_interactions_attach(sim);
  return ierr;
}

void pf_sim_number_bodies(pf_sim *sim, const pf_gid *count) {
  sim->gid0[0] = 0;
  for (int b = 0; b < sim->nbodies; b++) sim->gid0[b + 1] = sim->gid0[b] + count[b];
}

int pf_sim_distribute(pf_sim *sim, const pf_point_cloud *pc) {
  pf_gid count[PF_MAX_BODIES], *gid0 = sim->gid0;
  for (int b = 0; b < sim->nbodies; b++) count[b] = pc[b].n;
  pf_sim_number_bodies(sim, count);
  PF_CALL(make_slice(sim, pc, gid0, &sim->pts));
  pf_bond_rows rows;
  PF_CALL(pf_bond_rows_init(&rows));
  int ierr = 0;
  pf_int first = 0;
  for (int b = 0; b < sim->nbodies && !ierr; b++) {
    pf_int n = 0;
    while (first + n < sim->pts->n_owned && sim->pts->body[first + n] == b) n++;
    const pf_body_span s = {b, gid0[b], first, n};
    const pf_body *body = &sim->body[b];
    char where[512];
    pf_node_where(sim->deck, pf_node_item(pf_node_get(pf_deck_root(sim->deck), "bodies"), b), where, sizeof where);
    pf_error_context("(body '%s', %s)", sim->body_name[b], where);
    ierr = pf_body_find_rows(body, &pc[b], sim->pts, &s, &rows);
    pf_error_context(NULL);
    first += n;
  }
  if (!ierr) ierr = pf_sim_settle(sim, &rows, NULL, 1, NULL);
  pf_bond_rows_free(&rows);
  return ierr;
}

/* The bodies' tables over a re-partition, gathered whole before and set back after, with the
 * stable step of their last force evaluation. */
static int settle_keeping_tables(pf_sim *sim, pf_bond_rows *rows, const int *extra, double *imbalance) {
  pf_table t[PF_MAX_BODIES];
  double *full[PF_MAX_BODIES] = {NULL}, stable[PF_MAX_BODIES];
  int n = 0, ierr = pf_sim_body_tables(sim, t, &n);
  for (int k = 0, b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    stable[b] = pf_body_carries_stable_dt(body) ? pf_body_stable_dt_all(body, sim->pts) : INFINITY;
    if (ierr || !pf_body_table_shape(body, &(pf_gid){0}, &(int){0}, &(pf_int){0})) continue;
    if (!(full[b] = malloc(sizeof(double) * ((size_t)t[k].total * t[k].ncomp + 1))))
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    else ierr = pf_table_allgather(&t[k], full[b]);
    k++;
  }
  pf_sim_body_tables_free(t, n);
  if (!ierr) ierr = pf_sim_settle(sim, rows, extra, 0, imbalance);
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_body *body = &sim->body[b];
    if (!ierr && full[b]) pf_body_table_set(body, full[b]);
    if (!ierr) pf_body_set_stable_dt(body, stable[b]);
    free(full[b]);
  }
  return ierr;
}

/* The re-partition check: this partition's imbalance (imbalance_of) by the row weights kept at
 * the last partition (built from the bodies' rows when they are not there) and the
 * interactions' current work in extra. Collective. */
static int current_imbalance(pf_sim *sim, const int *extra, double *before) {
  const int *kept = kept_row_work(sim);
  if (pf_max_all(kept ? 0 : 1) == 0) /* (every rank takes the same way) */
    return imbalance_of(kept, extra, NULL, sim->pts->n_owned, before);
  int *w = NULL, ierr;
  pf_bond_rows rows;
  PF_CALL(pf_bond_rows_init(&rows));
  ierr = pf_sim_bond_rows(sim, &rows);
  if (!ierr && !(w = malloc(sizeof(int) * ((size_t)sim->pts->n_owned + 1))))
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  if (!ierr) row_weights(&rows, sim->pts->n_owned, w);
  if (!ierr) ierr = imbalance_of(w, extra, NULL, sim->pts->n_owned, before);
  free(w);
  pf_bond_rows_free(&rows);
  return ierr;
}

int pf_sim_rebalance(pf_sim *sim) {
  if (sim->rebalance_threshold <= 0 || pf_comm_size() == 1) return 0;
  int *extra = calloc((size_t)sim->pts->n_owned + 1, sizeof *extra), ierr = 0;
  double before = 0, after = 0;
  if (!extra) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  if (!ierr) pf_sim_interactions_work(sim, extra); /* (each point's interactions' work) */
  if (!ierr) ierr = current_imbalance(sim, extra, &before);
  if (!ierr && before > sim->rebalance_threshold) {
    pf_bond_rows rows;
    ierr = pf_bond_rows_init(&rows);
    if (!ierr) ierr = pf_sim_bond_rows(sim, &rows);
    if (!ierr) ierr = settle_keeping_tables(sim, &rows, extra, &after);
    pf_bond_rows_free(&rows);
  }
  free(extra);
  if (ierr || !(before > sim->rebalance_threshold)) return ierr;
  pf_log("step %ld: re-partitioned (work imbalance %.3f > %.3f); now %.3f\n", sim->step, before,
         sim->rebalance_threshold, after);
  return 0;
}
