/* Exodus II output of the point cloud (one file, serial for now).
 * Layout, as ParaView's Exodus reader expects it: a classic netCDF (64-bit offset) Exodus II
 * file in double precision holding the title, 3-D coordinates of the owned points, one element
 * block per body of type "SPHERE" with one node per element (element i of block b is point
 * body_start[b] + i), block names = body names, node and element id maps = global id + 1,
 * nodal variables displacement_{x,y,z}, velocity_{x,y,z}, force_{x,y,z} and then every field
 * flagged PF_FIELD_OUTPUT (ncomp 1: name, ncomp 3: name_{x,y,z}, ncomp 6 (a symmetric tensor, kept in
 * Voigt order xx, yy, zz, yz, xz, xy): name_{xx,yy,zz,xy,yz,zx} in that order, the suffixes and
 * order by which ParaView's Exodus readers join six variables into one symmetric tensor; else
 * name_0, name_1, ...),
 * and global variables. An output field flagged PF_FIELD_CONSTANT (horizon, region, blending
 * weight: set at the set-up, never changed) is no nodal variable but a nodal attribute of the
 * same name, written once with the first time step: not repeated in every frame, and read by
 * ParaView's IOSS reader as a point array at every time. Each pf_exodus_write appends one time
 * step and calls ex_update. */
#include "core/core.h"

#include <exodusII.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PF_EX_NAME_LEN 64 /* longest variable / block name we hand to Exodus */

struct pf_exodus {
  int exoid;      /* -1 when not open */
  char *path;     /* for error messages */
  int step;       /* last written time step (1-based), 0 before the first write */
  pf_int n;       /* number of nodes (owned points) */
  int64_t nelem;  /* elements over all blocks */
  int nvars;      /* nodal variables, built-ins first */
  int nglobals;   /* global variables */
  int *var_field; /* [nvars]: field index in pts->fields, or -1 - b for built-in b (u, v, f) */
  int *var_comp;  /* [nvars]: component in that field */
  int natts;      /* nodal attributes: the constant output fields' components */
  int *att_field, *att_comp;
  double *buf;    /* [n] one component of one variable */
};

/* Fail with the Exodus call, the file and Exodus's own last message when an ex_* call returns
 * a negative status (positive values are warnings). */
#define PF_EX_TRY(ex, status, call)                                                                \
  do {                                                                                             \
    if ((status) < 0) return pf_exodus_fail_((ex)->path, (call), __LINE__, __func__);              \
  } while (0)

static int pf_exodus_fail_(const char *path, const char *call, int line, const char *func) {
  const char *msg = NULL, *where = NULL;
  int code = 0;
  ex_get_err(&msg, &where, &code);
  char why[64]; /* netCDF gives a system error as its positive errno */
  if (code > 0) snprintf(why, sizeof why, "%s", strerror(code));
  else snprintf(why, sizeof why, "status %d", code);
  return pf_error_raise(PF_ERR_LIB, __FILE__, line, func, "Exodus: %s failed (file %s): %s (%s)", call, path,
                        msg && msg[0] ? msg : "no message", why);
}

/* ---- create ---------------------------------------------------------------- */

static int check_bodies(const pf_points *pts, int nbodies, const char *const *body_names,
                        const pf_int *body_start) {
  PF_CHECK(nbodies >= 0, PF_ERR_INPUT, "Exodus output: %d bodies", nbodies);
  if (nbodies == 0) return PF_SUCCESS;
  PF_CHECK(body_names && body_start, PF_ERR_INPUT, "Exodus output: no body names or starts");
  PF_CHECK(body_start[0] == 0 && body_start[nbodies] == pts->n_owned, PF_ERR_INPUT,
           "Exodus output: bodies cover points [%" PF_INT_FMT ", %" PF_INT_FMT
           "), expected [0, %" PF_INT_FMT ")",
           body_start[0], body_start[nbodies], pts->n_owned);
  for (int b = 0; b < nbodies; b++)
    PF_CHECK(body_start[b] <= body_start[b + 1] && body_names[b], PF_ERR_INPUT,
             "Exodus output: body %d has no name or a negative point count", b);
  return PF_SUCCESS;
}

static int field_is_output(const pf_field *fld) { return (fld->flags & PF_FIELD_OUTPUT) != 0; }

/* The built-in vectors, written first: sources -1, -2, -3 of var_field. */
static const char *const builtin_name[3] = {"displacement", "velocity", "force"};

