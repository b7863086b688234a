/* The contact search: the entities (PD particles of bodies in a pair, FE nodes on a pair's
 * surface) this rank owns, the ghosts it needs from other ranks, and each owned particle's
 * candidates, found in uniform bins (a counting sort, O(n)) with a skin s. The search is rebuilt
 * only when some entity has moved more than s/2 since the last build: two entities that come
 * within r_c of each other were then within r_c + s at the build, whatever their speed, so a
 * candidate list of every partner within r_c + s misses no contact (Verlet 1967; the LAMMPS
 * neighbor skin). Ghosts: every rank sends the entities that lie within a margin of another
 * rank's box of owned entities, margin = r_c + 2 s + twice the largest face size (a particle
 * needs every node of a face within reach). */
#include "contact/contact_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- bins ---------------------------------------------------------------------------------- */
int pf_contact_grid_build(pf_grid *g, pf_int n, const double *x, double cell) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (pf_int i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], x[3 * i + a]), hi[a] = fmax(hi[a], x[3 * i + a]);
  if (n == 0) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
  /* no more bins than 8 per point: widely scattered fragments widen the bins, not the memory */
  double nb;
  for (;;) {
    nb = 1;
    for (int a = 0; a < 3; a++) nb *= floor((hi[a] - lo[a]) / cell) + 1;
    if (nb <= 8.0 * n + 64) break;
    cell *= 2;
  }
  g->cell = cell;
  for (int a = 0; a < 3; a++) g->lo[a] = lo[a], g->dim[a] = (int)floor((hi[a] - lo[a]) / cell) + 1;
  pf_int nbins = (pf_int)nb;
  PF_MALLOC(g->start, nbins + 1);
  PF_MALLOC(g->item, n);
  pf_int *bin;
  PF_MALLOC(bin, n);
  for (pf_int i = 0; i < n; i++) {
    int k[3];
    for (int a = 0; a < 3; a++) {
      k[a] = (int)((x[3 * i + a] - lo[a]) / cell);
      if (k[a] >= g->dim[a]) k[a] = g->dim[a] - 1;
    }
    bin[i] = (k[2] * g->dim[1] + k[1]) * g->dim[0] + k[0];
    g->start[bin[i] + 1]++;
  }
  for (pf_int b = 0; b < nbins; b++) g->start[b + 1] += g->start[b];
  for (pf_int i = 0; i < n; i++) g->item[g->start[bin[i]]++] = i;
  for (pf_int b = nbins; b > 0; b--) g->start[b] = g->start[b - 1];
  g->start[0] = 0;
  free(bin);
  return 0;
}

void pf_contact_grid_free(pf_grid *g) {
  PF_FREE(g->start);
  PF_FREE(g->item);
}

void pf_contact_grid_range(const pf_grid *g, const double p[3], double r, int lo[3], int hi[3]) {
  for (int a = 0; a < 3; a++) {
    double l = floor((p[a] - r - g->lo[a]) / g->cell), h = floor((p[a] + r - g->lo[a]) / g->cell);
    lo[a] = (int)fmax(0, l);
    hi[a] = (int)fmin(g->dim[a] - 1, h);
  }
}

