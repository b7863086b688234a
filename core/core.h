/* perifem core: types, errors, logging, the point store, the deck, expressions,
 * point generators, regions, output and the state digest.
 * Everything another module may use from core/ is declared here. */
#ifndef PF_CORE_H
#define PF_CORE_H

#include <inttypes.h>
#include <mpi.h>
#include <stddef.h>
#include <stdlib.h>
#include <stdint.h>
#include <stdio.h>

#define PF_PI 3.14159265358979323846

/* ---- integer types ----------------------------------------------------- */
typedef int32_t pf_int; /* local indices */
typedef int64_t pf_gid; /* global ids and global counts */
#define PF_INT_FMT PRId32
#define PF_GID_FMT PRId64
#define PF_INT_MPI MPI_INT32_T
#define PF_GID_MPI MPI_INT64_T

/* ---- errors ------------------------------------------------------------- */
enum pf_error_code {
  PF_SUCCESS = 0,
  PF_ERR_RUN = 1,   /* a run failed: NaN, instability, I/O */
  PF_ERR_INPUT = 2, /* bad deck, bad mesh, bad command line */
  PF_ERR_MEMORY = 3,
  PF_ERR_LIB = 4, /* a library we call returned an error */
};

/* Record an error (first one wins) and print it once with its origin. Returns code. */
int pf_error_raise(int code, const char *file, int line, const char *func, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* The message of the first error raised since the last pf_error_clear(). */
const char *pf_error_message(void);
void pf_error_clear(void);
/* When quiet, errors are recorded but not printed (tests of bad input). */
void pf_error_set_quiet(int quiet);
/* Where the run is (e.g. "at step 80, t = 1.2e-06 s"), appended to an error raised until the
 * context is cleared with NULL: the writers of files do not know the step. */
void pf_error_context(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Collective: 0 when no rank failed; else this rank's ierr, or on a rank that did not fail a
 * PF_ERR_RUN "stopped: another rank failed <what>" (core/io_failure.c). For an error the failing
 * rank has already raised (a failed write); pf_error_agree below is for a check whose message
 * is not raised yet, and gives every rank the same message. */
int pf_agree(int ierr, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* A shared library opened on first use (core/shared_library.c): the handle, or NULL with why[]
 * (dlerror's text); one of its symbols copied into *slot (a function or object pointer), or -1
 * with why[] naming path and symbol. */
void *pf_library_open(const char *path, char *why, size_t len);
int pf_library_symbol(void *library, const char *path, const char *name, void *slot, char *why, size_t len);
/* A file left open after a failed write or close: the process must not call MPI_Finalize. */
void pf_io_abandon(void);
int pf_io_abandoned(void);

/* Collective: when ok is 0 on any rank, every rank raises the same error, with the message of
 * the lowest such rank (each failing rank passes its own text; the others may pass ""), and
 * returns code; else 0 everywhere. For checks whose outcome may differ between ranks, before
 * the next collective call. */
int pf_error_agree(int ok, int code, const char *file, int line, const char *func, const char *message);
#define PF_AGREE(ok, code, message)                                                                \
  do {                                                                                             \
    int pf_agree_ierr_ = pf_error_agree((ok), (code), __FILE__, __LINE__, __func__, (message));    \
    if (pf_agree_ierr_) return pf_agree_ierr_;                                                     \
  } while (0)

#define PF_CHECK(cond, code, ...)                                                                  \
  do {                                                                                             \
    if (!(cond)) return pf_error_raise((code), __FILE__, __LINE__, __func__, __VA_ARGS__);         \
  } while (0)
#define PF_CALL(expr)                                                                              \
  do {                                                                                             \
    int pf_call_ierr_ = (expr);                                                                    \
    if (pf_call_ierr_)                                                                             \
      return pf_error_raise(pf_call_ierr_, __FILE__, __LINE__, __func__, "called from here");      \
  } while (0)
/* Mark an array of bytes at p as wanting transparent huge pages, when it is large (a few MB)
 * and not yet touched: PF_MALLOC and PF_GROW do, and the bond rows' growth (core/huge_pages.c). */
void pf_memory_huge_pages(void *p, size_t bytes);
#define PF_MALLOC(ptr, count)                                                                      \
  do {                                                                                             \
    size_t pf_n_ = (size_t)(count);                                                                \
    (ptr) = calloc(pf_n_ ? pf_n_ : 1, sizeof(*(ptr)));                                             \
    PF_CHECK((ptr), PF_ERR_MEMORY, "out of memory allocating %zu x %zu bytes", pf_n_,             \
             sizeof(*(ptr)));                                                                      \
    pf_memory_huge_pages((ptr), pf_n_ * sizeof(*(ptr)));                                           \
  } while (0)
/* Room for one more element at index n of a growing array (ptr, its capacity cap, an int64_t):
 * when full, the capacity becomes 2 cap + extra. */
#define PF_GROW(ptr, n, cap, extra)                                                                \
  do {                                                                                             \
    if ((n) == (cap)) {                                                                            \
      int64_t pf_cap_ = 2 * (cap) + (extra);                                                       \
      void *pf_q_ = realloc((ptr), sizeof(*(ptr)) * (size_t)pf_cap_);                              \
      PF_CHECK(pf_q_, PF_ERR_MEMORY, "out of memory growing an array to %lld x %zu bytes",         \
               (long long)pf_cap_, sizeof(*(ptr)));                                                \
      (ptr) = pf_q_, (cap) = pf_cap_;                                                              \
      pf_memory_huge_pages((ptr), sizeof(*(ptr)) * (size_t)pf_cap_);                               \
    }                                                                                              \
  } while (0)
#define PF_FREE(ptr)                                                                               \
  do {                                                                                             \
    free(ptr);                                                                                     \
    (ptr) = NULL;                                                                                  \
  } while (0)

/* The versions of gmsh, METIS, Zoltan, netCDF and muparser built against, as one line. */
void pf_library_versions(char *out, size_t len);

/* ---- logging: rank 0 only ------------------------------------------------ */
void pf_log_set_quiet(int quiet);
void pf_log(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Rank 0's standard output is a terminal (and not --quiet): pf_log_status rewrites one line
 * in place there (no newline; the next pf_log or error ends it) and prints nothing elsewhere. */
int pf_log_terminal(void);
/* -1 (default): a status line when standard output is a terminal; 0: plain lines; 1: a status
 * line (--progress auto|plain|line). */
void pf_log_set_status(int mode);
void pf_log_status(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* ---- the point store (docs/architecture.md §2) -------------------------- */
enum pf_field_flags {
  PF_FIELD_GHOST = 1,   /* exchanged with ghosts */
  PF_FIELD_RESTART = 2, /* written to restart files */
  PF_FIELD_OUTPUT = 4,  /* written to Exodus output */
  PF_FIELD_CONSTANT = 8, /* set up once and never changed in a run: an output field written once */
};

#define PF_MAX_FIELDS 32
typedef struct {
  char name[32];
  int ncomp;
  int flags;
  double *data; /* [n_total * ncomp], component-minor */
} pf_field;

typedef struct pf_points {
  pf_int n_owned;  /* owned points come first */
  pf_int n_total;  /* owned + ghosts */
  pf_gid n_global; /* over all ranks */
  double *X;       /* reference position [3n] */
  double *u;       /* displacement [3n] */
  double *v;       /* velocity [3n] */
  double *f;       /* force [3n], N (force density times volume) */
  double *y;       /* current position X + u [3n], kept by the integrator */
  double *m;       /* lumped mass [n], kg */
  double *vol;     /* volume [n], m^3 */
  double *cell;    /* edge of the cube cell the point stands for [n], m */
  pf_gid *gid;     /* global id [n] */
  int32_t *body;   /* body index [n] */
  int nfields;
  pf_field fields[PF_MAX_FIELDS];
  struct pf_exchange *halo; /* who sends which owned point to whom (core/halo.c); NULL: no ghosts */
} pf_points;

/* The point field of the positions at the last force evaluation [3n], owned and ghosts (ghosted,
 * restarted): the integrator copies y into it after each evaluation (sim/step.c), so that a
 * kernel failing a bond can book its energy at the middle of the step (docs/theory/pd.md §5.1). */
#define PF_PREVIOUS_POSITIONS "previous_positions"

int pf_points_create(pf_int n, pf_points **pts);
/* Keep the first n_owned points and make room for n_ghost ghosts after them (every array and
 * field); new entries are zero. */
int pf_points_resize(pf_points *pts, pf_int n_owned, pf_int n_ghost);
int pf_points_destroy(pf_points **pts);
/* Register a per-point field; returns its index in *idx. Re-registering a name with the same
 * shape returns the existing field. */
int pf_points_field_register(pf_points *pts, const char *name, int ncomp, int flags, int *idx);
/* Field data by name, or NULL when no such field is registered. */
double *pf_points_field_get(const pf_points *pts, const char *name);
/* Reorder owned points by the permutation perm (new index k takes old point perm[k]). */
int pf_points_permute(pf_points *pts, const pf_int *perm);

/* ---- deck: YAML tree with source positions (core/deck.c) ------------------ */
typedef struct pf_deck pf_deck;
typedef struct pf_node pf_node; /* a node of the YAML tree */

int pf_deck_load(const char *path, pf_deck **deck);
/* The same with command-line overrides, each "a.b.c=value" (a YAML value; sequence items by
 * index or by their name:), applied after the deck's include: files and before its
 * parameters: are substituted (core/deck_compose.c). */
int pf_deck_load_with(const char *path, const char *const *sets, int nsets, pf_deck **deck);
/* The same from the YAML text of a deck that stands for the file path (not read): messages name
 * path, and files it names are relative to path's folder. */
int pf_deck_load_text(const char *path, const char *text, const char *const *sets, int nsets, pf_deck **deck);
int pf_deck_destroy(pf_deck **deck);
const pf_node *pf_deck_root(const pf_deck *deck);
const char *pf_deck_path(const pf_deck *deck);
/* The k-th file the deck included (include:), or NULL past the last (at most this many). */
enum { PF_DECK_MAX_INCLUDES = 32 };
const char *pf_deck_included(const pf_deck *deck, int k);
/* A file named in the deck, relative to the deck's folder unless absolute. */
void pf_deck_relative_path(const pf_deck *d, const char *name, char *out, size_t len);
/* A hash of the composed deck's tree (includes, overrides and parameters applied). */
uint64_t pf_deck_hash(const pf_deck *deck);

/* Kinds of value a key may hold, used by the schema tables. */
typedef enum {
  PF_KEY_REAL,
  PF_KEY_INT,
  PF_KEY_BOOL,
  PF_KEY_STRING,
  PF_KEY_VEC3,    /* [a, b, c] reals */
  PF_KEY_EXPR3,   /* [ex, ey, ez] expressions in x, y, z, t (or reals) */
  PF_KEY_EXPR,    /* one expression in x, y, z (or a real) */
  PF_KEY_MAP,     /* a nested mapping checked by its own table */
  PF_KEY_LIST,    /* a sequence of mappings, each checked by its own table */
  PF_KEY_STRLIST, /* a sequence of strings */
  PF_KEY_ANYMAP,  /* a mapping whose keys are user names (e.g. materials) */
  PF_KEY_MAT3,    /* [[a, b, c], [d, e, f], [g, h, i]]: three rows of three reals */
} pf_key_type;

/* One row of a schema table: the single source for validation and for docs. */
typedef struct pf_key {
  const char *name;
  pf_key_type type;
  int required;
  const char *default_value; /* as text, or NULL */
  const char *units;         /* SI units, or "" */
  const char *doc;
  const struct pf_key *sub; /* for MAP / LIST / ANYMAP: the table of the nested mapping; NULL for
                               LIST / ANYMAP: checked later by their owner (bodies by type,
                               materials by model) */
} pf_key;
#define PF_KEY_END {NULL, 0, 0, NULL, NULL, NULL, NULL}

/* A schema table assembled at run time from the rows of several owners (each model's own keys,
 * from an X-macro list): rows has room for cap rows and the PF_KEY_END, text for the joined
 * descriptions. Start with n = used = 0. */
typedef struct {
  pf_key *rows;
  int cap, n;
  char *text;
  size_t ntext, used;
} pf_key_table;
/* Append the rows of part (PF_KEY_END-ended, or NULL); a row whose name the table holds already
 * (of the same type and units) adds its description to that row's after "; ". The table stays
 * PF_KEY_END-ended; PF_ERR_RUN when it is full or a repeated row disagrees. */
int pf_key_table_add(pf_key_table *t, const pf_key *part);

/* Check every key of a mapping node against a table: unknown keys (with a suggestion), wrong
 * types and missing required keys are errors naming file:line:column and the key. Recurses
 * into MAP/LIST/ANYMAP rows. */
int pf_deck_validate(const pf_deck *deck, const pf_node *map, const pf_key *table,
                     const char *where);

/* The edit (Levenshtein) distance between two names, 99 when either is longer than 63
 * characters: the nearest known name is the one suggested for a misspelt one. */
int pf_edit_distance(const char *a, const char *b);

/* Lookups on a validated mapping; a missing optional key leaves *out untouched (callers set
 * the default first) and returns 0. */
const pf_node *pf_node_get(const pf_node *map, const char *key);
int pf_node_count(const pf_node *seq_or_map);
const pf_node *pf_node_item(const pf_node *seq, int i);              /* i-th sequence item */
const pf_node *pf_node_map_item(const pf_node *map, int i, const char **key); /* i-th pair */
const char *pf_node_text(const pf_node *scalar);
int pf_node_line(const pf_node *n);
int pf_node_column(const pf_node *n);
int pf_deck_real(const pf_deck *d, const pf_node *map, const char *key, double *out);
int pf_deck_int(const pf_deck *d, const pf_node *map, const char *key, long *out);
int pf_deck_bool(const pf_deck *d, const pf_node *map, const char *key, int *out);
int pf_deck_string(const pf_deck *d, const pf_node *map, const char *key, const char **out);
int pf_deck_vec3(const pf_deck *d, const pf_node *map, const char *key, double out[3]);
/* A 3 x 3 matrix given as three rows [[a, b, c], [d, e, f], [g, h, i]]. */
int pf_deck_mat3(const pf_deck *d, const pf_node *map, const char *key, double out[3][3]);
/* An optional real that must be positive: the value given (or the default left in *out). */
int pf_deck_positive(const pf_deck *d, const pf_node *map, const char *key, double *out);
/* A direction: the vector given, scaled to unit length; zero is an error. */
int pf_deck_unit_vec3(const pf_deck *d, const pf_node *map, const char *key, double u[3]);
/* The index of the body a scalar node names (item, under key) among names[nbodies]; an unknown
 * name is an error listing the known ones. */
int pf_deck_body_index(const pf_deck *d, const pf_node *item, const char *key, int nbodies,
                       const char *const *names, int *b);
/* A hash of a node's content (keys and scalar text, not layout or comments); 0-safe for NULL. */
uint64_t pf_node_hash(const pf_node *n);
/* Where a node was given: "deck.yaml:12:5" (the included file's name for an included node), or
 * "--set a.b=v" for an override. */
void pf_node_where(const pf_deck *d, const pf_node *n, char *out, size_t len);
/* An error about a node: "deck.yaml:12:5: key 'horizon': <message>". */
int pf_deck_error(const pf_deck *d, const pf_node *n, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* A warning about a node, on rank 0's stderr (also under --quiet):
 * "perifem warning: deck.yaml:12:5: key 'density': <message>". */
void pf_deck_warn(const pf_deck *d, const pf_node *n, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* ---- expressions in x, y, z, t (muparser) ------------------------------- */
typedef struct pf_expr pf_expr;
/* Compile an expression; errors name the deck position given by (deck, node, key). */
int pf_expr_create(const char *text, const pf_deck *d, const pf_node *n, const char *key,
                   pf_expr **e);
int pf_expr_destroy(pf_expr **e);
double pf_expr_eval(pf_expr *e, double x, double y, double z, double t);
/* The same with extra variables besides x, y, z, t (names[k], at most PF_EXPR_MAXVARS), whose
 * values pf_expr_eval_vars takes in that order. */
enum { PF_EXPR_MAXVARS = 4 };
int pf_expr_create_vars(const char *text, const pf_deck *d, const pf_node *n, const char *key,
                        const char *const *names, int nnames, pf_expr **e);
double pf_expr_eval_vars(pf_expr *e, double x, double y, double z, double t, const double *vars);
/* A constant expression of the deck's parameters (no x, y, z, t), evaluated; errors name the
 * deck position given by (deck, node, key). */
int pf_expr_constant(const pf_deck *d, const pf_node *n, const char *key, const char *text, double *v);
/* Refuse a value of e that is not finite at one of the n positions X[3n] (NULL: the origin) at
 * the nt + 1 times k t_end / nt, k = 0 .. nt (every position at every time up to 1e5 evaluations,
 * beyond that every position at 0 and t_end and the first one at every time): an error naming the
 * deck position and key e was compiled from and the earliest such time. Collective (each rank
 * gives its own positions). */
int pf_expr_check_finite(pf_expr *e, const double *X, pf_int n, double t_end, int nt);
/* Three expressions from a PF_KEY_EXPR3 node. */
int pf_expr3_create(const pf_deck *d, const pf_node *map, const char *key, pf_expr *e[3]);
void pf_expr3_destroy(pf_expr *e[3]);

/* ---- the distance to the nearest of a fixed set of points (core/nearest.c) ---- */
typedef struct pf_nearest pf_nearest;
int pf_nearest_create(const double *X, pf_int n, pf_nearest **q); /* X [3n], copied */
double pf_nearest_distance(const pf_nearest *q, const double x[3]);
void pf_nearest_destroy(pf_nearest **q);

/* ---- named point sets of the bodies (core/point_sets.c) ---------------------------
 * A mesh's node set, the nodes of a side set's faces, or a Peridigm Exodus discretization's node set, as
 * the global ids of the points it holds (global ids are the generation order, so a set does not
 * depend on the ranks and follows its points through migration and restart). */
typedef struct {
  char name[64];
  int body;     /* the body's index; -1 while the set belongs to a cloud not yet numbered */
  int side;     /* 0: node set, 1: side set */
  pf_gid n;
  pf_gid *gid;  /* [n] ascending, no repeats (in a cloud: indices into the cloud) */
} pf_point_set;
typedef struct {
  int n;
  pf_point_set *set;
  const char *const *body_name; /* [bodies] names for messages (borrowed) */
} pf_point_sets;
/* Append a set of n ids (copied, then sorted and made unique) to the table. */
int pf_point_sets_add(pf_point_sets *t, const char *name, int body, int side, const pf_gid *id, pf_gid n);
void pf_point_sets_free(pf_point_sets *t);
/* The set of the given kind named name, of body (or of any body when body < 0). Errors name
 * the deck key; an unknown name lists the known sets of that kind. */
int pf_point_sets_find(const pf_point_sets *t, const pf_deck *d, const pf_node *key_node, const char *key,
                       const char *name, int side, int body, const pf_point_set **out);
int pf_point_set_has(const pf_point_set *s, pf_gid gid);

/* ---- regions (point sets by geometry, or a named set of a body) ---------------------- */
typedef enum {
  PF_REGION_ALL,
  PF_REGION_BOX,
  PF_REGION_CYLINDER,
  PF_REGION_SPHERE,
  PF_REGION_SET /* a node set or side set (pf_point_set) */
} pf_region_kind;
typedef struct {
  pf_region_kind kind;
  double lo[3], hi[3]; /* box */
  double center[3];    /* cylinder (base centre) / sphere */
  int axis;            /* cylinder axis 0,1,2 */
  double radius, inner_radius, height;
  const pf_point_set *set; /* set: borrowed from the table it was found in */
} pf_region;
extern const pf_key pf_region_keys[];
/* A region from its deck mapping. sets: the named sets a `shape: node_set | side_set` may name
 * (NULL where no set can be named, e.g. a body's geometry); body: the body the caller restricts
 * to (-1: any), used to tell apart sets of the same name in two bodies. */
int pf_region_from_deck(const pf_deck *d, const pf_node *map, const pf_point_sets *sets, int body,
                        pf_region *r);
/* Geometric regions: is x inside (boundary inclusive)? A set region holds no position: 0. */
int pf_region_contains(const pf_region *r, const double x[3]);
/* Does the region select point i of the store (its reference position, or for a set its body
 * and global id)? */
int pf_region_selects(const pf_region *r, const pf_points *pts, pf_int i);

/* ---- point generation: lattices and point files -------------------------------- */
typedef struct {
  double *X;   /* [3n] */
  double *vol; /* [n] */
  double *cell;  /* [n] edge of the cube cell of each point */
  int32_t *block; /* [n] block id from a point file or an Exodus block (0 for lattices) */
  pf_int n;
  int nnamed;            /* Exodus: the blocks taken, each an id and a name (0 for a point file) */
  int32_t *named_id;     /* [nnamed] */
  char (*named)[64];     /* [nnamed] */
  int nsets;          /* named sets of the cloud's points (an Exodus discretization's node sets,
                        a point file's node-set files) */
  pf_point_set *sets; /* [nsets] ids are indices into the cloud; body -1 */
} pf_point_cloud;
extern const pf_key pf_geometry_keys[];
/* Points of a body from its `geometry:` mapping: a lattice inside a shape, or a point file. */
int pf_point_cloud_from_deck(const pf_deck *d, const pf_node *geometry, pf_point_cloud *pc);
int pf_point_cloud_free(pf_point_cloud *pc);
/* Before generating them: about how many points a lattice `geometry:` mapping makes and its
 * spacing (m), from the lattice cells covering the shape times the shape's share of them; 0 and
 * 0 for a point file or a mapping pf_point_cloud_from_deck refuses (a value it cannot read is
 * the same error here). Nothing is allocated. */
int pf_point_cloud_estimate(const pf_deck *d, const pf_node *geometry, double *points, double *spacing);
/* Simple cubic lattice origin + h*(i,j,k) inside region (boundary inclusive to 1e-9 h). */
int pf_lattice_fill(const pf_region *r, double h, const double origin[3], pf_point_cloud *pc);
/* The polar lattice of a cylinder or tube (core/lattice_polar.c): layers, rings and sectors
 * of edge about h tiling the shape, a point at each cell's centre with the cell's volume. */
int pf_polar_fill(const pf_region *r, double h, pf_point_cloud *pc);
int pf_point_file_read(const char *path, int peridigm, pf_point_cloud *pc);
/* geometry.node_set_files (Peridigm's node-set text files) as sets of the point file's cloud
 * (core/point_file_sets.c); after a block filter, keep the points whose new_index is >= 0. */
int pf_point_file_sets(const pf_deck *d, const pf_node *geometry, pf_point_cloud *pc);
void pf_point_file_sets_keep(pf_point_cloud *pc, const pf_int *new_index);
/* Refuse two points of a cloud at one position (a bond of zero length), naming label. */
int pf_point_cloud_check_distinct(const char *label, const pf_point_cloud *pc);
/* Permutation that orders points along a Morton (Z-order) curve. */
int pf_morton_order(pf_int n, const double *X, pf_int *perm);

/* ---- reductions (MPI_COMM_WORLD) --------------------------------------------- */
double pf_sum_all(double local);
double pf_min_all(double local);
double pf_max_all(double local);
/* Before MPI_Init: MPI settings perifem needs, unless the user set them (core/comm.c); after
 * it, pf_mpi_defaults_release takes back those that only MPI_Init reads, so that no process this
 * one starts (a Python campaign's mpirun) inherits them. */
void pf_mpi_defaults(void);
void pf_mpi_defaults_release(void);
int pf_comm_rank(void);
int pf_comm_size(void);
/* The OpenMP threads a parallel region of this rank runs (omp_get_max_threads; 1 without OpenMP). */
int pf_threads_per_rank(void);
/* The memory this process may use, in bytes: the machine's physical memory (sysconf), or the
 * address-space limit (ulimit -v, less the address space in use now) or data-segment limit
 * (ulimit -d) when lower. For refusing, before
 * allocating, a model that cannot fit (core/lattice.c, mesh/gmsh.c). */
double pf_memory_limit(void);
/* The largest resident memory of this process so far (getrusage ru_maxrss), bytes. */
double pf_memory_peak(void);
/* The resident memory of this process now (/proc/self/statm), bytes; 0 where unknown. */
double pf_memory_resident(void);
/* Give the heap's free memory back to the system (glibc's malloc_trim; elsewhere nothing): after
 * the set-up frees its temporaries, which freed blocks below the heap's top would otherwise keep
 * resident through the run. */
void pf_memory_trim(void);

/* ---- MPI domain decomposition (core/partition.c, migrate.c, halo.c) -------------- */
/* Bond lists in transit between ranks: one row per owned point, neighbours by global id, each
 * row ascending, with the per-bond quantities that travel with them as registered bond fields
 * (core/bond_fields.c): a model registers a field by name once, and migration, checkpoints and
 * the row operations below carry it without naming it. */
/* PF_BOND_UINT8 holds flags, 0 or 1 (a checkpoint's other values are refused). */
typedef enum { PF_BOND_UINT8, PF_BOND_FLOAT, PF_BOND_DOUBLE } pf_bond_type;
/* Bytes of one component of the type: 1, 4, 8. */
size_t pf_bond_type_size(pf_bond_type type);

#define PF_MAX_BOND_FIELDS 16
typedef struct {
  char name[32];
  pf_bond_type type;
  int ncomp;   /* components per bond */
  int flags;   /* PF_FIELD_RESTART: written to checkpoints (migration carries every field) */
  double init; /* the value of every component of a bond appended without one */
  void *data;  /* [offset[n] * ncomp] of type, component-minor (room for cap bonds) */
} pf_bond_field;

typedef struct {
  pf_int n;        /* rows */
  int64_t *offset; /* [n + 1] */
  pf_gid *gid;     /* [offset[n]] */
  int nfields;
  pf_bond_field field[PF_MAX_BOND_FIELDS]; /* ascending by name: the same order on every rank
                                              that has the same names */
  int64_t cap;     /* room for bonds */
  pf_int row_cap;  /* room for rows */
} pf_bond_rows;
int pf_bond_rows_init(pf_bond_rows *r);
/* Free the rows and the fields' data; the rows are empty and without fields afterwards. */
int pf_bond_rows_free(pf_bond_rows *r);
/* Drop every row, keeping the fields registered. */
void pf_bond_rows_clear(pf_bond_rows *r);
/* Room for nrows rows (in all) and nbonds more bonds, allocated exactly: appends within it do
 * not reallocate (a realloc may hold the old and the new block at once). */
int pf_bond_rows_reserve(pf_bond_rows *r, pf_int nrows, int64_t nbonds);
/* Drop every row as pf_bond_rows_clear, and give the bonds' memory (neighbours and fields)
 * back: for rows whose bonds are held elsewhere for a while (migration's packed records). */
int pf_bond_rows_release(pf_bond_rows *r);

/* Register a per-bond field of ncomp components of type, flags PF_FIELD_RESTART or 0, init the
 * value of a bond appended without one. The bonds already in the rows take init. Registering
 * a name again with the same type and init widens it to the larger ncomp (new components take
 * init) and adds the flags; another type or init is an error, as are the names "count" and
 * "gid" (the checkpoint keeps the rows' lengths and neighbours under them). Field data
 * pointers are valid until the next registration or append. */
int pf_bond_rows_field_register(pf_bond_rows *r, const char *name, pf_bond_type type, int ncomp,
                                int flags, double init);
/* The field registered under name, or NULL. */
const pf_bond_field *pf_bond_rows_field(const pf_bond_rows *r, const char *name);
/* The data of the field name when it is registered with this type, else NULL. */
void *pf_bond_rows_field_data(const pf_bond_rows *r, const char *name, pf_bond_type type);
/* Copy bonds [first, first + count) of the field name into out [count * ncomp] of its type
 * (type must be the field's): the first min(ncomp, field's ncomp) components of each bond; the
 * other components, and all of out when no such field is registered, are left as they are. */
int pf_bond_rows_field_copy(const pf_bond_rows *r, const char *name, pf_bond_type type,
                            int64_t first, int64_t count, int ncomp, void *out);
/* Register in dst every field of src (name, type, ncomp, flags, init). */
int pf_bond_rows_fields_copy(pf_bond_rows *dst, const pf_bond_rows *src);
/* Make every rank's fields the union of all ranks' (each the widest registered, flags
 * combined), hence the same fields in the same order everywhere. Collective. */
int pf_bond_rows_fields_agree(pf_bond_rows *r);

/* The values of one field for the bonds of a row being appended. */
typedef struct {
  const char *name; /* a registered field */
  const void *data; /* [count * ncomp] of the field's type */
  int ncomp;        /* components per bond in data, at most the field's (the others take init) */
} pf_bond_values;
/* Append a row of count bonds to the neighbours gid[count] (NULL: zeros, to be filled by the
 * caller); the fields named in values[nvalues] take those values, every other field its init. */
int pf_bond_rows_append(pf_bond_rows *r, pf_int count, const pf_gid *gid, int nvalues,
                        const pf_bond_values *values);
/* Append a row of count bonds to gid[count] whose fields take the values of the bonds from[k]
 * of src (bond indices into src's rows; -1: the field's init). A field src lacks takes init,
 * and so do the components beyond src's. */
int pf_bond_rows_append_from(pf_bond_rows *r, pf_int count, const pf_gid *gid,
                             const pf_bond_rows *src, const int64_t *from);
/* Append a copy of row `row` of src (neighbours and fields, as pf_bond_rows_append_from). */
int pf_bond_rows_append_row(pf_bond_rows *r, const pf_bond_rows *src, pf_int row);

typedef enum { PF_PARTITION_RCB, PF_PARTITION_METIS } pf_partition_method;
/* The work of owned point i as the partition weighs it, in bond evaluations: its bond count
 * (broken or not: the kernels visit both) plus one, plus extra[i] when extra is not NULL (the
 * work of its interactions). */
int pf_partition_weight(const pf_bond_rows *rows, const int *extra, pf_int i);
/* 2 when extra[] holds work on some rank (the interactions' phase, balanced on its own beside
 * the bodies' force loop), else 1. Collective. */
int pf_partition_phases(const int *extra, pf_int n);
/* The owner rank of every global id (owner_of[n_global], the same on every rank) after
 * partitioning the owned points: Zoltan recursive coordinate bisection of X weighted by
 * pf_partition_weight, or METIS k-way on the bond graph with the same vertex weights. extra:
 * NULL or [n_owned]; when it holds work (pf_partition_phases 2) each point carries two
 * weights, its bonds + 1 and extra[i], and both are balanced (multicriteria RCB, METIS's
 * multi-constraint k-way). Collective. */
int pf_partition_compute(pf_partition_method method, const pf_points *pts,
                         const pf_bond_rows *rows, const int *extra, int **owner_of);
/* Send each owned point (every array and field) and its bond row (every bond field, after
 * pf_bond_rows_fields_agree) to rank dest[i]. Afterwards the store holds what this rank
 * received, no ghosts, grouped by body (ascending) and in Morton order within a body;
 * body_start[nbodies + 1] gives the ranges. Collective. */
int pf_points_migrate(pf_points *pts, pf_bond_rows *rows, const int *dest, int nbodies,
                      pf_int *body_start);
/* Append as ghosts every neighbour in rows that this rank does not own, ordered by owner rank
 * and global id; build the halo; fill the ghosts' X, vol, cell, m, body and PF_FIELD_GHOST
 * fields; and write the local index of each bond's neighbour into local[offset[n]].
 * Collective. */
int pf_points_add_ghosts(pf_points *pts, const pf_bond_rows *rows, const int *owner_of,
                         pf_int *local);
/* Copy the owners' values of data (ncomp per point) into the ghosts. Collective; a no-op
 * without ghosts on one rank. */
int pf_points_exchange(pf_points *pts, double *data, int ncomp);
/* Exchange u and set y = X + u on the ghosts (the per-step halo update). */
int pf_points_exchange_positions(pf_points *pts);

/* ---- exchange plans (core/exchange.c): the halo's, and the contact view's ---------------- */
typedef struct pf_exchange pf_exchange;
/* A plan: this rank sends, to each rank r, send_count[r] local items, send_idx[] listing them
 * rank after rank (each in the order the receiver wants them); it receives recv_count[r] items
 * from each rank r, the blocks placed one after the other in rank order. Arrays [comm size]. */
int pf_exchange_create(const pf_int *send_count, const pf_int *send_idx, const pf_int *recv_count, pf_exchange **x);
/* Send ncomp doubles of each listed item of data[item * ncomp]; the k-th received item goes to
 * data[(first + k) * ncomp]. Collective among the plan's ranks (a NULL plan: nothing). */
int pf_exchange_doubles(pf_exchange *x, double *data, int ncomp, pf_int first);
pf_int pf_exchange_nrecv(const pf_exchange *x); /* items received */
void pf_exchange_destroy(pf_exchange **x);

/* ---- prescribed boundary conditions (core/bc.c) -------------------------------- */
typedef struct pf_bc pf_bc;
extern const pf_key pf_bc_keys[];
/* A prescribed velocity or displacement, component by component ("free" leaves a component
 * alone), or an applied body force (force per unit mass), on the points of a region (optionally of one body, by index into body_names); sets:
 * the named sets a region may select (NULL: none); index: its place in the deck's list, which
 * names it "bc<index>" unless the deck gives `name:`. */
int pf_bc_create(const pf_deck *d, const pf_node *map, const pf_points *pts, int nbodies,
                 const char *const *body_names, const pf_point_sets *sets, int index, pf_bc **bc);
int pf_bc_destroy(pf_bc **bc);
/* (Re)select the owned points of the condition's region and body (after a re-partition). */
int pf_bc_select(pf_bc *bc, const pf_points *pts);
/* Refuse a prescribed value or load that is not finite at the selected points' reference
 * positions over [0, t_end] (pf_expr_check_finite with nt + 1 times). Collective. */
int pf_bc_check_finite(const pf_bc *bc, const pf_points *pts, double t_end, int nt);
pf_int pf_bc_npoints(const pf_bc *bc);
const char *pf_bc_name(const pf_bc *bc);
/* This rank's impulse of the condition's reaction on its owned points (N s, the momentum the
 * condition gave them): over the last step taken (0 before the first) and over the last hook
 * below that was called (its own sum from 0: what the ledger books, the same bits after a
 * restart). */
void pf_bc_impulse(const pf_bc *bc, double step[3], double hook[3]);
/* Velocity Verlet hooks: after the first half kick (mid-step velocity at t + dt/2) and after
 * the second half kick (velocity at t; dt the step just taken). The work of the conditions'
 * reactions on owned point i is added to work[pts->body[i]] (J, per body; core/bc.c gives the
 * rule), their impulse to the condition's (pf_bc_impulse). */
void pf_bc_apply_midstep(pf_bc *bc, pf_points *pts, double t, double dt, double *work);
void pf_bc_apply_endstep(pf_bc *bc, pf_points *pts, double t, double dt, double *work);
/* A body-force condition adds its force m b(x, t) to the owned points' f at time t (the other
 * kinds do nothing); dt: the step just taken (0: the initial forces). Its work over the step
 * goes to work[pts->body[i]] and its impulse to the condition's, as the hooks above. */
void pf_bc_apply_force(pf_bc *bc, pf_points *pts, double t, double dt, double *work);
/* Set mask[3 i + c] = 1 for every component c of owned point i the condition prescribes. */
void pf_bc_mark(const pf_bc *bc, uint8_t *mask);
/* Quasi-static loading (sim/solver_relaxation.c): put the prescribed components of the selected
 * owned points at their values at pseudo-time t, u = g(X, t) for a displacement and
 * u += dt v(X, t - dt/2) for a velocity over the load step dt (y follows); a body force does
 * nothing here (its force hook adds it). */
void pf_bc_apply_static(const pf_bc *bc, pf_points *pts, double t, double dt);
/* This rank's sum of its selected owned points' displacements (the grip's mean displacement is
 * its sum over the ranks divided by the condition's points). */
void pf_bc_displacement_sum(const pf_bc *bc, const pf_points *pts, double sum[3]);
/* Quasi-static loading, at a load step's equilibrium (docs/theory/quasi_static.md §4): the terms
 * of the condition's books, one per selected owned point k (n = pf_bc_npoints), into
 * terms[j n + k]: j = 0, 1, 2 the force the condition exerts on the point (on each component it
 * prescribes, minus the point's force: its reaction; a body force: its load m b(X, t)), j = 3 the
 * work of that force over the load step from t - dt to t by the trapezoidal rule along its path,
 * (g0 + g1) / 2 . (u1 - u0) + (g1 + g) / 2 . (u - u1), j = 4, 5, 6 the point's displacement.
 * g0, u0: [3 n_owned] the force from outside and the displacement at the load step's start (a
 * body force takes m b(X, t - dt)); g1, u1: the same at its first equilibrium, before its damage
 * checks failed a bond (a body force takes m b(X, t)); NULL: no bond failed (g1 = g, u1 = u).
 * beyond: under sequential failure, each component's work along the scaled path past the first
 * equilibrium, taken for (g1 + g) / 2 . (u - u1) on the components the condition prescribes
 * (NULL otherwise). */
void pf_bc_static_terms(const pf_bc *bc, const pf_points *pts, double t, double dt, const double *g0,
                        const double *u0, const double *g1, const double *u1, const double *beyond, double *terms);

/* ---- tables of global rows (core/table.c) ------------------------------------------- */
/* Rows of a global [total][ncomp] table, each rank holding some of them (row id[k] is data[k]):
 * element state of FE bodies, which several ranks compute but one owns. */
typedef struct {
  char name[64];
  pf_gid total; /* rows */
  int ncomp;
  pf_int n;            /* this rank's rows */
  const pf_gid *id;    /* [n] */
  const double *data;  /* [n * ncomp] */
} pf_table;
/* The whole table on every rank: full[total * ncomp], rows no rank holds left zero. Collective. */
int pf_table_allgather(const pf_table *t, double *full);

/* ---- checkpoints (core/checkpoint.c): parallel HDF5 ---------------------------------- */
/* The checkpoint format this perifem writes, recorded in the file (attribute "format" of "/";
 * files without it are format 1). 2: the bodies' geometry (point and element counts, a hash of
 * the reference positions and connectivity), the walls' and contact pairs' forces. 3: the
 * history's running sums per body, per condition, per rigid surface and per wall (appended
 * scalars). 4: the point fields previous_positions and lost_weighted_volume, and the
 * correspondence record's three matrices by columns (by rows before: pf_pd_correspondence_upgrade).
 * 5: the run's books as the ledger's named records ("ledger:<column>") and the interactions'
 * state ("rigid:<name>_position_x" ...), in place of the fixed energy scalars of 2 to 4.
 * Formats PF_CHECKPOINT_FORMAT_OLDEST to PF_CHECKPOINT_FORMAT are read. */
#define PF_CHECKPOINT_FORMAT 5
#define PF_CHECKPOINT_FORMAT_OLDEST 5
/* Write the owned points (every array and field) and their bond rows (each bond field flagged
 * PF_FIELD_RESTART under /bonds/<name>, after pf_bond_rows_fields_agree), plus named scalars and
 * tables (each written whole, under /tables/<name>), to path (through path.tmp, renamed when
 * complete, so a kill leaves the previous checkpoint). Every dataset is chunked with HDF5's
 * Fletcher32 checksum, the file in the HDF5 1.10 format (checksummed metadata). Collective. */
int pf_checkpoint_write(const char *path, const pf_points *pts, pf_bond_rows *rows,
                        int nscalars, const char *const *names, const double *values,
                        int ntables, const pf_table *tables);
/* Read a checkpoint written on any number of ranks: this rank gets an equal slice of its
 * points (a new store, n_global set, fields registered) with their rows, and the scalars.
 * A file of a format this perifem does not read is refused first, naming the formats; *format
 * is the file's. A file of format 2 holds only the first nscalars_format2 scalars: the others
 * keep the values the caller put in values[] (the caller says what that means). rows
 * comes empty with the bond fields the caller keeps registered: each one flagged
 * PF_FIELD_RESTART is read (a file without it, or with another type or width, is refused naming
 * it), the others take their init; bond fields of the file the caller does not register are
 * not read. A missing scalar is an error. A failed checksum, a dataset without one, and content
 * that cannot be a state (ids out of range or repeated, negative bodies or bond counts, counts
 * not adding up to the bonds, rows not ascending, NaN values, non-finite scalars:
 * core/checkpoint_check.c) are refused before use with PF_ERR_INPUT and a message naming the
 * file and the dataset, on every rank alike. Collective. */
int pf_checkpoint_read(const char *path, pf_points **pts, pf_bond_rows *rows, int nscalars,
                       const char *const *names, double *values, int nscalars_format2, int *format);
/* Read more named scalars of a checkpoint (each there and finite), after pf_checkpoint_read.
 * Collective. */
int pf_checkpoint_read_scalars(const char *path, int n, const char *const *names, double *values);
/* Read a table written with the checkpoint whole on every rank: full[total * ncomp] (name,
 * total and ncomp as written; a mismatch is an error). Collective. */
int pf_checkpoint_read_table(const char *path, const pf_table *t, double *full);

/* ---- state digest ------------------------------------------------------- */
/* FNV-1a 64-bit hash of the displacement of all owned points in global-id order (gathered on
 * rank 0, broadcast to all). Collective. */
int pf_state_digest(const pf_points *pts, uint64_t *digest);
/* FNV-1a 64-bit over len bytes, continuing from h (PF_FNV1A_SEED to start). */
#define PF_FNV1A_SEED 1469598103934665603ULL
uint64_t pf_fnv1a(uint64_t h, const void *data, size_t len);


/* ---- output: Exodus II (core/output_exodus.c) and HDF5 history (core/history.c) ---- */
/* What made an output file, written into it: a title (the deck's), and lines of text (the code,
 * its version and git commit, the date, the command line, the deck and its parts). */
typedef struct {
  const char *title;
  const char *const *lines;
  int nlines;
} pf_provenance;
typedef struct pf_exodus pf_exodus;
/* How an Exodus file is written (NULL: every variable, double precision, no compression). */
typedef struct {
  const pf_provenance *prov; /* the title and the QA and info records, or NULL */
  int single;                /* 1: nodal and global values stored in single precision */
  int compression;           /* 1-9: a netCDF-4 file, deflated at that level (shuffled); 0: classic */
  const char *const *fields; /* the nodal variables written: displacement, velocity, force and output
                                field names; NULL: all of them */
  int nfields;
} pf_exodus_options;
/* Create an Exodus II file: coordinates of the owned points, one SPHERE element block per body
 * (body_start has nbodies + 1 entries from 0 to n_owned: points are grouped by body, body b
 * owning [body_start[b], body_start[b+1])), nodal variables displacement_{x,y,z},
 * velocity_{x,y,z}, force_{x,y,z} and every field flagged PF_FIELD_OUTPUT (a field with ncomp 3
 * gets _x/_y/_z, ncomp 6 _xx/_yy/_zz/_xy/_yz/_zx; one also flagged PF_FIELD_CONSTANT is a nodal
 * attribute instead, written with the first time step), and global variables named by global_names;
 * o->prov (or NULL) gives the title, a QA record (code, version, date, time) and the info records
 * (its lines, folded at 80 characters). */
int pf_exodus_create(const char *path, const pf_points *pts, int nbodies,
                     const char *const *body_names, const pf_int *body_start, int nglobals,
                     const char *const *global_names, const pf_exodus_options *o, pf_exodus **ex);
/* An FE body's block: HEX8 elements whose nodes are points of the file (0-based indices in the
 * order of pts), element ids first_id + 1, first_id + 2, ... */
typedef struct {
  pf_int nelem; /* 0: the body is a SPHERE block of its points */
  const pf_int *conn; /* [8 nelem] */
  int64_t first_id;
} pf_exodus_hexes;
/* As pf_exodus_create, with hexes[b] (nbodies entries, or NULL) making body b a HEX8 block. */
int pf_exodus_create_mixed(const char *path, const pf_points *pts, int nbodies,
                           const char *const *body_names, const pf_int *body_start,
                           const pf_exodus_hexes *hexes, int nglobals,
                           const char *const *global_names, const pf_exodus_options *o, pf_exodus **ex);
/* The path to hand to the Exodus library for a file (core/exodus_path.c), for core's writer and
 * mesh's readers and writer: p->use is the path itself, or for a long one a short alias through a
 * descriptor of its folder, which stays open until pf_exodus_path_end. An error names the path
 * and the limit. */
typedef enum { PF_EXODUS_CREATE, PF_EXODUS_CREATE4, PF_EXODUS_OPEN } pf_exodus_call; /* (4: a netCDF-4 file) */
typedef struct {
  const char *use;
  char alias[320];
  int dirfd;
} pf_exodus_path;
int pf_exodus_path_begin(const char *path, pf_exodus_call call, pf_exodus_path *p);
void pf_exodus_path_end(pf_exodus_path *p);
/* The joined view: rank 0 gets (*all, created on the first call) a copy of every owned point
 * in global-id order — X, u, v, f, body and the PF_FIELD_OUTPUT fields; other ranks get NULL.
 * Collective. */
int pf_points_gather(const pf_points *pts, pf_points **all);
/* Append one output step: time, the nodal variables, the global variables. */
int pf_exodus_write(pf_exodus *ex, double time, const pf_points *pts, const double *globals);
int pf_exodus_destroy(pf_exodus **ex);

typedef struct pf_history pf_history;
/* HDF5 history: one extendible 1-D dataset per column name under "/", plus attribute "units"
 * on each when given (units may be NULL); on "/" the attributes "columns" (the names in order),
 * "title" and "provenance" (prov's lines, one text; prov may be NULL). Rank 0 writes; others get
 * a NULL handle. */
int pf_history_create(const char *path, int ncol, const char *const *names,
                      const char *const *units, const pf_provenance *prov, pf_history **h);
int pf_history_append(pf_history *h, const double *row);
int pf_history_destroy(pf_history **h);

/* ---- small tensors (core/tensor.h inline, core/tensor.c) ------------------------- */
#include "core/tensor.h"
/* The smallest eigenvalue of a symmetric A (only its upper triangle is read). */
double pf_sym3_min_eigenvalue(double A[3][3]);
/* The smallest lambda of A v = lambda B v, min_n (n.A n)/(n.B n), for symmetric A and positive
 * definite B (0 when B is not). */
double pf_sym3_min_relative_eigenvalue(double A[3][3], double B[3][3]);

/* ---- wall clock ----------------------------------------------------------- */
double pf_wtime(void);

#endif