/* Whether the options select the variable named name (all when they list none). */
static int selected(const pf_exodus_options *o, const char *name) {
  if (!o || !o->fields) return 1;
  for (int k = 0; k < o->nfields; k++)
    if (!strcmp(o->fields[k], name)) return 1;
  return 0;
}

static int field_is_constant(const pf_field *fld) { return (fld->flags & PF_FIELD_CONSTANT) != 0; }

/* Append a field's components to a list of (source, component): *n grows by ncomp. */
static void add_source(int *field_of, int *comp_of, int *n, int field, int ncomp) {
  static const int tensor_order[6] = {0, 1, 2, 5, 3, 4}; /* xx yy zz xy yz zx from Voigt */
  for (int c = 0; c < ncomp; c++, (*n)++) {
    field_of[*n] = field;
    comp_of[*n] = ncomp == 6 ? tensor_order[c] : c;
  }
}

/* The nodal variables: the selected built-ins, then the selected output fields that change; for
 * each, its source (a field index, or -1 - b for built-in b) and component. The selected
 * constant fields are the nodal attributes. */
static int plan_variables(pf_exodus *ex, const pf_points *pts, const pf_exodus_options *o) {
  int max = 9;
  for (int k = 0; k < pts->nfields; k++)
    if (field_is_output(&pts->fields[k])) max += pts->fields[k].ncomp;
  PF_MALLOC(ex->var_field, max);
  PF_MALLOC(ex->var_comp, max);
  PF_MALLOC(ex->att_field, max);
  PF_MALLOC(ex->att_comp, max);
  ex->nvars = ex->natts = 0;
  for (int b = 0; b < 3; b++)
    if (selected(o, builtin_name[b])) add_source(ex->var_field, ex->var_comp, &ex->nvars, -1 - b, 3);
  for (int k = 0; k < pts->nfields; k++) {
    const pf_field *f = &pts->fields[k];
    if (!field_is_output(f) || !selected(o, f->name)) continue;
    if (field_is_constant(f)) add_source(ex->att_field, ex->att_comp, &ex->natts, k, f->ncomp);
    else add_source(ex->var_field, ex->var_comp, &ex->nvars, k, f->ncomp);
  }
  return PF_SUCCESS;
}

static void variable_name(const char *base, int ncomp, int comp, char *out) {
  static const char xyz[3] = {'x', 'y', 'z'};
  if (ncomp == 1)
    snprintf(out, PF_EX_NAME_LEN + 1, "%s", base);
  else if (ncomp == 3)
    snprintf(out, PF_EX_NAME_LEN + 1, "%s_%c", base, xyz[comp]);
  else if (ncomp == 6) /* comp: the Voigt component */
    snprintf(out, PF_EX_NAME_LEN + 1, "%s_%s", base, (const char *[]){"xx", "yy", "zz", "yz", "zx", "xy"}[comp]);
  else
    snprintf(out, PF_EX_NAME_LEN + 1, "%s_%d", base, comp);
}

/* The nodal variables' names (attributes: 0) or the nodal attributes' (1). */
static int put_variable_names(pf_exodus *ex, const pf_points *pts, int attributes) {
  const int n = attributes ? ex->natts : ex->nvars;
  const int *field_of = attributes ? ex->att_field : ex->var_field, *comp_of = attributes ? ex->att_comp : ex->var_comp;
  if (n == 0) return PF_SUCCESS;
  char(*store)[PF_EX_NAME_LEN + 1] = NULL;
  char **names = NULL;
  PF_MALLOC(store, n);
  memset(store, 0, sizeof(*store) * (size_t)n); /* (the file takes each name's whole buffer) */
  names = calloc((size_t)n, sizeof(*names));
  if (!names) {
    PF_FREE(store);
    return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory for %d Exodus variable names", n);
  }
  for (int j = 0; j < n; j++) {
    const int k = field_of[j];
    names[j] = store[j];
    if (k < 0) variable_name(builtin_name[-1 - k], 3, comp_of[j], store[j]);
    else variable_name(pts->fields[k].name, pts->fields[k].ncomp, comp_of[j], store[j]);
  }
  int st;
  if (attributes) {
    st = ex_put_attr_param(ex->exoid, EX_NODAL, 0, n);
    if (st >= 0) st = ex_put_attr_names(ex->exoid, EX_NODAL, 0, names);
    free(names), free(store);
    PF_EX_TRY(ex, st, "ex_put_attr_param/ex_put_attr_names(EX_NODAL)");
    return PF_SUCCESS;
  }
  st = ex_put_variable_param(ex->exoid, EX_NODAL, n);
  if (st >= 0) st = ex_put_variable_names(ex->exoid, EX_NODAL, n, names);
  free(names);
  PF_FREE(store);
  PF_EX_TRY(ex, st, "ex_put_variable_param/ex_put_variable_names(EX_NODAL)");
  return PF_SUCCESS;
}