static double dist2(const double *a, const double *b) {
  double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

/* ---- the owned entities and the view arrays ------------------------------------------------ */
static int view_reserve(pf_contact *c, pf_int n) {
  if (n <= c->cap) return 0;
  pf_int cap = n + n / 2 + 16;
  void *p[8] = {realloc(c->gid, sizeof *c->gid * (size_t)cap), NULL};
  PF_CHECK(p[0], PF_ERR_MEMORY, "out of memory");
  c->gid = p[0];
#define GROW(f, k)                                                                                 \
  do {                                                                                             \
    void *q_ = realloc(c->f, sizeof *c->f * (size_t)(k) * (size_t)cap);                            \
    PF_CHECK(q_, PF_ERR_MEMORY, "out of memory");                                                  \
    c->f = q_;                                                                                     \
  } while (0)
  GROW(vbody, 1);
  GROW(rank, 1);
  GROW(y, 3);
  GROW(v, 3);
  GROW(X, 3);
  GROW(vol, 1);
  GROW(m, 1);
  GROW(rad, 1);
#undef GROW
  c->cap = cap;
  return 0;
}

static int is_entity(const pf_contact *c, const pf_points *pts, pf_int i) {
  int b = pts->body[i];
  if (!c->body_used[b] || !(pts->m[i] > 0)) return 0; /* (mass 0: a dormant particle, a bare node) */
  if (!c->body[b].is_fe) return 1;
  return c->surface_node[b] && c->surface_node[b][pts->gid[i] - c->body[b].gid0];
}

int pf_contact_collect_owned(pf_contact *c, const pf_points *pts) {
  pf_int n = 0;
  for (pf_int i = 0; i < pts->n_owned; i++) n += is_entity(c, pts, i);
  free(c->local), free(c->y_build), free(c->force);
  c->local = NULL, c->y_build = NULL, c->force = NULL;
  PF_MALLOC(c->local, n);
  PF_MALLOC(c->y_build, 3 * n);
  PF_MALLOC(c->force, 3 * n);
  PF_CALL(view_reserve(c, n));
  int me = pf_comm_rank();
  const double *rad = pf_points_field_get(pts, "contact_radius");
  c->nown = c->nview = n;
  for (pf_int i = 0, e = 0; i < pts->n_owned; i++) {
    if (!is_entity(c, pts, i)) continue;
    c->local[e] = i;
    c->gid[e] = pts->gid[i];
    c->vbody[e] = pts->body[i];
    c->rank[e] = me;
    c->vol[e] = pts->vol[i];
    c->m[e] = pts->m[i];
    c->rad[e] = rad && rad[i] > 0 ? rad[i] : INFINITY;
    memcpy(&c->X[3 * e], &pts->X[3 * i], sizeof(double) * 3);
    e++;
  }
  c->built = 0;
  return 0;
}

/* ---- ghosts -------------------------------------------------------------------------------- */
/* Exchange n doubles per entity: owned entities in send order to the ghosts of other ranks
 * (core's exchange plan, made by send_lists). */
static int exchange_doubles(pf_contact *c, int n, double *data) {
  return pf_exchange_doubles(c->exchange, data, n, c->nown);
}

/* Positions and velocities of the ghosts, in one message per rank pair. */
static int exchange_motion(pf_contact *c) {
  if (c->nranks == 1) return 0;
  double *yv;
  PF_MALLOC(yv, 6 * (size_t)c->nview);
  for (pf_int e = 0; e < c->nown; e++)
    for (int a = 0; a < 3; a++) yv[6 * e + a] = c->y[3 * e + a], yv[6 * e + 3 + a] = c->v[3 * e + a];
  int ierr = exchange_doubles(c, 6, yv);
  for (pf_int e = c->nown; e < c->nview && !ierr; e++)
    for (int a = 0; a < 3; a++) c->y[3 * e + a] = yv[6 * e + a], c->v[3 * e + a] = yv[6 * e + 3 + a];
  free(yv);
  return ierr;
}

int pf_contact_exchange(pf_contact *c, const pf_points *pts) {
#pragma omp parallel for schedule(static)
  for (pf_int e = 0; e < c->nown; e++)
    for (int a = 0; a < 3; a++) {
      c->y[3 * e + a] = pts->y[3 * c->local[e] + a];
      c->v[3 * e + a] = pts->v[3 * c->local[e] + a];
    }
  if (!c->built) return 0; /* the build sends everything */
  return exchange_motion(c);
}

/* The largest node-to-node distance of the faces of side sd that have a node this rank owns
 * (the face's other nodes are then in the store: FE bodies ghost the nodes of the elements of
 * owned nodes). Collective. */
static int side_size(const pf_contact *c, const pf_points *pts, pf_contact_side *sd) {
  const pf_contact_body *fe = &c->body[sd->body];
  pf_int *at;
  PF_MALLOC(at, fe->mesh->nnodes);
  for (pf_int q = 0; q < fe->mesh->nnodes; q++) at[q] = -1;
  for (pf_int i = 0; i < pts->n_total; i++)
    if (pts->body[i] == sd->body) at[pts->gid[i] - fe->gid0] = i;
  double size = 0;
  for (pf_int f = 0; f < sd->nface; f++) {
    const pf_int *nd = sd->face[f].node;
    int owned = 0, have = 1;
    for (int q = 0; q < 4; q++) {
      owned |= at[nd[q]] >= 0 && at[nd[q]] < pts->n_owned;
      have &= at[nd[q]] >= 0;
    }
    if (!owned || !have) continue;
    for (int q = 0; q < 4; q++)
      for (int r = q + 1; r < 4; r++) size = fmax(size, dist2(&pts->y[3 * at[nd[q]]], &pts->y[3 * at[nd[r]]]));
  }
  free(at);
  sd->size = pf_max_all(sqrt(size));
  return 0;
}

/* A pair's largest face size: the largest of its sides' (0 for a short-range pair). */
static double face_size(const pf_contact_pair *p) {
  double size = 0;
  for (int s = 0; s < p->nside; s++) size = fmax(size, p->side[s].size);
  return size;
}

/* The face size of every pair's sides. Collective. */
static int face_sizes(pf_contact *c, const pf_points *pts) {
  for (int k = 0; k < c->npairs; k++)
    for (int s = 0; s < c->pair[k].nside; s++) PF_CALL(side_size(c, pts, &c->pair[k].side[s]));
  return 0;
}

/* Send lists: owned entities within the margin of each other rank's box. Collective. */
static int send_lists(pf_contact *c) {
  int me = pf_comm_rank(), R = c->nranks;
  double box[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY}, *all;
  for (pf_int e = 0; e < c->nown; e++)
    for (int a = 0; a < 3; a++) box[a] = fmin(box[a], c->y[3 * e + a]), box[3 + a] = fmax(box[3 + a], c->y[3 * e + a]);
  PF_MALLOC(all, 6 * R);
  MPI_Allgather(box, 6, MPI_DOUBLE, all, 6, MPI_DOUBLE, MPI_COMM_WORLD);
  free(c->send);
  c->send = NULL;
  pf_int total = 0;
  for (int pass = 0; pass < 2; pass++) {
    total = 0;
    for (int r = 0; r < R; r++) {
      c->sdispl[r] = total;
      const double *b = &all[6 * r];
      for (pf_int e = 0; e < c->nown && r != me; e++) {
        const double *y = &c->y[3 * e];
        int in = 1;
        for (int a = 0; a < 3; a++) in &= y[a] >= b[a] - c->margin && y[a] <= b[3 + a] + c->margin;
        if (!in) continue;
        if (pass) c->send[total] = e;
        total++;
      }
      c->scount[r] = total - c->sdispl[r];
    }
    if (!pass) PF_MALLOC(c->send, total);
  }
  free(all);
  MPI_Alltoall(c->scount, 1, MPI_INT, c->rcount, 1, MPI_INT, MPI_COMM_WORLD);
  pf_int nrecv = 0;
  for (int r = 0; r < R; r++) c->rdispl[r] = nrecv, nrecv += c->rcount[r];
  PF_CALL(view_reserve(c, c->nown + nrecv));
  c->nview = c->nown + nrecv;
  for (int r = 0; r < R; r++)
    for (pf_int k = c->rdispl[r]; k < c->rdispl[r] + c->rcount[r]; k++) c->rank[c->nown + k] = r;
  pf_exchange_destroy(&c->exchange);
  return pf_exchange_create(c->scount, c->send, c->rcount, &c->exchange);
}

/* Ghost data at a build: gid, body, volume, mass, reference position, then position and
 * velocity. Collective. */
static int send_ghosts(pf_contact *c) {
  if (c->nranks == 1) return 0;
  enum { META = 8 };
  double *meta;
  PF_MALLOC(meta, META * (size_t)c->nview);
  for (pf_int e = 0; e < c->nown; e++) {
    double *q = &meta[META * e];
    q[0] = (double)c->gid[e], q[1] = c->vbody[e], q[2] = c->vol[e], q[3] = c->m[e];
    memcpy(&q[4], &c->X[3 * e], sizeof(double) * 3);
    q[7] = c->rad[e];
  }
  int ierr = exchange_doubles(c, META, meta);
  for (pf_int e = c->nown; e < c->nview && !ierr; e++) {
    const double *q = &meta[META * e];
    c->gid[e] = (pf_gid)q[0], c->vbody[e] = (int32_t)q[1], c->vol[e] = q[2], c->m[e] = q[3];
    memcpy(&c->X[3 * e], &q[4], sizeof(double) * 3);
    c->rad[e] = q[7];
  }
  free(meta);
  if (ierr) return ierr;
  return exchange_motion(c);
}

/* node_view of every FE body in a pair: the view index of each of its mesh nodes. */
static void map_nodes(pf_contact *c) {
  for (int b = 0; b < c->nbodies; b++)
    if (c->node_view[b])
      for (pf_int q = 0; q < c->body[b].mesh->nnodes; q++) c->node_view[b][q] = -1;
  for (pf_int e = 0; e < c->nview; e++) {
    int b = c->vbody[e];
    if (c->body[b].is_fe && c->node_view[b]) c->node_view[b][c->gid[e] - c->body[b].gid0] = e;
  }
}

/* ---- candidates ---------------------------------------------------------------------------- */
static int cand_push(pf_contact *c, int64_t *n, int32_t pair, pf_int j, pf_gid key) {
  if (*n == c->cand_cap) {
    int64_t cap = 2 * c->cand_cap + 1024;
    pf_candidate *q = realloc(c->cand, sizeof *q * (size_t)cap);
    PF_CHECK(q, PF_ERR_MEMORY, "out of memory for contact candidates");
    c->cand = q, c->cand_cap = cap;
  }
  c->cand[(*n)++] = (pf_candidate){.pair = pair, .j = j, .key = key};
  return 0;
}

static int cand_cmp(const void *a, const void *b) {
  const pf_candidate *x = a, *y = b;
  if (x->pair != y->pair) return x->pair < y->pair ? -1 : 1;
  return x->key < y->key ? -1 : x->key > y->key;
}

/* Sort n candidates by (pair, key), stably: an insertion sort, inlined. A particle has a few
 * dozen candidates, for which this takes a quarter of qsort's instructions (its merge sort
 * calls the comparison through a pointer); both are stable, so the order is the same. */
static void cand_sort(pf_candidate *v, int64_t n) {
  for (int64_t i = 1; i < n; i++) {
    const pf_candidate x = v[i];
    int64_t j = i;
    for (; j > 0 && (v[j - 1].pair > x.pair || (v[j - 1].pair == x.pair && v[j - 1].key > x.key)); j--) v[j] = v[j - 1];
    v[j] = x;
  }
}

/* Partners of owned particle e in pair k among the view entities of body `other` (grid g). */
static int point_candidates(pf_contact *c, const pf_grid *g, pf_int e, int k, int other, int64_t *n) {
  double reach = c->pair[k].radius + c->skin;
  int lo[3], hi[3];
  pf_contact_grid_range(g, &c->y[3 * e], reach, lo, hi);
  for (int z = lo[2]; z <= hi[2]; z++)
    for (int y = lo[1]; y <= hi[1]; y++)
      for (int x = lo[0]; x <= hi[0]; x++) {
        pf_int bin = (z * g->dim[1] + y) * g->dim[0] + x;
        for (pf_int s = g->start[bin]; s < g->start[bin + 1]; s++) {
          pf_int j = g->item[s];
          if (j == e || c->vbody[j] != other || dist2(&c->y[3 * e], &c->y[3 * j]) > reach * reach) continue;
          PF_CALL(cand_push(c, n, k, j, c->gid[j]));
        }
      }
  return 0;
}

/* The faces of a pair's side whose nodes are all in the view: centres (for the face grid) and
 * boxes. */
typedef struct {
  pf_int n;
  pf_int *face;   /* [n] face index of the side */
  double *centre; /* [3n] */
  double *box;    /* [6n] */
  pf_grid grid;
} face_set;

static int face_set_build(const pf_contact *c, const pf_contact_pair *p, const pf_contact_side *sd, face_set *s) {
  const pf_int *nv = c->node_view[sd->body];
  memset(s, 0, sizeof *s);
  PF_MALLOC(s->face, sd->nface);
  PF_MALLOC(s->centre, 3 * sd->nface);
  PF_MALLOC(s->box, 6 * sd->nface);
  for (pf_int f = 0; f < sd->nface; f++) {
    const pf_int *nd = sd->face[f].node;
    if (nv[nd[0]] < 0 || nv[nd[1]] < 0 || nv[nd[2]] < 0 || nv[nd[3]] < 0) continue;
    double *ce = &s->centre[3 * s->n], *bx = &s->box[6 * s->n];
    for (int a = 0; a < 3; a++) ce[a] = 0, bx[a] = INFINITY, bx[3 + a] = -INFINITY;
    for (int q = 0; q < 4; q++)
      for (int a = 0; a < 3; a++) {
        double x = c->y[3 * nv[nd[q]] + a];
        ce[a] += 0.25 * x;
        bx[a] = fmin(bx[a], x), bx[3 + a] = fmax(bx[3 + a], x);
      }
    s->face[s->n++] = f;
  }
  /* a box grown by r_c + skin that contains p has its centre within r_c + skin + 2 l of p (l the
   * largest node distance: the box's half diagonal is at most sqrt(3)/2 l... and 2 l covers it) */
  return pf_contact_grid_build(&s->grid, s->n, s->centre, p->radius + c->skin + 2 * sd->size);
}

static void face_set_free(face_set *s) {
  free(s->face), free(s->centre), free(s->box);
  pf_contact_grid_free(&s->grid);
}

/* Faces of side sd of pair k whose box, grown by r_c + skin, contains owned entity e. On a pair
 * of two FE bodies a node does not meet the faces it belongs to (the bodies differ). */
static int face_candidates(pf_contact *c, const face_set *s, const pf_contact_side *sd, pf_int e, int k,
                           int64_t *n) {
  const double reach = c->pair[k].radius + c->skin, *y = &c->y[3 * e];
  int lo[3], hi[3];
  pf_contact_grid_range(&s->grid, y, reach + 2 * sd->size, lo, hi);
  for (int z = lo[2]; z <= hi[2]; z++)
    for (int yy = lo[1]; yy <= hi[1]; yy++)
      for (int x = lo[0]; x <= hi[0]; x++) {
        pf_int bin = (z * s->grid.dim[1] + yy) * s->grid.dim[0] + x;
        for (pf_int q = s->grid.start[bin]; q < s->grid.start[bin + 1]; q++) {
          pf_int t = s->grid.item[q];
          const double *bx = &s->box[6 * t];
          int in = 1;
          for (int a = 0; a < 3; a++) in &= y[a] >= bx[a] - reach && y[a] <= bx[3 + a] + reach;
          if (in) PF_CALL(cand_push(c, n, k, s->face[t], s->face[t]));
        }
      }
  return 0;
}

/* The candidates of owned entity e: a PD particle's in every pair of its body, an FE node's in
 * the pairs of two FE bodies (the particle's owner computes each FE <-> PD interaction). */
static int entity_candidates(pf_contact *c, const pf_grid *g, face_set (*fs)[2], pf_int e, int64_t *n) {
  const int b = c->vbody[e], fe = c->body[b].is_fe;
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    if ((p->a != b && p->b != b) || (fe && p->kind != PF_PAIR_SURFACES)) continue;
    if (p->kind == PF_PAIR_SURFACE || p->kind == PF_PAIR_SURFACES) {
      const pf_contact_side *sd = pf_contact_facing(p, b);
      PF_CALL(face_candidates(c, &fs[k][sd - p->side], sd, e, k, n));
    } else PF_CALL(point_candidates(c, g, e, k, p->a == b ? p->b : p->a, n));
  }
  return 0;
}

