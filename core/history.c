/* HDF5 history of global quantities (one row per output step), written by rank 0 only.
 * Layout: in the root group "/", one dataset per column, named by the column, holding a 1-D
 * extendible (maxdims H5S_UNLIMITED), chunked array of 64-bit IEEE doubles with one entry per
 * appended row; an optional fixed-length, null-terminated ASCII string attribute "units" on
 * each dataset. Link creation order is tracked, so the columns list in the order given.
 * The file is flushed after every row so a reader sees complete rows.
 * HDF5's own error printing is turned off; failures come back through PF_CHECK. After a failed
 * write (a full disk) the file is left open, not closed: HDF5 cannot close a file it cannot
 * write and keeps it half destroyed, to crash in MPI_Finalize (pf_io_abandon). */
#include "core/core.h"

#include <errno.h>
#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

#define PF_HISTORY_CHUNK 1024 /* rows per chunk */

struct pf_history {
  hid_t file;
  int ncol;
  hid_t *dset;   /* [ncol] */
  hsize_t nrows; /* rows written so far */
  char *path;    /* for error messages */
  int failed;    /* a write failed: leave the file open */
};

#define PF_H5_CHECK(h, ok, call, col)                                                              \
  PF_CHECK((ok), PF_ERR_LIB, "HDF5: %s failed (file %s, column '%s')", (call), (h)->path, (col))

/* A row that could not be written (err: errno right after the failing call). */
static int append_failed(pf_history *h, const char *call, int err) {
  h->failed = 1;
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                        "cannot write the history %s: HDF5 %s of row %llu failed (%s)", h->path, call,
                        (unsigned long long)h->nrows, err ? strerror(err) : "no system error reported");
}

/* ---- create ---------------------------------------------------------------- */

/* A fixed-length, null-terminated ASCII string attribute key = text on obj (named name), or, with
 * n > 0, an array of n such strings of width len (texts[k] at k * len). */
static int put_string_attr(pf_history *h, hid_t obj, const char *name, const char *key, const char *text, size_t n,
                           size_t len) {
  hid_t type = H5Tcopy(H5T_C_S1);
  PF_H5_CHECK(h, type >= 0, "H5Tcopy", name);
  herr_t st = H5Tset_size(type, n ? len : strlen(text) + 1);
  if (st >= 0) st = H5Tset_strpad(type, H5T_STR_NULLTERM);
  hsize_t dims[1] = {n};
  hid_t space = st >= 0 ? (n ? H5Screate_simple(1, dims, NULL) : H5Screate(H5S_SCALAR)) : -1;
  hid_t attr = space >= 0 ? H5Acreate2(obj, key, type, space, H5P_DEFAULT, H5P_DEFAULT) : -1;
  st = attr >= 0 ? H5Awrite(attr, type, text) : -1;
  if (attr >= 0) H5Aclose(attr);
  if (space >= 0) H5Sclose(space);
  H5Tclose(type);
  PF_H5_CHECK(h, st >= 0, "H5Acreate2/H5Awrite of a string attribute", name);
  return PF_SUCCESS;
}

static int put_units(pf_history *h, hid_t dset, const char *name, const char *units) {
  return put_string_attr(h, dset, name, "units", units, 0, 0);
}

static int create_column(pf_history *h, int i, const char *name, const char *units) {
  PF_CHECK(name && name[0], PF_ERR_INPUT, "history %s: column %d has no name", h->path, i);
  hsize_t dims[1] = {0}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {PF_HISTORY_CHUNK};
  hid_t space = H5Screate_simple(1, dims, maxdims);
  PF_H5_CHECK(h, space >= 0, "H5Screate_simple", name);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  herr_t st = dcpl >= 0 ? H5Pset_chunk(dcpl, 1, chunk) : -1;
  if (st >= 0)
    h->dset[i] = H5Dcreate2(h->file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dcpl >= 0) H5Pclose(dcpl);
  H5Sclose(space);
  PF_H5_CHECK(h, st >= 0, "H5Pcreate/H5Pset_chunk", name);
  PF_H5_CHECK(h, h->dset[i] >= 0, "H5Dcreate2", name);
  if (units && units[0]) PF_CALL(put_units(h, h->dset[i], name, units));
  return PF_SUCCESS;
}

