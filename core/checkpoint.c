/* Checkpoints in parallel HDF5 (MPI-IO, collective writes). Layout:
 *   /points/{gid,body,X,u,v,f,m,vol,cell}   one row per point, ranks' points one after another
 *   /fields/<name>                          [n][ncomp], attributes ncomp, flags
 *   /bonds/{count,gid}                      row lengths per point, then the bonds in that order
 *   /bonds/<name>                           [nbonds][ncomp] each bond field flagged
 *                                           PF_FIELD_RESTART, of its own type (uint8, float,
 *                                           double); a reader refuses a file without one of
 *                                           the fields it registers
 *   /tables/<name>                          [total][ncomp] whole tables (written by rank 0)
 *   attributes of "/": the named scalars (time, step, ...), written alike by every rank, and
 *                      the integer "format" (PF_CHECKPOINT_FORMAT; a file without it is of
 *                      format 1), which a reader checks before anything else.
 * The file is written as path.tmp and renamed by rank 0 once every rank has closed it, so a
 * kill at any moment leaves the previous checkpoint whole.
 * A failed write (a full disk) is agreed by every rank after each collective call; the ranks
 * then leave the file without closing it (HDF5's collective close of a file it cannot write
 * fails on one rank and hangs the others, and leaves the file half destroyed), rank 0 removes
 * path.tmp, and the process must end through MPI_Abort (pf_io_abandon).
 * A reader on any number of ranks
 * takes an equal slice of the rows; the caller re-partitions.
 * Integrity: every dataset is chunked and carries HDF5's Fletcher32 checksum filter (parallel
 * filtered writes, collective, HDF5 >= 1.10.2), and the file is written in the HDF5 1.10
 * format, whose superblock, object headers (with the attributes) and chunk indexes carry
 * HDF5's own checksums: a flipped byte fails a read, which the reader refuses naming the file
 * and the dataset. It refuses a dataset without the checksum too (a file written before them),
 * and checks what it read before using it (core/checkpoint_check.c). Reads are independent,
 * so a rank that meets a bad chunk returns from HDF5 alone; every read's outcome is then
 * agreed by all ranks (pf_error_agree). */
#include "core/checkpoint_impl.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct {
  hid_t file;
  const char *path;   /* the file open (path.tmp while writing) */
  const char *target; /* the checkpoint's name */
  hsize_t total, offset, count; /* rows: over all ranks, this rank's first and number */
} h5io;

#define H5_TRY(io, ok, what) PF_CHECK((ok), PF_ERR_LIB, "HDF5: %s failed (checkpoint %s)", (what), (io)->path)

/* What went wrong, from HDF5's error stack: its innermost message (where the error was found,
 * e.g. "data error detected by Fletcher32 checksum"), before another call clears it. */
static herr_t innermost(unsigned n, const H5E_error2_t *e, void *out) {
  if (n == 0) snprintf(out, 256, "%s: %s", e->func_name ? e->func_name : "", e->desc ? e->desc : "");
  return 0;
}

static void hdf5_reason(char *out) {
  out[0] = '\0';
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, out);
  H5Eclear2(H5E_DEFAULT);
}

/* Why a call failed: errno when it is set (the POSIX drivers), else HDF5's innermost message. */
static void h5_reason(int ok, int err, char *buf) {
  buf[0] = '\0';
  if (ok) return;
  if (err) snprintf(buf, 256, "%s", strerror(err));
  else hdf5_reason(buf);
}

/* A write that failed on this rank (err: errno right after it, why: the HDF5 error stack), agreed
 * with the other ranks. */
static int write_agree(const h5io *io, int ok, const char *what, const char *why) {
  int ierr = 0;
  if (!ok)
    ierr = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                          "cannot write the checkpoint %s: HDF5 failed writing %s to %s (%s); the previous "
                          "checkpoint, if any, is kept",
                          io->target, what, io->path, why);
  return pf_agree(ierr, "writing the checkpoint %s", io->target);
}

/* This rank's range of n items among all ranks' (an exclusive scan). */
static void rank_range(hsize_t n, hsize_t *total, hsize_t *offset) {
  unsigned long long mine = n, before = 0, all = 0;
  MPI_Exscan(&mine, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (pf_comm_rank() == 0) before = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  *total = all, *offset = before;
}

/* Select rows [offset, offset + count) x ncomp of a [total][ncomp] space, and the memory space. */
static void select_rows(hid_t fspace, hid_t *mspace, hsize_t offset, hsize_t count, int ncomp) {
  hsize_t start[2] = {offset, 0}, cnt[2] = {count, (hsize_t)ncomp}, one[2] = {1, (hsize_t)ncomp};
  int rank = ncomp > 1 ? 2 : 1;
  *mspace = H5Screate_simple(rank, count ? cnt : one, NULL);
  if (count) H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, cnt, NULL);
  else H5Sselect_none(fspace), H5Sselect_none(*mspace);
}