/* The candidates [s, t) of owned particle e, sorted by (pair, partner gid): each short-range
 * candidate of e's own body gets the bond of e's family to it (-1: never bonded), found by
 * merging the pair's candidates with e's family row, both sorted by global id (pd/family.c);
 * every other candidate gets -1. Each family entry read is counted. */
static void resolve_bonds(pf_contact *c, const pf_points *pts, pf_int e, int64_t s, int64_t t) {
  const pf_family *fam = c->body[c->vbody[e]].fam;
  const int64_t row0 = fam ? fam->offset[c->local[e] - fam->first] : 0;
  const int64_t row1 = fam ? fam->offset[c->local[e] - fam->first + 1] : 0;
  int64_t reads = 0;
  for (int64_t q = s; q < t;) {
    const int32_t k = c->cand[q].pair;
    const int mine = c->pair[k].kind == PF_PAIR_SHORT_RANGE && fam;
    int64_t b = row0;
    for (; q < t && c->cand[q].pair == k; q++) {
      pf_candidate *cd = &c->cand[q];
      const pf_gid g = cd->key;
      cd->bond = -1;
      if (!mine || c->vbody[cd->j] != c->vbody[e]) continue;
      while (b < row1 && (reads++, pts->gid[fam->neighbor[b]] < g)) b++;
      if (b < row1 && pts->gid[fam->neighbor[b]] == g) cd->bond = b;
    }
  }
  c->family_reads += reads;
}

