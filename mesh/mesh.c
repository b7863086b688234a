/* Hexahedral meshes: the `mesh:` keys of an FE body, the choice of reader by file extension
 * (readers registered by name in mesh/readers.h, docs/architecture.md §5), and the steps every
 * mesh goes through after its reader: block selection, dropping unused nodes, scale and translate,
 * and validation (positive Jacobian at every corner of every element, inside-out blocks turned
 * over). See docs/meshes.md. */
#include "mesh/mesh_impl.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

const pf_key pf_mesh_keys[] = {
    {"file", PF_KEY_STRING, 0, NULL, "",
     "mesh file, relative to the deck: .geo (gmsh geometry, meshed into hexahedra at start-up), "
     ".msh (gmsh mesh), .e/.exo/.g/.ex2 (Exodus II); give file or pamgen",
     NULL},
    {"pamgen", PF_KEY_STRING, 0, NULL, "",
     "Pamgen inline mesh text ('mesh rectilinear ... end end', 'mesh radial ...', 'mesh radial "
     "trisection ...'), e.g. a YAML block scalar 'pamgen: |'; give file or pamgen",
     NULL},
    {"element_size", PF_KEY_REAL, 0, NULL, "m",
     ".geo only: element edge length after scale (gmsh's Mesh.MeshSizeMax = element_size / scale; "
     "the shipped .geo files derive their divisions from it)",
     NULL},
    {"scale", PF_KEY_REAL, 0, "1", "",
     "multiply the coordinates by this (e.g. 1e-3 for a mesh in mm)", NULL},
    {"translate", PF_KEY_VEC3, 0, "[0, 0, 0]", "m", "then add this to the coordinates", NULL},
    {"blocks", PF_KEY_STRLIST, 0, NULL, "", "keep only the elements of these blocks (default: all)",
     NULL},
    PF_KEY_END};

/* ---- the reader registry (mesh/readers.h) ------------------------------------------- */
#define PF_MESH_READER(name) extern const pf_mesh_reader pf_mesh_reader_##name;
#include "mesh/readers.h"
#undef PF_MESH_READER
static const pf_mesh_reader *const readers[] = {
#define PF_MESH_READER(name) &pf_mesh_reader_##name,
#include "mesh/readers.h"
#undef PF_MESH_READER
};
static const int nreaders = (int)(sizeof readers / sizeof readers[0]);

static const pf_mesh_reader *reader_by_name(const char *name) {
  for (int r = 0; r < nreaders; r++)
    if (!strcmp(readers[r]->name, name)) return readers[r];
  return NULL;
}

/* The file's extension (with its dot), or "" when it has none. */
static const char *file_extension(const char *path) {
  const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
  return dot && (!slash || dot > slash) ? dot : "";
}

/* 1 when ext is one of the space-separated words of list (case-insensitive). */
static int in_list(const char *list, const char *ext) {
  size_t n = strlen(ext);
  for (const char *p = list; n && *p;) {
    size_t w = strcspn(p, " ");
    if (w == n && !strncasecmp(p, ext, n)) return 1;
    p += w;
    p += strspn(p, " ");
  }
  return 0;
}

static const pf_mesh_reader *reader_by_extension(const char *ext) {
  for (int r = 0; r < nreaders; r++)
    if (in_list(readers[r]->extensions, ext)) return readers[r];
  return NULL;
}

/* "'.geo .msh' (gmsh), '.e .exo .g .ex2' (exodus)" */
static void known_extensions(char *out, size_t len) {
  out[0] = '\0';
  for (int r = 0; r < nreaders; r++) {
    if (!readers[r]->extensions[0]) continue;
    size_t used = strlen(out);
    snprintf(out + used, len - used, "%s%s (%s)", used ? ", " : "", readers[r]->extensions,
             readers[r]->name);
  }
}

/* ---- shared helpers (mesh/mesh_impl.h) ---------------------------------------------------- */