/* Chunks of equal rows, up to 1 MiB each (the last one, stored whole, wastes little), with the
 * Fletcher32 checksum (an empty dataset stays contiguous: it has no data to check and HDF5
 * refuses chunks larger than the dataset). */
static hid_t checksummed_layout(hsize_t total, int ncomp, hid_t type) {
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (total == 0) return dcpl;
  hsize_t most = (hsize_t)(1 << 20) / ((hsize_t)ncomp * H5Tget_size(type));
  if (most < 1) most = 1;
  const hsize_t nchunks = (total + most - 1) / most;
  hsize_t chunk[2] = {(total + nchunks - 1) / nchunks, (hsize_t)ncomp};
  H5Pset_chunk(dcpl, ncomp > 1 ? 2 : 1, chunk);
  H5Pset_fletcher32(dcpl);
  return dcpl;
}

static int write_rows(const h5io *io, const char *name, hid_t type, int ncomp, const void *data) {
  hsize_t dims[2] = {io->total, (hsize_t)ncomp};
  hid_t fspace = H5Screate_simple(ncomp > 1 ? 2 : 1, dims, NULL), mspace;
  hid_t dcpl = checksummed_layout(io->total, ncomp, type);
  hid_t dset = H5Dcreate2(io->file, name, type, fspace, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  select_rows(fspace, &mspace, io->offset, io->count, ncomp);
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  errno = 0;
  herr_t st = dset >= 0 ? H5Dwrite(dset, type, mspace, fspace, dxpl, data) : -1;
  char why[256];
  h5_reason(st >= 0, errno, why);
  H5Pclose(dxpl), H5Sclose(mspace), H5Sclose(fspace);
  if (dset >= 0) H5Dclose(dset);
  return write_agree(io, st >= 0, name, why);
}


/* Is the dataset [total][ncomp] (or [total] when ncomp is 1), and checksummed when not empty? */
static int shape_ok(const h5io *io, hid_t dset, const char *name, int ncomp, char *msg, size_t len) {
  hid_t sp = H5Dget_space(dset), dcpl = H5Dget_create_plist(dset);
  hsize_t dims[2] = {0, 1};
  int rank = H5Sget_simple_extent_ndims(sp);
  if (rank == 1 || rank == 2) H5Sget_simple_extent_dims(sp, dims, NULL);
  unsigned flags = 0, conf = 0;
  size_t nelmts = 0;
  int summed = dims[0] == 0 || H5Pget_filter_by_id2(dcpl, H5Z_FILTER_FLETCHER32, &flags, &nelmts, NULL, 0, NULL,
                                                     &conf) >= 0;
  H5Eclear2(H5E_DEFAULT);
  H5Sclose(sp), H5Pclose(dcpl);
  int ok = (rank == 1 || rank == 2) && dims[0] == io->total && dims[1] == (hsize_t)ncomp && (ncomp == 1 || rank == 2);
  if (!ok)
    snprintf(msg, len, "checkpoint %s: dataset %s has %d dimensions (%llu x %llu), expected %llu x %d: the file is "
             "damaged or is not a perifem checkpoint of this run", io->path, name, rank, (unsigned long long)dims[0],
             (unsigned long long)dims[1], (unsigned long long)io->total, ncomp);
  else if (!summed)
    snprintf(msg, len, "checkpoint %s: dataset %s has no Fletcher32 checksum: written by a perifem from before "
             "checkpoints were checksummed, or by another tool", io->path, name);
  return ok && summed;
}

/* This rank's rows of the dataset name, checked against its checksums; every rank agrees on the
 * outcome. (Independent reads: a rank whose chunk fails leaves HDF5 alone, without a hang.) */
static int read_rows(const h5io *io, const char *name, hid_t type, int ncomp, void *data) {
  char msg[640] = "", why[256];
  hid_t dset = H5Dopen2(io->file, name, H5P_DEFAULT);
  int ok = dset >= 0;
  if (!ok) hdf5_reason(why), snprintf(msg, sizeof msg, "checkpoint %s: cannot open dataset %s (HDF5: %s): the file "
                                      "is damaged or is not a perifem checkpoint", io->path, name, why);
  if (ok) ok = shape_ok(io, dset, name, ncomp, msg, sizeof msg);
  if (ok) {
    hid_t fspace = H5Dget_space(dset), mspace;
    select_rows(fspace, &mspace, io->offset, io->count, ncomp);
    ok = H5Dread(dset, type, mspace, fspace, H5P_DEFAULT, data) >= 0;
    if (!ok) hdf5_reason(why); /* (before the next call clears HDF5's error stack) */
    H5Sclose(mspace), H5Sclose(fspace);
    if (!ok) snprintf(msg, sizeof msg, "checkpoint %s: dataset %s cannot be read (HDF5: %s): the "
                                        "file is damaged", io->path, name, why);
  }
  if (dset >= 0) H5Dclose(dset);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

static int int_attr(const h5io *io, hid_t obj, const char *name, int *value, int write) {
  hid_t a;
  if (write) {
    hid_t sp = H5Screate(H5S_SCALAR);
    a = H5Acreate2(obj, name, H5T_NATIVE_INT, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
  } else a = H5Aopen(obj, name, H5P_DEFAULT);
  H5_TRY(io, a >= 0, name);
  herr_t st = write ? H5Awrite(a, H5T_NATIVE_INT, value) : H5Aread(a, H5T_NATIVE_INT, value);
  H5Aclose(a);
  H5_TRY(io, st >= 0, name);
  return 0;
}

/* Create (why NULL) or open path on every rank; a failed open leaves HDF5's reason in why. */
static hid_t open_file(const char *path, int create, char *why) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL);
  if (create) H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST); /* checksummed metadata */
  hid_t f = create ? H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : H5Fopen(path, H5F_ACC_RDONLY, fapl);
  if (f < 0 && why) hdf5_reason(why);
  H5Pclose(fapl);
  return f;
}

