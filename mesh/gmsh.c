/* gmsh meshes through gmsh's C API (gmshc.h, gmsh 4.8): a .geo file is meshed at start-up
 * (dimension 3) and a .msh file read as it is. The 3-D mesh must be 8-node hexahedra (gmsh
 * element type 5, whose node order is Exodus HEX8's: checked against gmsh's reference
 * coordinates on every read). A .geo whose mesh is not all hexahedra is meshed again with
 * gmsh's all-hexahedra subdivision (Mesh.SubdivisionAlgorithm = 2, which splits each
 * tetrahedron into four hexahedra).
 *
 * Physical volumes become blocks (in physical-tag order, named by their physical name or
 * block_<tag>); with no physical volume, every volume is one block named after the file.
 * As gmsh itself does when it saves a mesh, elements of volumes outside every physical volume
 * are left out when there are physical volumes. Physical points, curves and surfaces become
 * node sets; physical surfaces also become side sets (each quadrilateral matched to the
 * hexahedron face with the same four nodes; both neighbours of an interior face). Nodes are
 * numbered by ascending gmsh node tag, elements block by block by ascending gmsh element tag. */
#include "mesh/mesh_impl.h"

#include "mesh/gmsh_library.h"
#include <locale.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <unistd.h>
#if defined(_OPENMP)
#include <omp.h>
#endif

#define GMSH_HEX8 5 /* gmsh element types */
#define GMSH_QUAD4 3

typedef struct {
  const pf_mesh_source *src;
  int is_geo;
  size_t log_seen; /* gmsh log entries already checked */
  size_t nnodes;
  size_t *node_tag; /* [nnodes] ascending: raw node i has gmsh tag node_tag[i] */
  /* hexahedra as collected: gmsh tag, block, gmsh node tags */
  size_t nhex, cap;
  size_t *hex_tag, *hex_nodes;
  int *hex_block;
  /* faces of the hexahedra, for side sets: sorted node indices, element, face */
  struct hex_face *faces;
} gmsh_reader;

struct hex_face {
  pf_int key[4];
  pf_int elem;
  int8_t face;
};

/* ---- errors -----------------------------------------------------------------------------------
 */
/* After a gmsh call: a non-zero ierr or an error in gmsh's log since the last check is a
 * failure naming the file, what was being done and gmsh's first new error message. (gmsh's
 * "last error" outlives gmshFinalize, so the log of this read is scanned instead.) */
static int gmsh_check(gmsh_reader *r, int ierr, const char *what) {
  char **log = NULL;
  size_t n = 0;
  int ierr2 = 0;
  gmshLoggerGet(&log, &n, &ierr2);
  const char *err = NULL;
  for (size_t i = r->log_seen; i < n; i++)
    if (!err && log[i] && !strncmp(log[i], "Error", 5)) err = log[i] + strcspn(log[i], ":");
  r->log_seen = n;
  int code = 0;
  if (ierr || err)
    code = PF_MESH_ERROR(r->src, "gmsh failed %s: %s", what,
                         err ? err + strspn(err, ": ") : "gmsh gave no message (out of memory?)");
  for (size_t i = 0; i < n; i++) gmshFree(log[i]);
  gmshFree(log);
  return code;
}
#define GMSH_TRY(r, what)                                                                          \
  do {                                                                                             \
    int pf_gmsh_code_ = gmsh_check((r), ierr, (what));                                             \
    if (pf_gmsh_code_) return pf_gmsh_code_;                                                       \
  } while (0)

/* ---- the process guarded against gmsh -------------------------------------------------------
 * gmsh ends the process itself in some cases: an `Exit;` command in a .geo file calls exit(0)
 * (gmsh 4.8's Msg::Exit; measured: perifem then ended with status 0 and nothing run, and
 * gmshOpen never returns whatever General.AbortOnError is, 0 to 3, so gmsh offers no way to
 * refuse it); an
 * exception escaping one of its OpenMP meshing loops (std::bad_alloc when memory runs out)
 * calls std::terminate, i.e. abort(); and its C API copies its results into malloc'ed arrays
 * without checking malloc, so it crashes on a null pointer when memory is short (measured under
 * ulimit -v). While gmsh runs, an atexit handler and a SIGABRT/SIGSEGV/SIGBUS handler turn these
 * into a perifem error naming the file and the deck key, with exit status 2. Nothing is
 * written during the set-up, so nothing is left half-written. */
