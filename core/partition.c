/* Partitioning the points over the ranks: Zoltan's recursive coordinate bisection
 * of the reference positions, each point weighted by its bond count plus one (the work of its
 * force loop: the batched kernels evaluate a broken bond under a mask, and the elastic-plastic
 * loop's test of it costs about an intact bond's evaluation, docs/parallel.md sec. 5), or METIS
 * k-way on the bond graph with the same vertex weights. When the caller gives the work of the
 * points' interactions (contact) and some rank has any, that is a second weight, balanced on its
 * own: the interactions are a phase of the step after the bodies' forces, and a rank light in
 * one phase waits for the others in it. Zoltan's RCB then tries a cut along every axis and keeps
 * the one whose larger imbalance of the two weights is smallest (RCB_MULTICRITERIA_NORM 3;
 * zoltan/src/rcb/rcb.c), METIS takes them as two constraints (Karypis & Kumar 1998). The result
 * is the owner of every global id, the same table on every rank. */
#include "core/core.h"

#include <metis.h>
#include <stdlib.h>
#include <string.h>
#include <zoltan.h>

typedef struct {
  const pf_points *pts;
  const pf_bond_rows *rows;
  const int *extra;
  int phases;
} zctx;

int pf_partition_weight(const pf_bond_rows *rows, const int *extra, pf_int i) {
  return 1 + (int)(rows->offset[i + 1] - rows->offset[i]) + (extra ? extra[i] : 0);
}

/* Point i's work in each phase of the step: w[0] its bonds + 1 (the bodies' force loop), and
 * with two phases w[1] = extra[i] (the interactions'), which the ranks reach one after the
 * other. */
static void phase_weights(const pf_bond_rows *rows, const int *extra, int phases, pf_int i, int *w) {
  w[0] = pf_partition_weight(rows, NULL, i);
  if (phases > 1) w[1] = extra[i];
}

int pf_partition_phases(const int *extra, pf_int n) {
  long long sum = 0;
  for (pf_int i = 0; extra && i < n; i++) sum += extra[i];
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return sum > 0 ? 2 : 1;
}

static int z_num_obj(void *data, int *ierr) {
  *ierr = ZOLTAN_OK;
  return ((const zctx *)data)->pts->n_owned;
}

static void z_obj_list(void *data, int ngid, int nlid, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids,
                       int wdim, float *w, int *ierr) {
  (void)ngid, (void)nlid;
  const zctx *z = data;
  for (pf_int i = 0; i < z->pts->n_owned; i++) {
    gids[i] = (ZOLTAN_ID_TYPE)z->pts->gid[i];
    lids[i] = (ZOLTAN_ID_TYPE)i;
    int pw[2];
    phase_weights(z->rows, z->extra, z->phases, i, pw);
    for (int k = 0; k < wdim; k++) w[(size_t)wdim * i + k] = (float)pw[k];
  }
  *ierr = ZOLTAN_OK;
}

static int z_num_geom(void *data, int *ierr) {
  (void)data;
  *ierr = ZOLTAN_OK;
  return 3;
}

static void z_geom_multi(void *data, int ngid, int nlid, int nobj, ZOLTAN_ID_PTR gids,
                         ZOLTAN_ID_PTR lids, int ndim, double *geom, int *ierr) {
  (void)ngid, (void)nlid, (void)gids, (void)ndim;
  const zctx *z = data;
  for (int k = 0; k < nobj; k++) memcpy(&geom[3 * k], &z->pts->X[3 * (size_t)lids[k]], 3 * sizeof(double));
  *ierr = ZOLTAN_OK;
}