int pf_mesh_error_(const char *key, const char *label, const char *file, int line,
                   const char *func, const char *fmt, ...) {
  char msg[1280];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (key) return pf_error_raise(PF_ERR_INPUT, file, line, func, "%s: %s: %s", key, label, msg);
  return pf_error_raise(PF_ERR_INPUT, file, line, func, "%s: %s", label, msg);
}

int pf_mesh_raw_alloc(pf_mesh_raw *raw, int64_t nnodes, int64_t nelem, int nblocks) {
  PF_CHECK(nnodes >= 0 && nnodes <= INT32_MAX && nelem >= 0 && nelem <= INT32_MAX / 8 &&
               nblocks >= 0,
           PF_ERR_INPUT, "a mesh of %" PRId64 " nodes and %" PRId64 " elements is too large",
           nnodes, nelem);
  pf_mesh *m = &raw->mesh;
  m->nnodes = (pf_int)nnodes;
  m->nelem = (pf_int)nelem;
  m->nblocks = nblocks;
  PF_MALLOC(m->X, 3 * (size_t)nnodes);
  PF_MALLOC(m->conn, 8 * (size_t)nelem);
  PF_MALLOC(m->block, nelem);
  PF_MALLOC(m->block_name, nblocks);
  PF_MALLOC(raw->elem_id, nelem);
  PF_MALLOC(raw->node_id, nnodes);
  return 0;
}

void pf_mesh_raw_free(pf_mesh_raw *raw) {
  pf_mesh_free(&raw->mesh);
  PF_FREE(raw->elem_id);
  PF_FREE(raw->node_id);
}

int pf_mesh_add_set(pf_mesh_set **sets, int *nsets, const char *name, int64_t n, int with_face,
                        pf_mesh_set **out) {
  PF_CHECK(n >= 0 && n <= INT32_MAX, PF_ERR_INPUT, "set '%s' of %" PRId64 " entries is too large",
           name, n);
  pf_mesh_set *grown = realloc(*sets, sizeof(pf_mesh_set) * (size_t)(*nsets + 1));
  PF_CHECK(grown, PF_ERR_MEMORY, "out of memory for %d sets", *nsets + 1);
  *sets = grown;
  pf_mesh_set *s = &grown[*nsets];
  memset(s, 0, sizeof *s);
  (*nsets)++;
  snprintf(s->name, sizeof s->name, "%s", name);
  s->n = (pf_int)n;
  PF_MALLOC(s->item, n);
  if (with_face) PF_MALLOC(s->face, n);
  *out = s;
  return 0;
}

void pf_mesh_set_name(char out[64], const char *name, const char *fallback, int64_t id) {
  size_t n = name ? strlen(name) : 0;
  while (n && (name[n - 1] == ' ' || name[n - 1] == '\t' || name[n - 1] == '\n')) n--;
  if (n)
    snprintf(out, 64, "%.*s", (int)(n < 63 ? n : 63), name);
  else
    snprintf(out, 64, "%s_%" PRId64, fallback, id);
}

static void free_sets(pf_mesh_set **sets, int *n) {
  for (int k = 0; *sets && k < *n; k++) {
    free((*sets)[k].item);
    free((*sets)[k].face);
  }
  PF_FREE(*sets);
  *n = 0;
}

int pf_mesh_free(pf_mesh *m) {
  if (!m) return 0;
  free(m->X);
  free(m->conn);
  free(m->block);
  free(m->block_name);
  free_sets(&m->nodeset, &m->nnodesets);
  free_sets(&m->sideset, &m->nsidesets);
  memset(m, 0, sizeof *m);
  return 0;
}

/* ---- hexahedron geometry ------------------------------------------------------------------ */
/* Jacobian determinant of the trilinear map x(xi) = sum_a N_a(xi) x_a at xi, with
 * N_a = (1 + s_a xi)(1 + t_a eta)(1 + u_a zeta) / 8 and (s_a, t_a, u_a) the node's corner. */
static double hex_det_j(const double x[8][3], const double xi[3]) {
  double J[3][3] = {{0}};
  for (int a = 0; a < 8; a++) {
    const double *s = pf_hex8_node_sign[a];
    double f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};
    double dN[3] = {s[0] * f[1] * f[2] / 8, s[1] * f[0] * f[2] / 8, s[2] * f[0] * f[1] / 8};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) J[i][j] += x[a][i] * dN[j];
  }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

