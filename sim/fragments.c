/* Fragments (`output: fragments: true`): the connected components of the intact bonds of each
 * peridynamic body (and of each FE body's coupled peridynamic nodes, whose rows also hold the
 * element neighbours), as in Peridigm's and LAMMPS's fragment post-processing of the expanding
 * tube and fragmenting cylinder. A point's fragment is the smallest global id in its component:
 * each rank joins its owned points through their intact bonds (union-find), and its local
 * components take the smallest label over themselves and the ghosts they are bonded to until no
 * label changes on any rank. The fixpoint is the component minimum whatever the order or the
 * partition, so the labels - and the fragment masses - are the same on any number of ranks.
 * Bonds are broken from both ends alike by every damage law here (the rows are symmetric), so a
 * bond joins its ends or neither.
 *
 * Output: the point field "fragment" (-1 on bodies without bonds) at every Exodus step, and
 * <file>.fragments.csv (rank 0) with one row per fragment per Exodus step: time, body, fragment
 * id, points, mass, centre of mass and mean velocity. The run summary gives the count and the
 * largest masses at the end. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* one record: body, fragment, the point's global id (the order of the sums), points, mass,
 * m y, m v */
enum { F_BODY, F_ID, F_GID, F_N, F_M, F_X, F_V = F_X + 3, F_NREC = F_V + 3 };

static const pf_family *body_family(const pf_sim *sim, int b) {
  const pf_body *body = &sim->body[b];
  return pf_body_family(body);
}

/* The representative of owned point p (path halving). */
static pf_int root_of(pf_int *parent, pf_int p) {
  while (parent[p] != p) p = parent[p] = parent[parent[p]];
  return p;
}

/* Join the owned ends of the intact bonds (the smaller root becomes the representative) and
 * list the intact bonds whose other end is a ghost, as (owned, ghost) pairs into *cross. */
static int join_owned(const pf_sim *sim, pf_int *parent, pf_int **cross, int64_t *ncross) {
  const pf_int n = sim->pts->n_owned;
  int64_t cap = 0;
  *cross = NULL, *ncross = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_family *fam = body_family(sim, b);
    for (pf_int i = 0; fam && i < fam->n; i++)
      for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
        if (fam->broken[k]) continue;
        const pf_int p = fam->first + i, j = fam->neighbor[k];
        if (j < n) {
          const pf_int rp = root_of(parent, p), rj = root_of(parent, j);
          if (rp < rj) parent[rj] = rp;
          else parent[rp] = rj;
          continue;
        }
        if (*ncross == cap) {
          cap = 2 * cap + 1024;
          pf_int *grown = realloc(*cross, sizeof **cross * 2 * (size_t)cap);
          PF_CHECK(grown, PF_ERR_MEMORY, "out of memory for the fragments' bonds across ranks");
          *cross = grown;
        }
        (*cross)[2 * *ncross] = p, (*cross)[2 * *ncross + 1] = j, (*ncross)++;
      }
  }
  return 0;
}

/* Label every point with its fragment: the owned points joined through their intact bonds
 * (union-find, one pass over the bonds), each local component taking the smallest label over
 * its points and the ghosts it is bonded to, until no label changes on any rank (one halo
 * exchange a round; a round a rank boundary that a component crosses). Collective. */
static int label_fragments(pf_sim *sim, double *label) {
  pf_points *pts = sim->pts;
  const pf_int n = pts->n_owned;
  for (pf_int i = 0; i < n; i++) label[i] = -1;
  for (int b = 0; b < sim->nbodies; b++) {
    const pf_family *fam = body_family(sim, b);
    for (pf_int i = 0; fam && i < fam->n; i++) label[fam->first + i] = (double)pts->gid[fam->first + i];
  }
  pf_int *parent = malloc(sizeof *parent * ((size_t)n + 1)), *cross = NULL;
  double *low = malloc(sizeof *low * ((size_t)n + 1));
  int64_t ncross = 0;
  int ierr = parent && low ? 0 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (pf_int i = 0; !ierr && i < n; i++) parent[i] = i;
  if (!ierr) ierr = join_owned(sim, parent, &cross, &ncross);
  for (pf_int i = 0; !ierr && i < n; i++) parent[i] = root_of(parent, i);
  ierr = pf_agree(ierr, "labelling the fragments"); /* (every rank takes the rounds, or none) */
  while (!ierr) {
    ierr = pf_points_exchange(pts, label, 1);
    if (ierr) break;
    for (pf_int i = 0; i < n; i++) low[i] = INFINITY;
    for (pf_int i = 0; i < n; i++)
      if (label[i] >= 0) low[parent[i]] = fmin(low[parent[i]], label[i]);
    for (int64_t c = 0; c < ncross; c++)
      if (label[cross[2 * c + 1]] >= 0) {
        const pf_int r = parent[cross[2 * c]];
        low[r] = fmin(low[r], label[cross[2 * c + 1]]);
      }
    long changed = 0;
    for (pf_int i = 0; i < n; i++)
      if (label[i] >= 0 && low[parent[i]] < label[i]) label[i] = low[parent[i]], changed++;
    if (pf_max_all((double)changed) == 0) break;
  }
  free(parent), free(low), free(cross);
  return ierr;
}

static int by_id(const void *a, const void *b) {
  const double *x = a, *y = b;
  for (int q = F_BODY; q <= F_GID; q++)
    if (x[q] != y[q]) return (x[q] > y[q]) - (x[q] < y[q]);
  return 0;
}