static int build_candidates(pf_contact *c, const pf_points *pts) {
  double cell = 0;
  for (int k = 0; k < c->npairs; k++) cell = fmax(cell, c->pair[k].radius + c->skin);
  pf_grid g;
  PF_CALL(pf_contact_grid_build(&g, c->nview, c->y, cell));
  face_set(*fs)[2];
  PF_MALLOC(fs, c->npairs);
  int ierr = 0;
  for (int k = 0; k < c->npairs && !ierr; k++)
    if (c->pair[k].kind == PF_PAIR_SURFACE || c->pair[k].kind == PF_PAIR_SURFACES)
      for (int s = 0; s < c->pair[k].nside && !ierr; s++)
        ierr = face_set_build(c, &c->pair[k], &c->pair[k].side[s], &fs[k][s]);
  free(c->cand_off);
  c->cand_off = malloc(sizeof *c->cand_off * (size_t)(c->nown + 1));
  if (!c->cand_off) ierr = PF_ERR_MEMORY;
  int64_t n = 0;
  for (pf_int e = 0; e < c->nown && !ierr; e++) {
    c->cand_off[e] = n;
    ierr = entity_candidates(c, &g, fs, e, &n);
    if (!ierr && n > c->cand_off[e]) { /* (none yet: c->cand may still be NULL, which qsort must not get) */
      const int64_t m = n - c->cand_off[e];
      if (m <= 64) cand_sort(&c->cand[c->cand_off[e]], m);
      else qsort(&c->cand[c->cand_off[e]], (size_t)m, sizeof *c->cand, cand_cmp);
      resolve_bonds(c, pts, e, c->cand_off[e], n);
    }
  }
  if (c->cand_off) c->cand_off[c->nown] = n;
  for (int k = 0; k < c->npairs; k++)
    if (c->pair[k].kind == PF_PAIR_SURFACE || c->pair[k].kind == PF_PAIR_SURFACES)
      for (int s = 0; s < c->pair[k].nside; s++) face_set_free(&fs[k][s]);
  free(fs);
  pf_contact_grid_free(&g);
  return ierr;
}

