/* Peridigm's Exodus discretization as a peridynamic body's points (`geometry: {shape: exodus}`):
 * an Exodus II file whose element blocks hold SPHERE, HEX8 or TET4 elements, one point per
 * element, as Peridigm's Exodus discretization reads them.
 *  - SPHERE (one node): the point sits at the node, with the volume the element's attribute named
 *    `volume` gives. When a block's attributes carry no names, the Sierra/SolidMechanics sphere
 *    convention that Peridigm follows applies: attribute 1 is the sphere's radius, attribute 2
 *    its volume.
 *  - HEX8 (type HEX, HEX8 or HEXAHEDRON, 8 nodes) and TET4 (TET, TET4, TETRA or TETRA4, 4 nodes):
 *    the point sits at the element's centroid with the element's volume, both computed from
 *    tetrahedra as Peridigm does (mesh/element_point.c); an element with a tetrahedron of
 *    negative volume is refused, as Peridigm refuses it.
 * Any other element type is refused naming the block. The points come in file order (blocks in
 * file order, elements in block order), each with its block's id.
 * A node set holds the points of every element that has one of its nodes (a SPHERE: the element
 * at the node; a hexahedron or tetrahedron: every element the node is a corner of), as Peridigm
 * maps a node set onto its points; elements of blocks not taken are left out. Side sets are
 * ignored, as Peridigm ignores them.
 * Exodus II format: Schoof & Yarberry, SAND92-2137 (1994); Peridigm's use of it: Parks,
 * Littlewood, Mitchell & Silling, Peridigm Users' Guide v1.0.0, SAND2012-7800 (2012), and
 * Peridigm's src/io/discretization/Peridigm_ExodusDiscretization.cpp (loadData: element types,
 * the node-set rule). */
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
  int64_t *pt_node; /* [8 points] the nodes (0-based) of each point's element, -1: none */
  int64_t *node_off; /* [nnodes + 1] node -> points: node_pts[node_off[k] .. node_off[k + 1]) */
  pf_int *node_pts;  /* the points of the elements on each node, ascending */
  int64_t nkind[4];  /* elements read of each kind (elem_kind) */
} exo_reader;

static void reader_free(exo_reader *r) {
  free(r->blk_id), free(r->blk_name), free(r->take), free(r->xyz), free(r->pt_node), free(r->node_off);
  free(r->node_pts);
  if (r->exoid >= 0) ex_close(r->exoid);
}