/* Sort the points' records by (body, fragment, global id) and sum those of each fragment in
 * that order (the same sums on any number of ranks). Returns the count. */
static int merge_records(double *r, int n) {
  qsort(r, (size_t)n, sizeof(double) * F_NREC, by_id);
  int out = 0;
  for (int k = 0; k < n; k++) {
    double *a = &r[F_NREC * k], *o = &r[F_NREC * (out - 1)];
    if (out > 0 && o[F_BODY] == a[F_BODY] && o[F_ID] == a[F_ID])
      for (int q = F_N; q < F_NREC; q++) o[q] += a[q];
    else memmove(&r[F_NREC * out++], a, sizeof(double) * F_NREC);
  }
  return out;
}

/* This rank's records, one per labelled owned point. */
static int local_records(const pf_sim *sim, const double *label, double **rec, int *n) {
  const pf_points *p = sim->pts;
  PF_MALLOC(*rec, (size_t)F_NREC * ((size_t)p->n_owned + 1));
  int c = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    if (label[i] < 0) continue;
    double *r = &(*rec)[F_NREC * c++];
    r[F_BODY] = p->body[i], r[F_ID] = label[i], r[F_GID] = (double)p->gid[i], r[F_N] = 1, r[F_M] = p->m[i];
    for (int a = 0; a < 3; a++) r[F_X + a] = p->m[i] * p->y[3 * i + a], r[F_V + a] = p->m[i] * p->v[3 * i + a];
  }
  *n = c;
  return 0;
}

/* Gather every rank's records to rank 0 and merge them there (*all NULL elsewhere). */
static int gather_records(const double *mine, int n, double **all, int *nall) {
  int size = pf_comm_size(), rank = pf_comm_rank(), len = F_NREC * n, *cnt = NULL, *dsp = NULL;
  PF_MALLOC(cnt, size);
  PF_MALLOC(dsp, size + 1);
  MPI_Gather(&len, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
  dsp[0] = 0;
  for (int r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  *all = NULL, *nall = 0;
  if (rank == 0) PF_MALLOC(*all, (size_t)dsp[size] + 1);
  MPI_Gatherv(mine, len, MPI_DOUBLE, *all, cnt, dsp, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (rank == 0) *nall = merge_records(*all, dsp[size] / F_NREC);
  free(cnt), free(dsp);
  return 0;
}

static int write_csv(pf_sim *sim, const double *r, int n) {
  FILE *f = fopen(sim->fragments_path, sim->fragments_rows ? "a" : "w");
  PF_CHECK(f, PF_ERR_RUN, "cannot open %s for writing", sim->fragments_path);
  if (!sim->fragments_rows)
    fprintf(f, "time,body,fragment,points,mass,x,y,z,vx,vy,vz\n");
  for (int k = 0; k < n; k++) {
    const double *a = &r[F_NREC * k], m = a[F_M];
    fprintf(f, "%.9e,%s,%.0f,%.0f,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e\n", sim->t, sim->body_name[(int)a[F_BODY]],
            a[F_ID], a[F_N], m, a[F_X] / m, a[F_X + 1] / m, a[F_X + 2] / m, a[F_V] / m, a[F_V + 1] / m,
            a[F_V + 2] / m);
  }
  sim->fragments_rows += n;
  PF_CHECK(fclose(f) == 0, PF_ERR_RUN, "cannot write %s", sim->fragments_path);
  return 0;
}

static int by_mass_desc(const void *a, const void *b) {
  const double x = ((const double *)a)[F_M], y = ((const double *)b)[F_M];
  return (x < y) - (x > y);
}

/* The end-of-run line: fragments per body and the largest masses. Rank 0. */
static void log_summary(const pf_sim *sim, double *r, int n) {
  qsort(r, (size_t)n, sizeof(double) * F_NREC, by_mass_desc);
  for (int b = 0; b < sim->nbodies; b++) {
    int count = 0;
    char top[256] = "";
    for (int k = 0; k < n; k++)
      if ((int)r[F_NREC * k + F_BODY] == b && count++ < 5) {
        size_t len = strlen(top);
        snprintf(top + len, sizeof top - len, "%s%.3g", count > 1 ? ", " : "", r[F_NREC * k + F_M] * 1e3);
      }
    if (count) pf_log("  fragments of %s: %d (largest %s g)\n", sim->body_name[b], count, top);
  }
}

int pf_sim_fragments(pf_sim *sim, int final) {
  if (!sim->fragments) return 0;
  double *label = pf_points_field_get(sim->pts, "fragment"), *mine = NULL, *all = NULL;
  int n = 0, nall = 0;
  PF_CALL(label_fragments(sim, label));
  int ierr = local_records(sim, label, &mine, &n);
  if (!ierr) ierr = gather_records(mine, n, &all, &nall);
  if (!ierr && all && !sim->opt.no_output) ierr = write_csv(sim, all, nall);
  if (!ierr && all && final) log_summary(sim, all, nall);
  free(mine), free(all);
  return ierr;
}

void pf_sim_fragments_name(pf_sim *sim) {
  size_t stem = strlen(sim->exodus_path);
  if (stem > 2 && !strcmp(sim->exodus_path + stem - 2, ".e")) stem -= 2;
  snprintf(sim->fragments_path, sizeof sim->fragments_path, "%.*s.fragments.csv", (int)stem, sim->exodus_path);
}

int pf_sim_fragments_setup(pf_sim *sim) {
  if (!sim->fragments) return 0;
  int idx;
  PF_CALL(pf_points_field_register(sim->pts, "fragment", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT, &idx));
  return 0;
}