static volatile sig_atomic_t in_gmsh = 0;
static char guard_exit_msg[2048], guard_crash_msg[2048];
static const int guard_signals[3] = {SIGABRT, SIGSEGV, SIGBUS};
static struct sigaction guard_old[3];

static void guard_write(const char *msg) {
  size_t n = strlen(msg);
  while (n > 0) {
    ssize_t w = write(STDERR_FILENO, msg, n);
    if (w <= 0) break;
    msg += w, n -= (size_t)w;
  }
}
static void guard_at_exit(void) {
  if (!in_gmsh) return;
  guard_write(guard_exit_msg);
  _exit(PF_ERR_INPUT);
}
static void guard_on_crash(int sig) {
  (void)sig;
  guard_write(guard_crash_msg);
  _exit(PF_ERR_INPUT);
}

static void guard_start(const pf_mesh_source *src) {
  static int registered = 0;
  if (!registered) registered = atexit(guard_at_exit) == 0;
  const char *key = src->key ? src->key : "mesh";
  snprintf(guard_exit_msg, sizeof guard_exit_msg,
           "perifem error: %s: %s: gmsh ended the process while reading or meshing this file (an "
           "'Exit;' command in it, or in a file it includes?); perifem needs the whole mesh, so "
           "the run stops here (nothing was run or written)\n",
           key, src->label);
  snprintf(guard_crash_msg, sizeof guard_crash_msg,
           "perifem error: %s: %s: gmsh aborted or crashed while reading or meshing this file "
           "(out of memory, e.g. std::bad_alloc from a too-fine element_size?); nothing was run "
           "or written\n",
           src->size_key ? src->size_key : key, src->label);
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = guard_on_crash;
  sigemptyset(&sa.sa_mask);
  for (int k = 0; k < 3; k++) sigaction(guard_signals[k], &sa, &guard_old[k]);
  in_gmsh = 1;
}

static void guard_stop(void) {
  in_gmsh = 0;
  for (int k = 0; k < 3; k++) sigaction(guard_signals[k], &guard_old[k], NULL);
}

/* ---- nodes ----------------------------------------------------------------------------------- */
static int by_size_t(const void *a, const void *b) {
  size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return x < y ? -1 : x > y;
}

/* Raw index of a gmsh node tag, or -1. */
static pf_int node_index(const gmsh_reader *r, size_t tag) {
  const size_t *p = bsearch(&tag, r->node_tag, r->nnodes, sizeof(size_t), by_size_t);
  return p ? (pf_int)(p - r->node_tag) : -1;
}

static const size_t *sort_tag;
static int by_tag_index(const void *a, const void *b) {
  size_t x = sort_tag[*(const size_t *)a], y = sort_tag[*(const size_t *)b];
  return x < y ? -1 : x > y;
}

/* Every node of the model, in ascending tag order, into raw (allocated here for nhex
 * hexahedra in nblocks blocks). */
static int read_nodes(gmsh_reader *r, pf_mesh_raw *raw, size_t nhex, int nblocks) {
  size_t *tags = NULL, ntags = 0, ncoord = 0, npar = 0, *order = NULL;
  double *coord = NULL, *par = NULL;
  int ierr = 0;
  gmshModelMeshGetNodes(&tags, &ntags, &coord, &ncoord, &par, &npar, -1, -1, 0, 0, &ierr);
  gmshFree(par);
  int code = gmsh_check(r, ierr, "reading the nodes");
  if (!code && ncoord != 3 * ntags)
    code = PF_MESH_ERROR(r->src, "gmsh returned %zu coordinates for %zu nodes", ncoord, ntags);
  if (!code) {
    order = malloc(sizeof *order * (ntags + 1));
    r->node_tag = malloc(sizeof *r->node_tag * (ntags + 1));
    if (!order || !r->node_tag)
      code = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  }
  if (!code) {
    for (size_t i = 0; i < ntags; i++) order[i] = i;
    sort_tag = tags;
    qsort(order, ntags, sizeof *order, by_tag_index);
    size_t n = 0; /* unique tags */
    for (size_t k = 0; k < ntags; k++)
      if (n == 0 || tags[order[k]] != r->node_tag[n - 1])
        order[n] = order[k], r->node_tag[n++] = tags[order[k]];
    r->nnodes = n;
    code = pf_mesh_raw_alloc(raw, (int64_t)n, (int64_t)nhex, nblocks);
    for (size_t i = 0; !code && i < n; i++) {
      memcpy(&raw->mesh.X[3 * i], &coord[3 * order[i]], 3 * sizeof(double));
      raw->node_id[i] = (int64_t)r->node_tag[i];
    }
  }
  free(order);
  gmshFree(tags);
  gmshFree(coord);
  return code;
}

