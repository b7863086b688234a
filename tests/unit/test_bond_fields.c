/* Per-bond fields (core/bond_fields.c) through migration and checkpoints, on any number of
 * ranks (tests/regression/mpi_bond_fields.sh runs it on 2 and 3).
 *   40 points on a line (global id g at x = g), each bonded to the ids within 3 of its own. Each
 *   rank builds the rows of an equal slice of the ids, with bond fields the code has never seen,
 *   whose values are closed-form functions of the bond's ids i -> j:
 *     test_tag    float,  restart:   1000 i + j
 *     test_pair   double, restart:   (i, j); registered with 1 component on rank 1 (which appends
 *                                    i only), 2 elsewhere, so that the rows widen to 2 and rank
 *                                    1's bonds have j = -1 (the field's init)
 *     test_parity uint8,  no restart: (i + j) mod 2 (init 3)
 *     test_rank0  uint8,  restart:   1, registered and set on rank 0 only (init 0)
 *   registered in another order on odd ranks;
 *   migration to rank (7 g + 3) mod N: every point arrives at its rank with its whole row, and
 *     every bond's values are the closed forms (the ranks' fields agreed: each rank has all four);
 *   a checkpoint written after the migration and read back on the same ranks (each reader takes
 *     an equal slice of the file): every bond's values again, and test_parity, not written, at its
 *     init;
 *   a checkpoint of the same rows without test_tag, and the first one read with test_pair of 3
 *     components: refused, the message naming the field.
 * usage: test_bond_fields [SCRATCH_DIR]   (default /tmp) */
#include "test_common.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

enum { NPOINTS = 40, REACH = 3 };

/* The rank that builds point g's row: g in [N r / size, N (r + 1) / size). */
static int origin(pf_gid g) {
  const int size = pf_comm_size();
  int r = 0;
  while (g >= (pf_gid)NPOINTS * (r + 1) / size) r++;
  return r;
}

static int migrated_to(pf_gid g) { return (int)((7 * g + 3) % pf_comm_size()); }

/* Point g's neighbours, ascending: the ids within REACH. */
static int neighbours(pf_gid g, pf_gid *out) {
  int n = 0;
  for (pf_gid j = g - REACH; j <= g + REACH; j++)
    if (j >= 0 && j < NPOINTS && j != g) out[n++] = j;
  return n;
}

static void register_fields(pf_bond_rows *rows, int rank, int all_ranks_alike) {
  const int odd = rank % 2, pair_comps = !all_ranks_alike && rank == 1 ? 1 : 2;
  for (int q = 0; q < 4; q++) {
    switch (odd ? 3 - q : q) {
    case 0: PF_TEST_OK(pf_bond_rows_field_register(rows, "test_tag", PF_BOND_FLOAT, 1, PF_FIELD_RESTART, 0)); break;
    case 1:
      PF_TEST_OK(pf_bond_rows_field_register(rows, "test_pair", PF_BOND_DOUBLE, pair_comps, PF_FIELD_RESTART, -1));
      break;
    case 2: PF_TEST_OK(pf_bond_rows_field_register(rows, "test_parity", PF_BOND_UINT8, 1, 0, 3)); break;
    default:
      if (all_ranks_alike || rank == 0)
        PF_TEST_OK(pf_bond_rows_field_register(rows, "test_rank0", PF_BOND_UINT8, 1, PF_FIELD_RESTART, 0));
    }
  }
}