/* ---- write ------------------------------------------------------------------ */

static int write_points(const h5io *io, const pf_points *p) {
  PF_CALL(write_rows(io, "/points/gid", H5T_NATIVE_INT64, 1, p->gid));
  PF_CALL(write_rows(io, "/points/body", H5T_NATIVE_INT32, 1, p->body));
  const char *vec[] = {"/points/X", "/points/u", "/points/v", "/points/f"};
  const double *vdata[] = {p->X, p->u, p->v, p->f};
  for (int k = 0; k < 4; k++) PF_CALL(write_rows(io, vec[k], H5T_NATIVE_DOUBLE, 3, vdata[k]));
  PF_CALL(write_rows(io, "/points/m", H5T_NATIVE_DOUBLE, 1, p->m));
  PF_CALL(write_rows(io, "/points/vol", H5T_NATIVE_DOUBLE, 1, p->vol));
  PF_CALL(write_rows(io, "/points/cell", H5T_NATIVE_DOUBLE, 1, p->cell));
  for (int k = 0; k < p->nfields; k++) {
    char name[64];
    snprintf(name, sizeof name, "/fields/%s", p->fields[k].name);
    PF_CALL(write_rows(io, name, H5T_NATIVE_DOUBLE, p->fields[k].ncomp, p->fields[k].data));
    hid_t d = H5Dopen2(io->file, name, H5P_DEFAULT);
    int ncomp = p->fields[k].ncomp, flags = p->fields[k].flags;
    int ierr = d >= 0 ? int_attr(io, d, "ncomp", &ncomp, 1) : 1;
    if (!ierr) ierr = int_attr(io, d, "flags", &flags, 1);
    if (d >= 0) H5Dclose(d);
    PF_CALL(write_agree(io, !ierr, name, "an attribute"));
  }
  return 0;
}

static hid_t h5_type(pf_bond_type t) {
  return t == PF_BOND_UINT8 ? H5T_NATIVE_UINT8 : t == PF_BOND_FLOAT ? H5T_NATIVE_FLOAT : H5T_NATIVE_DOUBLE;
}

/* The rows' lengths and neighbours, then each restart bond field (the fields agreed on every
 * rank, so that each writes the same datasets). */
static int write_bonds(const h5io *pio, const pf_points *p, const pf_bond_rows *rows) {
  int32_t *count;
  PF_MALLOC(count, p->n_owned);
  for (pf_int i = 0; i < p->n_owned; i++) count[i] = (int32_t)(rows->offset[i + 1] - rows->offset[i]);
  int ierr = write_rows(pio, "/bonds/count", H5T_NATIVE_INT32, 1, count);
  free(count);
  if (ierr) return ierr;
  h5io io = *pio;
  io.count = (hsize_t)pf_bond_rows_nbonds(rows);
  rank_range(io.count, &io.total, &io.offset);
  PF_CALL(write_rows(&io, "/bonds/gid", H5T_NATIVE_INT64, 1, rows->gid));
  for (int k = 0; k < rows->nfields; k++) {
    const pf_bond_field *f = &rows->field[k];
    if (!(f->flags & PF_FIELD_RESTART)) continue;
    char name[64];
    snprintf(name, sizeof name, "/bonds/%s", f->name);
    PF_CALL(write_rows(&io, name, h5_type(f->type), f->ncomp, f->data));
  }
  return 0;
}