/* An error about the file's content, naming the deck's `file` key and the file. */
#define FILE_ERROR(r, ...) file_error_((r), __VA_ARGS__)
static int file_error_(const exo_reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int file_error_(const exo_reader *r, const char *fmt, ...) {
  char msg[1536];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return pf_deck_error(r->d, r->file_node, "file", "%s: %s", r->path, msg);
}

static int exodus_call(const exo_reader *r, int status, const char *call) {
  if (status >= 0) return 0;
  const char *msg = NULL, *where = NULL;
  int code = 0;
  ex_get_err(&msg, &where, &code);
  return FILE_ERROR(r, "Exodus %s failed: %s", call, msg && msg[0] ? msg : "no message");
}
#define EXO(r, call) PF_CALL(exodus_call((r), (call), #call))

/* "'cylinder' (id 1), 'rings' (id 2)" */
static void block_list(const exo_reader *r, char *out, size_t len) {
  out[0] = '\0';
  for (int64_t b = 0; b < r->nblk; b++) {
    size_t used = strlen(out);
    snprintf(out + used, len - used, "%s'%s' (id %" PRId64 ")", b ? ", " : "", r->blk_name[b], r->blk_id[b]);
  }
}

static int read_header(exo_reader *r) {
  char title[MAX_LINE_LENGTH + 1];
  int64_t ndim = 0, nss = 0;
  EXO(r, ex_get_init(r->exoid, title, &ndim, &r->nnodes, &r->nelem, &r->nblk, &r->nns, &nss));
  if (ndim != 3) return FILE_ERROR(r, "a %" PRId64 "-D Exodus file; a discretization is 3-D", ndim);
  if (r->nblk == 0) return FILE_ERROR(r, "no element blocks");
  if (nss) pf_log("%s: %" PRId64 " side set(s) ignored (a Peridigm discretization reads node sets)\n", r->path, nss);
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
static int choose_blocks(exo_reader *r) {
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
static int volume_attribute(exo_reader *r, int64_t b, int64_t nattr, int64_t *which) {
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

typedef enum { ELEM_OTHER, ELEM_SPHERE, ELEM_TET, ELEM_HEX } elem_kind;
static const char *const kind_name[] = {"other", "SPHERE", "TET4", "HEX8"};

/* The kind of a block's elements from its type (any case) and nodes per element. */
static elem_kind element_kind(const char *type, int64_t npe) {
  static const struct {
    const char *type;
    elem_kind kind;
  } types[] = {{"HEX", ELEM_HEX},  {"HEX8", ELEM_HEX},  {"HEXAHEDRON", ELEM_HEX}, {"TET", ELEM_TET},
               {"TET4", ELEM_TET}, {"TETRA", ELEM_TET}, {"TETRA4", ELEM_TET}};
  static const int64_t nodes[] = {0, 1, 4, 8};
  if (!strncasecmp(type, "SPHERE", 6)) return npe == 1 ? ELEM_SPHERE : ELEM_OTHER;
  for (size_t k = 0; k < sizeof types / sizeof types[0]; k++)
    if (!strcasecmp(type, types[k].type)) return npe == nodes[types[k].kind] ? types[k].kind : ELEM_OTHER;
  return ELEM_OTHER;
}

/* Every node the block's connectivity names exists. */
static int check_nodes(const exo_reader *r, int64_t b, int64_t e0, const int64_t *conn, int64_t ne, int64_t npe) {
  for (int64_t k = 0; k < ne * npe; k++)
    if (conn[k] < 1 || conn[k] > r->nnodes)
      return FILE_ERROR(r, "element %" PRId64 " (block '%s') names node %" PRId64 " (nodes 1..%" PRId64 ")",
                        e0 + k / npe + 1, r->blk_name[b], conn[k], r->nnodes);
  return 0;
}

/* Append a point; nodes: its element's npe nodes (1-based). */
static void add_point(exo_reader *r, int64_t b, pf_point_cloud *pc, const double x[3], double vol,
                      const int64_t *nodes, int64_t npe) {
  const pf_int i = pc->n++;
  for (int c = 0; c < 3; c++) pc->X[3 * i + c] = x[c];
  pc->vol[i] = vol;
  pc->cell[i] = cbrt(vol);
  pc->block[i] = (int32_t)r->blk_id[b];
  for (int64_t a = 0; a < npe; a++) r->pt_node[8 * (size_t)i + a] = nodes[a] - 1;
}

/* A SPHERE block: each element a point at its node with its volume attribute. */
static int read_spheres(exo_reader *r, int64_t b, int64_t e0, int64_t ne, int64_t nattr, pf_point_cloud *pc,
                        const int64_t *conn, double *attr) {
  int64_t which = -1;
  PF_CALL(volume_attribute(r, b, nattr, &which));
  EXO(r, ex_get_attr(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], attr));
  const double s3 = r->scale * r->scale * r->scale;
  for (int64_t e = 0; e < ne; e++) {
    const int64_t node = conn[e];
    const double vol = attr[e * nattr + which] * s3;
    if (!(vol > 0 && isfinite(vol)))
      return FILE_ERROR(r, "element %" PRId64 " (block '%s') has volume %g (m^3 after scale); volumes must be "
                        "positive", e0 + e + 1, r->blk_name[b], vol);
    double x[3];
    for (int c = 0; c < 3; c++) x[c] = r->xyz[c * r->nnodes + node - 1] * r->scale;
    if (!isfinite(x[0] + x[1] + x[2]))
      return FILE_ERROR(r, "node %" PRId64 " has a coordinate that is not a finite number", node);
    add_point(r, b, pc, x, vol, &conn[e], 1);
  }
  return 0;
}

/* A HEX8 or TET4 block: each element a point at its centroid with its volume (Peridigm's rule). */
static int read_solids(exo_reader *r, int64_t b, int64_t e0, int64_t ne, elem_kind kind, pf_point_cloud *pc,
                       const int64_t *conn) {
  const int64_t npe = kind == ELEM_HEX ? 8 : 4;
  for (int64_t e = 0; e < ne; e++) {
    const int64_t *nodes = conn + e * npe;
    double x[8][3], c[3], vol = 0;
    for (int64_t a = 0; a < npe; a++) {
      for (int i = 0; i < 3; i++) x[a][i] = r->xyz[i * r->nnodes + nodes[a] - 1] * r->scale;
      if (!isfinite(x[a][0] + x[a][1] + x[a][2]))
        return FILE_ERROR(r, "node %" PRId64 " has a coordinate that is not a finite number", nodes[a]);
    }
    const double least = kind == ELEM_HEX ? pf_mesh_hex_point((const double(*)[3])x, c, &vol)
                                          : pf_mesh_tet_point((const double(*)[3])x, c, &vol);
    if (!(least >= 0 && vol > 0 && isfinite(vol)))
      return FILE_ERROR(r, "element %" PRId64 " (block '%s', %s) has volume %g with a tetrahedron of volume %g "
                        "(m^3 after scale) in Peridigm's split: the element is inverted or flat, or its nodes "
                        "are not in Exodus order", e0 + e + 1, r->blk_name[b], kind_name[kind], vol, least);
    add_point(r, b, pc, c, vol, nodes, npe);
  }
  return 0;
}

/* One block's elements into the cloud from point pc->n on; e0: the file's number of its first
 * element less one. */
static int read_block(exo_reader *r, int64_t b, int64_t e0, pf_point_cloud *pc, int64_t *buf, double *attr) {
  char type[MAX_STR_LENGTH + 1] = "";
  int64_t ne = 0, npe = 0, nedge = 0, nface = 0, nattr = 0;
  EXO(r, ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], type, &ne, &npe, &nedge, &nface, &nattr));
  if (ne == 0) return 0;
  const elem_kind kind = element_kind(type, npe);
  if (kind == ELEM_OTHER)
    return FILE_ERROR(r,
                      "block '%s' (id %" PRId64 ") holds %s elements of %" PRId64 " nodes; a Peridigm "
                      "discretization is read from SPHERE (1 node), HEX8 (HEX, HEX8, HEXAHEDRON: 8 nodes) "
                      "and TET4 (TET, TET4, TETRA, TETRA4: 4 nodes) blocks; leave the block out with "
                      "geometry.blocks",
                      r->blk_name[b], r->blk_id[b], type, npe);
  EXO(r, ex_get_conn(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], buf, NULL, NULL));
  PF_CALL(check_nodes(r, b, e0, buf, ne, npe));
  r->nkind[kind] += ne;
  if (kind == ELEM_SPHERE) return read_spheres(r, b, e0, ne, nattr, pc, buf, attr);
  return read_solids(r, b, e0, ne, kind, pc, buf);
}

