/* Point generation for a body: a simple cubic lattice inside a shape (with an optional
 * seeded random perturbation, as Peridigm's and Ruestes et al.'s decks do), or a plain-text
 * point file "x y z volume block" like Peridigm's text discretization. (Peridigm's Exodus
 * discretization, shape: exodus, is read by mesh/exodus_points.c; its keys are listed here
 * with the others of `geometry:`.) */
#include "core/core.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const pf_key pf_geometry_keys[] = {
    {"shape", PF_KEY_STRING, 1, NULL, "",
     "box | cylinder | sphere | points_file | exodus (Peridigm's Exodus discretization: SPHERE, "
     "HEX8 and TET4 elements, one point each)", NULL},
    {"lo", PF_KEY_VEC3, 0, NULL, "m", "box: lower corner", NULL},
    {"hi", PF_KEY_VEC3, 0, NULL, "m", "box: upper corner", NULL},
    {"center", PF_KEY_VEC3, 0, "[0, 0, 0]", "m", "cylinder: centre of the base; sphere: centre",
     NULL},
    {"axis", PF_KEY_STRING, 0, "z", "", "cylinder axis: x, y or z", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "cylinder or sphere radius", NULL},
    {"inner_radius", PF_KEY_REAL, 0, "0", "m", "cylinder: inner radius (a tube when > 0)", NULL},
    {"height", PF_KEY_REAL, 0, NULL, "m", "cylinder height along the axis", NULL},
    {"spacing", PF_KEY_REAL, 0, NULL, "m", "lattice spacing h (each point stands for an h^3 cell)",
     NULL},
    {"point_volume", PF_KEY_REAL, 0, NULL, "m^3",
     "lattice: each point's volume instead of its cell's h^3 (grains of a packing: spheres of diameter h on a "
     "cubic lattice have (pi / 6) h^3, as in Ruestes et al. 2012's clusters)", NULL},
    {"lattice", PF_KEY_STRING, 0, "cubic", "",
     "cubic (origin + h (i, j, k) inside the shape) | polar (cylinder: rings of cells tiling it, core/lattice_polar.c)", NULL},
    {"origin", PF_KEY_VEC3, 0, "[0, 0, 0]", "m",
     "a lattice point; points are origin + h (i, j, k) inside the shape, boundary included", NULL},
    {"perturbation", PF_KEY_REAL, 0, "0", "",
     "random offset of each point, uniform in [-a h, a h] per component", NULL},
    {"seed", PF_KEY_INT, 0, "1", "", "seed of the perturbation", NULL},
    {"file", PF_KEY_STRING, 0, NULL, "",
     "points_file: text file, one point a line (relative to the deck; '#' starts a comment); "
     "exodus: the Exodus II file (.g .e .exo)", NULL},
    {"columns", PF_KEY_STRING, 0, "perifem", "",
     "points_file: perifem (x y z volume [block]) | peridigm (x y z block_id volume, Peridigm's text "
     "discretization)", NULL},
    {"scale", PF_KEY_REAL, 0, "1", "",
     "points_file, exodus: the file's length unit in metres (x, y, z times scale, volume times "
     "scale^3)", NULL},
    {"block", PF_KEY_INT, 0, NULL, "", "points_file: take only the points of this block", NULL},
    {"node_set_files", PF_KEY_STRLIST, 0, NULL, "",
     "points_file: Peridigm node-set text files (point numbers counting from 1 in the point file's order); "
     "each is a node set named after its file without folder and extension, for regions {shape: node_set}", NULL},
    {"blocks", PF_KEY_STRLIST, 0, NULL, "",
     "exodus: take only these element blocks, by name or id (default: every block); each must hold "
     "SPHERE elements with a 'volume' attribute, HEX8 or TET4 elements", NULL},
    PF_KEY_END};

