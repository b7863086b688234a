/* Peridigm's Exodus discretization as a peridynamic body's points (`geometry: {shape: exodus}`):
 * an Exodus II file whose element blocks hold SPHERE elements, one node each; every element is
 * one point at its node, of the volume the element's attribute named `volume` gives. When a
 * block's attributes carry no names, the Sierra/SolidMechanics sphere convention that Peridigm
 * follows applies: attribute 1 is the sphere's radius, attribute 2 its volume. The points come
 * in file order (blocks in file order, elements in block order), each with its block's id.
 * A node set holds the points of the elements on its nodes (for SPHERE elements: the element at
 * each node), as Peridigm reads it; side sets have no meaning for spheres and are ignored.
 * Exodus II format: Schoof & Yarberry, SAND92-2137 (1994); Peridigm's use of it: Parks,
 * Littlewood, Mitchell & Silling, Peridigm Users' Guide v1.0.0, SAND2012-7800 (2012). */
#include "mesh/mesh_impl.h"

#include <errno.h>
#include <exodusII.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define NAME_LEN 63

typedef struct {
  const pf_deck *d;
  const pf_node *g, *file_node; /* the geometry mapping and its `file` key */
  char path[4096];
  int exoid;
  double scale;
  int64_t nnodes, nelem, nblk, nns;
  int64_t *blk_id;
  char (*blk_name)[64];
  int *take;       /* [nblk] 1: the deck takes this block */
  double *xyz;     /* [3 nnodes] coordinates, component-major as Exodus stores them */
  pf_int *node_pt; /* [nnodes] the cloud point at each node, -1: none */
} sphere_reader;

static void reader_free(sphere_reader *r) {
  free(r->blk_id), free(r->blk_name), free(r->take), free(r->xyz), free(r->node_pt);
  if (r->exoid >= 0) ex_close(r->exoid);
}