/* Zoltan RCB: the new rank of each owned point into part[]. */
static int rcb(const pf_points *pts, const pf_bond_rows *rows, const int *extra, int *part) {
  static int initialized = 0;
  float ver;
  if (!initialized) PF_CHECK(Zoltan_Initialize(0, NULL, &ver) == ZOLTAN_OK, PF_ERR_LIB, "Zoltan_Initialize failed");
  initialized = 1;
  struct Zoltan_Struct *zz = Zoltan_Create(MPI_COMM_WORLD);
  PF_CHECK(zz, PF_ERR_LIB, "Zoltan_Create failed");
  const char *params[][2] = {{"DEBUG_LEVEL", "0"},     {"LB_METHOD", "RCB"},        {"NUM_GID_ENTRIES", "1"},
                             {"NUM_LID_ENTRIES", "1"}, {"RETURN_LISTS", "PARTS"},  {"IMBALANCE_TOL", "1.01"},
                             {"RCB_OUTPUT_LEVEL", "0"}, {"KEEP_CUTS", "0"}};
  for (size_t k = 0; k < sizeof params / sizeof params[0]; k++) Zoltan_Set_Param(zz, params[k][0], params[k][1]);
  zctx z = {pts, rows, extra, pf_partition_phases(extra, pts->n_owned)};
  /* Two phases: Zoltan's multicriteria RCB, each cut along whichever axis gives the smallest
   * largest imbalance of the two weights (the max-norm, RCB_MULTICRITERIA_NORM 3). */
  Zoltan_Set_Param(zz, "OBJ_WEIGHT_DIM", z.phases > 1 ? "2" : "1");
  if (z.phases > 1) Zoltan_Set_Param(zz, "RCB_MULTICRITERIA_NORM", "3");
  Zoltan_Set_Num_Obj_Fn(zz, z_num_obj, &z);
  Zoltan_Set_Obj_List_Fn(zz, z_obj_list, &z);
  Zoltan_Set_Num_Geom_Fn(zz, z_num_geom, &z);
  Zoltan_Set_Geom_Multi_Fn(zz, z_geom_multi, &z);
  int changes, ngid, nlid, nimp, nexp, *imp_procs, *imp_parts, *exp_procs, *exp_parts;
  ZOLTAN_ID_PTR imp_g, imp_l, exp_g, exp_l;
  int st = Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &imp_g, &imp_l, &imp_procs, &imp_parts,
                               &nexp, &exp_g, &exp_l, &exp_procs, &exp_parts);
  if (st == ZOLTAN_OK)
    for (int k = 0; k < nexp; k++) part[exp_l[k]] = exp_parts[k];
  Zoltan_LB_Free_Part(&imp_g, &imp_l, &imp_procs, &imp_parts);
  Zoltan_LB_Free_Part(&exp_g, &exp_l, &exp_procs, &exp_parts);
  Zoltan_Destroy(&zz);
  PF_CHECK(st == ZOLTAN_OK, PF_ERR_LIB, "Zoltan_LB_Partition (RCB) returned %d", st);
  return 0;
}

/* Gather counts and the displacements of a gather of per-rank counts. */
static int gather_counts(int mine, int **counts, int **displs, int *total) {
  int size = pf_comm_size();
  PF_MALLOC(*counts, size);
  PF_MALLOC(*displs, size + 1);
  MPI_Allgather(&mine, 1, MPI_INT, *counts, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) (*displs)[r + 1] = (*displs)[r] + (*counts)[r];
  *total = (*displs)[size];
  return 0;
}

/* owner_of[gid] from each rank's (gid, part) pairs. */
static int owner_table(const pf_points *pts, const int *part, int *owner_of) {
  int *cnt, *dsp, total;
  PF_CALL(gather_counts(pts->n_owned, &cnt, &dsp, &total));
  pf_gid *g = malloc(sizeof(pf_gid) * (size_t)(total + 1));
  int *p = malloc(sizeof(int) * (size_t)(total + 1));
  int ok = g && p;
  if (ok) {
    MPI_Allgatherv(pts->gid, pts->n_owned, PF_GID_MPI, g, cnt, dsp, PF_GID_MPI, MPI_COMM_WORLD);
    MPI_Allgatherv(part, pts->n_owned, MPI_INT, p, cnt, dsp, MPI_INT, MPI_COMM_WORLD);
    for (int k = 0; k < total; k++) owner_of[g[k]] = p[k];
  }
  free(g), free(p), free(cnt), free(dsp);
  PF_CHECK(ok, PF_ERR_MEMORY, "out of memory gathering %d owners", total);
  return 0;
}

/* The bond graph in METIS's CSR form, vertices in global-id order (rank 0 only). */
typedef struct {
  idx_t n, ncon, *xadj, *adj, *vwgt;
} graph;