static int cloud_grow(pf_point_cloud *pc, pf_int *cap) {
  pf_int nc = *cap ? 2 * *cap : 1024;
  double *X = realloc(pc->X, 3 * sizeof(double) * (size_t)nc);
  if (X) pc->X = X;
  double *v = realloc(pc->vol, sizeof(double) * (size_t)nc);
  if (v) pc->vol = v;
  double *c = realloc(pc->cell, sizeof(double) * (size_t)nc);
  if (c) pc->cell = c;
  int32_t *b = realloc(pc->block, sizeof(int32_t) * (size_t)nc);
  if (b) pc->block = b;
  PF_CHECK(X && v && c && b, PF_ERR_MEMORY, "out of memory for %" PF_INT_FMT " points", nc);
  *cap = nc;
  return 0;
}

static int cloud_push(pf_point_cloud *pc, pf_int *cap, const double x[3], double vol,
                      int32_t block) {
  if (pc->n == *cap) PF_CALL(cloud_grow(pc, cap));
  memcpy(&pc->X[3 * pc->n], x, 3 * sizeof(double));
  pc->vol[pc->n] = vol;
  pc->cell[pc->n] = cbrt(vol);
  pc->block[pc->n] = block;
  pc->n++;
  return 0;
}

int pf_point_cloud_free(pf_point_cloud *pc) {
  for (int k = 0; pc->sets && k < pc->nsets; k++) free(pc->sets[k].gid);
  PF_FREE(pc->sets);
  pc->nsets = 0;
  PF_FREE(pc->X);
  PF_FREE(pc->vol);
  PF_FREE(pc->cell);
  PF_FREE(pc->block);
  PF_FREE(pc->named_id);
  PF_FREE(pc->named);
  pc->n = pc->nnamed = 0;
  return 0;
}

/* Bounding box of a region. */
static void region_bounds(const pf_region *r, double lo[3], double hi[3]) {
  for (int c = 0; c < 3; c++) {
    lo[c] = r->center[c] - r->radius;
    hi[c] = r->center[c] + r->radius;
  }
  if (r->kind == PF_REGION_BOX) {
    memcpy(lo, r->lo, sizeof(double) * 3);
    memcpy(hi, r->hi, sizeof(double) * 3);
  } else if (r->kind == PF_REGION_CYLINDER) {
    lo[r->axis] = r->center[r->axis];
    hi[r->axis] = r->center[r->axis] + r->height;
  }
}

/* The region grown by tol on every face, so points exactly on the boundary are kept whatever
 * the round-off of origin + h i. */
static pf_region region_grow(const pf_region *r, double tol) {
  pf_region g = *r;
  for (int c = 0; c < 3; c++) g.lo[c] -= tol, g.hi[c] += tol;
  g.radius += tol;
  g.inner_radius = r->inner_radius > tol ? r->inner_radius - tol : 0;
  g.center[g.axis] -= r->kind == PF_REGION_CYLINDER ? tol : 0;
  g.height += 2 * tol;
  return g;
}

/* The index range [i0, i1] of lattice sites that cover the region; returns their number. */
static double lattice_range(const pf_region *r, double h, const double origin[3], long i0[3],
                            long i1[3]) {
  double lo[3], hi[3];
  region_bounds(r, lo, hi);
  for (int c = 0; c < 3; c++) {
    double a = floor((lo[c] - origin[c]) / h) - 1, b = ceil((hi[c] - origin[c]) / h) + 1;
    if (!(b - a < 4e9)) return INFINITY; /* would overflow long on the way */
    i0[c] = (long)a;
    i1[c] = (long)b;
  }
  return (double)(i1[0] - i0[0] + 1) * (i1[1] - i0[1] + 1) * (i1[2] - i0[2] + 1);
}

#define PF_LATTICE_MAX_CELLS 2e9