static int put_global_names(pf_exodus *ex, int nglobals, const char *const *global_names) {
  ex->nglobals = nglobals;
  if (nglobals <= 0) return PF_SUCCESS;
  PF_CHECK(global_names, PF_ERR_INPUT, "Exodus output: %d globals but no names", nglobals);
  PF_EX_TRY(ex, ex_put_variable_param(ex->exoid, EX_GLOBAL, nglobals),
            "ex_put_variable_param(EX_GLOBAL)");
  /* Exodus takes char **; it does not modify the names. */
  PF_EX_TRY(ex, ex_put_variable_names(ex->exoid, EX_GLOBAL, nglobals, (char **)global_names),
            "ex_put_variable_names(EX_GLOBAL)");
  return PF_SUCCESS;
}

static int put_coordinates(pf_exodus *ex, const pf_points *pts) {
  char *cnames[3] = {"x", "y", "z"};
  PF_EX_TRY(ex, ex_put_coord_names(ex->exoid, cnames), "ex_put_coord_names");
  if (ex->n == 0) return PF_SUCCESS;
  double *xyz = NULL;
  PF_MALLOC(xyz, 3 * (size_t)ex->n);
  for (pf_int i = 0; i < ex->n; i++)
    for (int d = 0; d < 3; d++) xyz[(size_t)d * ex->n + i] = pts->X[3 * (size_t)i + d];
  int st = ex_put_coord(ex->exoid, xyz, xyz + ex->n, xyz + 2 * (size_t)ex->n);
  PF_FREE(xyz);
  PF_EX_TRY(ex, st, "ex_put_coord");
  return PF_SUCCESS;
}

/* Node id map: global id + 1 (Exodus ids are 1-based). Element id map: a SPHERE element takes
 * its point's id; a HEX8 element takes first_id + its index + 1. */
static int put_id_maps(pf_exodus *ex, const pf_points *pts, int nbodies, const pf_int *body_start,
                       const pf_exodus_hexes *hexes) {
  if (ex->n == 0) return PF_SUCCESS;
  int64_t *ids = NULL;
  PF_MALLOC(ids, ex->n);
  for (pf_int i = 0; i < ex->n; i++) ids[i] = (int64_t)pts->gid[i] + 1;
  int st = ex_put_id_map(ex->exoid, EX_NODE_MAP, ids);
  PF_FREE(ids);
  PF_EX_TRY(ex, st, "ex_put_id_map(EX_NODE_MAP)");
  if (nbodies == 0) return PF_SUCCESS;
  PF_MALLOC(ids, ex->nelem);
  int64_t k = 0;
  for (int b = 0; b < nbodies; b++)
    if (hexes && hexes[b].nelem > 0)
      for (pf_int e = 0; e < hexes[b].nelem; e++) ids[k++] = hexes[b].first_id + e + 1;
    else
      for (pf_int i = body_start[b]; i < body_start[b + 1]; i++) ids[k++] = (int64_t)pts->gid[i] + 1;
  st = ex_put_id_map(ex->exoid, EX_ELEM_MAP, ids);
  PF_FREE(ids);
  PF_EX_TRY(ex, st, "ex_put_id_map(EX_ELEM_MAP)");
  return PF_SUCCESS;
}

static int put_block(pf_exodus *ex, int b, pf_int start, pf_int count) {
  PF_EX_TRY(ex, ex_put_block(ex->exoid, EX_ELEM_BLOCK, b + 1, "SPHERE", count, 1, 0, 0, 0),
            "ex_put_block");
  if (count == 0) return PF_SUCCESS;
  int64_t *conn = NULL;
  PF_MALLOC(conn, count);
  for (pf_int i = 0; i < count; i++) conn[i] = (int64_t)start + i + 1;
  int st = ex_put_conn(ex->exoid, EX_ELEM_BLOCK, b + 1, conn, NULL, NULL);
  PF_FREE(conn);
  PF_EX_TRY(ex, st, "ex_put_conn");
  return PF_SUCCESS;
}