static int write_scalars(const h5io *io, int n, const char *const *names, const double *values) {
  for (int k = 0; k < n; k++) {
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(io->file, names[k], H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
    errno = 0;
    herr_t st = a >= 0 ? H5Awrite(a, H5T_NATIVE_DOUBLE, &values[k]) : -1;
    char why[256];
    h5_reason(st >= 0, errno, why);
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    PF_CALL(write_agree(io, st >= 0, names[k], why));
  }
  return 0;
}

/* A whole table, gathered and written by rank 0 (tables are small beside the points). */
static int write_table(const h5io *pio, const pf_table *t) {
  double *full = NULL;
  PF_MALLOC(full, (size_t)t->total * t->ncomp);
  int ierr = pf_agree(pf_table_allgather(t, full), "gathering the table %s", t->name);
  char name[128];
  snprintf(name, sizeof name, "/tables/%s", t->name);
  h5io io = *pio;
  io.total = (hsize_t)t->total, io.offset = 0, io.count = pf_comm_rank() == 0 ? (hsize_t)t->total : 0;
  if (!ierr) ierr = write_rows(&io, name, H5T_NATIVE_DOUBLE, t->ncomp, full);
  free(full);
  return ierr;
}

static int write_all(const h5io *io, const pf_points *pts, const pf_bond_rows *rows, int n,
                     const char *const *names, const double *values, int ntables, const pf_table *tables) {
  const char *groups[] = {"/points", "/fields", "/bonds", "/tables"};
  for (int k = 0; k < 4; k++) {
    errno = 0;
    hid_t g = H5Gcreate2(io->file, groups[k], H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    char why[256];
    h5_reason(g >= 0, errno, why);
    if (g >= 0) H5Gclose(g);
    PF_CALL(write_agree(io, g >= 0, groups[k], why));
  }
  PF_CALL(write_points(io, pts));
  PF_CALL(write_bonds(io, pts, rows));
  for (int k = 0; k < ntables; k++) PF_CALL(write_table(io, &tables[k]));
  int format = PF_CHECKPOINT_FORMAT, ierr = int_attr(io, io->file, "format", &format, 1);
  PF_CALL(write_agree(io, !ierr, "the attribute format", "an attribute"));
  return write_scalars(io, n, names, values);
}

/* Room for the file, taken by rank 0 before any dataset is created and again before the
 * collective close. HDF5 creates chunked datasets collectively (allocating their chunks behind a
 * barrier) and writes its metadata when it closes the file; a write that fails there on one rank
 * leaves the others waiting inside HDF5 for ever. So rank 0 first reserves the whole file (the
 * data's size plus a margin) and, once every dataset is written, a margin past the file's end
 * for the metadata still to come (HDF5 1.10's MPI-IO driver cannot tell its end of allocated
 * space); the close sets the size back to HDF5's end. A full disk (ENOSPC) or a file-size limit
 * (EFBIG) then fails here, where the ranks can still agree. */
#define PF_CHECKPOINT_MARGIN (1 << 20)

static int reserve_room(const h5io *io, int at_end, off_t bytes) {
  int ierr = 0;
  if (pf_comm_rank() == 0) {
    struct stat st;
    int fd = open(io->path, O_WRONLY), e = 0;
    if (fd < 0 || fstat(fd, &st)) e = errno ? errno : EIO;
    else e = posix_fallocate(fd, at_end ? st.st_size : 0, bytes);
    if (fd >= 0) close(fd);
    if (e)
      ierr = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                            "cannot write the checkpoint %s: no room for %s %lld kB of %s (%s); the previous "
                            "checkpoint, if any, is kept",
                            io->target, at_end ? "the last" : "its", (long long)(bytes >> 10), io->path, strerror(e));
  }
  return pf_agree(ierr, "writing the checkpoint %s", io->target);
}

/* The bytes of the checkpoint's datasets, over all ranks, plus 2 % and the margin (chunk
 * indexes, checksums, headers). */
static off_t data_bytes(const pf_points *pts, const pf_bond_rows *rows, int ntables, const pf_table *tables) {
  double point = 8 + 4 + 4 * 24 + 3 * 8 + 4, bond = 8, table = 0;
  for (int k = 0; k < pts->nfields; k++) point += 8.0 * pts->fields[k].ncomp;
  for (int k = 0; k < rows->nfields; k++)
    if (rows->field[k].flags & PF_FIELD_RESTART)
      bond += (double)rows->field[k].ncomp * (double)H5Tget_size(h5_type(rows->field[k].type));
  for (int k = 0; k < ntables; k++) table += 8.0 * (double)tables[k].total * tables[k].ncomp;
  double local = point * (double)pts->n_owned + bond * (double)pf_bond_rows_nbonds(rows);
  return (off_t)(1.02 * (pf_sum_all(local) + table)) + PF_CHECKPOINT_MARGIN;
}

/* Every rank agreed that the write failed: leave the file open (see the top), remove path.tmp.
 * Only a file some rank holds open is left for MPI_Abort: when no rank could create it (a folder
 * that does not exist), HDF5 holds nothing and the process may go on and finalize. */
static int discard(const h5io *io, int ierr) {
  if (pf_max_all(io->file >= 0) > 0) pf_io_abandon();
  if (pf_comm_rank() == 0) unlink(io->path);
  return ierr;
}

/* H5Fclose failed on this rank: the others may wait inside it for ever, and no reduction can
 * reach them. Say so, remove path.tmp and end every rank. */
static void close_failed(const h5io *io, const char *why) {
  pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                 "cannot write the checkpoint %s: HDF5 failed closing %s (%s); the previous checkpoint, if any, "
                 "is kept",
                 io->target, io->path, why);
  unlink(io->path);
  fflush(stdout), fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, PF_ERR_RUN);
}