/* An error about the file's content, naming the deck's `file` key and the file. */
#define FILE_ERROR(r, ...) file_error_((r), __VA_ARGS__)
static int file_error_(const sphere_reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int file_error_(const sphere_reader *r, const char *fmt, ...) {
  char msg[1536];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return pf_deck_error(r->d, r->file_node, "file", "%s: %s", r->path, msg);
}

static int exodus_call(const sphere_reader *r, int status, const char *call) {
  if (status >= 0) return 0;
  const char *msg = NULL, *where = NULL;
  int code = 0;
  ex_get_err(&msg, &where, &code);
  return FILE_ERROR(r, "Exodus %s failed: %s", call, msg && msg[0] ? msg : "no message");
}
#define EXO(r, call) PF_CALL(exodus_call((r), (call), #call))

/* "'cylinder' (id 1), 'rings' (id 2)" */
static void block_list(const sphere_reader *r, char *out, size_t len) {
  out[0] = '\0';
  for (int64_t b = 0; b < r->nblk; b++) {
    size_t used = strlen(out);
    snprintf(out + used, len - used, "%s'%s' (id %" PRId64 ")", b ? ", " : "", r->blk_name[b], r->blk_id[b]);
  }
}

static int read_header(sphere_reader *r) {
  char title[MAX_LINE_LENGTH + 1];
  int64_t ndim = 0, nss = 0;
  EXO(r, ex_get_init(r->exoid, title, &ndim, &r->nnodes, &r->nelem, &r->nblk, &r->nns, &nss));
  if (ndim != 3) return FILE_ERROR(r, "a %" PRId64 "-D Exodus file; a discretization is 3-D", ndim);
  if (r->nblk == 0) return FILE_ERROR(r, "no element blocks");
  if (nss) pf_log("%s: %" PRId64 " side set(s) ignored (SPHERE elements have no sides)\n", r->path, nss);
  PF_MALLOC(r->blk_id, r->nblk);
  PF_MALLOC(r->blk_name, r->nblk);
  PF_MALLOC(r->take, r->nblk);
  EXO(r, ex_get_ids(r->exoid, EX_ELEM_BLOCK, r->blk_id));
  char **names = NULL, *store = NULL;
  PF_MALLOC(names, r->nblk);
  store = calloc((size_t)r->nblk, NAME_LEN + 1);
  if (!store) free(names);
  PF_CHECK(store, PF_ERR_MEMORY, "out of memory");
  for (int64_t b = 0; b < r->nblk; b++) names[b] = store + (NAME_LEN + 1) * b;
  int st = ex_get_names(r->exoid, EX_ELEM_BLOCK, names);
  for (int64_t b = 0; st >= 0 && b < r->nblk; b++) pf_mesh_set_name(r->blk_name[b], names[b], "block", r->blk_id[b]);
  free(names), free(store);
  EXO(r, st);
  PF_MALLOC(r->xyz, 3 * (size_t)r->nnodes);
  if (r->nnodes) EXO(r, ex_get_coord(r->exoid, r->xyz, r->xyz + r->nnodes, r->xyz + 2 * r->nnodes));
  return 0;
}

/* The deck's `blocks:` (names or ids), or every block. */
static int choose_blocks(sphere_reader *r) {
  const pf_node *list = pf_node_get(r->g, "blocks");
  for (int64_t b = 0; b < r->nblk; b++) r->take[b] = !list;
  for (int i = 0; list && i < pf_node_count(list); i++) {
    const pf_node *it = pf_node_item(list, i);
    const char *want = pf_node_text(it);
    char *end = NULL;
    const long long id = want ? strtoll(want, &end, 10) : 0;
    const int numeric = want && end != want && *end == '\0';
    int64_t b = 0;
    while (b < r->nblk && !(want && !strcmp(r->blk_name[b], want))) b++;
    if (b == r->nblk && numeric)
      for (b = 0; b < r->nblk && r->blk_id[b] != id; b++) {}
    if (b == r->nblk) {
      char known[2048];
      block_list(r, known, sizeof known);
      return pf_deck_error(r->d, it, "blocks", "%s has no block named or numbered '%s' (its blocks: %s)", r->path,
                           want ? want : "", known);
    }
    r->take[b] = 1;
  }
  return 0;
}

/* The index of the attribute that holds the volume, or an error. */
static int volume_attribute(sphere_reader *r, int64_t b, int64_t nattr, int64_t *which) {
  char **names = NULL, *store = NULL;
  PF_MALLOC(names, nattr + 1);
  store = calloc((size_t)nattr + 1, NAME_LEN + 1);
  if (!store) free(names);
  PF_CHECK(store, PF_ERR_MEMORY, "out of memory");
  for (int64_t a = 0; a < nattr; a++) names[a] = store + (NAME_LEN + 1) * a;
  int st = nattr ? ex_get_attr_names(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], names) : 0;
  int named = 0;
  char known[1024] = "";
  *which = -1;
  for (int64_t a = 0; st >= 0 && a < nattr; a++) {
    char name[64];
    pf_mesh_set_name(name, names[a], "", 0);
    if (names[a][strspn(names[a], " ")] == '\0') continue; /* blank */
    named = 1;
    if (!strcasecmp(name, "volume") && *which < 0) *which = a;
    size_t used = strlen(known);
    snprintf(known + used, sizeof known - used, "%s'%s'", used ? ", " : "", name);
  }
  free(names), free(store);
  PF_CALL(exodus_call(r, st, "ex_get_attr_names"));
  if (*which >= 0) return 0;
  if (!named && nattr >= 2) { /* unnamed: radius, volume (the Sierra/SolidMechanics order) */
    *which = 1;
    return 0;
  }
  return FILE_ERROR(r,
                    "block '%s' (id %" PRId64 ") has no volume attribute (its %" PRId64 " attribute(s): %s); "
                    "Peridigm's SPHERE format gives each element its volume in an attribute named 'volume' "
                    "(or, unnamed, the second of 'radius, volume')",
                    r->blk_name[b], r->blk_id[b], nattr, nattr ? (named ? known : "unnamed") : "none");
}

static int cloud_alloc(pf_point_cloud *pc, int64_t n) {
  PF_CHECK(n <= INT32_MAX, PF_ERR_INPUT, "a discretization of %" PRId64 " points is too large for one body", n);
  PF_MALLOC(pc->X, 3 * (size_t)n);
  PF_MALLOC(pc->vol, n);
  PF_MALLOC(pc->cell, n);
  PF_MALLOC(pc->block, n);
  return 0;
}

/* One block's elements into the cloud from point pc->n on; e0: the file's number of its first
 * element less one. */