/* V = int det J dxi over [-1, 1]^3 by 2x2x2 Gauss-Legendre (points +-1/sqrt 3, weights 1).
 * Exact: x(xi) is trilinear, so column j of J = dx/dxi_j does not depend on xi_j and is bilinear
 * in the other two coordinates; det J, a sum of products of one entry from each column, is
 * then at most quadratic in each of xi, eta, zeta, and the 2-point rule integrates cubics
 * exactly in each direction (Hughes, The Finite Element Method, 2000, sec. 3.8; the closed form
 * of the same volume as a sum of triple products: J. Grandy, "Efficient computation of volume
 * of hexahedral cells", LLNL UCRL-ID-128886, 1997). */
double pf_mesh_hex_volume(const double x[8][3]) {
  double c[8][3], B[8][3]; /* the element kernels' exact volume (mesh/hex8.c) */
  memcpy(c, x, sizeof c);
  return pf_hex8_mean_gradient(c, B);
}

static void element_nodes(const pf_mesh *m, pf_int e, double x[8][3]) {
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) x[a][i] = m->X[3 * (size_t)m->conn[8 * (size_t)e + a] + i];
}

/* +1 when det J > 0 at all 8 corners, -1 when < 0 at all 8, 0 otherwise; the corner with the
 * smallest det J (in the element's own orientation sense, sign as computed) in *corner. */
static int hex_orientation(const double x[8][3], double *det_min, int *corner) {
  int npos = 0, nneg = 0;
  *det_min = INFINITY;
  *corner = 0;
  for (int k = 0; k < 8; k++) {
    double d = hex_det_j(x, pf_hex8_node_sign[k]);
    npos += d > 0;
    nneg += d < 0;
    if (!(d >= *det_min)) *det_min = d, *corner = k;
  }
  return npos == 8 ? 1 : nneg == 8 ? -1 : 0;
}

/* ---- the common steps after a reader -------------------------------------------------------- */
static int64_t elem_id(const pf_mesh_raw *raw, pf_int e) {
  return raw->elem_id ? raw->elem_id[e] : (int64_t)e + 1;
}

/* Every index the reader produced is in range and blocks are contiguous. */
static int check_structure(const pf_mesh_raw *raw, const char *key, const char *label) {
  const pf_mesh *m = &raw->mesh;
  for (pf_int e = 0; e < m->nelem; e++) {
    for (int a = 0; a < 8; a++) {
      pf_int k = m->conn[8 * (size_t)e + a];
      if (k < 0 || k >= m->nnodes)
        return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                                  "element %" PRId64 " names node %" PRId64
                                  " but the mesh has %" PF_INT_FMT " nodes",
                                  elem_id(raw, e), (int64_t)k + 1, m->nnodes);
    }
    PF_CHECK(m->block[e] >= 0 && m->block[e] < m->nblocks, PF_ERR_INPUT,
             "%s: element %" PRId64 " is in block %d of %d", label, elem_id(raw, e), m->block[e],
             m->nblocks);
    PF_CHECK(e == 0 || m->block[e] >= m->block[e - 1], PF_ERR_INPUT,
             "%s: the reader did not group elements by block (element %" PRId64 ")", label,
             elem_id(raw, e));
  }
  for (int s = 0; s < m->nnodesets; s++)
    for (pf_int i = 0; i < m->nodeset[s].n; i++)
      if (m->nodeset[s].item[i] < 0 || m->nodeset[s].item[i] >= m->nnodes)
        return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                                  "node set '%s' names node %" PRId64 " of %" PF_INT_FMT,
                                  m->nodeset[s].name, (int64_t)m->nodeset[s].item[i] + 1,
                                  m->nnodes);
  for (int s = 0; s < m->nsidesets; s++)
    for (pf_int i = 0; i < m->sideset[s].n; i++)
      if (m->sideset[s].item[i] < 0 || m->sideset[s].item[i] >= m->nelem ||
          m->sideset[s].face[i] < 0 || m->sideset[s].face[i] > 5)
        return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                                  "side set '%s' names side %d of element %" PRId64
                                  " (elements 1..%" PF_INT_FMT ", sides 1..6)",
                                  m->sideset[s].name, m->sideset[s].face[i] + 1,
                                  (int64_t)m->sideset[s].item[i] + 1, m->nelem);
  return 0;
}