static int gather_graph(const pf_points *pts, const pf_bond_rows *rows, const int *extra, graph *gr) {
  int rank = pf_comm_rank(), n = pts->n_owned;
  int nnz = (int)rows->offset[n], *cnt = NULL, *dsp = NULL, *ecnt = NULL, *edsp = NULL, total, etotal;
  const int nc = pf_partition_phases(extra, n);
  PF_CALL(gather_counts(n, &cnt, &dsp, &total));
  PF_CALL(gather_counts(nnz, &ecnt, &edsp, &etotal));
  pf_gid *gid = NULL, *nbr = NULL;
  int *len = NULL, *mylen = NULL, *w = NULL, *myw = NULL;
  PF_MALLOC(mylen, n);
  PF_MALLOC(myw, nc * n);
  for (int i = 0; i < n; i++) mylen[i] = (int)(rows->offset[i + 1] - rows->offset[i]);
  for (int i = 0; i < n; i++) phase_weights(rows, extra, nc, i, &myw[nc * i]);
  if (rank == 0) {
    PF_MALLOC(gid, total);
    PF_MALLOC(len, total);
    PF_MALLOC(w, nc * total);
    PF_MALLOC(nbr, etotal);
  }
  MPI_Gatherv(pts->gid, n, PF_GID_MPI, gid, cnt, dsp, PF_GID_MPI, 0, MPI_COMM_WORLD);
  MPI_Gatherv(mylen, n, MPI_INT, len, cnt, dsp, MPI_INT, 0, MPI_COMM_WORLD);
  if (nc > 1) /* (the counts in weights) */
    for (int r = 0; r < pf_comm_size(); r++) cnt[r] *= nc, dsp[r] *= nc;
  MPI_Gatherv(myw, nc * n, MPI_INT, w, cnt, dsp, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Gatherv(rows->gid, nnz, PF_GID_MPI, nbr, ecnt, edsp, PF_GID_MPI, 0, MPI_COMM_WORLD);
  if (rank == 0) {
    gr->n = total, gr->ncon = nc;
    PF_MALLOC(gr->xadj, total + 1);
    PF_MALLOC(gr->vwgt, nc * total);
    PF_MALLOC(gr->adj, etotal);
    int64_t *start;
    PF_MALLOC(start, total + 1);
    for (int k = 0; k < total; k++) {
      start[gid[k] + 1] = len[k];
      for (int c = 0; c < nc; c++) gr->vwgt[nc * gid[k] + c] = w[nc * k + c];
    }
    for (int g = 0; g < total; g++) start[g + 1] += start[g], gr->xadj[g + 1] = (idx_t)start[g + 1];
    for (int k = 0, e = 0; k < total; e += len[k], k++)
      for (int q = 0; q < len[k]; q++) gr->adj[start[gid[k]] + q] = (idx_t)nbr[e + q];
    free(start);
  }
  free(gid), free(len), free(w), free(myw), free(nbr), free(mylen), free(cnt), free(dsp), free(ecnt), free(edsp);
  return 0;
}

static int metis(const pf_points *pts, const pf_bond_rows *rows, const int *extra, int *owner_of) {
  graph gr = {0};
  PF_CALL(gather_graph(pts, rows, extra, &gr));
  int st = METIS_OK;
  if (pf_comm_rank() == 0) {
    idx_t nparts = pf_comm_size(), objval, options[METIS_NOPTIONS], *part;
    PF_MALLOC(part, gr.n);
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 20240101; /* fixed: the same partition on every run */
    options[METIS_OPTION_UFACTOR] = 10;    /* 1 % load imbalance */
    st = METIS_PartGraphKway(&gr.n, &gr.ncon, gr.xadj, gr.adj, gr.vwgt, NULL, NULL, &nparts, NULL, NULL,
                             options, &objval, part);
    for (idx_t g = 0; g < gr.n; g++) owner_of[g] = (int)part[g];
    free(part), free(gr.xadj), free(gr.adj), free(gr.vwgt);
  }
  MPI_Bcast(&st, 1, MPI_INT, 0, MPI_COMM_WORLD);
  PF_CHECK(st == METIS_OK, PF_ERR_LIB, "METIS_PartGraphKway returned %d", st);
  MPI_Bcast(owner_of, (int)pts->n_global, MPI_INT, 0, MPI_COMM_WORLD);
  return 0;
}

int pf_partition_compute(pf_partition_method method, const pf_points *pts, const pf_bond_rows *rows,
                         const int *extra, int **owner_of) {
  PF_CHECK(pts->n_global < (pf_gid)INT32_MAX, PF_ERR_INPUT,
           "%" PF_GID_FMT " points: partitioning handles fewer than 2^31", pts->n_global);
  PF_MALLOC(*owner_of, pts->n_global);
  int size = pf_comm_size();
  if (size == 1) return 0;
  if (pts->n_global < 2 * (pf_gid)size) { /* too few points to bisect: one block of ids a rank */
    pf_log("%" PF_GID_FMT " points on %d ranks: points split by global id%s\n", pts->n_global, size,
           pts->n_global < size ? ", some ranks hold none" : "");
    for (pf_gid g = 0; g < pts->n_global; g++) (*owner_of)[g] = (int)(g * size / pts->n_global);
    return 0;
  }
  if (method == PF_PARTITION_METIS) return metis(pts, rows, extra, *owner_of);
  int *part;
  PF_MALLOC(part, pts->n_owned);
  int ierr = rcb(pts, rows, extra, part);
  if (!ierr) ierr = owner_table(pts, part, *owner_of);
  free(part);
  return ierr;
}
