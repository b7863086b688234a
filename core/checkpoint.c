/* Checkpoints in parallel HDF5 (MPI-IO, collective writes). Layout:
 *   /points/{gid,body,X,u,v,f,m,vol,cell}   one row per point, ranks' points one after another
 *   /fields/<name>                          [n][ncomp], attributes ncomp, flags
 *   /bonds/{count,gid}                      row lengths per point, then the bonds in that order
 *   /bonds/<name>                           [nbonds][ncomp] each bond field flagged
 *                                           PF_FIELD_RESTART, of its own type (uint8, float,
 *                                           double); a reader refuses a file without one of
 *                                           the fields it registers
 *   /tables/<name>                          [total][ncomp] whole tables (written by rank 0)
 *   attributes of "/": the named scalars (time, step, ...), written alike by every rank.
 * The file is written as path.tmp and renamed by rank 0 once every rank has closed it, so a
 * kill at any moment leaves the previous checkpoint whole. A failed write (a full disk) is
 * agreed by every rank after each collective call; the ranks then leave the file without
 * closing it (HDF5's collective close of a file it cannot write fails on one rank and hangs the
 * others, and leaves the file half destroyed), rank 0 removes path.tmp, and the process must
 * end through MPI_Abort (pf_io_abandon). A reader on any number of ranks
 * takes an equal slice of the rows; the caller re-partitions. */
#include "core/bond_rows_impl.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
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

/* The innermost message of HDF5's error stack (the failing call's, before another call clears it). */
static herr_t first_error(unsigned n, const H5E_error2_t *e, void *out) {
  if (n == 0) snprintf((char *)out, 256, "%s: %s", e->func_name, e->desc);
  return 0;
}

/* Why a call failed: errno when it is set (the POSIX drivers), else HDF5's innermost message. */
static void h5_reason(int ok, int err, char *buf) {
  buf[0] = '\0';
  if (ok) return;
  snprintf(buf, 256, "%s", err ? strerror(err) : "no system error reported");
  if (!err) H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_error, buf);
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

static int write_rows(const h5io *io, const char *name, hid_t type, int ncomp, const void *data) {
  hsize_t dims[2] = {io->total, (hsize_t)ncomp};
  hid_t fspace = H5Screate_simple(ncomp > 1 ? 2 : 1, dims, NULL), mspace;
  hid_t dset = H5Dcreate2(io->file, name, type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
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

static int read_rows(const h5io *io, const char *name, hid_t type, int ncomp, void *data) {
  hid_t dset = H5Dopen2(io->file, name, H5P_DEFAULT);
  H5_TRY(io, dset >= 0, name);
  hid_t fspace = H5Dget_space(dset), mspace;
  select_rows(fspace, &mspace, io->offset, io->count, ncomp);
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  herr_t st = H5Dread(dset, type, mspace, fspace, dxpl, data);
  H5Pclose(dxpl), H5Sclose(mspace), H5Sclose(fspace), H5Dclose(dset);
  H5_TRY(io, st >= 0, name);
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

static hid_t open_file(const char *path, int create) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL);
  hid_t f = create ? H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : H5Fopen(path, H5F_ACC_RDONLY, fapl);
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
  return write_scalars(io, n, names, values);
}

/* Room for the rest of the file, taken before the collective close: HDF5's close writes the
 * metadata and sets the file's size, and a write that fails there on one rank leaves the others
 * waiting inside HDF5 for ever. Once every dataset is written (the file as long as its data),
 * rank 0 reserves a margin past the file's end for the metadata still to come (a few kB here;
 * HDF5 1.10's MPI-IO driver cannot tell its end of allocated space), and the close sets the
 * size back to HDF5's end, so that a full disk (ENOSPC) or a file-size limit (EFBIG) fails
 * here, where the ranks can still agree. */
#define PF_CHECKPOINT_MARGIN (1 << 20)

static int reserve_tail(const h5io *io) {
  int ierr = 0;
  if (pf_comm_rank() == 0) {
    struct stat st;
    int fd = open(io->path, O_WRONLY), e = 0;
    if (fd < 0 || fstat(fd, &st)) e = errno ? errno : EIO;
    else e = posix_fallocate(fd, st.st_size, PF_CHECKPOINT_MARGIN);
    if (fd >= 0) close(fd);
    if (e)
      ierr = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                            "cannot write the checkpoint %s: no room for the last %d kB of %s (%s); the previous "
                            "checkpoint, if any, is kept",
                            io->target, PF_CHECKPOINT_MARGIN >> 10, io->path, strerror(e));
  }
  return pf_agree(ierr, "writing the checkpoint %s", io->target);
}