/* ---- hexahedra --------------------------------------------------------------------------------
 */
/* Check that gmsh's 8-node hexahedron has Exodus HEX8's node order. */
static int check_node_order(gmsh_reader *r) {
  char *name = NULL;
  int dim = 0, order = 0, nn = 0, nprim = 0, ierr = 0;
  double *lc = NULL;
  size_t nlc = 0;
  gmshModelMeshGetElementProperties(GMSH_HEX8, &name, &dim, &order, &nn, &lc, &nlc, &nprim, &ierr);
  int code = gmsh_check(r, ierr, "describing its hexahedron");
  int same = !code && nn == 8 && nlc == 24;
  for (int a = 0; same && a < 8; a++)
    for (int i = 0; i < 3; i++) same &= lc[3 * a + i] == pf_hex8_node_sign[a][i];
  if (!code && !same)
    code = PF_MESH_ERROR(r->src,
                         "this gmsh's 8-node hexahedron does not have the Exodus HEX8 node order");
  gmshFree(name);
  gmshFree(lc);
  return code;
}

/* The 3-D element types other than 8-node hexahedra, e.g. "788 Tetrahedron 4"; "" if none.
 * *n3 is the number of 3-D element types. */
static int other_3d_types(gmsh_reader *r, char *out, size_t len, size_t *n3) {
  int *types = NULL, ierr = 0;
  size_t ntypes = 0;
  out[0] = '\0';
  gmshModelMeshGetElementTypes(&types, &ntypes, 3, -1, &ierr);
  int code = gmsh_check(r, ierr, "listing the 3-D element types");
  *n3 = ntypes;
  for (size_t t = 0; !code && t < ntypes; t++) {
    if (types[t] == GMSH_HEX8) continue;
    char *name = NULL;
    int dim, order, nn, nprim;
    double *lc = NULL;
    size_t nlc = 0, *etags = NULL, ne = 0, *ntags = NULL, nn2 = 0;
    gmshModelMeshGetElementProperties(types[t], &name, &dim, &order, &nn, &lc, &nlc, &nprim, &ierr);
    if (!ierr) gmshModelMeshGetElementsByType(types[t], &etags, &ne, &ntags, &nn2, -1, 0, 1, &ierr);
    code = gmsh_check(r, ierr, "counting the 3-D elements");
    size_t used = strlen(out);
    if (!code)
      snprintf(out + used, len - used, "%s%zu %s", used ? ", " : "", ne, name ? name : "?");
    gmshFree(name), gmshFree(lc), gmshFree(etags), gmshFree(ntags);
  }
  gmshFree(types);
  return code;
}

static int hex_push(gmsh_reader *r, size_t tag, int block, const size_t *nodes) {
  if (r->nhex == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 1024;
    size_t *t = realloc(r->hex_tag, sizeof *t * cap);
    if (t) r->hex_tag = t;
    size_t *nd = realloc(r->hex_nodes, sizeof *nd * 8 * cap);
    if (nd) r->hex_nodes = nd;
    int *b = realloc(r->hex_block, sizeof *b * cap);
    if (b) r->hex_block = b;
    PF_CHECK(t && nd && b, PF_ERR_MEMORY, "out of memory for %zu hexahedra", cap);
    r->cap = cap;
  }
  r->hex_tag[r->nhex] = tag;
  r->hex_block[r->nhex] = block;
  memcpy(&r->hex_nodes[8 * r->nhex], nodes, 8 * sizeof(size_t));
  r->nhex++;
  return 0;
}