int pf_checkpoint_write(const char *path, const pf_points *pts, pf_bond_rows *rows, int nscalars,
                        const char *const *names, const double *values, int ntables, const pf_table *tables) {
  char tmp[4200];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  PF_CALL(pf_bond_rows_fields_agree(rows));
  errno = 0;
  h5io io = {open_file(tmp, 1, NULL), tmp, path, 0, 0, (hsize_t)pts->n_owned};
  char why[256];
  h5_reason(io.file >= 0, errno, why);
  int ierr = write_agree(&io, io.file >= 0, "the file (H5Fcreate)", why);
  rank_range(io.count, &io.total, &io.offset);
  const off_t bytes = data_bytes(pts, rows, ntables, tables); /* (collective) */
  if (!ierr) ierr = reserve_room(&io, 0, bytes);
  if (!ierr) ierr = write_all(&io, pts, rows, nscalars, names, values, ntables, tables);
  if (!ierr) ierr = reserve_room(&io, 1, PF_CHECKPOINT_MARGIN);
  if (ierr) return discard(&io, ierr);
  errno = 0;
  if (H5Fclose(io.file) < 0) h5_reason(0, errno, why), close_failed(&io, why);
  MPI_Barrier(MPI_COMM_WORLD);
  int ok = 1;
  if (pf_comm_rank() == 0) ok = rename(tmp, path) == 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  PF_CHECK(ok, PF_ERR_RUN, "cannot rename checkpoint %s to %s", tmp, path);
  return 0;
}

/* ---- read ------------------------------------------------------------------- */

/* The rows (first dimension) of the dataset name, the same on every rank. */
static int dataset_rows(const h5io *io, const char *name, hsize_t *rows) {
  char msg[640] = "", why[256];
  hsize_t dims[2] = {0, 0};
  hid_t d = H5Dopen2(io->file, name, H5P_DEFAULT);
  int ok = d >= 0;
  if (ok) {
    hid_t sp = H5Dget_space(d);
    int rank = H5Sget_simple_extent_ndims(sp);
    ok = (rank == 1 || rank == 2) && H5Sget_simple_extent_dims(sp, dims, NULL) >= 0;
    H5Sclose(sp), H5Dclose(d);
  }
  if (!ok) hdf5_reason(why), snprintf(msg, sizeof msg, "checkpoint %s: cannot open dataset %s (HDF5: %s): the file is "
                                      "damaged or is not a perifem checkpoint", io->path, name, why);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  *rows = dims[0];
  return 0;
}

