/* Exodus II meshes: read HEX8 element blocks, node sets and side sets (.e .exo .g .ex2), and
 * write a mesh the same way (pf_mesh_write_exodus). Exodus numbers nodes 1..nnodes,
 * elements 1..nelem block after block in block order, and the sides of a hexahedron 1..6 (the
 * side numbering of the Exodus II manual, Schoof & Yarberry, SAND92-2137, 1994); perifem keeps
 * 0-based indices and sides 0..5 (mesh/mesh_impl.h). Calls go through the int64 API. */
#include "mesh/mesh_impl.h"

#include <exodusII.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define NAME_LEN 63 /* names are read into the 64-byte slots of pf_mesh */

/* Fail with the Exodus call, the file and Exodus's own last message. */
static int exodus_fail(int code, const char *path, const char *call, int line, const char *func) {
  const char *msg = NULL, *where = NULL;
  int status = 0;
  ex_get_err(&msg, &where, &status);
  return pf_error_raise(code, __FILE__, line, func, "%s: Exodus %s failed: %s", path, call,
                        msg && msg[0] ? msg : "no message");
}
/* Reading: a failing call means a bad file (PF_ERR_INPUT); writing: PF_ERR_LIB. */
#define EX_TRY(path, status, call)                                                                 \
  do {                                                                                             \
    if ((status) < 0) return exodus_fail(PF_ERR_INPUT, (path), (call), __LINE__, __func__);        \
  } while (0)
#define EX_TRY_WRITE(path, status, call)                                                           \
  do {                                                                                             \
    if ((status) < 0) return exodus_fail(PF_ERR_LIB, (path), (call), __LINE__, __func__);          \
  } while (0)

/* ---- read -------------------------------------------------------------------------------------
 */
typedef struct {
  int exoid;
  const pf_mesh_source *src;
  int64_t nnodes, nelem, nblk, nns, nss;
  int64_t *blk_ids, *ns_ids, *ss_ids;
  char **names; /* [max(nblk, nns, nss)] name buffers for ex_get_names */
  char *name_store;
  int64_t *buf, *buf2; /* scratch */
  double *xyz;
} exo_reader;

static void reader_free(exo_reader *r) {
  free(r->blk_ids), free(r->ns_ids), free(r->ss_ids), free(r->names), free(r->name_store);
  free(r->buf), free(r->buf2), free(r->xyz);
  if (r->exoid >= 0) ex_close(r->exoid);
}

/* Names of the objects of one kind (id-based fallback "prefix_<id>"). */
static int read_names(exo_reader *r, ex_entity_type kind, int64_t n, const int64_t *ids,
                      const char *prefix, char (*out)[64]) {
  if (n == 0) return 0;
  for (int64_t k = 0; k < n; k++) r->names[k][0] = '\0';
  EX_TRY(r->src->path, ex_get_names(r->exoid, kind, r->names), "ex_get_names");
  for (int64_t k = 0; k < n; k++) pf_mesh_set_name(out[k], r->names[k], prefix, ids[k]);
  return 0;
}

