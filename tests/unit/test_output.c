/* Output files: writes an Exodus II file (core/output_exodus.c) and an HDF5 history
 * (core/history.c) for a 5-point, 2-body cloud, reads them back with the Exodus and HDF5 C
 * APIs and checks the layout (blocks, names, maps) and the values. Also checks that a failed
 * create reports the library call and the path. Files: test_output_*.{e,h5}, removed at the end. */
#include "test_common.h"

#include <exodusII.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>

#define EXO_PATH "test_output_points.e"
#define H5_PATH "test_output_history.h5"
#define NPTS 5
#define NAME_BUF 257 /* NC_MAX_NAME + 1: longer than any name Exodus returns */

static const char *const body_names[2] = {"plate", "impactor"};
static const pf_int body_start[3] = {0, 2, 5};
static const char *const global_names[2] = {"kinetic_energy", "strain_energy"};
static const double times[2] = {1.5e-6, 3.0e-6};

/* Expected values at output step s (1 or 2) of point i, component d. */
static double u_at(int s, int i, int d) { return s * (10.0 * i + d + 0.25); }
static double damage_at(int s, int i) { return 0.1 * s * i; }
static double global_at(int s, int g) { return 100.0 * s + g; }

static void fill_step(pf_points *pts, int s, int damage, int traction) {
  for (int i = 0; i < NPTS; i++) {
    for (int d = 0; d < 3; d++) {
      pts->u[3 * i + d] = u_at(s, i, d);
      pts->v[3 * i + d] = -u_at(s, i, d);
      pts->f[3 * i + d] = 2.0 * u_at(s, i, d);
      pts->fields[traction].data[3 * i + d] = 7.0 * s + d;
    }
    pts->fields[damage].data[i] = damage_at(s, i);
  }
}

static pf_points *make_points(int *damage, int *traction) {
  pf_points *pts = NULL;
  int scratch = -1;
  PF_TEST_OK(pf_points_create(NPTS, &pts));
  if (!pts) return NULL;
  for (int i = 0; i < NPTS; i++) {
    for (int d = 0; d < 3; d++) pts->X[3 * i + d] = 0.001 * (i + 1) * (d + 1);
    pts->gid[i] = NPTS - 1 - i; /* a non-trivial id map */
  }
  PF_TEST_OK(pf_points_field_register(pts, "damage", 1, PF_FIELD_OUTPUT, damage));
  PF_TEST_OK(pf_points_field_register(pts, "scratch", 1, PF_FIELD_GHOST, &scratch));
  PF_TEST_OK(pf_points_field_register(pts, "traction", 3, PF_FIELD_OUTPUT, traction));
  return pts;
}

/* ---- Exodus ------------------------------------------------------------------ */

static int open_exo(void) {
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  int exoid = ex_open(EXO_PATH, EX_READ, &cpu_ws, &io_ws, &version);
  PF_TEST_TRUE(exoid >= 0);
  PF_TEST_TRUE(io_ws == 8);
  return exoid;
}

/* Index (1-based) of the nodal variable called name, 0 when absent. */
static int nodal_index(int exoid, const char *name) {
  int nv = 0;
  ex_get_variable_param(exoid, EX_NODAL, &nv);
  char buf[NAME_BUF];
  for (int j = 1; j <= nv; j++)
    if (ex_get_variable_name(exoid, EX_NODAL, j, buf) >= 0 && !strcmp(buf, name)) return j;
  return 0;
}

static void check_nodal(int exoid, int step, const char *name, const double *want) {
  double got[NPTS] = {0};
  int j = nodal_index(exoid, name);
  PF_TEST_TRUE(j > 0);
  PF_TEST_TRUE(ex_get_var(exoid, step, EX_NODAL, j, 1, NPTS, got) >= 0);
  for (int i = 0; i < NPTS; i++) PF_TEST_CLOSE(got[i], want[i], 0, 0);
}