/* A point field's components and flags, as its attributes give them: 1..64 and PF_FIELD_*. */
static int field_shape(const h5io *io, const char *full, int *ncomp, int *flags) {
  hid_t d = H5Dopen2(io->file, full, H5P_DEFAULT);
  int ok = d >= 0 && !int_attr(io, d, "ncomp", ncomp, 0) && !int_attr(io, d, "flags", flags, 0);
  if (d >= 0) H5Dclose(d);
  char msg[512] = "";
  const int known = PF_FIELD_GHOST | PF_FIELD_RESTART | PF_FIELD_OUTPUT | PF_FIELD_CONSTANT;
  ok = ok && *ncomp >= 1 && *ncomp <= 64 && *flags >= 0 && (*flags & ~known) == 0;
  if (!ok) snprintf(msg, sizeof msg, "checkpoint %s: dataset %s: attributes ncomp %d, flags %d missing or out of "
                    "range: the file is damaged", io->path, full, *ncomp, *flags);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

static herr_t count_link(hid_t g, const char *name, const H5L_info_t *info, void *n) {
  (void)g, (void)name, (void)info;
  ++*(hsize_t *)n;
  return 0;
}

/* 1 when a walk of group g's links in their stored order (which builds no table) finds all
 * nlinks of them. HDF5 1.10's lookup by index in a damaged dense group frees link messages it
 * never decoded (an invalid free; found by tests/fuzz/fuzz_checkpoint.c): only a group whose
 * walk is whole is read by index. */
static int links_whole(hid_t g, hsize_t nlinks) {
  hsize_t n = 0;
  return H5Literate(g, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, count_link, &n) >= 0 && n == nlinks;
}

static int read_fields(const h5io *io, pf_points *p) {
  hid_t g = H5Gopen2(io->file, "/fields", H5P_DEFAULT);
  H5G_info_t info = {0};
  int ok = g >= 0 && H5Gget_info(g, &info) >= 0 && links_whole(g, info.nlinks);
  char msg[512] = "";
  if (!ok) snprintf(msg, sizeof msg, "checkpoint %s: cannot open group /fields: the file is damaged", io->path);
  if (!ok && g >= 0) H5Gclose(g);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  int ierr = 0;
  for (hsize_t k = 0; k < info.nlinks && !ierr; k++) {
    char name[40], full[64];
    int ncomp = 0, flags = 0, idx;
    ok = H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT) >= 0;
    snprintf(full, sizeof full, "/fields/%s", ok ? name : "?");
    if (!ok) snprintf(msg, sizeof msg, "checkpoint %s: cannot name field %llu of /fields", io->path, (unsigned long long)k);
    ierr = pf_error_agree(ok, PF_ERR_INPUT, __FILE__, __LINE__, __func__, msg);
    if (!ierr) ierr = field_shape(io, full, &ncomp, &flags);
    if (!ierr) ierr = pf_points_field_register(p, name, ncomp, flags, &idx);
    if (!ierr) ierr = read_rows(io, full, H5T_NATIVE_DOUBLE, ncomp, p->fields[idx].data);
    if (!ierr) ierr = pf_ckpt_check_values(io->path, full, p->fields[idx].data, io->count * (size_t)ncomp, -INFINITY, 1);
  }
  H5Gclose(g);
  return ierr;
}

/* The points' arrays, each checked: ids distinct and in range, bodies not negative, positions,
 * motion and forces finite, masses, volumes and cells finite and not negative. */
static int read_points(const h5io *io, pf_points *p) {
  const size_t n = io->count;
  PF_CALL(read_rows(io, "/points/gid", H5T_NATIVE_INT64, 1, p->gid));
  PF_CALL(pf_ckpt_check_ids(io->path, "/points/gid", p->gid, (int64_t)n, (pf_gid)io->total, 1));
  PF_CALL(read_rows(io, "/points/body", H5T_NATIVE_INT32, 1, p->body));
  PF_CALL(pf_ckpt_check_bodies(io->path, p->body, (int64_t)n));
  const char *vec[] = {"/points/X", "/points/u", "/points/v", "/points/f"};
  double *vdata[] = {p->X, p->u, p->v, p->f};
  for (int k = 0; k < 4; k++) {
    PF_CALL(read_rows(io, vec[k], H5T_NATIVE_DOUBLE, 3, vdata[k]));
    PF_CALL(pf_ckpt_check_values(io->path, vec[k], vdata[k], 3 * n, -INFINITY, 0));
  }
  const char *sca[] = {"/points/m", "/points/vol", "/points/cell"};
  double *sdata[] = {p->m, p->vol, p->cell};
  for (int k = 0; k < 3; k++) {
    PF_CALL(read_rows(io, sca[k], H5T_NATIVE_DOUBLE, 1, sdata[k]));
    PF_CALL(pf_ckpt_check_values(io->path, sca[k], sdata[k], n, 0.0, 0));
  }
  for (size_t i = 0; i < 3 * n; i++) p->y[i] = p->X[i] + p->u[i];
  return read_fields(io, p);
}

/* Is the file's /bonds/<name> the restart field f: its type and components? */
static int field_matches(const h5io *io, const char *name, const pf_bond_field *f) {
  if (H5Lexists(io->file, name, H5P_DEFAULT) <= 0) return 0;
  hid_t d = H5Dopen2(io->file, name, H5P_DEFAULT);
  if (d < 0) return 0;
  hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 1};
  int rank = H5Sget_simple_extent_dims(sp, dims, NULL);
  const H5T_class_t want = f->type == PF_BOND_UINT8 ? H5T_INTEGER : H5T_FLOAT;
  int ok = H5Tget_class(t) == want && H5Tget_size(t) == pf_bond_type_size(f->type) &&
           (rank == 1 || rank == 2) && (rank == 2 ? dims[1] : 1) == (hsize_t)f->ncomp;
  H5Tclose(t), H5Sclose(sp), H5Dclose(d);
  return ok;
}

static const char *type_name(pf_bond_type t) {
  return t == PF_BOND_UINT8 ? "uint8" : t == PF_BOND_FLOAT ? "float" : "double";
}