static int read_header(exo_reader *r, pf_mesh_raw *raw) {
  const char *path = r->src->path;
  char title[MAX_LINE_LENGTH + 1];
  int64_t ndim = 0;
  EX_TRY(path,
         ex_get_init(r->exoid, title, &ndim, &r->nnodes, &r->nelem, &r->nblk, &r->nns, &r->nss),
         "ex_get_init");
  if (ndim != 3)
    return PF_MESH_ERROR(r->src, "a %" PRId64 "-D Exodus mesh; perifem reads 3-D hexahedra", ndim);
  PF_CALL(pf_mesh_raw_alloc(raw, r->nnodes, r->nelem, (int)r->nblk));
  int64_t nmax = r->nblk > r->nns ? r->nblk : r->nns;
  nmax = nmax > r->nss ? nmax : r->nss;
  PF_MALLOC(r->names, nmax);
  PF_MALLOC(r->name_store, (NAME_LEN + 1) * (size_t)nmax);
  for (int64_t k = 0; k < nmax; k++) r->names[k] = r->name_store + (NAME_LEN + 1) * k;
  PF_MALLOC(r->blk_ids, r->nblk);
  PF_MALLOC(r->ns_ids, r->nns);
  PF_MALLOC(r->ss_ids, r->nss);
  if (r->nblk)
    EX_TRY(path, ex_get_ids(r->exoid, EX_ELEM_BLOCK, r->blk_ids), "ex_get_ids(EX_ELEM_BLOCK)");
  if (r->nns) EX_TRY(path, ex_get_ids(r->exoid, EX_NODE_SET, r->ns_ids), "ex_get_ids(EX_NODE_SET)");
  if (r->nss) EX_TRY(path, ex_get_ids(r->exoid, EX_SIDE_SET, r->ss_ids), "ex_get_ids(EX_SIDE_SET)");
  return 0;
}

static int read_nodes(exo_reader *r, pf_mesh_raw *raw) {
  const char *path = r->src->path;
  int64_t n = r->nnodes;
  if (n == 0) return 0;
  PF_MALLOC(r->xyz, 3 * (size_t)n);
  EX_TRY(path, ex_get_coord(r->exoid, r->xyz, r->xyz + n, r->xyz + 2 * n), "ex_get_coord");
  for (int64_t i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) raw->mesh.X[3 * i + c] = r->xyz[c * n + i];
  EX_TRY(path, ex_get_id_map(r->exoid, EX_NODE_MAP, raw->node_id), "ex_get_id_map(EX_NODE_MAP)");
  return 0;
}

static int read_blocks(exo_reader *r, pf_mesh_raw *raw) {
  const char *path = r->src->path;
  pf_mesh *m = &raw->mesh;
  PF_CALL(read_names(r, EX_ELEM_BLOCK, r->nblk, r->blk_ids, "block", m->block_name));
  int64_t e0 = 0;
  for (int64_t b = 0; b < r->nblk; b++) {
    char type[MAX_STR_LENGTH + 1] = "";
    int64_t ne = 0, npe = 0, nedge = 0, nface = 0, nattr = 0;
    EX_TRY(path,
           ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_ids[b], type, &ne, &npe, &nedge, &nface,
                        &nattr),
           "ex_get_block");
    if (ne == 0) continue;
    if (strncasecmp(type, "HEX", 3) || npe != 8)
      return PF_MESH_ERROR(r->src,
                           "element block %" PRId64 " ('%s') holds %s elements with %" PRId64
                           " nodes, which perifem does not support: it reads 8-node hexahedra "
                           "(HEX8) only",
                           r->blk_ids[b], m->block_name[b], type, npe);
    if (e0 + ne > r->nelem)
      return PF_MESH_ERROR(
          r->src, "element blocks hold more than the %" PRId64 " elements of the header", r->nelem);
    EX_TRY(path, ex_get_conn(r->exoid, EX_ELEM_BLOCK, r->blk_ids[b], r->buf, NULL, NULL),
           "ex_get_conn");
    for (int64_t e = 0; e < ne; e++) {
      for (int a = 0; a < 8; a++) {
        int64_t k = r->buf[8 * e + a];
        if (k < 1 || k > r->nnodes)
          return PF_MESH_ERROR(r->src,
                               "element %" PRId64 " of block %" PRId64 " names node %" PRId64
                               " (nodes 1..%" PRId64 ")",
                               e0 + e + 1, r->blk_ids[b], k, r->nnodes);
        m->conn[8 * (e0 + e) + a] = (pf_int)(k - 1);
      }
      m->block[e0 + e] = (int32_t)b;
    }
    e0 += ne;
  }
  if (e0 != r->nelem)
    return PF_MESH_ERROR(
        r->src, "element blocks hold %" PRId64 " elements, the header says %" PRId64, e0, r->nelem);
  if (r->nelem)
    EX_TRY(path, ex_get_id_map(r->exoid, EX_ELEM_MAP, raw->elem_id), "ex_get_id_map(EX_ELEM_MAP)");
  return 0;
}