static void check_mesh(int exoid) {
  char title[MAX_LINE_LENGTH + 1];
  int ndim = 0, nnodes = 0, nelem = 0, nblk = 0, nns = -1, nss = -1;
  PF_TEST_TRUE(ex_get_init(exoid, title, &ndim, &nnodes, &nelem, &nblk, &nns, &nss) >= 0);
  PF_TEST_TRUE(ndim == 3 && nnodes == NPTS && nelem == NPTS && nblk == 2);
  PF_TEST_TRUE(nns == 0 && nss == 0);
  double x[NPTS], y[NPTS], z[NPTS];
  PF_TEST_TRUE(ex_get_coord(exoid, x, y, z) >= 0);
  for (int i = 0; i < NPTS; i++) {
    PF_TEST_CLOSE(x[i], 0.001 * (i + 1), 0, 0);
    PF_TEST_CLOSE(z[i], 0.003 * (i + 1), 0, 0);
  }
  int nmap[NPTS], emap[NPTS];
  PF_TEST_TRUE(ex_get_id_map(exoid, EX_NODE_MAP, nmap) >= 0);
  PF_TEST_TRUE(ex_get_id_map(exoid, EX_ELEM_MAP, emap) >= 0);
  for (int i = 0; i < NPTS; i++) PF_TEST_TRUE(nmap[i] == NPTS - i && emap[i] == NPTS - i);
}

static void check_blocks(int exoid) {
  int ids[2] = {0, 0};
  PF_TEST_TRUE(ex_get_ids(exoid, EX_ELEM_BLOCK, ids) >= 0);
  char store[2][NAME_BUF], *names[2] = {store[0], store[1]};
  PF_TEST_TRUE(ex_get_names(exoid, EX_ELEM_BLOCK, names) >= 0);
  for (int b = 0; b < 2; b++) {
    char type[MAX_STR_LENGTH + 1] = "";
    int nel = 0, npe = 0, ned = 0, nfa = 0, nattr = 0;
    int st = ex_get_block(exoid, EX_ELEM_BLOCK, ids[b], type, &nel, &npe, &ned, &nfa, &nattr);
    PF_TEST_TRUE(st >= 0);
    PF_TEST_TRUE(!strcmp(type, "SPHERE") && npe == 1);
    PF_TEST_TRUE(nel == body_start[b + 1] - body_start[b]);
    PF_TEST_TRUE(!strcmp(names[b], body_names[b]));
    int conn[3] = {0, 0, 0};
    PF_TEST_TRUE(ex_get_conn(exoid, EX_ELEM_BLOCK, ids[b], conn, NULL, NULL) >= 0);
    for (int i = 0; i < nel; i++) PF_TEST_TRUE(conn[i] == body_start[b] + i + 1);
  }
}

static void check_variable_names(int exoid) {
  static const char *const want[] = {
      "displacement_x", "displacement_y", "displacement_z", "velocity_x", "velocity_y",
      "velocity_z",     "force_x",        "force_y",        "force_z",    "damage",
      "traction_x",     "traction_y",     "traction_z"};
  int nv = 0, ng = 0;
  PF_TEST_TRUE(ex_get_variable_param(exoid, EX_NODAL, &nv) >= 0);
  PF_TEST_TRUE(nv == (int)(sizeof want / sizeof want[0]));
  for (int j = 1; j <= nv && j <= 13; j++) {
    char buf[NAME_BUF] = "";
    PF_TEST_TRUE(ex_get_variable_name(exoid, EX_NODAL, j, buf) >= 0);
    PF_TEST_TRUE(!strcmp(buf, want[j - 1]));
  }
  PF_TEST_TRUE(ex_get_variable_param(exoid, EX_GLOBAL, &ng) >= 0);
  PF_TEST_TRUE(ng == 2);
  char buf[NAME_BUF] = "";
  PF_TEST_TRUE(ex_get_variable_name(exoid, EX_GLOBAL, 2, buf) >= 0);
  PF_TEST_TRUE(!strcmp(buf, "strain_energy"));
}