static double largest_move(const pf_contact *c) {
  double m2 = 0;
#pragma omp parallel for schedule(static) reduction(max : m2)
  for (pf_int e = 0; e < c->nown; e++) {
    const double d2 = dist2(&c->y[3 * e], &c->y_build[3 * e]);
    m2 = d2 > m2 ? d2 : m2; /* (NaN positions are the guard's to report) */
  }
  return pf_max_all(sqrt(m2));
}

int pf_contact_search(pf_contact *c, const pf_points *pts) {
  if (c->built && largest_move(c) <= 0.5 * c->skin) return 0;
  PF_CALL(face_sizes(c, pts));
  c->margin = c->skin;
  /* a partner within r_c at any time before the next build was within r_c + skin at this one;
   * the nodes of a face whose grown box holds a particle within r_c + skin + 2 l of it; and the
   * face may grow by the skin before the next build */
  for (int k = 0; k < c->npairs; k++)
    c->margin = fmax(c->margin, c->pair[k].radius + 2 * c->skin + 2 * face_size(&c->pair[k]));
  c->nview = c->nown;
  PF_CALL(send_lists(c));
  PF_CALL(send_ghosts(c));
  map_nodes(c);
  PF_CALL(build_candidates(c, pts));
  memcpy(c->y_build, c->y, sizeof(double) * 3 * (size_t)c->nown);
  c->built = 1;
  c->rebuilds++;
  return 0;
}