static int read_node_sets(exo_reader *r, pf_mesh_raw *raw) {
  const char *path = r->src->path;
  pf_mesh *m = &raw->mesh;
  char(*names)[64] = NULL;
  if (r->nns == 0) return 0;
  PF_MALLOC(names, r->nns);
  int ierr = read_names(r, EX_NODE_SET, r->nns, r->ns_ids, "nodeset", names);
  for (int64_t s = 0; !ierr && s < r->nns; s++) {
    int64_t n = 0, ndf = 0;
    pf_mesh_set *set = NULL;
    if (ex_get_set_param(r->exoid, EX_NODE_SET, r->ns_ids[s], &n, &ndf) < 0) {
      ierr = exodus_fail(PF_ERR_INPUT, path, "ex_get_set_param(EX_NODE_SET)", __LINE__, __func__);
      break;
    }
    ierr = pf_mesh_add_set(&m->nodeset, &m->nnodesets, names[s], n, 0, &set);
    int64_t *list = ierr ? NULL : calloc((size_t)n + 1, sizeof *list);
    if (!ierr && !list)
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (!ierr && n && ex_get_set(r->exoid, EX_NODE_SET, r->ns_ids[s], list, NULL) < 0)
      ierr = exodus_fail(PF_ERR_INPUT, path, "ex_get_set(EX_NODE_SET)", __LINE__, __func__);
    for (int64_t i = 0; !ierr && i < n; i++) {
      if (list[i] < 1 || list[i] > r->nnodes)
        ierr = PF_MESH_ERROR(r->src, "node set '%s' names node %" PRId64 " (nodes 1..%" PRId64 ")",
                             names[s], list[i], r->nnodes);
      else
        set->item[i] = (pf_int)(list[i] - 1);
    }
    free(list);
  }
  free(names);
  return ierr;
}

static int read_side_sets(exo_reader *r, pf_mesh_raw *raw) {
  const char *path = r->src->path;
  pf_mesh *m = &raw->mesh;
  char(*names)[64] = NULL;
  if (r->nss == 0) return 0;
  PF_MALLOC(names, r->nss);
  int ierr = read_names(r, EX_SIDE_SET, r->nss, r->ss_ids, "sideset", names);
  for (int64_t s = 0; !ierr && s < r->nss; s++) {
    int64_t n = 0, ndf = 0;
    pf_mesh_set *set = NULL;
    if (ex_get_set_param(r->exoid, EX_SIDE_SET, r->ss_ids[s], &n, &ndf) < 0) {
      ierr = exodus_fail(PF_ERR_INPUT, path, "ex_get_set_param(EX_SIDE_SET)", __LINE__, __func__);
      break;
    }
    ierr = pf_mesh_add_set(&m->sideset, &m->nsidesets, names[s], n, 1, &set);
    int64_t *elem = ierr ? NULL : calloc(2 * (size_t)n + 1, sizeof *elem);
    if (!ierr && !elem)
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (!ierr && n && ex_get_set(r->exoid, EX_SIDE_SET, r->ss_ids[s], elem, elem + n) < 0)
      ierr = exodus_fail(PF_ERR_INPUT, path, "ex_get_set(EX_SIDE_SET)", __LINE__, __func__);
    for (int64_t i = 0; !ierr && i < n; i++) {
      int64_t e = elem[i], side = elem[n + i];
      if (e < 1 || e > r->nelem || side < 1 || side > 6)
        ierr = PF_MESH_ERROR(r->src,
                             "side set '%s' names side %" PRId64 " of element %" PRId64
                             " (elements 1..%" PRId64 ", HEX8 sides 1..6)",
                             names[s], side, e, r->nelem);
      else {
        set->item[i] = (pf_int)(e - 1);
        set->face[i] = (int8_t)(side - 1);
      }
    }
    free(elem);
  }
  free(names);
  return ierr;
}