/* The hexahedra of volume entity `entity` into block `block`; their count in *count. */
static int collect_volume(gmsh_reader *r, int entity, int block, size_t *count) {
  size_t *etags = NULL, ne = 0, *ntags = NULL, nn = 0;
  int ierr = 0;
  gmshModelMeshGetElementsByType(GMSH_HEX8, &etags, &ne, &ntags, &nn, entity, 0, 1, &ierr);
  int code = gmsh_check(r, ierr, "reading the hexahedra of a volume");
  if (!code && nn != 8 * ne)
    code = PF_MESH_ERROR(r->src, "gmsh returned %zu nodes for %zu hexahedra", nn, ne);
  for (size_t e = 0; !code && e < ne; e++) code = hex_push(r, etags[e], block, &ntags[8 * e]);
  *count = ne;
  gmshFree(etags);
  gmshFree(ntags);
  return code;
}

/* The physical groups of one dimension as tags, ascending. */
static int physical_groups(gmsh_reader *r, int dim, int **tags, size_t *n) {
  int *dimtags = NULL, ierr = 0;
  size_t ndt = 0;
  *tags = NULL;
  *n = 0;
  gmshModelGetPhysicalGroups(&dimtags, &ndt, dim, &ierr);
  int code = gmsh_check(r, ierr, "listing the physical groups");
  if (!code) {
    *tags = calloc(ndt / 2 + 1, sizeof **tags);
    if (!*tags) code = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
  }
  for (size_t k = 0; !code && k < ndt / 2; k++) (*tags)[(*n)++] = dimtags[2 * k + 1];
  gmshFree(dimtags);
  for (size_t i = 1; i < *n; i++) /* insertion sort: a handful of groups */
    for (size_t j = i; j > 0 && (*tags)[j - 1] > (*tags)[j]; j--) {
      int t = (*tags)[j];
      (*tags)[j] = (*tags)[j - 1];
      (*tags)[j - 1] = t;
    }
  return code;
}

static int group_name(gmsh_reader *r, int dim, int tag, const char *prefix, char out[64]) {
  char *name = NULL;
  int ierr = 0;
  gmshModelGetPhysicalName(dim, tag, &name, &ierr);
  int code = gmsh_check(r, ierr, "reading a physical name");
  if (!code) pf_mesh_set_name(out, name, prefix, tag);
  gmshFree(name);
  return code;
}

static int group_entities(gmsh_reader *r, int dim, int tag, int **ents, size_t *n) {
  int ierr = 0;
  *ents = NULL;
  *n = 0;
  gmshModelGetEntitiesForPhysicalGroup(dim, tag, ents, n, &ierr);
  return gmsh_check(r, ierr, "listing the entities of a physical group");
}

/* The block names and the hexahedra of every block. */
static int collect_blocks(gmsh_reader *r, char (**names)[64], int *nblocks) {
  int *groups = NULL;
  size_t ngroups = 0;
  PF_CALL(physical_groups(r, 3, &groups, &ngroups));
  *names = calloc(ngroups + 1, sizeof **names);
  if (!*names) free(groups);
  PF_CHECK(*names, PF_ERR_MEMORY, "out of memory");
  int code = 0;
  if (ngroups == 0) { /* one block of every volume, named after the file */
    const char *base = strrchr(r->src->path, '/');
    base = base ? base + 1 : r->src->path;
    const char *dot = strrchr(base, '.');
    snprintf((*names)[0], 64, "%.*s", (int)(dot ? (size_t)(dot - base) : strlen(base)), base);
    *nblocks = 1;
    size_t count;
    code = collect_volume(r, -1, 0, &count);
    free(groups);
    return code;
  }
  int *done = NULL; /* volume entities already in a block: the first physical group wins */
  size_t ndone = 0, total = 0;
  *nblocks = (int)ngroups;
  for (size_t g = 0; !code && g < ngroups; g++) {
    int *ents = NULL;
    size_t nents = 0;
    code = group_name(r, 3, groups[g], "block", (*names)[g]);
    if (!code) code = group_entities(r, 3, groups[g], &ents, &nents);
    int *grown = code ? NULL : realloc(done, sizeof *done * (ndone + nents + 1));
    if (!code && !grown)
      code = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (grown) done = grown;
    for (size_t k = 0; !code && k < nents; k++) {
      size_t j = 0, count = 0;
      while (j < ndone && done[j] != ents[k]) j++;
      if (j < ndone) continue;
      done[ndone++] = ents[k];
      code = collect_volume(r, ents[k], (int)g, &count);
      total += count;
    }
    gmshFree(ents);
  }
  free(done);
  free(groups);
  if (code) return code;
  size_t *etags = NULL, ne = 0, *ntags = NULL, nn = 0;
  int ierr = 0;
  gmshModelMeshGetElementsByType(GMSH_HEX8, &etags, &ne, &ntags, &nn, -1, 0, 1, &ierr);
  gmshFree(etags);
  gmshFree(ntags);
  GMSH_TRY(r, "counting the hexahedra");
  if (ne > total)
    pf_log("mesh %s: %zu hexahedra of volumes outside every physical volume are left out\n",
           r->src->label, ne - total);
  return 0;
}