static void check_steps(int exoid, int nsteps) {
  PF_TEST_TRUE(ex_inquire_int(exoid, EX_INQ_TIME) == nsteps);
  double t[2] = {0, 0}, g[2] = {0, 0}, want[NPTS];
  PF_TEST_TRUE(ex_get_all_times(exoid, t) >= 0);
  for (int s = 0; s < nsteps; s++) PF_TEST_CLOSE(t[s], times[s], 0, 0);
  for (int i = 0; i < NPTS; i++) want[i] = damage_at(1, i);
  check_nodal(exoid, 1, "damage", want);
  PF_TEST_TRUE(ex_get_var(exoid, nsteps, EX_GLOBAL, 1, 0, 2, g) >= 0);
  PF_TEST_CLOSE(g[1], global_at(nsteps, 1), 0, 0);
  if (nsteps < 2) return;
  for (int i = 0; i < NPTS; i++) want[i] = u_at(2, i, 1);
  check_nodal(exoid, 2, "displacement_y", want);
  for (int i = 0; i < NPTS; i++) want[i] = 2.0 * u_at(2, i, 2);
  check_nodal(exoid, 2, "force_z", want);
  for (int i = 0; i < NPTS; i++) want[i] = 7.0 * 2 + 1;
  check_nodal(exoid, 2, "traction_y", want);
}

/* Read the file with a second handle while the writer still has it open (a run that dies
 * after this step leaves a readable file), or after it is closed. */
static void check_exodus(int nsteps) {
  int exoid = open_exo();
  if (exoid < 0) return;
  check_mesh(exoid);
  check_blocks(exoid);
  check_variable_names(exoid);
  check_steps(exoid, nsteps);
  ex_close(exoid);
}

static void test_exodus(void) {
  int damage = -1, traction = -1;
  pf_points *pts = make_points(&damage, &traction);
  if (!pts || damage < 0 || traction < 0) return;
  pf_exodus *ex = NULL;
  PF_TEST_OK(pf_exodus_create(EXO_PATH, pts, 2, body_names, body_start, 2, global_names, NULL, &ex));
  for (int s = 1; s <= 2 && ex; s++) {
    double g[2] = {global_at(s, 0), global_at(s, 1)};
    fill_step(pts, s, damage, traction);
    PF_TEST_OK(pf_exodus_write(ex, times[s - 1], pts, g));
    if (s == 1) check_exodus(1);
  }
  PF_TEST_OK(pf_exodus_destroy(&ex));
  PF_TEST_TRUE(ex == NULL);
  PF_TEST_OK(pf_exodus_destroy(&ex)); /* destroying NULL is fine */
  check_exodus(2);
  pf_points_destroy(&pts);
}

/* ---- HDF5 history ------------------------------------------------------------ */

static const char *const cols[3] = {"time", "kinetic_energy", "damaged_fraction"};
static const char *const units[3] = {"s", "J", NULL};
static double row_value(int r, int c) { return 0.5 * r + 10.0 * c + 0.125; }

static void check_units(hid_t dset, const char *want) {
  if (!want) {
    PF_TEST_TRUE(H5Aexists(dset, "units") == 0);
    return;
  }
  char buf[64] = "";
  hid_t attr = H5Aopen(dset, "units", H5P_DEFAULT);
  PF_TEST_TRUE(attr >= 0);
  if (attr < 0) return;
  hid_t type = H5Aget_type(attr);
  PF_TEST_TRUE(H5Tget_class(type) == H5T_STRING && H5Tget_size(type) < sizeof buf);
  if (H5Tget_size(type) < sizeof buf) PF_TEST_TRUE(H5Aread(attr, type, buf) >= 0);
  PF_TEST_TRUE(!strcmp(buf, want));
  H5Tclose(type);
  H5Aclose(attr);
}