static int read_file(exo_reader *r, pf_mesh_raw *raw) {
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  pf_exodus_path at;
  PF_CALL(pf_exodus_path_begin(r->src->path, PF_EXODUS_OPEN, &at));
  r->exoid = ex_open(at.use, EX_READ, &cpu_ws, &io_ws, &version);
  pf_exodus_path_end(&at);
  EX_TRY(r->src->path, r->exoid, "ex_open (is it an Exodus II file?)");
  EX_TRY(r->src->path, ex_set_int64_status(r->exoid, EX_ALL_INT64_API), "ex_set_int64_status");
  EX_TRY(r->src->path, ex_set_max_name_length(r->exoid, NAME_LEN), "ex_set_max_name_length");
  PF_CALL(read_header(r, raw));
  /* the largest block's connectivity */
  int64_t most = 0;
  for (int64_t b = 0; b < r->nblk; b++) {
    char type[MAX_STR_LENGTH + 1];
    int64_t ne = 0, npe = 0, x1, x2, x3;
    EX_TRY(r->src->path,
           ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_ids[b], type, &ne, &npe, &x1, &x2, &x3),
           "ex_get_block");
    if (ne * npe > most) most = ne * npe;
  }
  PF_MALLOC(r->buf, most);
  PF_CALL(read_nodes(r, raw));
  PF_CALL(read_blocks(r, raw));
  PF_CALL(read_node_sets(r, raw));
  PF_CALL(read_side_sets(r, raw));
  return 0;
}

static int exodus_read(const pf_mesh_source *src, pf_mesh_raw *raw) {
  exo_reader r;
  memset(&r, 0, sizeof r);
  r.exoid = -1;
  r.src = src;
  int ierr = read_file(&r, raw);
  reader_free(&r);
  return ierr;
}

const pf_mesh_reader pf_mesh_reader_exodus = {"exodus", ".e .exo .g .ex2", exodus_read};

/* ---- write ------------------------------------------------------------------------------------
 */
/* Names as the char ** Exodus takes (it does not modify them). */
static int put_names(int exoid, const char *path, ex_entity_type kind, int n, const char *first,
                     size_t stride) {
  if (n == 0) return 0;
  char **names = NULL;
  PF_MALLOC(names, n);
  for (int k = 0; k < n; k++) names[k] = (char *)(first + stride * (size_t)k);
  int st = ex_put_names(exoid, kind, names);
  free(names);
  EX_TRY_WRITE(path, st, "ex_put_names");
  return 0;
}

static int write_blocks(int exoid, const char *path, const pf_mesh *m, int64_t *exo_elem) {
  int64_t *conn = NULL;
  PF_MALLOC(conn, 8 * (size_t)m->nelem);
  int64_t next = 0;
  for (int b = 0; b < m->nblocks; b++) {
    int64_t ne = 0;
    for (pf_int e = 0; e < m->nelem; e++) {
      if (m->block[e] != b) continue;
      for (int a = 0; a < 8; a++) conn[8 * ne + a] = (int64_t)m->conn[8 * (size_t)e + a] + 1;
      exo_elem[e] = ++next; /* elements are numbered block after block */
      ne++;
    }
    int st = ex_put_block(exoid, EX_ELEM_BLOCK, b + 1, "HEX8", ne, 8, 0, 0, 0);
    if (st >= 0 && ne) st = ex_put_conn(exoid, EX_ELEM_BLOCK, b + 1, conn, NULL, NULL);
    if (st < 0) free(conn);
    EX_TRY_WRITE(path, st, "ex_put_block/ex_put_conn");
  }
  free(conn);
  return put_names(exoid, path, EX_ELEM_BLOCK, m->nblocks, m->block_name[0],
                   sizeof m->block_name[0]);
}