static int open_history(pf_history *h, const char *const *names, const char *const *units) {
  PF_MALLOC(h->dset, h->ncol);
  for (int i = 0; i < h->ncol; i++) h->dset[i] = H5I_INVALID_HID;
  /* Track link creation order so readers can list the columns in the order given. */
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  PF_CHECK(fcpl >= 0, PF_ERR_LIB, "HDF5: H5Pcreate failed (file %s)", h->path);
  herr_t st = H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  errno = 0;
  if (st >= 0) h->file = H5Fcreate(h->path, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  const int err = errno; /* (the system's reason, when HDF5's open failed) */
  H5Pclose(fcpl);
  PF_CHECK(st >= 0, PF_ERR_LIB, "HDF5: H5Pset_link_creation_order failed (file %s)", h->path);
  PF_CHECK(h->file >= 0, PF_ERR_LIB, "output.history_file: the history '%s' cannot be created: %s (HDF5 H5Fcreate)",
           h->path, err ? strerror(err) : "HDF5 gives no system reason");
  for (int i = 0; i < h->ncol; i++) PF_CALL(create_column(h, i, names[i], units ? units[i] : NULL));
  PF_CHECK(H5Fflush(h->file, H5F_SCOPE_LOCAL) >= 0, PF_ERR_LIB, "HDF5: H5Fflush failed (file %s)",
           h->path);
  return PF_SUCCESS;
}

/* The file's attributes: "title", "provenance" (the lines, one text) and "columns" (the column
 * names in their order, which readers listing datasets by name do not keep). */
static int put_provenance(pf_history *h, const char *const *names, const pf_provenance *p) {
  size_t width = 1, len = 1;
  for (int i = 0; i < h->ncol; i++) width = strlen(names[i]) + 1 > width ? strlen(names[i]) + 1 : width;
  for (int k = 0; p && k < p->nlines; k++) len += strlen(p->lines[k]) + 1;
  char *cols = calloc((size_t)h->ncol * width + 1, 1), *text = calloc(len, 1);
  int ierr = cols && text ? 0 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (int i = 0; !ierr && i < h->ncol; i++) memcpy(cols + (size_t)i * width, names[i], strlen(names[i]));
  for (int k = 0; !ierr && p && k < p->nlines; k++) strcat(strcat(text, p->lines[k]), "\n");
  if (!ierr && h->ncol) ierr = put_string_attr(h, h->file, "/", "columns", cols, (size_t)h->ncol, width);
  if (!ierr) ierr = put_string_attr(h, h->file, "/", "title", p && p->title ? p->title : "", 0, 0);
  if (!ierr) ierr = put_string_attr(h, h->file, "/", "provenance", text, 0, 0);
  free(cols), free(text);
  return ierr;
}

int pf_history_create(const char *path, int ncol, const char *const *names,
                      const char *const *units, const pf_provenance *prov, pf_history **h) {
  PF_CHECK(h, PF_ERR_INPUT, "pf_history_create: NULL handle");
  *h = NULL;
  if (pf_comm_rank() != 0) return PF_SUCCESS;
  PF_CHECK(path && (names || ncol == 0) && ncol >= 0, PF_ERR_INPUT,
           "pf_history_create: bad arguments (path %s, %d columns)", path ? path : "(null)", ncol);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  pf_history *hh = NULL;
  PF_MALLOC(hh, 1);
  hh->file = H5I_INVALID_HID;
  hh->ncol = ncol;
  size_t len = strlen(path) + 1;
  hh->path = malloc(len);
  if (!hh->path) {
    PF_FREE(hh);
    return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__,
                          "out of memory for the history path %s", path);
  }
  memcpy(hh->path, path, len);
  int err = open_history(hh, names, units);
  if (!err) err = put_provenance(hh, names, prov);
  if (err) {
    pf_history_destroy(&hh);
    return err;
  }
  *h = hh;
  return PF_SUCCESS;
}

/* ---- append ---------------------------------------------------------------- */

/* Extend column i by one entry and write value there. */
static int append_value(pf_history *h, int i, double value) {
  hid_t dset = h->dset[i];
  hsize_t newdims[1] = {h->nrows + 1}, start[1] = {h->nrows}, one[1] = {1};
  errno = 0;
  herr_t st = H5Dset_extent(dset, newdims);
  hid_t fspace = st >= 0 ? H5Dget_space(dset) : -1;
  st = fspace >= 0 ? H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, one, NULL) : -1;
  hid_t mspace = st >= 0 ? H5Screate_simple(1, one, NULL) : -1;
  st = mspace >= 0 ? H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, &value) : -1;
  int err = errno;
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  return st >= 0 ? PF_SUCCESS : append_failed(h, "H5Dset_extent/H5Dwrite", err);
}

int pf_history_append(pf_history *h, const double *row) {
  if (!h) return PF_SUCCESS;
  PF_CHECK(row || h->ncol == 0, PF_ERR_INPUT, "history %s: NULL row", h->path);
  for (int i = 0; i < h->ncol; i++) PF_CALL(append_value(h, i, row[i]));
  errno = 0;
  if (H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0) return append_failed(h, "H5Fflush", errno);
  h->nrows++;
  return PF_SUCCESS;
}

/* ---- destroy --------------------------------------------------------------- */

int pf_history_destroy(pf_history **h) {
  if (!h || !*h) return PF_SUCCESS;
  pf_history *hh = *h;
  *h = NULL;
  int bad = 0;
  if (hh->failed) pf_io_abandon();
  for (int i = 0; hh->dset && i < hh->ncol && !hh->failed; i++)
    if (hh->dset[i] >= 0 && H5Dclose(hh->dset[i]) < 0) bad = 1;
  if (hh->file >= 0 && !hh->failed && H5Fclose(hh->file) < 0) bad = 1, pf_io_abandon();
  int err = bad ? pf_error_raise(PF_ERR_LIB, __FILE__, __LINE__, __func__,
                                 "HDF5: H5Dclose/H5Fclose failed (file %s)", hh->path)
                : PF_SUCCESS;
  PF_FREE(hh->dset);
  PF_FREE(hh->path);
  PF_FREE(hh);
  return err;
}