static int put_hex_block(pf_exodus *ex, int b, const pf_exodus_hexes *h) {
  PF_EX_TRY(ex, ex_put_block(ex->exoid, EX_ELEM_BLOCK, b + 1, "HEX8", h->nelem, 8, 0, 0, 0), "ex_put_block");
  int64_t *conn = NULL;
  PF_MALLOC(conn, 8 * (size_t)h->nelem);
  for (size_t k = 0; k < 8 * (size_t)h->nelem; k++) conn[k] = (int64_t)h->conn[k] + 1;
  int st = ex_put_conn(ex->exoid, EX_ELEM_BLOCK, b + 1, conn, NULL, NULL);
  PF_FREE(conn);
  PF_EX_TRY(ex, st, "ex_put_conn(HEX8)");
  return PF_SUCCESS;
}

static int put_blocks(pf_exodus *ex, int nbodies, const char *const *body_names,
                      const pf_int *body_start, const pf_exodus_hexes *hexes) {
  if (nbodies == 0) return PF_SUCCESS;
  for (int b = 0; b < nbodies; b++)
    if (hexes && hexes[b].nelem > 0) PF_CALL(put_hex_block(ex, b, &hexes[b]));
    else PF_CALL(put_block(ex, b, body_start[b], body_start[b + 1] - body_start[b]));
  /* Exodus takes char **; it does not modify the names. */
  PF_EX_TRY(ex, ex_put_names(ex->exoid, EX_ELEM_BLOCK, (char **)body_names),
            "ex_put_names(EX_ELEM_BLOCK)");
  return PF_SUCCESS;
}

static int open_file(pf_exodus *ex, int nbodies, const pf_int *body_start, const pf_exodus_hexes *hexes,
                     const pf_exodus_options *o) {
  const char *title = o && o->prov && o->prov->title && o->prov->title[0] ? o->prov->title : NULL;
  int cpu_ws = 8, io_ws = o && o->single ? 4 : 8; /* (Exodus converts the doubles given to it) */
  int mode = EX_CLOBBER | EX_MAPS_INT64_API | EX_BULK_INT64_API;
  mode |= o && o->compression > 0 ? EX_NETCDF4 : EX_LARGE_MODEL;
  pf_exodus_path at;
  PF_CALL(pf_exodus_path_begin(ex->path, mode & EX_NETCDF4 ? PF_EXODUS_CREATE4 : PF_EXODUS_CREATE, &at));
  ex->exoid = ex_create(at.use, mode, &cpu_ws, &io_ws);
  pf_exodus_path_end(&at);
  PF_EX_TRY(ex, ex->exoid, "ex_create");
  if (o && o->compression > 0) {
    PF_EX_TRY(ex, ex_set_option(ex->exoid, EX_OPT_COMPRESSION_LEVEL, o->compression), "ex_set_option(compression)");
    PF_EX_TRY(ex, ex_set_option(ex->exoid, EX_OPT_COMPRESSION_SHUFFLE, 1), "ex_set_option(shuffle)");
  }
  PF_EX_TRY(ex, ex_set_max_name_length(ex->exoid, PF_EX_NAME_LEN), "ex_set_max_name_length");
  int64_t nelem = 0; /* one SPHERE element per point of a PD body, the hexahedra of an FE body */
  for (int b = 0; b < nbodies; b++)
    nelem += hexes && hexes[b].nelem > 0 ? hexes[b].nelem : body_start[b + 1] - body_start[b];
  ex->nelem = nelem;
  char line[MAX_LINE_LENGTH + 1];
  snprintf(line, sizeof line, "%s", title ? title : "perifem output");
  PF_EX_TRY(ex, ex_put_init(ex->exoid, line, 3, ex->n, nelem, nbodies, 0, 0), "ex_put_init");
  return PF_SUCCESS;
}

/* One QA record (code, version, date, time of now, UTC) and the provenance's lines as info
 * records, each folded into pieces of at most 80 characters. */
