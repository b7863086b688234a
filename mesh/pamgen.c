/* Pamgen inline meshes (Trilinos Pamgen: Hensinger, Drake, Foucar & Gardiner, "Pamgen, a
 * library for parallel generation of simple finite element meshes", SAND2008-1933): the deck's
 * text ("mesh rectilinear ... end", "mesh radial ...", "mesh radial trisection ...") is handed to
 * Create_Pamgen_Mesh for one processor, and the mesh read back through Pamgen's in-memory
 * Exodus II interface (im_ex_get_*), which numbers things as Exodus does (mesh/exodus.c).
 * Pamgen keeps one mesh in static storage, so this reader is not reentrant. */
#include "mesh/mesh_impl.h"
#include "mesh/pamgen_guard.h"

#include <create_inline_mesh.h>
#include <limits.h>
#include <pamgen_im_exodusII.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define PAMGEN_DB 0 /* the im_ex_* functions take a database id and ignore it */

/* Pamgen's message for a failed Create_Pamgen_Mesh: parse errors go to the echo stream (which
 * accumulates over calls, so only the part after `echo_start`); set-up errors to the error
 * stream, which exists only when the mesh description was created (ERROR_CREATING_MS). Gives
 * the first line holding "ERROR" and the last echoed input line ("   12: text") before it. */
static void pamgen_message(long long status, long long echo_start, char *out, size_t len) {
  out[0] = '\0';
  int from_echo = status != ERROR_CREATING_MS;
  long long n = from_echo ? getPamgenEchoStreamSize() : getPamgenErrorStreamSize();
  char *all = calloc((size_t)n + 1, 1);
  if (!all) return;
  if (from_echo)
    getPamgenEchoStream(all);
  else
    getPamgenErrorStream(all);
  const char *text = from_echo && echo_start <= n ? all + echo_start : all;
  const char *err = strstr(text, "ERROR"), *input = NULL, *p = text;
  while (err && p < err) { /* lines that end before the error line */
    const char *q = p + strspn(p, " "), *eol = strchr(p, '\n');
    if (!eol || eol >= err) break;
    if (q[0] >= '0' && q[0] <= '9' && q[strspn(q, "0123456789")] == ':') input = q;
    p = eol + 1;
  }
  if (err) {
    const char *line = err; /* the whole error line, without its "12: " and "***** " */
    while (line > text && line[-1] != '\n') line--;
    line += strspn(line, " 0123456789");
    line += line[0] == ':' ? 1 : 0;
    line += strspn(line, " *");
    int errlen = (int)strcspn(line, "\n"), inlen = input ? (int)strcspn(input, "\n") : 0;
    if (input)
      snprintf(out, len, "%.*s (after Pamgen text line %.*s)", errlen > 400 ? 400 : errlen, line,
               inlen > 200 ? 200 : inlen, input);
    else
      snprintf(out, len, "%.*s", errlen > 400 ? 400 : errlen, line);
  } else {
    snprintf(out, len, "%.400s", text);
  }
  free(all);
}

typedef struct {
  const pf_mesh_source *src;
  int nnodes, nelem, nblk, nns, nss;
  int *ids, *buf, *buf2;
  double *xyz;
} pamgen_reader;

static int read_nodes(pamgen_reader *r, pf_mesh_raw *raw) {
  int n = r->nnodes;
  PF_MALLOC(r->xyz, 3 * (size_t)n);
  if (im_ex_get_coord(PAMGEN_DB, r->xyz, r->xyz + n, r->xyz + 2 * (size_t)n) < 0)
    return PF_MESH_ERROR(r->src, "Pamgen returned no coordinates");
  for (int i = 0; i < n; i++) {
    for (int c = 0; c < 3; c++) raw->mesh.X[3 * (size_t)i + c] = r->xyz[(size_t)c * n + i];
    raw->node_id[i] = i + 1;
  }
  return 0;
}