int pf_lattice_fill(const pf_region *r, double h, const double origin[3], pf_point_cloud *pc) {
  PF_CHECK(h > 0, PF_ERR_INPUT, "lattice spacing must be positive (got %g)", h);
  PF_CHECK(r->kind != PF_REGION_ALL, PF_ERR_INPUT, "a lattice needs a bounded shape");
  long i0[3], i1[3];
  double cells = lattice_range(r, h, origin, i0, i1);
  PF_CHECK(cells < PF_LATTICE_MAX_CELLS, PF_ERR_INPUT, "lattice of %.3g cells is too large (spacing %g m)", cells,
           h);
  pf_region g = region_grow(r, 1e-9 * h);
  pf_int cap = 0;
  memset(pc, 0, sizeof *pc);
  for (long k = i0[2]; k <= i1[2]; k++)
    for (long j = i0[1]; j <= i1[1]; j++)
      for (long i = i0[0]; i <= i1[0]; i++) {
        double x[3] = {origin[0] + h * i, origin[1] + h * j, origin[2] + h * k};
        if (pf_region_contains(&g, x)) PF_CALL(cloud_push(pc, &cap, x, h * h * h, 0));
      }
  return 0;
}

/* splitmix64: a seeded, platform-independent random stream for the perturbation. */
static uint64_t splitmix64(uint64_t *s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

static void perturb(pf_point_cloud *pc, double amplitude, uint64_t seed) {
  uint64_t s = seed;
  for (pf_int i = 0; i < 3 * pc->n; i++) {
    double u01 = (double)(splitmix64(&s) >> 11) * 0x1.0p-53;
    pc->X[i] += amplitude * (2 * u01 - 1);
  }
}

/* One point of a line: "x y z volume [block]", or Peridigm's "x y z block_id volume"; the
 * number of values read (0 when the line has text after them). */
static int parse_point(const char *p, int peridigm, double x[3], double *vol, double *block) {
  double v[5];
  int used = 0, got = 0;
  for (; got < 5; got++) {
    int more = 0;
    if (sscanf(p + used, "%lf %n", &v[got], &more) != 1) break;
    used += more;
  }
  if (p[used] != '\0' && p[used] != '#' && p[used] != '\n') return 0; /* trailing text */
  x[0] = v[0], x[1] = v[1], x[2] = v[2], *block = 0;
  if (peridigm) {
    if (got != 5) return 0;
    *block = v[3], *vol = v[4];
  } else {
    if (got < 4) return 0;
    *vol = v[3];
    if (got == 5) *block = v[4];
  }
  return got;
}

int pf_point_file_read(const char *path, int peridigm, pf_point_cloud *pc) {
  memset(pc, 0, sizeof *pc);
  FILE *fp = fopen(path, "r");
  PF_CHECK(fp, PF_ERR_INPUT, "cannot open point file '%s': %s", path, strerror(errno));
  char line[1024];
  pf_int cap = 0;
  int lineno = 0, ierr = 0;
  while (!ierr && fgets(line, sizeof line, fp)) {
    lineno++;
    char *p = line;
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '#' || *p == '\n' || *p == '\0') continue;
    double x[3], vol = 0, block = 0;
    if (!parse_point(p, peridigm, x, &vol, &block) || !isfinite(x[0] + x[1] + x[2] + vol) || !(vol > 0) ||
        block != floor(block))
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                            "%s:%d: expected '%s' with a positive volume and an integer block", path, lineno,
                            peridigm ? "x y z block_id volume" : "x y z volume [block]");
    else
      ierr = cloud_push(pc, &cap, x, vol, (int32_t)block);
  }
  fclose(fp);
  if (!ierr && pc->n == 0)
    ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: no points", path);
  if (ierr) pf_point_cloud_free(pc);
  return ierr;
}

/* A file name from the deck, taken relative to the deck's folder. */
static const double *sort_base;
static int by_position(const void *a, const void *b) {
  const double *p = &sort_base[3 * *(const pf_int *)a], *q = &sort_base[3 * *(const pf_int *)b];
  for (int c = 0; c < 3; c++)
    if (p[c] != q[c]) return p[c] < q[c] ? -1 : 1;
  return 0;
}

