/* Private to mesh/: the readers (mesh/): the reader ops table, the raw mesh a reader hands
 * back, and the helpers the readers share. A new reader is one file defining
 * `const pf_mesh_reader pf_mesh_reader_<name>` and one line in mesh/readers.h. */
#ifndef PF_MESH_IMPL_H
#define PF_MESH_IMPL_H

#include "mesh/mesh.h"

/* What a reader reads: a file (path set) or inline text (text set, for Pamgen). */
typedef struct {
  const char *path;    /* the mesh file, resolved against the deck's folder; NULL for text */
  const char *text;    /* inline mesh description; NULL for files */
  const char *label;   /* names the source in messages: the path, or "pamgen mesh at deck:l:c" */
  double element_size; /* element edge in the file's units (the deck's m / scale); 0: none */
  const char *key;     /* the deck key naming the source, "deck.yaml:L:C: key 'file'"; or NULL */
  const char *size_key; /* the same for element_size (NULL when not given) */
} pf_mesh_source;

/* A mesh as a reader returns it, before the common steps (block selection, dropping unused
 * nodes, scale and translate, validation). Elements must come block by block; nodes may be
 * unused. */
typedef struct {
  pf_mesh mesh;
  int64_t *elem_id; /* [nelem] the element's number in the source (for messages), or NULL: e+1 */
  int64_t *node_id; /* [nnodes] the node's number in the source (for messages), or NULL: i+1 */
} pf_mesh_raw;

/* The ops table of a mesh reader. */
typedef struct {
  const char *name;       /* "gmsh", "exodus", "pamgen": the name in mesh_readers.h */
  const char *extensions; /* file extensions it reads, space separated (".geo .msh"); "" for none */
  /* Required: read the source into raw (zeroed on entry). On error the caller frees raw, so a
   * reader may return with raw half filled; everything else it allocated it frees itself. */
  int (*read)(const pf_mesh_source *src, pf_mesh_raw *raw);
} pf_mesh_reader;

/* Bytes one element costs at its peak while a mesher builds it and perifem reads it: measured
 * 1.3 KB per hexahedron with gmsh on meshes/bar.geo (1.25 million transfinite hexahedra, 1.6 GB
 * peak resident), 1.0 KB with Pamgen (a million-element rectilinear block, 1.0 GB); 2 KB allows
 * for the tetrahedra of an unstructured mesh before its subdivision. */
#define PF_MESH_BYTES_PER_ELEMENT 2048.0
#define PF_MESH_MAX_ELEMENTS 2.6e8 /* pf_mesh's 32-bit connectivity: 8 nelem <= INT32_MAX */

/* Allocate raw's nodes, elements and blocks (zeroed; ids too). */
int pf_mesh_raw_alloc(pf_mesh_raw *raw, int64_t nnodes, int64_t nelem, int nblocks);
void pf_mesh_raw_free(pf_mesh_raw *raw);
/* Append an empty set of n items to *sets (a side set when with_face): returns it in *out. */
int pf_mesh_add_set(pf_mesh_set **sets, int *nsets, const char *name, int64_t n, int with_face,
                        pf_mesh_set **out);
/* Copy a name into a 64-byte slot: trailing blanks dropped; fallback when the name is empty. */
void pf_mesh_set_name(char out[64], const char *name, const char *fallback, int64_t id);
/* Raise a PF_ERR_INPUT error whose message starts with the deck key naming the source (when
 * known) and the source label: "deck.yaml:9:11: key 'file': meshes/bar.geo: ...". */
#define PF_MESH_ERROR(src, ...)                                                                    \
  pf_mesh_error_((src)->key, (src)->label, __FILE__, __LINE__, __func__, __VA_ARGS__)
int pf_mesh_error_(const char *key, const char *label, const char *file, int line,
                   const char *func, const char *fmt, ...) __attribute__((format(printf, 6, 7)));

#endif