static gmsh_reader *sort_reader;
static int by_block_tag(const void *a, const void *b) {
  size_t i = *(const size_t *)a, j = *(const size_t *)b;
  const gmsh_reader *r = sort_reader;
  if (r->hex_block[i] != r->hex_block[j]) return r->hex_block[i] < r->hex_block[j] ? -1 : 1;
  return r->hex_tag[i] < r->hex_tag[j] ? -1 : r->hex_tag[i] > r->hex_tag[j];
}

/* The collected hexahedra, block by block and by tag, into raw. */
static int store_hexahedra(gmsh_reader *r, pf_mesh_raw *raw) {
  size_t *order = NULL;
  PF_MALLOC(order, r->nhex);
  for (size_t i = 0; i < r->nhex; i++) order[i] = i;
  sort_reader = r;
  qsort(order, r->nhex, sizeof *order, by_block_tag);
  for (size_t e = 0; e < r->nhex; e++) {
    size_t h = order[e];
    for (int a = 0; a < 8; a++) {
      pf_int k = node_index(r, r->hex_nodes[8 * h + a]);
      if (k < 0) {
        free(order);
        return PF_MESH_ERROR(r->src, "element %zu names node %zu, which is not in the mesh",
                             r->hex_tag[h], r->hex_nodes[8 * h + a]);
      }
      raw->mesh.conn[8 * e + a] = k;
    }
    raw->mesh.block[e] = r->hex_block[h];
    raw->elem_id[e] = (int64_t)r->hex_tag[h];
  }
  free(order);
  return 0;
}

/* ---- node sets and side sets ---------------------------------------------------------------- */
static int by_pf_int(const void *a, const void *b) {
  pf_int x = *(const pf_int *)a, y = *(const pf_int *)b;
  return x < y ? -1 : x > y;
}
static int by_face_key(const void *a, const void *b) {
  const struct hex_face *p = a, *q = b;
  for (int i = 0; i < 4; i++)
    if (p->key[i] != q->key[i]) return p->key[i] < q->key[i] ? -1 : 1;
  return p->elem != q->elem ? (p->elem < q->elem ? -1 : 1)
                            : (p->face > q->face) - (p->face < q->face);
}

static void sort4(pf_int k[4]) {
  for (int i = 1; i < 4; i++)
    for (int j = i; j > 0 && k[j - 1] > k[j]; j--) {
      pf_int t = k[j];
      k[j] = k[j - 1];
      k[j - 1] = t;
    }
}

static int build_faces(gmsh_reader *r, const pf_mesh *m) {
  if (r->faces) return 0;
  PF_MALLOC(r->faces, 6 * (size_t)m->nelem);
  for (pf_int e = 0; e < m->nelem; e++)
    for (int f = 0; f < 6; f++) {
      struct hex_face *hf = &r->faces[6 * (size_t)e + f];
      for (int i = 0; i < 4; i++) hf->key[i] = m->conn[8 * (size_t)e + pf_hex8_face[f][i]];
      sort4(hf->key);
      hf->elem = e;
      hf->face = (int8_t)f;
    }
  qsort(r->faces, 6 * (size_t)m->nelem, sizeof *r->faces, by_face_key);
  return 0;
}