/* Two points at one position would make a bond of zero length. */
int pf_point_cloud_check_distinct(const char *path, const pf_point_cloud *pc) {
  pf_int *order;
  PF_MALLOC(order, pc->n);
  for (pf_int i = 0; i < pc->n; i++) order[i] = i;
  sort_base = pc->X;
  qsort(order, (size_t)pc->n, sizeof *order, by_position);
  for (pf_int k = 1; k < pc->n; k++) {
    if (by_position(&order[k - 1], &order[k])) continue;
    pf_int a = order[k - 1] < order[k] ? order[k - 1] : order[k], b = order[k - 1] ^ order[k] ^ a;
    const double *x = &pc->X[3 * a];
    free(order);
    PF_CHECK(0, PF_ERR_INPUT, "%s: points %" PF_INT_FMT " and %" PF_INT_FMT " (counting from 1 in file order) "
             "coincide at (%g, %g, %g)", path, a + 1, b + 1, x[0], x[1], x[2]);
  }
  free(order);
  return 0;
}

static int cloud_from_file(const pf_deck *d, const pf_node *g, pf_point_cloud *pc) {
  const char *file = NULL;
  char path[4096];
  PF_CALL(pf_deck_string(d, g, "file", &file));
  if (!file) return pf_deck_error(d, g, "file", "shape 'points_file' needs key 'file'");
  pf_deck_relative_path(d, file, path, sizeof path);
  FILE *probe = fopen(path, "r");
  if (!probe)
    return pf_deck_error(d, pf_node_get(g, "file"), "file", "cannot open point file '%s': %s",
                         path, strerror(errno));
  fclose(probe);
  const char *columns = "perifem";
  double scale = 1;
  PF_CALL(pf_deck_string(d, g, "columns", &columns));
  PF_CALL(pf_deck_real(d, g, "scale", &scale));
  if (strcmp(columns, "perifem") && strcmp(columns, "peridigm"))
    return pf_deck_error(d, pf_node_get(g, "columns"), "columns", "perifem or peridigm (got '%s')", columns);
  if (!(scale > 0)) return pf_deck_error(d, pf_node_get(g, "scale"), "scale", "must be positive (got %g)", scale);
  PF_CALL(pf_point_file_read(path, !strcmp(columns, "peridigm"), pc));
  for (pf_int i = 0; i < pc->n; i++) {
    for (int c = 0; c < 3; c++) pc->X[3 * i + c] *= scale;
    pc->vol[i] *= scale * scale * scale;
    pc->cell[i] *= scale;
  }
  PF_CALL(pf_point_cloud_check_distinct(path, pc));
  PF_CALL(pf_point_file_sets(d, g, pc));
  long block = -1;
  PF_CALL(pf_deck_int(d, g, "block", &block));
  if (block < 0) return 0;
  pf_int k = 0, *new_index;
  PF_MALLOC(new_index, pc->n);
  for (pf_int i = 0; i < pc->n; i++) {
    new_index[i] = pc->block[i] == block ? k : -1;
    if (pc->block[i] != block) continue;
    memmove(&pc->X[3 * k], &pc->X[3 * i], 3 * sizeof(double));
    pc->vol[k] = pc->vol[i];
    pc->cell[k] = pc->cell[i];
    pc->block[k++] = pc->block[i];
  }
  pf_point_file_sets_keep(pc, new_index);
  free(new_index);
  pc->n = k;
  if (k == 0) return pf_deck_error(d, pf_node_get(g, "block"), "block", "no point of block %ld in '%s'", block, path);
  return 0;
}

/* A box of zero extent in exactly one axis (lo[c] == hi[c]) is a sheet of one point layer, whose
 * families are flat discs that a 3-D material model was not calibrated for (the PMB and LPS
 * moduli assume full spheres): refused. Zero extent in two or three axes (a line or a single
 * point, as the two-point tests use) stays valid. */
static int check_thickness(const pf_deck *d, const pf_node *g, const pf_region *r, double h) {
  if (r->kind != PF_REGION_BOX) return 0;
  int zero = -1, nzero = 0;
  for (int c = 0; c < 3; c++)
    if (r->hi[c] == r->lo[c]) zero = c, nzero++;
  if (nzero != 1) return 0;
  return pf_deck_error(d, pf_node_get(g, "hi"), "hi",
                       "the box has zero thickness in %c (lo[%d] = hi[%d] = %g m): one layer of points "
                       "whose families are flat, which a 3-D material model is not calibrated for; give "
                       "it a thickness of at least one spacing (%g m), e.g. hi[%d] = %g",
                       'x' + zero, zero, zero, r->lo[zero], h, zero, r->lo[zero] + h);
}