/* Refuse a file without one of the restart fields the rows register (or of another type or width). */
static int bond_fields_present(const h5io *io, const pf_bond_rows *rows) {
  for (int k = 0; k < rows->nfields; k++) {
    const pf_bond_field *f = &rows->field[k];
    char name[64];
    snprintf(name, sizeof name, "/bonds/%s", f->name);
    PF_CHECK(!(f->flags & PF_FIELD_RESTART) || field_matches(io, name, f), PF_ERR_INPUT,
             "checkpoint %s has no bond field '%s' (%s, %d per bond), which this run keeps: it was written "
             "by another model or another version of perifem", io->path, f->name, type_name(f->type), f->ncomp);
  }
  return 0;
}

/* Each restart field the rows register (the others keep their init), checked: not NaN, flags 0 or 1. */
static int read_bond_fields(const h5io *io, pf_bond_rows *rows) {
  for (int k = 0; k < rows->nfields; k++) {
    const pf_bond_field *f = &rows->field[k];
    if (!(f->flags & PF_FIELD_RESTART)) continue;
    char name[64];
    snprintf(name, sizeof name, "/bonds/%s", f->name);
    PF_CALL(read_rows(io, name, h5_type(f->type), f->ncomp, f->data));
    const size_t n = io->count * (size_t)f->ncomp;
    if (f->type == PF_BOND_DOUBLE) PF_CALL(pf_ckpt_check_values(io->path, name, f->data, n, -INFINITY, 1));
    if (f->type == PF_BOND_FLOAT) PF_CALL(pf_ckpt_check_floats(io->path, name, f->data, n));
    if (f->type == PF_BOND_UINT8) PF_CALL(pf_ckpt_check_flags(io->path, name, f->data, n));
  }
  return 0;
}

/* This rank's rows: their lengths (checked: not negative, adding up to the bonds in the file)
 * and neighbours (in range, ascending), then each restart field the rows register. */
static int read_bonds(const h5io *pio, pf_bond_rows *rows) {
  PF_CHECK(rows->n == 0, PF_ERR_RUN, "reading a checkpoint into bond rows that are not empty");
  PF_CALL(pf_bond_rows_fields_agree(rows));
  PF_CALL(bond_fields_present(pio, rows));
  hsize_t nbonds = 0;
  PF_CALL(dataset_rows(pio, "/bonds/gid", &nbonds));
  int32_t *count;
  PF_MALLOC(count, pio->count);
  int ierr = read_rows(pio, "/bonds/count", H5T_NATIVE_INT32, 1, count);
  if (!ierr) ierr = pf_ckpt_check_counts(pio->path, count, (int64_t)pio->count, (pf_gid)pio->total, (int64_t)nbonds);
  h5io io = *pio;
  io.count = 0;
  for (hsize_t i = 0; i < pio->count && !ierr; i++) io.count += (hsize_t)count[i];
  if (!ierr) rank_range(io.count, &io.total, &io.offset);
  for (hsize_t i = 0; i < pio->count && !ierr; i++) ierr = pf_bond_rows_append(rows, count[i], NULL, 0, NULL);
  free(count);
  if (!ierr) ierr = read_rows(&io, "/bonds/gid", H5T_NATIVE_INT64, 1, rows->gid);
  if (!ierr) ierr = pf_ckpt_check_rows(pio->path, rows, (pf_gid)pio->total);
  if (!ierr) ierr = read_bond_fields(&io, rows);
  return ierr;
}

/* The named scalars, each there and finite (the same attributes on every rank). */
static int read_scalars(const h5io *io, int n, const char *const *names, double *values) {
  for (int k = 0; k < n; k++) {
    char msg[640] = "", why[256] = "";
    hid_t a = H5Aopen(io->file, names[k], H5P_DEFAULT);
    int ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, &values[k]) >= 0;
    if (!ok) hdf5_reason(why);
    if (a >= 0) H5Aclose(a);
    if (!ok) snprintf(msg, sizeof msg, "checkpoint %s has no attribute '%s' (HDF5: %s): not a perifem checkpoint of "
                      "this kind, or damaged", io->path, names[k], why);
    else if (!isfinite(values[k]))
      ok = 0, snprintf(msg, sizeof msg, "checkpoint %s: attribute '%s' is %g, not finite: the file is damaged", io->path,
                       names[k], values[k]);
    PF_AGREE(ok, PF_ERR_INPUT, msg);
  }
  return 0;
}