/* Node set of the physical group (dim, tag). */
static int add_node_set(gmsh_reader *r, pf_mesh *m, int dim, int tag, const char *name) {
  size_t *ntags = NULL, nn = 0, nc = 0;
  double *coord = NULL;
  int ierr = 0;
  pf_mesh_set *set = NULL;
  gmshModelMeshGetNodesForPhysicalGroup(dim, tag, &ntags, &nn, &coord, &nc, &ierr);
  gmshFree(coord);
  int code = gmsh_check(r, ierr, "reading the nodes of a physical group");
  if (!code) code = pf_mesh_add_set(&m->nodeset, &m->nnodesets, name, (int64_t)nn, 0, &set);
  pf_int n = 0;
  for (size_t i = 0; !code && i < nn; i++) {
    pf_int k = node_index(r, ntags[i]);
    if (k >= 0) set->item[n++] = k;
  }
  gmshFree(ntags);
  if (code) return code;
  qsort(set->item, (size_t)n, sizeof(pf_int), by_pf_int);
  pf_int u = 0;
  for (pf_int i = 0; i < n; i++)
    if (u == 0 || set->item[i] != set->item[u - 1]) set->item[u++] = set->item[i];
  set->n = u;
  return 0;
}

/* Append to set the hexahedron faces matching the quadrilaterals of one surface entity. */
static int match_quads(gmsh_reader *r, const pf_mesh *m, int entity, const char *name,
                       pf_mesh_set *set, pf_int *cap) {
  int *types = NULL, ierr = 0;
  size_t ntypes = 0;
  gmshModelMeshGetElementTypes(&types, &ntypes, 2, entity, &ierr);
  int code = gmsh_check(r, ierr, "listing the elements of a physical surface"), other = 0;
  for (size_t t = 0; t < ntypes; t++) other |= types[t] != GMSH_QUAD4;
  gmshFree(types);
  if (code) return code;
  if (other)
    return PF_MESH_ERROR(r->src,
                         "physical surface '%s' holds elements other than quadrilaterals, so it "
                         "is not made of hexahedron faces",
                         name);
  size_t *etags = NULL, ne = 0, *ntags = NULL, nn = 0, unmatched = 0;
  gmshModelMeshGetElementsByType(GMSH_QUAD4, &etags, &ne, &ntags, &nn, entity, 0, 1, &ierr);
  code = gmsh_check(r, ierr, "reading the quadrilaterals of a physical surface");
  for (size_t q = 0; !code && q < ne; q++) {
    struct hex_face key;
    memset(&key, 0, sizeof key);
    for (int i = 0; i < 4; i++) key.key[i] = node_index(r, ntags[4 * q + i]);
    sort4(key.key);
    key.elem = -1;                            /* sorts before every match */
    size_t lo = 0, hi = 6 * (size_t)m->nelem; /* first face with key >= key */
    while (lo < hi) {
      size_t mid = (lo + hi) / 2;
      if (by_face_key(&r->faces[mid], &key) < 0)
        lo = mid + 1;
      else
        hi = mid;
    }
    int found = 0;
    for (size_t k = lo;
         k < 6 * (size_t)m->nelem && !memcmp(r->faces[k].key, key.key, sizeof key.key); k++) {
      if (set->n == *cap) {
        pf_int nc = 2 * *cap + 16;
        pf_int *it = realloc(set->item, sizeof *it * (size_t)nc);
        if (it) set->item = it;
        int8_t *fc = realloc(set->face, sizeof *fc * (size_t)nc);
        if (fc) set->face = fc;
        if (!it || !fc) {
          code = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
          break;
        }
        *cap = nc;
      }
      set->item[set->n] = r->faces[k].elem;
      set->face[set->n++] = r->faces[k].face;
      found = 1;
    }
    unmatched += !found;
  }
  gmshFree(etags);
  gmshFree(ntags);
  if (!code && unmatched)
    code = PF_MESH_ERROR(r->src,
                         "%zu quadrilaterals of physical surface '%s' are not faces of any "
                         "hexahedron of a physical volume",
                         unmatched, name);
  return code;
}