/* Every rank agreed that the write failed: leave the file open (see the top), remove path.tmp. */
static int discard(const h5io *io, int ierr) {
  pf_io_abandon();
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
  h5io io = {open_file(tmp, 1), tmp, path, 0, 0, (hsize_t)pts->n_owned};
  char why[256];
  h5_reason(io.file >= 0, errno, why);
  int ierr = write_agree(&io, io.file >= 0, "the file (H5Fcreate)", why);
  rank_range(io.count, &io.total, &io.offset);
  if (!ierr) ierr = write_all(&io, pts, rows, nscalars, names, values, ntables, tables);
  if (!ierr) ierr = reserve_tail(&io);
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

static int read_fields(const h5io *io, pf_points *p) {
  hid_t g = H5Gopen2(io->file, "/fields", H5P_DEFAULT);
  H5_TRY(io, g >= 0, "/fields");
  H5G_info_t info;
  herr_t st = H5Gget_info(g, &info);
  int ierr = st < 0;
  for (hsize_t k = 0; k < info.nlinks && !ierr; k++) {
    char name[40], full[64];
    if (H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT) < 0) {
      ierr = 1;
      break;
    }
    snprintf(full, sizeof full, "/fields/%s", name);
    hid_t d = H5Dopen2(io->file, full, H5P_DEFAULT);
    int ncomp = 0, flags = 0, idx;
    ierr = d < 0 || int_attr(io, d, "ncomp", &ncomp, 0) || int_attr(io, d, "flags", &flags, 0);
    if (d >= 0) H5Dclose(d);
    if (!ierr) ierr = pf_points_field_register(p, name, ncomp, flags, &idx);
    if (!ierr) ierr = read_rows(io, full, H5T_NATIVE_DOUBLE, ncomp, p->fields[idx].data);
  }
  H5Gclose(g);
  H5_TRY(io, !ierr, "reading /fields");
  return 0;
}