static int put_provenance(pf_exodus *ex, const pf_provenance *p) {
  char qa_store[4][MAX_STR_LENGTH + 1], *qa[1][4];
  const time_t now = time(NULL);
  struct tm utc;
  gmtime_r(&now, &utc);
  snprintf(qa_store[0], sizeof qa_store[0], "perifem");
  snprintf(qa_store[1], sizeof qa_store[1], "%s", PERIFEM_VERSION);
  strftime(qa_store[2], sizeof qa_store[2], "%Y-%m-%d", &utc);
  strftime(qa_store[3], sizeof qa_store[3], "%H:%M:%S", &utc);
  for (int k = 0; k < 4; k++) qa[0][k] = qa_store[k];
  PF_EX_TRY(ex, ex_put_qa(ex->exoid, 1, qa), "ex_put_qa");
  int n = 0;
  for (int k = 0; k < p->nlines; k++) n += strlen(p->lines[k]) ? (int)((strlen(p->lines[k]) + 79) / 80) : 1;
  if (n == 0) return PF_SUCCESS;
  char(*store)[MAX_LINE_LENGTH + 1] = NULL;
  char **info = NULL;
  PF_MALLOC(store, n);
  info = malloc(sizeof *info * (size_t)n);
  if (!info) PF_FREE(store);
  PF_CHECK(info, PF_ERR_MEMORY, "out of memory for the Exodus info records");
  int j = 0;
  for (int k = 0; k < p->nlines; k++) {
    const char *s = p->lines[k];
    do {
      snprintf(store[j], sizeof store[j], "%.80s", s);
      info[j] = store[j], j++;
      s += strlen(s) > 80 ? 80 : strlen(s);
    } while (*s);
  }
  const int st = ex_put_info(ex->exoid, n, info);
  free(info), free(store);
  PF_EX_TRY(ex, st, "ex_put_info");
  return PF_SUCCESS;
}

static int setup(pf_exodus *ex, const pf_points *pts, int nbodies, const char *const *body_names,
                 const pf_int *body_start, const pf_exodus_hexes *hexes, int nglobals,
                 const char *const *global_names, const pf_exodus_options *o) {
  const pf_provenance *prov = o ? o->prov : NULL;
  PF_CALL(plan_variables(ex, pts, o));
  PF_MALLOC(ex->buf, ex->n);
  PF_CALL(open_file(ex, nbodies, body_start, hexes, o));
  if (prov) PF_CALL(put_provenance(ex, prov));
  PF_CALL(put_coordinates(ex, pts));
  PF_CALL(put_blocks(ex, nbodies, body_names, body_start, hexes));
  PF_CALL(put_id_maps(ex, pts, nbodies, body_start, hexes));
  if (ex->n > 0) PF_CALL(put_variable_names(ex, pts, 0)); /* Exodus refuses nodal variables without nodes */
  if (ex->n > 0) PF_CALL(put_variable_names(ex, pts, 1));
  PF_CALL(put_global_names(ex, nglobals, global_names));
  PF_EX_TRY(ex, ex_update(ex->exoid), "ex_update");
  return PF_SUCCESS;
}

int pf_exodus_create(const char *path, const pf_points *pts, int nbodies,
                     const char *const *body_names, const pf_int *body_start, int nglobals,
                     const char *const *global_names, const pf_exodus_options *o, pf_exodus **ex) {
  return pf_exodus_create_mixed(path, pts, nbodies, body_names, body_start, NULL, nglobals,
                                global_names, o, ex);
}

int pf_exodus_create_mixed(const char *path, const pf_points *pts, int nbodies,
                           const char *const *body_names, const pf_int *body_start,
                           const pf_exodus_hexes *hexes, int nglobals,
                           const char *const *global_names, const pf_exodus_options *o, pf_exodus **ex) {
  PF_CHECK(path && pts && ex, PF_ERR_INPUT, "pf_exodus_create: NULL argument");
  *ex = NULL;
  PF_CALL(check_bodies(pts, nbodies, body_names, body_start));
  PF_CHECK(pts->n_global < INT32_MAX, PF_ERR_INPUT,
           "Exodus output %s: %" PF_GID_FMT " points exceed the 32-bit id maps", path,
           pts->n_global);
  pf_exodus *e = NULL;
  PF_MALLOC(e, 1);
  e->exoid = -1;
  e->n = pts->n_owned;
  size_t len = strlen(path) + 1;
  e->path = malloc(len);
  if (!e->path) {
    PF_FREE(e);
    return pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__,
                          "out of memory for the Exodus path %s", path);
  }
  memcpy(e->path, path, len);
  int err = setup(e, pts, nbodies, body_names, body_start, hexes, nglobals, global_names, o);
  if (err) {
    pf_exodus_destroy(&e);
    return err;
  }
  *ex = e;
  return PF_SUCCESS;
}