/* Keep only the blocks the deck lists (in file order), their elements and their sides. */
static int select_blocks(const pf_deck *d, const pf_node *mn, pf_mesh_raw *raw) {
  const pf_node *list = pf_node_get(mn, "blocks");
  if (!list) return 0;
  pf_mesh *m = &raw->mesh;
  int *newb = NULL;
  PF_MALLOC(newb, m->nblocks);
  for (int b = 0; b < m->nblocks; b++) newb[b] = -1;
  for (int i = 0; i < pf_node_count(list); i++) {
    const pf_node *it = pf_node_item(list, i);
    const char *name = pf_node_text(it);
    int b = 0;
    while (b < m->nblocks && (!name || strcmp(m->block_name[b], name))) b++;
    if (b == m->nblocks) {
      char known[1024] = "";
      for (int k = 0; k < m->nblocks; k++) {
        size_t used = strlen(known);
        snprintf(known + used, sizeof known - used, "%s'%s'", k ? ", " : "", m->block_name[k]);
      }
      free(newb);
      return pf_deck_error(d, it, "blocks", "the mesh has no block '%s' (its blocks: %s)",
                           name ? name : "", known);
    }
    newb[b] = 0;
  }
  int nb = 0;
  for (int b = 0; b < m->nblocks; b++)
    if (newb[b] == 0) {
      memmove(m->block_name[nb], m->block_name[b], sizeof m->block_name[b]);
      newb[b] = nb++;
    }
  pf_int *newe = NULL;
  newe = calloc((size_t)m->nelem + 1, sizeof *newe);
  if (!newe) free(newb);
  PF_CHECK(newe, PF_ERR_MEMORY, "out of memory");
  pf_int ne = 0;
  for (pf_int e = 0; e < m->nelem; e++) {
    int b = newb[m->block[e]];
    newe[e] = b < 0 ? -1 : ne;
    if (b < 0) continue;
    memmove(&m->conn[8 * (size_t)ne], &m->conn[8 * (size_t)e], 8 * sizeof(pf_int));
    m->block[ne] = b;
    if (raw->elem_id) raw->elem_id[ne] = raw->elem_id[e];
    ne++;
  }
  for (int s = 0; s < m->nsidesets; s++) {
    pf_mesh_set *set = &m->sideset[s];
    pf_int k = 0;
    for (pf_int i = 0; i < set->n; i++) {
      if (newe[set->item[i]] < 0) continue;
      set->item[k] = newe[set->item[i]];
      set->face[k++] = set->face[i];
    }
    set->n = k;
  }
  m->nelem = ne;
  m->nblocks = nb;
  free(newe);
  free(newb);
  return 0;
}

/* Drop the nodes no element uses, keeping the order of the others. */
static int drop_unused_nodes(pf_mesh_raw *raw) {
  pf_mesh *m = &raw->mesh;
  pf_int *newn = NULL;
  PF_MALLOC(newn, m->nnodes);
  for (size_t k = 0; k < 8 * (size_t)m->nelem; k++) newn[m->conn[k]] = 1;
  pf_int n = 0;
  for (pf_int i = 0; i < m->nnodes; i++) {
    if (!newn[i]) {
      newn[i] = -1;
      continue;
    }
    memmove(&m->X[3 * (size_t)n], &m->X[3 * (size_t)i], 3 * sizeof(double));
    if (raw->node_id) raw->node_id[n] = raw->node_id[i];
    newn[i] = n++;
  }
  for (size_t k = 0; k < 8 * (size_t)m->nelem; k++) m->conn[k] = newn[m->conn[k]];
  for (int s = 0; s < m->nnodesets; s++) {
    pf_mesh_set *set = &m->nodeset[s];
    pf_int k = 0;
    for (pf_int i = 0; i < set->n; i++)
      if (newn[set->item[i]] >= 0) set->item[k++] = newn[set->item[i]];
    set->n = k;
  }
  m->nnodes = n;
  free(newn);
  return 0;
}