/* This rank's slice of the points, with their rows. */
static pf_points *build(pf_bond_rows *rows) {
  const int rank = pf_comm_rank(), size = pf_comm_size();
  const pf_gid lo = (pf_gid)NPOINTS * rank / size, hi = (pf_gid)NPOINTS * (rank + 1) / size;
  pf_points *pts = NULL;
  PF_TEST_OK(pf_points_create((pf_int)(hi - lo), &pts));
  pts->n_global = NPOINTS;
  PF_TEST_OK(pf_bond_rows_init(rows));
  register_fields(rows, rank, 0);
  for (pf_gid g = lo; g < hi; g++) {
    const pf_int i = (pf_int)(g - lo);
    pts->gid[i] = g, pts->X[3 * i] = pts->y[3 * i] = (double)g;
    pts->vol[i] = pts->cell[i] = pts->m[i] = 1.0;
    pf_gid nb[2 * REACH];
    float tag[2 * REACH];
    double pair[4 * REACH];
    uint8_t parity[2 * REACH], one[2 * REACH];
    const int n = neighbours(g, nb), pc = rank == 1 ? 1 : 2;
    for (int k = 0; k < n; k++) {
      tag[k] = (float)(1000 * g + nb[k]), parity[k] = (uint8_t)((g + nb[k]) % 2), one[k] = 1;
      pair[pc * k] = (double)g;
      if (pc == 2) pair[pc * k + 1] = (double)nb[k];
    }
    const pf_bond_values v[4] = {
        {"test_tag", tag, 1}, {"test_pair", pair, pc}, {"test_parity", parity, 1}, {"test_rank0", one, 1}};
    PF_TEST_OK(pf_bond_rows_append(rows, n, nb, rank == 0 ? 4 : 3, v));
  }
  return pts;
}

/* Every bond of every row holds its closed-form values; parity_written: test_parity came with
 * the rows (else it is at its init, 3). */
static void check(const pf_points *pts, const pf_bond_rows *rows, int parity_written, const char *when) {
  const float *tag = pf_bond_rows_field_data(rows, "test_tag", PF_BOND_FLOAT);
  const double *pair = pf_bond_rows_field_data(rows, "test_pair", PF_BOND_DOUBLE);
  const uint8_t *parity = pf_bond_rows_field_data(rows, "test_parity", PF_BOND_UINT8);
  const uint8_t *rank0 = pf_bond_rows_field_data(rows, "test_rank0", PF_BOND_UINT8);
  const pf_bond_field *pf = pf_bond_rows_field(rows, "test_pair");
  int ok = rows->n == pts->n_owned && rows->nfields == 4 && tag && pair && parity && rank0 && pf->ncomp == 2;
  if (!ok) {
    fprintf(stderr, "%s (rank %d): %d rows for %d points, %d bond fields\n", when, pf_comm_rank(), (int)rows->n,
            (int)pts->n_owned, rows->nfields);
    pf_test_failures++;
    return;
  }
  int bad = 0;
  for (pf_int i = 0; i < pts->n_owned; i++) {
    const pf_gid g = pts->gid[i];
    pf_gid nb[2 * REACH];
    const int n = neighbours(g, nb);
    bad += rows->offset[i + 1] - rows->offset[i] != n;
    for (int64_t k = rows->offset[i], q = 0; q < n && k < rows->offset[i + 1]; k++, q++) {
      const pf_gid j = rows->gid[k];
      bad += j != nb[q] || tag[k] != (float)(1000 * g + j);
      bad += pair[2 * k] != (double)g || pair[2 * k + 1] != (origin(g) == 1 ? -1.0 : (double)j);
      bad += parity[k] != (parity_written ? (g + j) % 2 : 3) || rank0[k] != (origin(g) == 0);
    }
  }
  if (bad) fprintf(stderr, "%s (rank %d): %d wrong bonds or values\n", when, pf_comm_rank(), bad);
  pf_test_failures += bad > 0;
}

static void migrate(pf_points *pts, pf_bond_rows *rows) {
  int dest[NPOINTS];
  pf_int body_start[2];
  for (pf_int i = 0; i < pts->n_owned; i++) dest[i] = migrated_to(pts->gid[i]);
  PF_TEST_OK(pf_points_migrate(pts, rows, dest, 1, body_start));
  pf_int want = 0;
  for (pf_gid g = 0; g < NPOINTS; g++) want += migrated_to(g) == pf_comm_rank();
  PF_TEST_TRUE(pts->n_owned == want);
  for (pf_int i = 0; i < pts->n_owned; i++) PF_TEST_TRUE(migrated_to(pts->gid[i]) == pf_comm_rank());
}