/* ---- write ----------------------------------------------------------------- */

/* Copy component `comp` of an interleaved array with `ncomp` components into ex->buf. */
static void gather(pf_exodus *ex, const double *data, int ncomp, int comp) {
  for (pf_int i = 0; i < ex->n; i++) ex->buf[i] = data[(size_t)i * ncomp + comp];
}

static int put_nodal(pf_exodus *ex, int var) {
  if (ex->n == 0) return PF_SUCCESS;
  PF_EX_TRY(ex, ex_put_var(ex->exoid, ex->step, EX_NODAL, var + 1, 1, ex->n, ex->buf),
            "ex_put_var(EX_NODAL)");
  return PF_SUCCESS;
}

static int check_fields(const pf_exodus *ex, const pf_points *pts) {
  PF_CHECK(pts->n_owned == ex->n, PF_ERR_RUN,
           "Exodus output %s: %" PF_INT_FMT " points, the file was created with %" PF_INT_FMT,
           ex->path, pts->n_owned, ex->n);
  for (int j = 0; j < ex->nvars + ex->natts; j++) {
    const int k = j < ex->nvars ? ex->var_field[j] : ex->att_field[j - ex->nvars];
    const int c = j < ex->nvars ? ex->var_comp[j] : ex->att_comp[j - ex->nvars];
    if (k < 0) continue;
    PF_CHECK(k < pts->nfields && field_is_output(&pts->fields[k]) && c < pts->fields[k].ncomp,
             PF_ERR_RUN, "Exodus output %s: the output fields changed since the file was created",
             ex->path);
  }
  return PF_SUCCESS;
}

/* The nodal attributes (the constant fields), with the first time step. */
static int put_attributes(pf_exodus *ex, const pf_points *pts) {
  if (ex->n == 0) return PF_SUCCESS;
  for (int j = 0; j < ex->natts; j++) {
    const pf_field *f = &pts->fields[ex->att_field[j]];
    gather(ex, f->data, f->ncomp, ex->att_comp[j]);
    PF_EX_TRY(ex, ex_put_one_attr(ex->exoid, EX_NODAL, 0, j + 1, ex->buf), "ex_put_one_attr(EX_NODAL)");
  }
  return PF_SUCCESS;
}

int pf_exodus_write(pf_exodus *ex, double time, const pf_points *pts, const double *globals) {
  PF_CHECK(ex && pts, PF_ERR_INPUT, "pf_exodus_write: NULL argument");
  PF_CALL(check_fields(ex, pts));
  ex->step++;
  PF_EX_TRY(ex, ex_put_time(ex->exoid, ex->step, &time), "ex_put_time");
  if (ex->step == 1) PF_CALL(put_attributes(ex, pts));
  const double *vec[3] = {pts->u, pts->v, pts->f};
  for (int j = 0; j < ex->nvars; j++) {
    const int k = ex->var_field[j];
    if (k < 0) gather(ex, vec[-1 - k], 3, ex->var_comp[j]);
    else gather(ex, pts->fields[k].data, pts->fields[k].ncomp, ex->var_comp[j]);
    PF_CALL(put_nodal(ex, j));
  }
  if (ex->nglobals > 0) {
    PF_CHECK(globals, PF_ERR_INPUT, "Exodus output %s: no global values", ex->path);
    PF_EX_TRY(ex, ex_put_var(ex->exoid, ex->step, EX_GLOBAL, 1, 0, ex->nglobals, globals),
              "ex_put_var(EX_GLOBAL)");
  }
  PF_EX_TRY(ex, ex_update(ex->exoid), "ex_update");
  return PF_SUCCESS;
}

/* ---- destroy --------------------------------------------------------------- */

int pf_exodus_destroy(pf_exodus **ex) {
  if (!ex || !*ex) return PF_SUCCESS;
  pf_exodus *e = *ex;
  *ex = NULL;
  int st = e->exoid >= 0 ? ex_close(e->exoid) : 0;
  int err = st < 0 ? pf_exodus_fail_(e->path, "ex_close", __LINE__, __func__) : PF_SUCCESS;
  PF_FREE(e->var_field);
  PF_FREE(e->var_comp);
  PF_FREE(e->att_field);
  PF_FREE(e->att_comp);
  PF_FREE(e->buf);
  PF_FREE(e->path);
  PF_FREE(e);
  return err;
}