/* Positive Jacobians: turn over blocks whose every element is inside out, then every element
 * must have det J > 0 at its 8 corners. */
static int validate(pf_mesh_raw *raw, const char *key, const char *label) {
  pf_mesh *m = &raw->mesh;
  if (m->nelem == 0) {
    char known[1024] = "";
    for (int k = 0; k < m->nblocks; k++) {
      size_t used = strlen(known);
      snprintf(known + used, sizeof known - used, "%s'%s'", k ? ", " : "", m->block_name[k]);
    }
    return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                              "no hexahedra to read (blocks kept: %s)",
                              m->nblocks ? known : "none");
  }
  for (pf_int i = 0; i < 3 * m->nnodes; i++)
    if (!isfinite(m->X[i]))
      return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                                "node %" PRId64 " has a coordinate that is not a finite number",
                                raw->node_id ? raw->node_id[i / 3] : (int64_t)i / 3 + 1);
  int8_t *sign = NULL;
  PF_MALLOC(sign, m->nelem);
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3], dmin;
    int corner;
    element_nodes(m, e, x);
    sign[e] = (int8_t)hex_orientation((const double(*)[3])x, &dmin, &corner);
  }
  for (int b = 0; b < m->nblocks; b++) {
    pf_int first = -1, last = -1, all_inverted = 1;
    for (pf_int e = 0; e < m->nelem; e++)
      if (m->block[e] == b) {
        if (first < 0) first = e;
        last = e;
        all_inverted &= sign[e] == -1;
      }
    if (first < 0 || !all_inverted) continue;
    for (pf_int e = first; e <= last; e++) {
      pf_int *c = &m->conn[8 * (size_t)e];
      for (int a = 0; a < 4; a++) {
        pf_int t = c[a];
        c[a] = c[a + 4];
        c[a + 4] = t;
      }
      sign[e] = 1;
    }
    for (int s = 0; s < m->nsidesets; s++)
      for (pf_int i = 0; i < m->sideset[s].n; i++) {
        pf_mesh_set *set = &m->sideset[s];
        if (set->item[i] >= first && set->item[i] <= last && set->face[i] >= 4)
          set->face[i] = (int8_t)(9 - set->face[i]); /* bottom <-> top */
      }
    pf_log("mesh %s: every element of block '%s' is inside out (negative Jacobian); turned "
           "over by swapping nodes 1-4 with 5-8\n",
           label, m->block_name[b]);
  }
  for (pf_int e = 0; e < m->nelem; e++) {
    if (sign[e] == 1) continue;
    double x[8][3], dmin, c[3] = {0, 0, 0};
    int corner;
    element_nodes(m, e, x);
    hex_orientation((const double(*)[3])x, &dmin, &corner);
    double L = 0; /* the longest edge between corners: a scale for det J ~ L^3 / 8 */
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) c[i] += x[a][i] / 8;
    for (int f = 0; f < 6; f++)
      for (int v = 0; v < 4; v++) {
        const double *p = x[pf_hex8_face[f][v]],
                     *q = x[pf_hex8_face[f][(v + 1) % 4]];
        L = fmax(L, sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                         (p[2] - q[2]) * (p[2] - q[2])));
      }
    int flat = fabs(dmin) <= 1e-10 * L * L * L; /* zero to round-off: a flat or collapsed corner */
    free(sign);
    return pf_mesh_error_(
        key, label, __FILE__, __LINE__, __func__,
        "element %" PRId64 " (block '%s', centroid (%g, %g, %g) m) is %s: det J = %g at its "
        "node %d; elements need a positive Jacobian at all 8 corners with nodes in Exodus HEX8 "
        "order (1-4 counter-clockwise seen from 5-8)",
        elem_id(raw, e), m->block_name[m->block[e]], c[0], c[1], c[2],
        flat ? "degenerate (a flat or collapsed corner)" : "inverted or tangled", dmin, corner + 1);
  }
  free(sign);
  return 0;
}