/* Read path into rows registered as register_fields does on every rank (pair_comps components
 * of test_pair); returns the error code, the store in *pts. */
static int read_back(const char *path, int pair_comps, pf_points **pts, pf_bond_rows *rows, double *t) {
  const char *names[] = {"time"};
  PF_TEST_OK(pf_bond_rows_init(rows));
  register_fields(rows, pf_comm_rank(), 1);
  if (pair_comps != 2)
    PF_TEST_OK(pf_bond_rows_field_register(rows, "test_pair", PF_BOND_DOUBLE, pair_comps, PF_FIELD_RESTART, -1));
  int format;
  return pf_checkpoint_read(path, pts, rows, 1, names, t, 1, &format);
}

/* A read of path that must be refused naming the field. */
static void refused(const char *path, int pair_comps, const char *field) {
  pf_points *pts = NULL;
  pf_bond_rows rows;
  double t = 0;
  pf_error_set_quiet(1);
  const int ierr = read_back(path, pair_comps, &pts, &rows, &t);
  if (ierr != PF_ERR_INPUT || !strstr(pf_error_message(), field)) {
    fprintf(stderr, "reading %s: error %d '%s', expected an input error naming '%s'\n", path, ierr,
            pf_error_message(), field);
    pf_test_failures++;
  }
  pf_error_clear();
  pf_error_set_quiet(0);
  pf_points_destroy(&pts);
  pf_bond_rows_free(&rows);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *dir = argc > 1 ? argv[1] : "/tmp";
  int pid = (int)getpid();
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  char path[512], bare[512];
  snprintf(path, sizeof path, "%s/pf_test_bond_fields_%d.h5", dir, pid);
  snprintf(bare, sizeof bare, "%s/pf_test_bond_fields_%d_bare.h5", dir, pid);

  pf_bond_rows rows;
  pf_points *pts = build(&rows);
  migrate(pts, &rows);
  check(pts, &rows, 1, "after the migration");

  const char *names[] = {"time"};
  const double written = 2.5;
  PF_TEST_OK(pf_checkpoint_write(path, pts, &rows, 1, names, &written, 0, NULL));
  pf_points *back = NULL;
  pf_bond_rows rows_back;
  double t = 0;
  PF_TEST_OK(read_back(path, 2, &back, &rows_back, &t));
  PF_TEST_TRUE(t == written);
  if (back) check(back, &rows_back, 0, "read from the checkpoint");

  pf_bond_rows plain; /* the same rows without test_tag */
  PF_TEST_OK(pf_bond_rows_init(&plain));
  PF_TEST_OK(pf_bond_rows_field_register(&plain, "test_pair", PF_BOND_DOUBLE, 2, PF_FIELD_RESTART, -1));
  PF_TEST_OK(pf_bond_rows_field_register(&plain, "test_parity", PF_BOND_UINT8, 1, 0, 3));
  PF_TEST_OK(pf_bond_rows_field_register(&plain, "test_rank0", PF_BOND_UINT8, 1, PF_FIELD_RESTART, 0));
  for (pf_int i = 0; i < rows.n; i++) PF_TEST_OK(pf_bond_rows_append_row(&plain, &rows, i));
  PF_TEST_OK(pf_checkpoint_write(bare, pts, &plain, 1, names, &written, 0, NULL));
  refused(bare, 2, "test_tag");
  refused(path, 3, "test_pair");

  pf_test_remove_shared(path);
  pf_test_remove_shared(bare);
  pf_bond_rows_free(&rows), pf_bond_rows_free(&rows_back), pf_bond_rows_free(&plain);
  pf_points_destroy(&pts), pf_points_destroy(&back);
  return pf_test_finish();
}