static int write_sets(int exoid, const char *path, const pf_mesh *m, const int64_t *exo_elem) {
  for (int side = 0; side < 2; side++) {
    int n = side ? m->nsidesets : m->nnodesets;
    const pf_mesh_set *sets = side ? m->sideset : m->nodeset;
    ex_entity_type kind = side ? EX_SIDE_SET : EX_NODE_SET;
    for (int s = 0; s < n; s++) {
      int64_t *list = NULL, len = sets[s].n;
      PF_MALLOC(list, 2 * (size_t)len);
      for (pf_int i = 0; i < len; i++) {
        list[i] = side ? exo_elem[sets[s].item[i]] : (int64_t)sets[s].item[i] + 1;
        if (side) list[len + i] = sets[s].face[i] + 1;
      }
      int st = ex_put_set_param(exoid, kind, s + 1, len, 0);
      if (st >= 0 && len) st = ex_put_set(exoid, kind, s + 1, list, side ? list + len : NULL);
      free(list);
      EX_TRY_WRITE(path, st, side ? "ex_put_set(EX_SIDE_SET)" : "ex_put_set(EX_NODE_SET)");
    }
    if (n) PF_CALL(put_names(exoid, path, kind, n, sets[0].name, sizeof(pf_mesh_set)));
  }
  return 0;
}

static int write_file(int exoid, const char *path, const pf_mesh *m, int64_t *exo_elem) {
  EX_TRY_WRITE(path, ex_set_max_name_length(exoid, NAME_LEN), "ex_set_max_name_length");
  EX_TRY_WRITE(path,
               ex_put_init(exoid, "perifem mesh", 3, m->nnodes, m->nelem, m->nblocks, m->nnodesets,
                           m->nsidesets),
               "ex_put_init");
  char *cnames[3] = {"x", "y", "z"};
  EX_TRY_WRITE(path, ex_put_coord_names(exoid, cnames), "ex_put_coord_names");
  double *xyz = NULL;
  PF_MALLOC(xyz, 3 * (size_t)m->nnodes);
  for (pf_int i = 0; i < m->nnodes; i++)
    for (int c = 0; c < 3; c++) xyz[(size_t)c * m->nnodes + i] = m->X[3 * (size_t)i + c];
  int st = ex_put_coord(exoid, xyz, xyz + m->nnodes, xyz + 2 * (size_t)m->nnodes);
  free(xyz);
  EX_TRY_WRITE(path, st, "ex_put_coord");
  PF_CALL(write_blocks(exoid, path, m, exo_elem));
  PF_CALL(write_sets(exoid, path, m, exo_elem));
  return 0;
}

int pf_mesh_write_exodus(const char *path, const pf_mesh *m) {
  PF_CHECK(m && m->nnodes > 0 && m->nelem > 0, PF_ERR_INPUT, "%s: no mesh to write", path);
  int cpu_ws = 8, io_ws = 8;
  pf_exodus_path at;
  PF_CALL(pf_exodus_path_begin(path, PF_EXODUS_CREATE, &at));
  int exoid = ex_create(at.use, EX_CLOBBER | EX_LARGE_MODEL | EX_ALL_INT64_API, &cpu_ws, &io_ws);
  pf_exodus_path_end(&at);
  EX_TRY_WRITE(path, exoid, "ex_create");
  int64_t *exo_elem = calloc((size_t)m->nelem, sizeof *exo_elem);
  int ierr = exo_elem
                 ? write_file(exoid, path, m, exo_elem)
                 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  free(exo_elem);
  if (ex_close(exoid) < 0 && !ierr)
    ierr = exodus_fail(PF_ERR_LIB, path, "ex_close", __LINE__, __func__);
  return ierr;
}