static int add_side_set(gmsh_reader *r, pf_mesh *m, int tag, const char *name) {
  pf_mesh_set *set = NULL;
  PF_CALL(build_faces(r, m));
  PF_CALL(pf_mesh_add_set(&m->sideset, &m->nsidesets, name, 0, 1, &set));
  int *ents = NULL;
  size_t nents = 0;
  pf_int cap = 0;
  set->n = 0;
  int code = group_entities(r, 2, tag, &ents, &nents);
  for (size_t k = 0; !code && k < nents; k++) code = match_quads(r, m, ents[k], name, set, &cap);
  gmshFree(ents);
  return code;
}

static int collect_sets(gmsh_reader *r, pf_mesh *m) {
  static const char *const prefix[3] = {"point", "curve", "surface"};
  for (int dim = 0; dim <= 2; dim++) {
    int *groups = NULL;
    size_t ngroups = 0;
    PF_CALL(physical_groups(r, dim, &groups, &ngroups));
    int code = 0;
    for (size_t g = 0; !code && g < ngroups; g++) {
      char name[64];
      code = group_name(r, dim, groups[g], prefix[dim], name);
      if (!code) code = add_node_set(r, m, dim, groups[g], name);
      if (!code && dim == 2) code = add_side_set(r, m, groups[g], name);
    }
    free(groups);
    if (code) return code;
  }
  return 0;
}

/* ---- the model ---------------------------------------------------------------------------------
 */
static int mesh_geo(gmsh_reader *r) {
  int ierr = 0;
  gmshModelMeshGenerate(3, &ierr);
  GMSH_TRY(r, "meshing the geometry in 3-D");
  char others[512];
  size_t n3 = 0;
  PF_CALL(other_3d_types(r, others, sizeof others, &n3));
  if (!others[0]) return 0;
  pf_log("mesh %s: the 3-D mesh is not all hexahedra (%s); meshing it again with gmsh's "
         "all-hexahedra subdivision (Mesh.SubdivisionAlgorithm = 2)\n",
         r->src->label, others);
  gmshModelMeshClear(NULL, 0, &ierr);
  GMSH_TRY(r, "clearing the mesh");
  gmshOptionSetNumber("Mesh.SubdivisionAlgorithm", 2, &ierr);
  GMSH_TRY(r, "setting Mesh.SubdivisionAlgorithm");
  if (r->src->element_size > 0) { /* subdivision halves the edges */
    gmshOptionSetNumber("Mesh.MeshSizeMax", 2 * r->src->element_size, &ierr);
    GMSH_TRY(r, "setting Mesh.MeshSizeMax");
  }
  gmshModelMeshGenerate(3, &ierr);
  GMSH_TRY(r, "meshing the geometry in 3-D with all-hexahedra subdivision");
  return 0;
}

/* Before meshing a .geo with element_size h: the number of elements estimated from the
 * geometry's bounding box, prod_i max(1, ceil(L_i / h)), refused beyond the 32-bit limit or
 * beyond what the memory this process may use (pf_memory_limit) would hold. */
static int check_estimate(gmsh_reader *r) {
  const double h = r->src->element_size;
  if (!(h > 0)) return 0; /* the .geo sets its own sizes */
  double lo[3], hi[3];
  int ierr = 0;
  gmshModelGetBoundingBox(-1, -1, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2], &ierr);
  GMSH_TRY(r, "computing the bounding box of the geometry");
  double n = 1, div[3];
  for (int c = 0; c < 3; c++) {
    double L = hi[c] - lo[c];
    div[c] = isfinite(L) && L > 0 ? fmax(1, ceil(L / h - 1e-6)) : 1;
    n *= div[c];
  }
  const double bytes = n * PF_MESH_BYTES_PER_ELEMENT, limit = pf_memory_limit();
  if (n <= PF_MESH_MAX_ELEMENTS && bytes <= limit) return 0;
  return pf_error_raise(
      PF_ERR_INPUT, __FILE__, __LINE__, __func__,
      "%s: %s: element_size %g (in the file's units) would make about %.3g elements "
      "(%.0f x %.0f x %.0f divisions of the geometry's bounding box), needing about %.3g GB; "
      "%s (this process may use %.3g GB); use a larger element_size",
      r->src->size_key ? r->src->size_key : "mesh", r->src->label, h, n, div[0], div[1], div[2],
      bytes / 1e9,
      n > PF_MESH_MAX_ELEMENTS ? "perifem's meshes hold at most 2.6e8 elements"
                               : "more than the memory available",
      limit / 1e9);
}