static int read_points(const h5io *io, pf_points *p) {
  PF_CALL(read_rows(io, "/points/gid", H5T_NATIVE_INT64, 1, p->gid));
  PF_CALL(read_rows(io, "/points/body", H5T_NATIVE_INT32, 1, p->body));
  const char *vec[] = {"/points/X", "/points/u", "/points/v", "/points/f"};
  double *vdata[] = {p->X, p->u, p->v, p->f};
  for (int k = 0; k < 4; k++) PF_CALL(read_rows(io, vec[k], H5T_NATIVE_DOUBLE, 3, vdata[k]));
  PF_CALL(read_rows(io, "/points/m", H5T_NATIVE_DOUBLE, 1, p->m));
  PF_CALL(read_rows(io, "/points/vol", H5T_NATIVE_DOUBLE, 1, p->vol));
  PF_CALL(read_rows(io, "/points/cell", H5T_NATIVE_DOUBLE, 1, p->cell));
  for (size_t i = 0; i < 3 * (size_t)p->n_owned; i++) p->y[i] = p->X[i] + p->u[i];
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

/* This rank's rows: their lengths and neighbours, then each restart field the rows register
 * (the others keep their init). */
static int read_bonds(const h5io *pio, pf_bond_rows *rows) {
  PF_CHECK(rows->n == 0, PF_ERR_RUN, "reading a checkpoint into bond rows that are not empty");
  PF_CALL(pf_bond_rows_fields_agree(rows));
  for (int k = 0; k < rows->nfields; k++) {
    const pf_bond_field *f = &rows->field[k];
    char name[64];
    snprintf(name, sizeof name, "/bonds/%s", f->name);
    PF_CHECK(!(f->flags & PF_FIELD_RESTART) || field_matches(pio, name, f), PF_ERR_INPUT,
             "checkpoint %s has no bond field '%s' (%s, %d per bond), which this run keeps: it was written "
             "by another model or another version of perifem", pio->path, f->name, type_name(f->type), f->ncomp);
  }
  int32_t *count;
  PF_MALLOC(count, pio->count);
  int ierr = read_rows(pio, "/bonds/count", H5T_NATIVE_INT32, 1, count);
  h5io io = *pio;
  io.count = 0;
  for (hsize_t i = 0; i < pio->count; i++) io.count += (hsize_t)count[i];
  rank_range(io.count, &io.total, &io.offset);
  for (hsize_t i = 0; i < pio->count && !ierr; i++) ierr = pf_bond_rows_append(rows, count[i], NULL, 0, NULL);
  free(count);
  if (!ierr) ierr = read_rows(&io, "/bonds/gid", H5T_NATIVE_INT64, 1, rows->gid);
  for (int k = 0; k < rows->nfields && !ierr; k++) {
    const pf_bond_field *f = &rows->field[k];
    char name[64];
    snprintf(name, sizeof name, "/bonds/%s", f->name);
    if (f->flags & PF_FIELD_RESTART) ierr = read_rows(&io, name, h5_type(f->type), f->ncomp, f->data);
  }
  return ierr;
}

static int read_scalars(const h5io *io, int n, const char *const *names, double *values) {
  for (int k = 0; k < n; k++) {
    hid_t a = H5Aopen(io->file, names[k], H5P_DEFAULT);
    PF_CHECK(a >= 0, PF_ERR_INPUT, "checkpoint %s has no '%s': not a perifem checkpoint of this kind", io->path,
             names[k]);
    herr_t st = H5Aread(a, H5T_NATIVE_DOUBLE, &values[k]);
    H5Aclose(a);
    H5_TRY(io, st >= 0, names[k]);
  }
  return 0;
}

static int read_all(h5io *io, pf_points **pts, pf_bond_rows *rows, int n, const char *const *names,
                    double *values) {
  hid_t d = H5Dopen2(io->file, "/points/gid", H5P_DEFAULT);
  PF_CHECK(d >= 0, PF_ERR_INPUT, "checkpoint %s has no /points/gid: not a perifem checkpoint", io->path);
  hid_t sp = H5Dget_space(d);
  hsize_t total = 0;
  H5Sget_simple_extent_dims(sp, &total, NULL);
  H5Sclose(sp), H5Dclose(d);
  int rank = pf_comm_rank(), size = pf_comm_size();
  io->total = total;
  io->offset = total * (hsize_t)rank / (hsize_t)size;
  io->count = total * (hsize_t)(rank + 1) / (hsize_t)size - io->offset;
  PF_CALL(pf_points_create((pf_int)io->count, pts));
  (*pts)->n_global = (pf_gid)total;
  PF_CALL(read_points(io, *pts));
  PF_CALL(read_bonds(io, rows));
  return read_scalars(io, n, names, values);
}

int pf_checkpoint_read(const char *path, pf_points **pts, pf_bond_rows *rows, int nscalars,
                       const char *const *names, double *values) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  FILE *fp = fopen(path, "rb");
  PF_CHECK(fp, PF_ERR_INPUT, "cannot open the checkpoint %s", path);
  fclose(fp);
  h5io io = {open_file(path, 0), path, path, 0, 0, 0};
  PF_CHECK(io.file >= 0, PF_ERR_INPUT, "%s is not an HDF5 file (a perifem checkpoint)", path);
  int ierr = read_all(&io, pts, rows, nscalars, names, values);
  H5Fclose(io.file);
  return ierr;
}

int pf_checkpoint_read_table(const char *path, const pf_table *t, double *full) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  h5io io = {open_file(path, 0), path, path, (hsize_t)t->total, 0, (hsize_t)t->total};
  PF_CHECK(io.file >= 0, PF_ERR_INPUT, "%s is not an HDF5 file (a perifem checkpoint)", path);
  char name[128];
  snprintf(name, sizeof name, "/tables/%s", t->name);
  hid_t d = H5Dopen2(io.file, name, H5P_DEFAULT);
  hsize_t dims[2] = {0, 1};
  if (d >= 0) {
    hid_t sp = H5Dget_space(d);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    H5Sclose(sp), H5Dclose(d);
  }
  int ierr = 0;
  if (d < 0 || dims[0] != (hsize_t)t->total || (t->ncomp > 1 && dims[1] != (hsize_t)t->ncomp))
    ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                          "checkpoint %s has no table %s of %" PF_GID_FMT " x %d (the mesh or the model changed?)",
                          path, name, t->total, t->ncomp);
  if (!ierr) ierr = read_rows(&io, name, H5T_NATIVE_DOUBLE, t->ncomp, full);
  H5Fclose(io.file);
  return ierr;
}