/* Bytes a point costs at the peak of the set-up without its bonds (the clouds, the points'
 * fields, the Morton order and the partition): measured about 1 KB per point on a 227 000-point
 * PMB box (docs/deck_guide.md §4); the bonds add their share in the PD body (sim/body_pd.c). */
#define PF_LATTICE_BYTES_PER_POINT 1024.0

/* The geometry's point_volume, when given, for every point of a lattice (at most the cell's h^3:
 * a point stands for a grain inside its cell). */
static int point_volume(const pf_deck *d, const pf_node *g, double h, pf_point_cloud *pc) {
  const pf_node *key = pf_node_get(g, "point_volume");
  if (!key) return 0;
  double v = 0;
  PF_CALL(pf_deck_real(d, g, "point_volume", &v));
  if (!(v > 0 && v <= h * h * h * (1 + 1e-12)))
    return pf_deck_error(d, key, "point_volume", "must be positive and at most the cell's h^3 = %g m^3 (got %g)",
                         h * h * h, v);
  for (pf_int i = 0; i < pc->n; i++) pc->vol[i] = v;
  return 0;
}

/* Before filling: the points the lattice would make, estimated as the lattice cells covering
 * the shape's bounding box times the shape's share of that box, refused beyond the local index
 * range (pf_int) or beyond the memory each rank may use for its share. */
static double region_volume(const pf_region *r, double *box) {
  double lo[3], hi[3];
  region_bounds(r, lo, hi);
  *box = 1;
  for (int c = 0; c < 3; c++) *box *= hi[c] - lo[c];
  if (r->kind == PF_REGION_BOX) return *box;
  if (r->kind == PF_REGION_CYLINDER)
    return 3.14159265358979323846 * (r->radius * r->radius - r->inner_radius * r->inner_radius) * r->height;
  return 4.0 / 3.0 * 3.14159265358979323846 * r->radius * r->radius * r->radius;
}

static double lattice_points(const pf_region *r, double cells) {
  double box;
  const double vol = region_volume(r, &box);
  return cells * (box > 0 && vol < box ? vol / box : 1);
}

static int check_lattice_size(const pf_deck *d, const pf_node *g, const pf_region *r, double h,
                              double cells) {
  const double points = lattice_points(r, cells);
  const double bytes = points * PF_LATTICE_BYTES_PER_POINT, limit = pf_memory_limit();
  const int ranks = pf_comm_size();
  if (points < INT32_MAX && bytes / ranks <= limit) return 0;
  return pf_deck_error(d, pf_node_get(g, "spacing"), "spacing",
                       "spacing %g m would make about %.3g points, needing about %.3g GB before "
                       "any bond (%.3g GB on each of %d rank(s)); %s (a rank may use %.3g GB here); "
                       "use a larger spacing or a smaller geometry (a length in millimetres typed "
                       "as metres?)",
                       h, points, bytes / 1e9, bytes / ranks / 1e9, ranks,
                       points < INT32_MAX ? "more than the memory available"
                                          : "more than the 2^31 points one rank can index",
                       limit / 1e9);
}