static int read_blocks(pamgen_reader *r, pf_mesh_raw *raw) {
  pf_mesh *m = &raw->mesh;
  PF_MALLOC(r->ids, r->nblk);
  PF_MALLOC(r->buf, 8 * (size_t)r->nelem);
  if (r->nblk && im_ex_get_elem_blk_ids(PAMGEN_DB, r->ids) < 0)
    return PF_MESH_ERROR(r->src, "Pamgen returned no element block ids");
  int e0 = 0;
  for (int b = 0; b < r->nblk; b++) {
    char type[MAX_STR_LENGTH + 1] = "";
    int ne = 0, npe = 0, nattr = 0;
    pf_mesh_set_name(m->block_name[b], NULL, "block", r->ids[b]);
    if (im_ex_get_elem_block(PAMGEN_DB, r->ids[b], type, &ne, &npe, &nattr) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no element block %d", r->ids[b]);
    if (ne == 0) continue;
    if (strncasecmp(type, "HEX", 3) || npe != 8)
      return PF_MESH_ERROR(r->src,
                           "block %d holds %s elements with %d nodes; perifem reads 8-node "
                           "hexahedra only (is the mesh 3-D?)",
                           r->ids[b], type, npe);
    if (ne > r->nelem - e0)
      return PF_MESH_ERROR(r->src, "Pamgen's blocks hold more than its %d elements", r->nelem);
    if (im_ex_get_elem_conn(PAMGEN_DB, r->ids[b], r->buf) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no connectivity for block %d", r->ids[b]);
    for (int e = 0; e < ne; e++) {
      for (int a = 0; a < 8; a++) {
        int k = r->buf[8 * (size_t)e + a];
        if (k < 1 || k > r->nnodes)
          return PF_MESH_ERROR(r->src, "element %d names node %d of %d", e0 + e + 1, k, r->nnodes);
        m->conn[8 * (size_t)(e0 + e) + a] = k - 1;
      }
      m->block[e0 + e] = b;
      raw->elem_id[e0 + e] = e0 + e + 1;
    }
    e0 += ne;
  }
  if (e0 != r->nelem)
    return PF_MESH_ERROR(r->src, "Pamgen's blocks hold %d elements, its header %d", e0, r->nelem);
  return 0;
}

static int read_node_sets(pamgen_reader *r, pf_mesh_raw *raw) {
  pf_mesh *m = &raw->mesh;
  if (r->nns == 0) return 0;
  free(r->ids);
  PF_MALLOC(r->ids, r->nns);
  if (im_ex_get_node_set_ids(PAMGEN_DB, r->ids) < 0)
    return PF_MESH_ERROR(r->src, "Pamgen returned no node set ids");
  for (int s = 0; s < r->nns; s++) {
    int n = 0, ndf = 0;
    char name[64];
    pf_mesh_set *set = NULL;
    if (im_ex_get_node_set_param(PAMGEN_DB, r->ids[s], &n, &ndf) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no node set %d", r->ids[s]);
    pf_mesh_set_name(name, NULL, "nodeset", r->ids[s]);
    PF_CALL(pf_mesh_add_set(&m->nodeset, &m->nnodesets, name, n, 0, &set));
    free(r->buf);
    PF_MALLOC(r->buf, n);
    if (n && im_ex_get_node_set(PAMGEN_DB, r->ids[s], r->buf) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no nodes for node set %d", r->ids[s]);
    for (int i = 0; i < n; i++) {
      if (r->buf[i] < 1 || r->buf[i] > r->nnodes)
        return PF_MESH_ERROR(r->src, "node set %d names node %d of %d", r->ids[s], r->buf[i],
                             r->nnodes);
      set->item[i] = r->buf[i] - 1;
    }
  }
  return 0;
}

static int read_side_sets(pamgen_reader *r, pf_mesh_raw *raw) {
  pf_mesh *m = &raw->mesh;
  if (r->nss == 0) return 0;
  free(r->ids);
  PF_MALLOC(r->ids, r->nss);
  if (im_ex_get_side_set_ids(PAMGEN_DB, r->ids) < 0)
    return PF_MESH_ERROR(r->src, "Pamgen returned no side set ids");
  for (int s = 0; s < r->nss; s++) {
    int n = 0, ndf = 0;
    char name[64];
    pf_mesh_set *set = NULL;
    if (im_ex_get_side_set_param(PAMGEN_DB, r->ids[s], &n, &ndf) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no side set %d", r->ids[s]);
    pf_mesh_set_name(name, NULL, "sideset", r->ids[s]);
    PF_CALL(pf_mesh_add_set(&m->sideset, &m->nsidesets, name, n, 1, &set));
    free(r->buf), free(r->buf2);
    r->buf2 = NULL;
    PF_MALLOC(r->buf, n);
    PF_MALLOC(r->buf2, n);
    if (n && im_ex_get_side_set(PAMGEN_DB, r->ids[s], r->buf, r->buf2) < 0)
      return PF_MESH_ERROR(r->src, "Pamgen returned no sides for side set %d", r->ids[s]);
    for (int i = 0; i < n; i++) {
      if (r->buf[i] < 1 || r->buf[i] > r->nelem || r->buf2[i] < 1 || r->buf2[i] > 6)
        return PF_MESH_ERROR(r->src, "side set %d names side %d of element %d", r->ids[s],
                             r->buf2[i], r->buf[i]);
      set->item[i] = r->buf[i] - 1;
      set->face[i] = (int8_t)(r->buf2[i] - 1);
    }
  }
  return 0;
}

static int read_mesh(pamgen_reader *r, pf_mesh_raw *raw) {
  char title[MAX_LINE_LENGTH + 1] = "";
  int ndim = 0;
  if (im_ex_get_init(PAMGEN_DB, title, &ndim, &r->nnodes, &r->nelem, &r->nblk, &r->nns, &r->nss) <
      0)
    return PF_MESH_ERROR(r->src, "Pamgen returned no mesh header");
  if (ndim != 3)
    return PF_MESH_ERROR(r->src, "a %d-D Pamgen mesh; perifem reads 3-D hexahedra", ndim);
  PF_CALL(pf_mesh_raw_alloc(raw, r->nnodes, r->nelem, r->nblk));
  PF_CALL(read_nodes(r, raw));
  PF_CALL(read_blocks(r, raw));
  PF_CALL(read_node_sets(r, raw));
  PF_CALL(read_side_sets(r, raw));
  return 0;
}

/* The text checked, and the estimated mesh held against perifem's limit and the memory. */
static int check_text(const pf_mesh_source *src) {
  char msg[512];
  double n = 0;
  if (pf_pamgen_check(src->text, &n, msg, sizeof msg)) return PF_MESH_ERROR(src, "%s", msg);
  const double bytes = n * PF_MESH_BYTES_PER_ELEMENT, limit = pf_memory_limit();
  if (n <= PF_MESH_MAX_ELEMENTS && bytes <= limit) return 0;
  return PF_MESH_ERROR(src,
                       "the Pamgen text asks for about %.3g elements, needing about %.3g GB; %s "
                       "(this process may use %.3g GB); use fewer intervals",
                       n, bytes / 1e9,
                       n > PF_MESH_MAX_ELEMENTS ? "perifem's meshes hold at most 2.6e8 elements"
                                                : "more than the memory available",
                       limit / 1e9);
}

static int pamgen_read(const pf_mesh_source *src, pf_mesh_raw *raw) {
  PF_CALL(check_text(src));
  long long echo_start = getPamgenEchoStreamSize();
  char thrown[256] = "";
  long long status = pf_pamgen_create(src->text, thrown, sizeof thrown);
  if (status == PF_PAMGEN_THREW)
    return PF_MESH_ERROR(src, "Pamgen failed while building the mesh (it threw: %s)", thrown);
  if (status != ERROR_FREE_CREATION) {
    char msg[1024];
    pamgen_message(status, echo_start, msg, sizeof msg);
    Delete_Pamgen_Mesh();
    return PF_MESH_ERROR(src, "Pamgen cannot build the mesh: %s", msg[0] ? msg : "no message");
  }
  pamgen_reader r;
  memset(&r, 0, sizeof r);
  r.src = src;
  int ierr = read_mesh(&r, raw);
  free(r.ids), free(r.buf), free(r.buf2), free(r.xyz);
  Delete_Pamgen_Mesh();
  return ierr;
}

const pf_mesh_reader pf_mesh_reader_pamgen = {"pamgen", "", pamgen_read};