static int read_model(gmsh_reader *r, pf_mesh_raw *raw) {
  int ierr = 0;
  gmshOptionSetNumber("General.Terminal", 0, &ierr);
  if (!ierr) gmshLoggerStart(&ierr);
  GMSH_TRY(r, "starting");
  if (r->src->element_size > 0) {
    gmshOptionSetNumber("Mesh.MeshSizeMax", r->src->element_size, &ierr);
    GMSH_TRY(r, "setting Mesh.MeshSizeMax");
  }
  gmshOpen(r->src->path, &ierr);
  GMSH_TRY(r, "reading the file");
  if (r->is_geo) PF_CALL(check_estimate(r));
  if (r->is_geo) PF_CALL(mesh_geo(r));
  char others[512];
  size_t n3 = 0;
  PF_CALL(other_3d_types(r, others, sizeof others, &n3));
  if (n3 == 0)
    return PF_MESH_ERROR(r->src, "no 3-D elements (%s)",
                         r->is_geo ? "does the file define a Volume?" : "is it a surface mesh?");
  if (others[0])
    return PF_MESH_ERROR(
        r->src, "the 3-D mesh holds %s elements; perifem reads 8-node hexahedra only%s", others,
        r->is_geo ? " (even after gmsh's all-hexahedra subdivision)"
                  : " (mesh the .geo with Mesh.SubdivisionAlgorithm = 2, or "
                    "transfinite volumes with Recombine)");
  PF_CALL(check_node_order(r));
  char(*names)[64] = NULL;
  int nblocks = 0;
  int code = collect_blocks(r, &names, &nblocks);
  if (!code) code = read_nodes(r, raw, r->nhex, nblocks);
  if (!code) memcpy(raw->mesh.block_name, names, sizeof *names * (size_t)nblocks);
  free(names);
  if (code) return code;
  PF_CALL(store_hexahedra(r, raw));
  PF_CALL(collect_sets(r, &raw->mesh));
  return 0;
}

static int gmsh_read(const pf_mesh_source *src, pf_mesh_raw *raw) {
  gmsh_reader r;
  memset(&r, 0, sizeof r);
  r.src = src;
  const char *dot = strrchr(src->path, '.');
  r.is_geo = dot && !strcasecmp(dot, ".geo");
  /* gmshInitialize sets the locale and lifts the stack limit for its own sake, and sets
   * OpenMP's thread count to its own General.NumThreads (1); all three are put back after
   * gmshFinalize. */
#if defined(_OPENMP)
  const int threads = omp_get_max_threads();
#endif
  char locale[512] = "";
  const char *lc = setlocale(LC_ALL, NULL);
  if (lc) snprintf(locale, sizeof locale, "%s", lc);
  struct rlimit stack;
  int have_stack = getrlimit(RLIMIT_STACK, &stack) == 0;
  int ierr = 0, code = 0;
  char why[512] = "";
  if (pf_gmsh_load(why, sizeof why)) return PF_MESH_ERROR(src, "cannot load gmsh: %s", why);
  guard_start(src);
  gmshInitialize(0, NULL, 0, &ierr);
  if (ierr)
    code = PF_MESH_ERROR(src, "cannot start gmsh (gmshInitialize returned %d)", ierr);
  else {
    code = read_model(&r, raw);
    gmshLoggerStop(&ierr);
    if (!code && ierr) code = PF_MESH_ERROR(src, "gmshLoggerStop returned %d", ierr);
    ierr = 0;
    gmshFinalize(&ierr);
    if (!code && ierr) code = PF_MESH_ERROR(src, "gmshFinalize returned %d", ierr);
  }
  guard_stop();
  if (locale[0]) setlocale(LC_ALL, locale);
  if (have_stack) setrlimit(RLIMIT_STACK, &stack);
#if defined(_OPENMP)
  omp_set_num_threads(threads);
#endif
  free(r.node_tag), free(r.hex_tag), free(r.hex_nodes), free(r.hex_block), free(r.faces);
  return code;
}

const pf_mesh_reader pf_mesh_reader_gmsh = {"gmsh", ".geo .msh", gmsh_read};