static int read_block(sphere_reader *r, int64_t b, int64_t e0, pf_point_cloud *pc, int64_t *buf, double *attr) {
  char type[MAX_STR_LENGTH + 1] = "";
  int64_t ne = 0, npe = 0, nedge = 0, nface = 0, nattr = 0, which = -1;
  EXO(r, ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], type, &ne, &npe, &nedge, &nface, &nattr));
  if (ne == 0) return 0;
  if (strncasecmp(type, "SPHERE", 6) || npe != 1)
    return FILE_ERROR(r,
                      "block '%s' (id %" PRId64 ") holds %s elements of %" PRId64 " nodes, not SPHERE elements "
                      "(one node each) as a Peridigm discretization does; a hexahedral mesh is an FE body's "
                      "mesh:, or leave the block out with geometry.blocks",
                      r->blk_name[b], r->blk_id[b], type, npe);
  PF_CALL(volume_attribute(r, b, nattr, &which));
  EXO(r, ex_get_conn(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], buf, NULL, NULL));
  EXO(r, ex_get_attr(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], attr));
  const double s3 = r->scale * r->scale * r->scale;
  for (int64_t e = 0; e < ne; e++) {
    const int64_t node = buf[e];
    const double vol = attr[e * nattr + which] * s3;
    if (node < 1 || node > r->nnodes)
      return FILE_ERROR(r, "element %" PRId64 " (block '%s') names node %" PRId64 " (nodes 1..%" PRId64 ")",
                        e0 + e + 1, r->blk_name[b], node, r->nnodes);
    if (!(vol > 0 && isfinite(vol)))
      return FILE_ERROR(r, "element %" PRId64 " (block '%s') has volume %g (m^3 after scale); volumes must be "
                        "positive", e0 + e + 1, r->blk_name[b], vol);
    const pf_int i = pc->n++;
    for (int c = 0; c < 3; c++) pc->X[3 * i + c] = r->xyz[c * r->nnodes + node - 1] * r->scale;
    if (!isfinite(pc->X[3 * i] + pc->X[3 * i + 1] + pc->X[3 * i + 2]))
      return FILE_ERROR(r, "node %" PRId64 " has a coordinate that is not a finite number", node);
    pc->vol[i] = vol;
    pc->cell[i] = cbrt(vol);
    pc->block[i] = (int32_t)r->blk_id[b];
    r->node_pt[node - 1] = i;
  }
  return 0;
}

static int read_blocks(sphere_reader *r, pf_point_cloud *pc) {
  int64_t most = 0, total = 0;
  for (int64_t b = 0; b < r->nblk; b++) {
    char type[MAX_STR_LENGTH + 1];
    int64_t ne = 0, npe = 0, x1, x2, nattr = 0;
    EXO(r, ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], type, &ne, &npe, &x1, &x2, &nattr));
    most = fmax(most, ne * (npe > nattr ? npe : nattr));
    total += r->take[b] ? ne : 0;
  }
  PF_CALL(cloud_alloc(pc, total));
  PF_MALLOC(r->node_pt, r->nnodes);
  for (int64_t k = 0; k < r->nnodes; k++) r->node_pt[k] = -1;
  int64_t *buf = malloc(sizeof *buf * (size_t)(most + 1));
  double *attr = malloc(sizeof *attr * (size_t)(most + 1));
  int ierr = buf && attr ? 0 : pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  int64_t e0 = 0;
  for (int64_t b = 0; b < r->nblk && !ierr; b++) {
    char type[MAX_STR_LENGTH + 1];
    int64_t ne = 0, npe = 0, x1, x2, x3;
    ierr = exodus_call(r, ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], type, &ne, &npe, &x1, &x2, &x3),
                       "ex_get_block");
    if (!ierr && r->take[b]) ierr = read_block(r, b, e0, pc, buf, attr);
    e0 += ne;
  }
  free(buf), free(attr);
  if (!ierr && pc->n == 0) {
    char known[2048];
    block_list(r, known, sizeof known);
    return FILE_ERROR(r, "the blocks taken hold no element (its blocks: %s)", known);
  }
  return ierr;
}