static int read_all(h5io *io, pf_points **pts, pf_bond_rows *rows, int n, const char *const *names,
                    double *values) {
  hsize_t total = 0;
  PF_CALL(dataset_rows(io, "/points/gid", &total));
  PF_CHECK(total <= (hsize_t)INT32_MAX * 64, PF_ERR_INPUT, "checkpoint %s: dataset /points/gid has %llu rows: the "
           "file is damaged", io->path, (unsigned long long)total);
  int rank = pf_comm_rank(), size = pf_comm_size();
  io->total = total;
  io->offset = total * (hsize_t)rank / (hsize_t)size;
  io->count = total * (hsize_t)(rank + 1) / (hsize_t)size - io->offset;
  PF_CALL(read_scalars(io, n, names, values)); /* the smallest part first */
  PF_CALL(pf_points_create((pf_int)io->count, pts));
  (*pts)->n_global = (pf_gid)total;
  PF_CALL(read_points(io, *pts));
  return read_bonds(io, rows);
}

/* Open for reading on every rank, or refuse naming the file and HDF5's reason (e.g. "truncated
 * file"). */
static int open_for_reading(const char *path, hid_t *file) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  FILE *fp = fopen(path, "rb");
  PF_CHECK(fp, PF_ERR_INPUT, "cannot open the checkpoint %s", path);
  fclose(fp);
  char msg[640] = "", why[256] = "";
  *file = open_file(path, 0, why);
  if (*file < 0) snprintf(msg, sizeof msg, "checkpoint %s cannot be opened as HDF5 (%s): not a perifem checkpoint, or "
                          "damaged (truncated?)", path, why);
  PF_AGREE(*file >= 0, PF_ERR_INPUT, msg);
  return 0;
}

/* The file's format (1 when it has no "format" attribute: written before checkpoints recorded
 * it), refused unless it is this perifem's, before anything else is read. */
static int check_format(const h5io *io, int *file_format) {
  int format = 1, ok = 1;
  char msg[640] = "";
  if (H5Aexists(io->file, "format") > 0) {
    hid_t a = H5Aopen(io->file, "format", H5P_DEFAULT);
    ok = a >= 0 && H5Aread(a, H5T_NATIVE_INT, &format) >= 0;
    if (a >= 0) H5Aclose(a);
  }
  H5Eclear2(H5E_DEFAULT);
  if (!ok) snprintf(msg, sizeof msg, "checkpoint %s: attribute 'format' cannot be read: the file is damaged", io->path);
  else if (format < PF_CHECKPOINT_FORMAT_OLDEST || format > PF_CHECKPOINT_FORMAT)
    ok = 0, snprintf(msg, sizeof msg, "checkpoint %s is of format %d, this perifem reads formats %d to %d only (%s): "
                     "restart it with the perifem that wrote it, or run the deck from the start", io->path, format,
                     PF_CHECKPOINT_FORMAT_OLDEST, PF_CHECKPOINT_FORMAT, format < PF_CHECKPOINT_FORMAT_OLDEST ?
                     "written by an older perifem, whose checkpoints lack state this one restores and checks" :
                     "written by a newer perifem");
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  *file_format = format;
  return 0;
}

int pf_checkpoint_read(const char *path, pf_points **pts, pf_bond_rows *rows, int nscalars,
                       const char *const *names, double *values, int nscalars_format2, int *format) {
  h5io io = {-1, path, path, 0, 0, 0};
  PF_CALL(open_for_reading(path, &io.file));
  int ierr = check_format(&io, format);
  if (!ierr && *format == 2) nscalars = nscalars_format2;
  if (!ierr) ierr = read_all(&io, pts, rows, nscalars, names, values);
  H5Fclose(io.file);
  return ierr;
}

int pf_checkpoint_read_scalars(const char *path, int n, const char *const *names, double *values) {
  h5io io = {-1, path, path, 0, 0, 0};
  PF_CALL(open_for_reading(path, &io.file));
  int ierr = read_scalars(&io, n, names, values);
  H5Fclose(io.file);
  return ierr;
}

int pf_checkpoint_read_table(const char *path, const pf_table *t, double *full) {
  h5io io = {-1, path, path, (hsize_t)t->total, 0, (hsize_t)t->total};
  PF_CALL(open_for_reading(path, &io.file));
  char name[128];
  snprintf(name, sizeof name, "/tables/%s", t->name);
  int ierr = H5Lexists(io.file, "/tables", H5P_DEFAULT) > 0 && H5Lexists(io.file, name, H5P_DEFAULT) > 0 ? 0 : 1;
  H5Eclear2(H5E_DEFAULT);
  if (ierr)
    ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                          "checkpoint %s has no table %s of %" PF_GID_FMT " x %d (the mesh or the model changed?)",
                          path, name, t->total, t->ncomp);
  if (!ierr) ierr = read_rows(&io, name, H5T_NATIVE_DOUBLE, t->ncomp, full);
  if (!ierr) ierr = pf_ckpt_check_values(path, name, full, (size_t)t->total * (size_t)t->ncomp, -INFINITY, 1);
  H5Fclose(io.file);
  return ierr;
}