int pf_point_cloud_from_deck(const pf_deck *d, const pf_node *g, pf_point_cloud *pc) {
  memset(pc, 0, sizeof *pc);
  const char *shape = NULL;
  PF_CALL(pf_deck_string(d, g, "shape", &shape));
  if (shape && !strcmp(shape, "points_file")) return cloud_from_file(d, g, pc);
  if (shape && !strcmp(shape, "exodus"))
    return pf_deck_error(d, pf_node_get(g, "shape"), "shape", "an Exodus discretization is read by the mesh "
                         "module (a peridynamic body's points); it is not a lattice");
  pf_region r;
  PF_CALL(pf_region_from_deck(d, g, NULL, -1, &r));
  if (r.kind == PF_REGION_ALL) return pf_deck_error(d, g, "shape", "a body needs a bounded shape");
  double h = 0, origin[3] = {0, 0, 0}, amp = 0;
  long seed = 1;
  if (!pf_node_get(g, "spacing")) return pf_deck_error(d, g, "spacing", "a lattice needs 'spacing'");
  PF_CALL(pf_deck_real(d, g, "spacing", &h));
  if (!(h > 0)) return pf_deck_error(d, pf_node_get(g, "spacing"), "spacing", "must be positive (got %g)", h);
  PF_CALL(pf_deck_vec3(d, g, "origin", origin));
  PF_CALL(pf_deck_real(d, g, "perturbation", &amp));
  PF_CALL(pf_deck_int(d, g, "seed", &seed));
  if (!(amp >= 0 && amp < 0.5))
    return pf_deck_error(d, pf_node_get(g, "perturbation"), "perturbation",
                         "must be in [0, 0.5) of the spacing (got %g)", amp);
  const char *lattice = "cubic";
  PF_CALL(pf_deck_string(d, g, "lattice", &lattice));
  if (strcmp(lattice, "cubic") && strcmp(lattice, "polar"))
    return pf_deck_error(d, pf_node_get(g, "lattice"), "lattice", "unknown lattice '%s' (known: cubic, polar)", lattice);
  if (!strcmp(lattice, "polar")) {
    if (r.kind != PF_REGION_CYLINDER)
      return pf_deck_error(d, pf_node_get(g, "lattice"), "lattice", "a polar lattice needs shape: cylinder");
    if (pf_node_get(g, "origin"))
      return pf_deck_error(d, pf_node_get(g, "origin"), "origin", "a polar lattice has no origin (its rings start at the inner radius)");
    PF_CALL(pf_polar_fill(&r, h, pc));
    if (amp > 0) perturb(pc, amp * h, (uint64_t)seed);
    return point_volume(d, g, h, pc);
  }
  long i0[3], i1[3];
  double cells = lattice_range(&r, h, origin, i0, i1);
  if (!(cells < PF_LATTICE_MAX_CELLS))
    return pf_deck_error(d, pf_node_get(g, "spacing"), "spacing",
                         "the lattice of %.3g cells is too large for spacing %g m (at most 2e9 cells; "
                         "a length in millimetres typed as metres?)", cells, h);
  PF_CALL(check_thickness(d, g, &r, h));
  PF_CALL(check_lattice_size(d, g, &r, h, cells));
  PF_CALL(pf_lattice_fill(&r, h, origin, pc));
  if (pc->n == 0) return pf_deck_error(d, g, "shape", "the shape holds no lattice point (spacing %g m)", h);
  if (amp > 0) perturb(pc, amp * h, (uint64_t)seed);
  return point_volume(d, g, h, pc);
}

/* The reads in pf_point_cloud_from_deck's order, so that a bad value raises the same error
 * first; what that function refuses with its own message is left to it (points 0). The origin
 * is not read: it moves the cells by less than one layer. */
int pf_point_cloud_estimate(const pf_deck *d, const pf_node *g, double *points, double *spacing) {
  const char *shape = NULL, *lattice = pf_node_text(pf_node_get(g, "lattice"));
  double h = 0, box;
  const double origin[3] = {0, 0, 0};
  pf_region r;
  *points = 0, *spacing = 0;
  PF_CALL(pf_deck_string(d, g, "shape", &shape));
  if (shape && (!strcmp(shape, "points_file") || !strcmp(shape, "exodus"))) return 0;
  PF_CALL(pf_region_from_deck(d, g, NULL, -1, &r));
  if (r.kind == PF_REGION_ALL || !pf_node_get(g, "spacing")) return 0;
  PF_CALL(pf_deck_real(d, g, "spacing", &h));
  if (!(h > 0)) return 0;
  *spacing = h;
  if (lattice && !strcmp(lattice, "polar")) *points = region_volume(&r, &box) / (h * h * h);
  else {
    long i0[3], i1[3];
    *points = lattice_points(&r, lattice_range(&r, h, origin, i0, i1));
  }
  return 0;
}