/* Node sets: the points at their nodes (nodes of blocks not taken are left out). */
static int read_node_sets(sphere_reader *r, pf_point_cloud *pc) {
  if (r->nns == 0) return 0;
  int64_t *ids = NULL;
  PF_MALLOC(ids, r->nns);
  char(*names)[64] = NULL;
  char **np = NULL, *store = NULL;
  int ierr = exodus_call(r, ex_get_ids(r->exoid, EX_NODE_SET, ids), "ex_get_ids(EX_NODE_SET)");
  names = calloc((size_t)r->nns, sizeof *names);
  np = calloc((size_t)r->nns, sizeof *np);
  store = calloc((size_t)r->nns, NAME_LEN + 1);
  if (!ierr && !(names && np && store)) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (int64_t s = 0; !ierr && s < r->nns; s++) np[s] = store + (NAME_LEN + 1) * s;
  if (!ierr) ierr = exodus_call(r, ex_get_names(r->exoid, EX_NODE_SET, np), "ex_get_names(EX_NODE_SET)");
  pc->sets = ierr ? NULL : calloc((size_t)r->nns, sizeof *pc->sets);
  if (!ierr && !pc->sets) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  for (int64_t s = 0; !ierr && s < r->nns; s++) {
    pf_point_set *set = &pc->sets[pc->nsets];
    int64_t n = 0, ndf = 0;
    pf_mesh_set_name(names[s], np[s], "nodelist", ids[s]); /* Peridigm's name for an unnamed set */
    for (int64_t q = 0; q < s; q++)
      if (!strcmp(names[q], names[s])) ierr = FILE_ERROR(r, "two node sets named '%s'", names[s]);
    if (!ierr) ierr = exodus_call(r, ex_get_set_param(r->exoid, EX_NODE_SET, ids[s], &n, &ndf), "ex_get_set_param");
    int64_t *list = ierr ? NULL : calloc((size_t)n + 1, sizeof *list);
    set->gid = ierr ? NULL : calloc((size_t)n + 1, sizeof *set->gid);
    if (!ierr && !(list && set->gid)) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (!ierr) {
      pc->nsets++;
      snprintf(set->name, sizeof set->name, "%s", names[s]);
      set->body = -1;
    }
    if (!ierr && n) ierr = exodus_call(r, ex_get_set(r->exoid, EX_NODE_SET, ids[s], list, NULL), "ex_get_set");
    for (int64_t k = 0; !ierr && k < n; k++) {
      if (list[k] < 1 || list[k] > r->nnodes)
        ierr = FILE_ERROR(r, "node set '%s' names node %" PRId64 " (nodes 1..%" PRId64 ")", names[s], list[k],
                          r->nnodes);
      else if (r->node_pt[list[k] - 1] >= 0)
        set->gid[set->n++] = r->node_pt[list[k] - 1];
    }
    free(list);
  }
  free(ids), free(names), free(np), free(store);
  return ierr;
}

static int read_file(sphere_reader *r, pf_point_cloud *pc) {
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  pf_exodus_path at;
  PF_CALL(pf_exodus_path_begin(r->path, PF_EXODUS_OPEN, &at));
  r->exoid = ex_open(at.use, EX_READ, &cpu_ws, &io_ws, &version);
  pf_exodus_path_end(&at);
  if (r->exoid < 0) return FILE_ERROR(r, "not an Exodus II file (ex_open failed)");
  EXO(r, ex_set_int64_status(r->exoid, EX_ALL_INT64_API));
  EXO(r, ex_set_max_name_length(r->exoid, NAME_LEN));
  PF_CALL(read_header(r));
  PF_CALL(choose_blocks(r));
  PF_CALL(read_blocks(r, pc));
  PF_CALL(read_node_sets(r, pc));
  return pf_point_cloud_check_distinct(r->path, pc);
}

int pf_mesh_spheres_from_deck(const pf_deck *d, const pf_node *g, pf_point_cloud *pc) {
  memset(pc, 0, sizeof *pc);
  sphere_reader r;
  memset(&r, 0, sizeof r);
  r.exoid = -1;
  r.d = d, r.g = g, r.file_node = pf_node_get(g, "file");
  const char *file = NULL;
  PF_CALL(pf_deck_string(d, g, "file", &file));
  if (!file) return pf_deck_error(d, g, "file", "shape 'exodus' needs key 'file'");
  if (pf_node_get(g, "block"))
    return pf_deck_error(d, pf_node_get(g, "block"), "block", "shape 'exodus' takes 'blocks' (a list of block "
                         "names or ids)");
  r.scale = 1;
  PF_CALL(pf_deck_real(d, g, "scale", &r.scale));
  if (!(r.scale > 0 && isfinite(r.scale)))
    return pf_deck_error(d, pf_node_get(g, "scale"), "scale", "must be positive (got %g)", r.scale);
  pf_deck_relative_path(d, file, r.path, sizeof r.path);
  FILE *probe = fopen(r.path, "r");
  if (!probe) return pf_deck_error(d, r.file_node, "file", "cannot open '%s': %s", r.path, strerror(errno));
  fclose(probe);
  int ierr = read_file(&r, pc);
  if (!ierr)
    pf_log("%s: %" PF_INT_FMT " points from SPHERE elements, %d node set(s)\n", r.path, pc->n, pc->nsets);
  reader_free(&r);
  if (ierr) pf_point_cloud_free(pc);
  return ierr;
}