static int read_blocks(exo_reader *r, pf_point_cloud *pc) {
  int64_t most = 0, total = 0;
  for (int64_t b = 0; b < r->nblk; b++) {
    char type[MAX_STR_LENGTH + 1];
    int64_t ne = 0, npe = 0, x1, x2, nattr = 0;
    EXO(r, ex_get_block(r->exoid, EX_ELEM_BLOCK, r->blk_id[b], type, &ne, &npe, &x1, &x2, &nattr));
    most = fmax(most, ne * (npe > nattr ? npe : nattr));
    total += r->take[b] ? ne : 0;
  }
  PF_CALL(cloud_alloc(pc, total));
  PF_MALLOC(r->pt_node, 8 * (size_t)total);
  for (int64_t k = 0; k < 8 * total; k++) r->pt_node[k] = -1;
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

/* node -> the points of the elements on it (ascending), from each point's element nodes. */
static int node_points(exo_reader *r, const pf_point_cloud *pc) {
  PF_MALLOC(r->node_off, r->nnodes + 1);
  for (size_t k = 0; k < 8 * (size_t)pc->n; k++)
    if (r->pt_node[k] >= 0) r->node_off[r->pt_node[k] + 1]++;
  for (int64_t k = 0; k < r->nnodes; k++) r->node_off[k + 1] += r->node_off[k];
  int64_t *fill = NULL;
  PF_MALLOC(fill, r->nnodes + 1);
  r->node_pts = malloc(sizeof *r->node_pts * (size_t)(r->node_off[r->nnodes] + 1));
  if (!r->node_pts) free(fill);
  PF_CHECK(r->node_pts, PF_ERR_MEMORY, "out of memory");
  for (pf_int i = 0; i < pc->n; i++)
    for (int a = 0; a < 8; a++) {
      const int64_t k = r->pt_node[8 * (size_t)i + a];
      if (k >= 0) r->node_pts[r->node_off[k] + fill[k]++] = i;
    }
  free(fill);
  return 0;
}

static int ascending(const void *a, const void *b) {
  const pf_gid x = *(const pf_gid *)a, y = *(const pf_gid *)b;
  return (x > y) - (x < y);
}

/* A node set's points: every element on one of its nodes, once (Peridigm's rule); mark[i] ==
 * stamp: point i is in the set already. */
static int map_node_set(const exo_reader *r, const char *name, const int64_t *list, int64_t n, int *mark,
                        int stamp, pf_point_set *set) {
  for (int64_t k = 0; k < n; k++) {
    if (list[k] < 1 || list[k] > r->nnodes)
      return FILE_ERROR(r, "node set '%s' names node %" PRId64 " (nodes 1..%" PRId64 ")", name, list[k], r->nnodes);
    for (int64_t q = r->node_off[list[k] - 1]; q < r->node_off[list[k]]; q++)
      if (mark[r->node_pts[q]] != stamp) mark[r->node_pts[q]] = stamp, set->gid[set->n++] = r->node_pts[q];
  }
  qsort(set->gid, (size_t)set->n, sizeof *set->gid, ascending);
  return 0;
}

/* Node sets: the points of the elements on their nodes (elements of blocks not taken are left
 * out). */
static int read_node_sets(exo_reader *r, pf_point_cloud *pc) {
  if (r->nns == 0) return 0;
  PF_CALL(node_points(r, pc));
  int64_t *ids = NULL;
  int *mark = NULL;
  PF_MALLOC(mark, pc->n);
  ids = calloc((size_t)r->nns, sizeof *ids);
  if (!ids) free(mark);
  PF_CHECK(ids, PF_ERR_MEMORY, "out of memory");
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
    set->gid = ierr ? NULL : calloc((size_t)pc->n + 1, sizeof *set->gid);
    if (!ierr && !(list && set->gid)) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (!ierr) {
      pc->nsets++;
      snprintf(set->name, sizeof set->name, "%s", names[s]);
      set->body = -1;
    }
    if (!ierr && n) ierr = exodus_call(r, ex_get_set(r->exoid, EX_NODE_SET, ids[s], list, NULL), "ex_get_set");
    if (!ierr) ierr = map_node_set(r, names[s], list, n, mark, (int)s + 1, set);
    free(list);
  }
  free(ids), free(names), free(np), free(store), free(mark);
  return ierr;
}