/* ---- duplicate hexahedra ------------------------------------------------------------------- */
typedef struct {
  pf_int node[8]; /* the element's nodes, sorted */
  pf_int e;
} sorted_hex;

static int by_nodes(const void *pa, const void *pb) {
  const sorted_hex *a = pa, *b = pb;
  for (int k = 0; k < 8; k++)
    if (a->node[k] != b->node[k]) return a->node[k] < b->node[k] ? -1 : 1;
  return (a->e > b->e) - (a->e < b->e);
}

static int by_value(const void *pa, const void *pb) {
  const pf_int a = *(const pf_int *)pa, b = *(const pf_int *)pb;
  return (a > b) - (a < b);
}

/* No two elements on the same 8 nodes, in any order (twice the mass and stiffness there): sorted
 * node tuples, sorted, then neighbours compared; O(n log n). */
static int check_duplicates(const pf_mesh_raw *raw, const char *key, const char *label) {
  const pf_mesh *m = &raw->mesh;
  sorted_hex *h;
  PF_MALLOC(h, m->nelem);
  for (pf_int e = 0; e < m->nelem; e++) {
    memcpy(h[e].node, &m->conn[8 * (size_t)e], sizeof h[e].node);
    qsort(h[e].node, 8, sizeof(pf_int), by_value);
    h[e].e = e;
  }
  qsort(h, (size_t)m->nelem, sizeof *h, by_nodes);
  pf_int a = -1, b = -1;
  for (pf_int k = 1; k < m->nelem && a < 0; k++)
    if (!memcmp(h[k - 1].node, h[k].node, sizeof h[k].node)) a = h[k - 1].e, b = h[k].e;
  free(h);
  if (a < 0) return 0;
  return pf_mesh_error_(key, label, __FILE__, __LINE__, __func__,
                        "elements %" PRId64 " (block '%s') and %" PRId64 " (block '%s') have the same 8 nodes: "
                        "a duplicated hexahedron would count its mass and stiffness twice; remove one",
                        elem_id(raw, a), m->block_name[m->block[a]], elem_id(raw, b), m->block_name[m->block[b]]);
}

/* ---- pf_mesh_read ------------------------------------------------------------------------ */
typedef struct {
  const pf_mesh_reader *reader;
  pf_mesh_source src;
  char path[4096];
  char label[4200];
  char key[4200], size_key[4200]; /* "deck.yaml:L:C: key 'file'" and the same for element_size */
  double scale, translate[3];
} mesh_request;