static void check_column(hid_t file, int c, int nrows) {
  char name[64] = "";
  H5Lget_name_by_idx(file, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, (hsize_t)c, name, sizeof name,
                     H5P_DEFAULT);
  PF_TEST_TRUE(!strcmp(name, cols[c])); /* columns listed in the order given */
  hid_t dset = H5Dopen2(file, cols[c], H5P_DEFAULT);
  PF_TEST_TRUE(dset >= 0);
  if (dset < 0) return;
  hid_t space = H5Dget_space(dset);
  hsize_t dims[1] = {0};
  PF_TEST_TRUE(H5Sget_simple_extent_ndims(space) == 1);
  H5Sget_simple_extent_dims(space, dims, NULL);
  PF_TEST_TRUE(dims[0] == (hsize_t)nrows);
  double got[4] = {0, 0, 0, 0};
  if (dims[0] == (hsize_t)nrows)
    PF_TEST_TRUE(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, got) >= 0);
  for (int r = 0; r < nrows; r++) PF_TEST_CLOSE(got[r], row_value(r, c), 0, 0);
  check_units(dset, units[c]);
  H5Sclose(space);
  H5Dclose(dset);
}

static void test_history(void) {
  pf_history *h = NULL;
  PF_TEST_OK(pf_history_create(H5_PATH, 3, cols, units, NULL, &h));
  PF_TEST_TRUE(h != NULL);
  for (int r = 0; r < 4 && h; r++) {
    double row[3] = {row_value(r, 0), row_value(r, 1), row_value(r, 2)};
    PF_TEST_OK(pf_history_append(h, row));
  }
  PF_TEST_OK(pf_history_destroy(&h));
  PF_TEST_TRUE(h == NULL);
  PF_TEST_OK(pf_history_append(NULL, NULL)); /* NULL handle: no-op */
  PF_TEST_OK(pf_history_destroy(&h));
  hid_t file = H5Fopen(H5_PATH, H5F_ACC_RDONLY, H5P_DEFAULT);
  PF_TEST_TRUE(file >= 0);
  if (file < 0) return;
  for (int c = 0; c < 3; c++) check_column(file, c, 4);
  H5Fclose(file);
}

/* ---- failures name the call and the file --------------------------------------- */

static void test_errors(void) {
  const char *bad_exo = "test_output_no_such_dir/x.e", *bad_h5 = "test_output_no_such_dir/x.h5";
  pf_points *pts = NULL;
  PF_TEST_OK(pf_points_create(NPTS, &pts));
  pf_exodus *ex = NULL;
  pf_history *h = NULL;
  pf_error_set_quiet(1);
  pf_error_clear();
  PF_TEST_TRUE(pf_exodus_create(bad_exo, pts, 2, body_names, body_start, 0, NULL, NULL, &ex) ==
               PF_ERR_LIB);
  PF_TEST_TRUE(ex == NULL && strstr(pf_error_message(), "ex_create"));
  PF_TEST_TRUE(strstr(pf_error_message(), bad_exo) != NULL);
  pf_error_clear();
  PF_TEST_TRUE(pf_history_create(bad_h5, 3, cols, units, NULL, &h) == PF_ERR_LIB);
  PF_TEST_TRUE(h == NULL && strstr(pf_error_message(), "H5Fcreate"));
  PF_TEST_TRUE(strstr(pf_error_message(), bad_h5) != NULL);
  /* "Nothing silently wrong" (messages that name their cause): the key and the system's reason */
  PF_TEST_TRUE(strstr(pf_error_message(), "output.history_file") != NULL);
  PF_TEST_TRUE(strstr(pf_error_message(), strerror(ENOENT)) != NULL);
  pf_error_clear();
  pf_error_set_quiet(0);
  pf_points_destroy(&pts);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  test_exodus();
  test_history();
  test_errors();
  remove(EXO_PATH);
  remove(H5_PATH);
  return pf_test_finish();
}