/* The ids and names of the blocks taken, for a body's material_regions by block name. */
static int name_blocks(const exo_reader *r, pf_point_cloud *pc) {
  PF_MALLOC(pc->named_id, r->nblk);
  PF_MALLOC(pc->named, r->nblk);
  for (int64_t b = 0; b < r->nblk; b++) {
    if (!r->take[b]) continue;
    pc->named_id[pc->nnamed] = (int32_t)r->blk_id[b];
    memcpy(pc->named[pc->nnamed++], r->blk_name[b], sizeof pc->named[0]);
  }
  return 0;
}

/* "cyl.g: 4560 points from 4560 HEX8 elements, 4 node set(s)" */
static void log_read(const exo_reader *r, const pf_point_cloud *pc) {
  char kinds[160] = "";
  for (int k = ELEM_SPHERE; k <= ELEM_HEX; k++) {
    size_t used = strlen(kinds);
    if (r->nkind[k])
      snprintf(kinds + used, sizeof kinds - used, "%s%" PRId64 " %s", used ? ", " : "", r->nkind[k], kind_name[k]);
  }
  pf_log("%s: %" PF_INT_FMT " points from %s elements, %d node set(s)\n", r->path, pc->n, kinds, pc->nsets);
}

static int read_file(exo_reader *r, pf_point_cloud *pc) {
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
  PF_CALL(name_blocks(r, pc));
  PF_CALL(read_node_sets(r, pc));
  return pf_point_cloud_check_distinct(r->path, pc);
}

int pf_mesh_exodus_points_from_deck(const pf_deck *d, const pf_node *g, pf_point_cloud *pc) {
  memset(pc, 0, sizeof *pc);
  exo_reader r;
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
    log_read(&r, pc);
  reader_free(&r);
  if (ierr) pf_point_cloud_free(pc);
  return ierr;
}