static int parse_request(const pf_deck *d, const pf_node *mn, mesh_request *rq) {
  const char *file = NULL, *text = NULL;
  PF_CALL(pf_deck_string(d, mn, "file", &file));
  PF_CALL(pf_deck_string(d, mn, "pamgen", &text));
  if (!file == !text)
    return pf_deck_error(d, mn, file ? "pamgen" : "file",
                         "give exactly one of 'file' (a .geo, .msh or Exodus file) and 'pamgen' "
                         "(an inline Pamgen mesh)");
  rq->scale = 1;
  PF_CALL(pf_deck_real(d, mn, "scale", &rq->scale));
  PF_CALL(pf_deck_vec3(d, mn, "translate", rq->translate));
  PF_CALL(pf_deck_real(d, mn, "element_size", &rq->src.element_size));
  if (!(rq->scale > 0 && isfinite(rq->scale)))
    return pf_deck_error(d, pf_node_get(mn, "scale"), "scale", "must be positive (got %g)",
                         rq->scale);
  const pf_node *es = pf_node_get(mn, "element_size");
  if (es && !(rq->src.element_size > 0))
    return pf_deck_error(d, es, "element_size", "must be positive (got %g)", rq->src.element_size);
  rq->src.element_size /= rq->scale; /* in the file's units */
  if (text) {
    rq->reader = reader_by_name("pamgen");
    rq->src.text = text;
    const pf_node *tn = pf_node_get(mn, "pamgen");
    char where[400];
    pf_node_where(d, tn, where, sizeof where);
    snprintf(rq->label, sizeof rq->label, "pamgen mesh at %s", where);
    if (es)
      return pf_deck_error(d, es, "element_size",
                           "applies to .geo files only; a Pamgen text gives its own intervals");
  } else {
    const pf_node *fn = pf_node_get(mn, "file");
    const char *ext = file_extension(file);
    rq->reader = reader_by_extension(ext);
    if (!rq->reader) {
      char known[512];
      known_extensions(known, sizeof known);
      return pf_deck_error(d, fn, "file",
                           "no mesh reader for '%s' (extension '%s'); known extensions: %s; or "
                           "give an inline mesh under 'pamgen'",
                           file, ext, known);
    }
    pf_deck_relative_path(d, file, rq->path, sizeof rq->path);
    FILE *probe = fopen(rq->path, "r");
    if (!probe)
      return pf_deck_error(d, fn, "file", "cannot open mesh file '%s': %s", rq->path,
                           strerror(errno));
    fclose(probe);
    if (es && strcasecmp(ext, ".geo"))
      return pf_deck_error(d, es, "element_size",
                           "applies to .geo files only ('%s' is already a mesh)", file);
    rq->src.path = rq->path;
    snprintf(rq->label, sizeof rq->label, "%s", rq->path);
    char where[400];
    pf_node_where(d, fn, where, sizeof where);
    snprintf(rq->key, sizeof rq->key, "%s: key 'file'", where);
    rq->src.key = rq->key;
    if (es) {
      pf_node_where(d, es, where, sizeof where);
      snprintf(rq->size_key, sizeof rq->size_key, "%s: key 'element_size'", where);
      rq->src.size_key = rq->size_key;
    }
  }
  rq->src.label = rq->label;
  PF_CHECK(rq->reader, PF_ERR_INPUT, "no mesh reader named '%s' is registered",
           text ? "pamgen" : "");
  return 0;
}

int pf_mesh_read(const pf_deck *d, const pf_node *mn, pf_mesh *m) {
  memset(m, 0, sizeof *m);
  PF_CHECK(mn, PF_ERR_INPUT, "%s: an FE body needs a 'mesh:' mapping", pf_deck_path(d));
  mesh_request *rq = NULL;
  PF_MALLOC(rq, 1);
  pf_mesh_raw raw;
  memset(&raw, 0, sizeof raw);
  int ierr = parse_request(d, mn, rq);
  if (!ierr) ierr = rq->reader->read(&rq->src, &raw);
  if (!ierr) ierr = check_structure(&raw, rq->src.key, rq->label);
  if (!ierr) ierr = select_blocks(d, mn, &raw);
  if (!ierr) ierr = drop_unused_nodes(&raw);
  if (!ierr)
    for (pf_int i = 0; i < raw.mesh.nnodes; i++)
      for (int c = 0; c < 3; c++)
        raw.mesh.X[3 * (size_t)i + c] =
            rq->scale * raw.mesh.X[3 * (size_t)i + c] + rq->translate[c];
  if (!ierr) ierr = validate(&raw, rq->src.key, rq->label);
  if (!ierr) ierr = check_duplicates(&raw, rq->src.key, rq->label);
  if (!ierr)
    pf_log("mesh %s: %" PF_INT_FMT " nodes, %" PF_INT_FMT " hexahedra in %d block(s), %d node "
           "set(s), %d side set(s)\n",
           rq->label, raw.mesh.nnodes, raw.mesh.nelem, raw.mesh.nblocks, raw.mesh.nnodesets,
           raw.mesh.nsidesets);
  free(rq);
  if (ierr) {
    pf_mesh_raw_free(&raw);
    return ierr;
  }
  *m = raw.mesh;
  free(raw.elem_id);
  free(raw.node_id);
  return 0;
}
