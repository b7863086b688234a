/* The contact search: the entities (PD particles of bodies in a pair, FE nodes on a pair's
 * surface) this rank owns, the ghosts it needs from other ranks, and each owned particle's
 * candidates, found in uniform bins (a counting sort, O(n)) with a skin s. A pair's candidates
 * are rebuilt only when two entities of the pair's bodies may have moved relative to each other
 * by more than s since the pair's last build (each more than s/2, or more than s relative to
 * the bodies' motion as a whole: pair_keeps, affine_keeps): two entities that come within r_c of
 * each other were then within r_c + s at the build, whatever their speed, so a candidate list of
 * every partner within r_c + s misses no contact (Verlet 1967; the LAMMPS neighbor skin). Each
 * pair has its own rule (pair_stale): a fast projectile's surface pair is rebuilt without its
 * target's self-contact. The builds are threaded over fixed chunks of entities
 * (chunked_candidates). Ghosts: every rank sends an entity to each rank whose box of owned
 * entities of a body that needs it (its partners' body in a pair) lies within the pair's margin,
 * r_c + 2 s + twice the largest face size (a particle needs every node of a face within reach;
 * send_lists). */
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
    lo[a] = l > 0 ? (int)l : 0; /* (as fmax(0, l) and fmin(dim - 1, h), NaN included, inlined) */
    hi[a] = h < g->dim[a] - 1 ? (int)h : g->dim[a] - 1;
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
  PF_MALLOC(c->y_build, 3 * (size_t)n * (size_t)c->npairs);
  if (!c->stale) PF_MALLOC(c->stale, c->npairs);
  if (!c->built_at) PF_MALLOC(c->built_at, c->npairs);
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

/* 1 when pair p's owned entities of body E need the entities of body P as ghosts: E has
 * entities in the pair (a PD body; an FE body whose nodes have candidates, fe_entities) and P
 * holds their partners (the other body; the body itself in a self pair), or P is E's own FE body,
 * whose faces give a node its normal (node_normal). */
static int needs_body(const pf_contact *c, const pf_contact_pair *p, int E, int P) {
  if ((p->a != E && p->b != E) || (p->a != P && p->b != P)) return 0;
  const int fe = c->body[E].is_fe;
  if (fe && !p->method->fe_entities) return 0;
  return P == (p->a == E ? p->b : p->a) || fe;
}

/* margin[B * nb + E]: the largest margin of the pairs in which the entities of body E need
 * those of body B (needs_body), -1 where none does. A pair's margin is r_c + 2 s + 2 l (r_c: the
 * pair's length, which is half the finer spacing for a pair of FE bodies that meet at r_c = 0): a
 * partner within r_c at any time before the next build was within r_c + s at this one, the
 * nodes of a face whose grown box holds a particle within r_c + s + 2 l of it, and the face may
 * grow by the skin before the next build. */
static void body_margins(const pf_contact *c, double *margin) {
  const int nb = c->nbodies;
  for (int q = 0; q < nb * nb; q++) margin[q] = -1;
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    const double m = fmax(c->skin, p->length + 2 * c->skin + 2 * face_size(p));
    for (int B = 0; B < nb; B++)
      for (int E = 0; E < nb; E++)
        if (needs_body(c, p, E, B)) margin[B * nb + E] = fmax(margin[B * nb + E], m);
  }
}

/* 1 when owned entity e is within the margin of rank r's box of owned entities of some body
 * whose entities need e's (boxes: [R][nb][6], lo then hi; an empty box, +inf to -inf, holds
 * nothing). */
static int sent_to(const pf_contact *c, const double *boxes, const double *margin, int r, pf_int e) {
  const int nb = c->nbodies, B = c->vbody[e];
  const double *y = &c->y[3 * e];
  for (int E = 0; E < nb; E++) {
    const double m = margin[B * nb + E], *b = &boxes[6 * ((size_t)r * nb + E)];
    if (m < 0) continue;
    int in = 1;
    for (int a = 0; a < 3; a++) in &= y[a] >= b[a] - m && y[a] <= b[3 + a] + m;
    if (in) return 1;
  }
  return 0;
}

/* Send lists: each owned entity to every other rank whose owned entities of a body that needs
 * it lie within the pair's margin (body_margins), by the ranks' boxes of each body's owned
 * entities: a rank gets the particles that may touch its own and the nodes of the faces its
 * particles may touch, not every entity near any of its entities (a projectile's nodes owned by
 * one rank inside a tube owned by the other need the tube's particles on neither). Collective. */
static int send_lists(pf_contact *c) {
  int me = pf_comm_rank(), R = c->nranks;
  const int nb = c->nbodies;
  double *mine, *all, *margin;
  PF_MALLOC(mine, 6 * (size_t)nb + (size_t)nb * nb);
  margin = mine + 6 * (size_t)nb;
  for (int b = 0; b < nb; b++)
    for (int a = 0; a < 3; a++) mine[6 * b + a] = INFINITY, mine[6 * b + 3 + a] = -INFINITY;
  for (pf_int e = 0; e < c->nown; e++) {
    double *box = &mine[6 * c->vbody[e]];
    for (int a = 0; a < 3; a++) box[a] = fmin(box[a], c->y[3 * e + a]), box[3 + a] = fmax(box[3 + a], c->y[3 * e + a]);
  }
  body_margins(c, margin);
  all = malloc(sizeof *all * 6 * (size_t)nb * (size_t)R);
  if (!all) free(mine);
  PF_CHECK(all, PF_ERR_MEMORY, "out of memory for the contact's boxes");
  MPI_Allgather(mine, 6 * nb, MPI_DOUBLE, all, 6 * nb, MPI_DOUBLE, MPI_COMM_WORLD);
  free(c->send);
  c->send = NULL;
  pf_int total = 0;
  for (int pass = 0; pass < 2; pass++) {
    total = 0;
    for (int r = 0; r < R; r++) {
      c->sdispl[r] = total;
      for (pf_int e = 0; e < c->nown && r != me; e++) {
        if (!sent_to(c, all, margin, r, e)) continue;
        if (pass) c->send[total] = e;
        total++;
      }
      c->scount[r] = total - c->sdispl[r];
    }
    if (!pass && !(c->send = malloc(sizeof *c->send * (size_t)(total + 1)))) break;
  }
  free(all), free(mine);
  PF_CHECK(c->send, PF_ERR_MEMORY, "out of memory for the contact's send lists");
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
/* A growing list of candidates: each chunk of owned entities fills its own at a build. */
typedef struct {
  pf_candidate *v;
  int64_t n, cap;
} cand_list;

static int cand_append(cand_list *l, const pf_candidate *x) {
  PF_GROW(l->v, l->n, l->cap, 1024);
  l->v[l->n++] = *x;
  return 0;
}

static int cand_push(cand_list *l, int32_t pair, pf_int j, pf_gid key) {
  const pf_candidate x = {.pair = pair, .j = j, .key = key};
  return cand_append(l, &x);
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

/* The view entities of one body in bins, in the grid's slot order (bin by bin): their view
 * indices and positions, one array a coordinate, so that a search reads each row of bins as one
 * contiguous run, and an entity looking for the partners of another body reads only that body's
 * (two clusters far apart but for their contact zone find their few cross pairs at once). */
typedef struct {
  pf_grid g;
  pf_int *view; /* [n] view index of each slot's entity */
  double *x[3];
} body_bins;

static int body_bins_build(const pf_contact *c, int b, double cell, body_bins *bb) {
  pf_int n = 0;
  for (pf_int j = 0; j < c->nview; j++) n += c->vbody[j] == b;
  double *pos;
  pf_int *idx;
  PF_MALLOC(pos, 3 * (size_t)n);
  PF_MALLOC(idx, n);
  for (pf_int j = 0, q = 0; j < c->nview; j++)
    if (c->vbody[j] == b) memcpy(&pos[3 * (size_t)q], &c->y[3 * (size_t)j], sizeof(double) * 3), idx[q++] = j;
  int ierr = pf_contact_grid_build(&bb->g, n, pos, cell);
  bb->view = malloc(sizeof *bb->view * (size_t)(n + 1));
  for (int a = 0; a < 3; a++) bb->x[a] = malloc(sizeof(double) * (size_t)(n + 1));
  if (!ierr && !(bb->view && bb->x[0] && bb->x[1] && bb->x[2]))
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory for the contact's bins");
  for (pf_int s = 0; s < n && !ierr; s++) {
    const pf_int q = bb->g.item[s];
    bb->view[s] = idx[q];
    for (int a = 0; a < 3; a++) bb->x[a][s] = pos[3 * (size_t)q + a];
  }
  free(pos), free(idx);
  return ierr;
}

static void body_bins_free(body_bins *bb) {
  pf_contact_grid_free(&bb->g);
  PF_FREE(bb->view);
  for (int a = 0; a < 3; a++) PF_FREE(bb->x[a]);
}

/* Partners of owned particle e in pair k among the view entities of body `other` (its bins bb).
 * The bins of a row along x are consecutive slots: each row is one run, tested in blocks without
 * a branch (the distance as dist2 forms it), then its hits pushed in slot order. */
static int point_candidates(const pf_contact *c, const body_bins *bb, pf_int e, int k, cand_list *l) {
  enum { B = 64 };
  const pf_grid *g = &bb->g;
  const double reach = c->pair[k].radius + c->skin, r2 = reach * reach;
  const double p0 = c->y[3 * e], p1 = c->y[3 * e + 1], p2 = c->y[3 * e + 2];
  int lo[3], hi[3];
  pf_contact_grid_range(g, &c->y[3 * e], reach, lo, hi);
  if (lo[0] > hi[0]) return 0; /* (beyond the body's bins along x: no run) */
  for (int z = lo[2]; z <= hi[2]; z++)
    for (int y = lo[1]; y <= hi[1]; y++) {
      const pf_int row = (z * g->dim[1] + y) * g->dim[0];
      const pf_int s1 = g->start[row + hi[0] + 1];
      for (pf_int s0 = g->start[row + lo[0]]; s0 < s1; s0 += B) {
        const int n = s1 - s0 < B ? (int)(s1 - s0) : B;
        uint8_t hit[B];
        for (int q = 0; q < n; q++) {
          const double d0 = p0 - bb->x[0][s0 + q], d1 = p1 - bb->x[1][s0 + q], d2 = p2 - bb->x[2][s0 + q];
          hit[q] = d0 * d0 + d1 * d1 + d2 * d2 <= r2;
        }
        for (int q = 0; q < n; q++) {
          const pf_int j = bb->view[s0 + q];
          if (hit[q] && j != e) PF_CALL(cand_push(l, k, j, c->gid[j]));
        }
      }
    }
  return 0;
}

/* The faces of a pair's side whose nodes are all in the view, with their boxes, binned by their
 * boxes grown by the pair's reach r_c + skin: a face is listed in every bin its grown box
 * overlaps, so that an entity inside a grown box finds the face in its own bin, and an entity
 * reads one bin instead of the bins of every face centre within reach + 2 l. */
typedef struct {
  pf_int n;
  pf_int *face;   /* [n] face index of the side */
  double *box;    /* [6n] */
  double reach;   /* r_c + skin (r_c: the pair's length) */
  double lo[3], cell;
  int dim[3];
  pf_int *start;  /* [nbins + 1] */
  pf_int *item;   /* [start[nbins]] face-set index of each entry, ascending in each bin */
} face_set;

/* The bin range [klo, khi] of face t's grown box along each axis. The bins are those of
 * floor((x - lo) / cell), which rounding keeps monotone in x: an entity y with
 * box - reach <= y <= box + reach has its bin in the range. */
static void face_bins(const face_set *s, pf_int t, int klo[3], int khi[3]) {
  const double *bx = &s->box[6 * t];
  for (int a = 0; a < 3; a++) {
    klo[a] = (int)floor((bx[a] - s->reach - s->lo[a]) / s->cell);
    khi[a] = (int)floor((bx[3 + a] + s->reach - s->lo[a]) / s->cell);
  }
}

/* Count (pass 0) or fill (pass 1) the entries of the face set's bins. */
static pf_int face_bin_entries(face_set *s, int pass) {
  pf_int total = 0;
  for (pf_int t = 0; t < s->n; t++) {
    int klo[3], khi[3];
    face_bins(s, t, klo, khi);
    for (int z = klo[2]; z <= khi[2]; z++)
      for (int y = klo[1]; y <= khi[1]; y++)
        for (int x = klo[0]; x <= khi[0]; x++) {
          const pf_int bin = (z * s->dim[1] + y) * s->dim[0] + x;
          if (pass) s->item[s->start[bin]++] = t;
          else s->start[bin + 1]++;
          total++;
        }
  }
  return total;
}

static int face_set_build(const pf_contact *c, const pf_contact_pair *p, const pf_contact_side *sd, face_set *s) {
  const pf_int *nv = c->node_view[sd->body];
  memset(s, 0, sizeof *s);
  PF_MALLOC(s->face, sd->nface);
  PF_MALLOC(s->box, 6 * sd->nface);
  s->reach = p->length + c->skin;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (pf_int f = 0; f < sd->nface; f++) {
    const pf_int *nd = sd->face[f].node;
    if (nv[nd[0]] < 0 || nv[nd[1]] < 0 || nv[nd[2]] < 0 || nv[nd[3]] < 0) continue;
    double *bx = &s->box[6 * s->n];
    for (int a = 0; a < 3; a++) bx[a] = INFINITY, bx[3 + a] = -INFINITY;
    for (int q = 0; q < 4; q++)
      for (int a = 0; a < 3; a++) {
        double x = c->y[3 * nv[nd[q]] + a];
        bx[a] = fmin(bx[a], x), bx[3 + a] = fmax(bx[3 + a], x);
      }
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], bx[a] - s->reach), hi[a] = fmax(hi[a], bx[3 + a] + s->reach);
    s->face[s->n++] = f;
  }
  if (s->n == 0) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
  /* bins of half the reach plus the face size: a face in at most 4^3 of them; no more bins than
   * 64 a face (scattered faces widen the bins, not the memory) */
  double nb;
  s->cell = 0.5 * (s->reach + sd->size);
  for (;;) {
    nb = 1;
    for (int a = 0; a < 3; a++) nb *= floor((hi[a] - lo[a]) / s->cell) + 1;
    if (nb <= 64.0 * s->n + 64) break;
    s->cell *= 2;
  }
  for (int a = 0; a < 3; a++) s->lo[a] = lo[a], s->dim[a] = (int)floor((hi[a] - lo[a]) / s->cell) + 1;
  const pf_int nbins = (pf_int)nb;
  PF_MALLOC(s->start, nbins + 1);
  const pf_int total = face_bin_entries(s, 0);
  PF_MALLOC(s->item, total);
  for (pf_int b = 0; b < nbins; b++) s->start[b + 1] += s->start[b];
  face_bin_entries(s, 1);
  for (pf_int b = nbins; b > 0; b--) s->start[b] = s->start[b - 1];
  s->start[0] = 0;
  return 0;
}

static void face_set_free(face_set *s) {
  free(s->face), free(s->box), free(s->start), free(s->item);
}

/* Faces of face set s of pair k whose box, grown by r_c + skin, contains owned entity e: those
 * of e's bin that pass the test (face_set). On a pair of two FE bodies a node does not meet the
 * faces it belongs to (the bodies differ). */
static int face_candidates(const pf_contact *c, const face_set *s, pf_int e, int k, cand_list *l) {
  const double reach = s->reach, *y = &c->y[3 * e];
  int kb[3];
  for (int a = 0; a < 3; a++) {
    const double u = floor((y[a] - s->lo[a]) / s->cell);
    if (!(u >= 0 && u < s->dim[a])) return 0; /* outside every grown box */
    kb[a] = (int)u;
  }
  const pf_int bin = (kb[2] * s->dim[1] + kb[1]) * s->dim[0] + kb[0];
  for (pf_int q = s->start[bin]; q < s->start[bin + 1]; q++) {
    pf_int t = s->item[q];
    const double *bx = &s->box[6 * t];
    int in = 1;
    for (int a = 0; a < 3; a++) in &= y[a] >= bx[a] - reach && y[a] <= bx[3 + a] + reach;
    if (in) PF_CALL(cand_push(l, k, s->face[t], s->face[t]));
  }
  return 0;
}

/* The last build's candidates, kept for the pairs not rebuilt: CSR over the owned entities
 * (which a build does not change), and the new view index of each of the last view's ghosts
 * (NULL on one rank: no ghosts), and the
 * global ids of those ghosts. */
typedef struct {
  const int64_t *off;
  const pf_candidate *cand;
  const pf_int *ghost; /* [last nview - nown] new view index, -1: not in the new view */
  const pf_gid *gid;   /* [last nview - nown] the last view's ghosts' global ids */
} kept_list;

/* The partner's global id of candidate x of the last build (a candidate's key gives way to its
 * bond once built): an owned entity keeps its view index from build to build. */
static pf_gid kept_gid(const pf_contact *c, const kept_list *old, const pf_candidate *x) {
  return x->j < c->nown ? c->gid[x->j] : old->gid[x->j - c->nown];
}

/* The first entry of the family row [lo, hi) (sorted by global id) whose neighbour's global id
 * is not below g, by bisection; adds the entries read to *reads. */
static int64_t row_lower_bound(const pf_points *pts, const pf_family *fam, int64_t lo, int64_t hi, pf_gid g,
                               int64_t *reads) {
  while (lo < hi) {
    const int64_t mid = lo + (hi - lo) / 2;
    ++*reads;
    if (pts->gid[fam->neighbor[mid]] < g) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/* The m candidates v of pair k of owned particle e, sorted by partner gid: each short-range
 * candidate of e's own body gets the bond of e's family to it (-1: never bonded); every other
 * candidate gets -1. A partner that was a candidate of the pair at the last build (o, no of
 * them, sorted by gid) takes the bond found then; a new one's is found by bisection of e's
 * family row (sorted by global id, pd/family.c) from the last one found on. Between two builds
 * most partners stay, so a build reads a few family entries a particle, not half its row.
 * Returns the family entries read. */
static int64_t resolve_bonds(const pf_contact *c, const pf_points *pts, pf_int e, int k, pf_candidate *v, int64_t m,
                             const kept_list *old, const pf_candidate *o, int64_t no) {
  const pf_family *fam = c->body[c->vbody[e]].fam;
  const int mine = c->pair[k].method->bonds && fam;
  const int64_t row0 = mine ? fam->offset[c->local[e] - fam->first] : 0;
  const int64_t row1 = mine ? fam->offset[c->local[e] - fam->first + 1] : 0;
  int64_t reads = 0, b = row0, t = 0;
  for (int64_t q = 0; q < m; q++) {
    pf_candidate *cd = &v[q];
    const pf_gid g = cd->key;
    cd->bond = -1;
    if (!mine || c->vbody[cd->j] != c->vbody[e]) continue;
    while (t < no && kept_gid(c, old, &o[t]) < g) t++;
    if (t < no && kept_gid(c, old, &o[t]) == g) {
      cd->bond = o[t].bond;
      continue;
    }
    b = row_lower_bound(pts, fam, b, row1, g, &reads);
    if (b < row1 && (reads++, pts->gid[fam->neighbor[b]] == g)) cd->bond = b;
  }
  return reads;
}

/* Pair k's candidates of owned entity e from the last build (from *q on, the entity's list
 * sorted by pair) into l, their ghost partners renumbered; counts into *missed a partner no
 * longer in the view (none: pair_stale). */
static int kept_candidates(const pf_contact *c, const kept_list *old, pf_int e, int k, int64_t *q, cand_list *l,
                           int64_t *missed) {
  const int64_t q1 = old->off[e + 1];
  const int views = c->pair[k].method->partners == PF_CONTACT_PARTNER_POINTS; /* (else faces) */
  while (*q < q1 && old->cand[*q].pair < k) (*q)++;
  for (; *q < q1 && old->cand[*q].pair == k; (*q)++) {
    pf_candidate x = old->cand[*q];
    if (views && x.j >= c->nown) {
      x.j = old->ghost ? old->ghost[x.j - c->nown] : -1;
      if (x.j < 0) {
        (*missed)++;
        continue;
      }
    }
    PF_CALL(cand_append(l, &x));
  }
  return 0;
}

/* The candidates of owned entity e into l: a PD particle's in every pair of its body, an FE
 * node's in the pairs of two FE bodies (the particle's owner computes each FE <-> PD
 * interaction); a stale pair's searched, sorted by partner (gid or face index) and its bonds
 * resolved, another pair's kept from the last build (old). In pair order: the list is sorted
 * by (pair, partner). Adds the family entries read to *reads. */
static int entity_candidates(const pf_contact *c, const pf_points *pts, const body_bins *bins, const face_set (*fs)[2],
                             const kept_list *old, pf_int e, cand_list *l, int64_t *reads, int64_t *missed) {
  const int b = c->vbody[e], fe = c->body[b].is_fe;
  int64_t q = old ? old->off[e] : 0;
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    if ((p->a != b && p->b != b) || (fe && !p->method->fe_entities)) continue;
    if (!c->stale[k]) {
      PF_CALL(kept_candidates(c, old, e, k, &q, l, missed));
      continue;
    }
    const int64_t s = l->n;
    if (p->method->partners == PF_CONTACT_PARTNER_FACES) {
      const pf_contact_side *sd = pf_contact_facing(p, b);
      PF_CALL(face_candidates(c, &fs[k][sd - p->side], e, k, l));
    } else PF_CALL(point_candidates(c, &bins[p->a == b ? p->b : p->a], e, k, l));
    const int64_t m = l->n - s;
    if (m == 0) continue; /* (none yet: l->v may still be NULL, which qsort must not get) */
    if (m <= 64) cand_sort(&l->v[s], m);
    else qsort(&l->v[s], (size_t)m, sizeof *l->v, cand_cmp);
    int64_t o0 = old ? old->off[e] : 0, o1 = o0; /* the pair's candidates at the last build */
    while (old && o0 < old->off[e + 1] && old->cand[o0].pair < k) o0++;
    for (o1 = o0; old && o1 < old->off[e + 1] && old->cand[o1].pair == k; o1++) continue;
    *reads += resolve_bonds(c, pts, e, k, &l->v[s], m, old, old ? &old->cand[o0] : NULL, o1 - o0);
  }
  return 0;
}

/* The candidates of owned entities [e0, e1) into l; off[e - e0] the start of entity e's. */
static int chunk_candidates(const pf_contact *c, const pf_points *pts, const body_bins *bins, const face_set (*fs)[2],
                            const kept_list *old, pf_int e0, pf_int e1, cand_list *l, int64_t *off, int64_t *reads,
                            int64_t *missed) {
  for (pf_int e = e0; e < e1; e++) {
    off[e - e0] = l->n;
    PF_CALL(entity_candidates(c, pts, bins, fs, old, e, l, reads, missed));
  }
  return 0;
}

/* Every owned entity's candidates into a new CSR (*off_out, *cand_out). OpenMP threads take
 * fixed chunks of entities, each filling its own list, and the lists are joined in chunk order:
 * an entity's candidates depend on it alone, so the lists are the same bits on any number of
 * threads. Adds to *missed the kept partners no longer in the view. */
static int chunked_candidates(pf_contact *c, const pf_points *pts, const body_bins *bins, const face_set (*fs)[2],
                              const kept_list *old, int64_t **off_out, pf_candidate **cand_out, int64_t *cap_out,
                              int64_t *missed) {
  enum { CHUNK = 1024 };
  const int64_t nchunk = (c->nown + CHUNK - 1) / CHUNK;
  int64_t *off;
  PF_MALLOC(off, c->nown + 1);
  cand_list *list = calloc((size_t)nchunk + 1, sizeof *list);
  if (!list) free(off);
  PF_CHECK(list, PF_ERR_MEMORY, "out of memory for the contact candidates of %lld chunks", (long long)nchunk);
  int64_t reads = 0, miss = 0;
  int ierr = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(max : ierr) reduction(+ : reads, miss)
  for (int64_t q = 0; q < nchunk; q++) {
    const pf_int e0 = (pf_int)(q * CHUNK), e1 = (pf_int)(q + 1 < nchunk ? (q + 1) * CHUNK : c->nown);
    const int err = chunk_candidates(c, pts, bins, fs, old, e0, e1, &list[q], &off[e0], &reads, &miss);
    ierr = err > ierr ? err : ierr; /* (the reduction's private copy starts at INT_MIN) */
  }
  int64_t n = 0;
  for (int64_t q = 0; q < nchunk; q++) n += list[q].n;
  pf_candidate *cand = ierr ? NULL : malloc(sizeof *cand * (size_t)(n + 1));
  if (!ierr && !cand)
    ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory for contact candidates");
  n = 0;
  for (int64_t q = 0; q < nchunk && !ierr; q++) {
    const pf_int e0 = (pf_int)(q * CHUNK), e1 = (pf_int)(q + 1 < nchunk ? (q + 1) * CHUNK : c->nown);
    for (pf_int e = e0; e < e1; e++) off[e] += n;
    if (list[q].n) memcpy(&cand[n], list[q].v, sizeof *list[q].v * (size_t)list[q].n);
    n += list[q].n;
  }
  off[c->nown] = n;
  for (int64_t q = 0; q < nchunk; q++) free(list[q].v);
  free(list);
  if (ierr) {
    free(off);
    return ierr;
  }
  c->family_reads += reads;
  *missed += miss;
  *off_out = off, *cand_out = cand, *cap_out = n + 1;
  return 0;
}

static int gid_cmp(const void *a, const void *b) {
  const pf_gid x = *(const pf_gid *)a, y = *(const pf_gid *)b;
  return x < y ? -1 : x > y;
}

/* The new view index of each ghost of the last view (gid[nown + i] of the last view in
 * last_gid[i], n of them): by the gids of the new view's ghosts, sorted. */
static int renumber_ghosts(const pf_contact *c, const pf_gid *last_gid, pf_int n, pf_int **out) {
  const pf_int ng = c->nview - c->nown;
  pf_gid *sorted;
  pf_int *ghost;
  PF_MALLOC(sorted, 2 * (size_t)ng); /* pairs (gid, view index) */
  PF_MALLOC(ghost, n);
  for (pf_int i = 0; i < ng; i++) sorted[2 * i] = c->gid[c->nown + i], sorted[2 * i + 1] = c->nown + i;
  if (ng > 1) qsort(sorted, (size_t)ng, 2 * sizeof *sorted, gid_cmp);
  for (pf_int i = 0; i < n; i++) {
    const pf_gid *hit = ng ? bsearch(&last_gid[i], sorted, (size_t)ng, 2 * sizeof *sorted, gid_cmp) : NULL;
    ghost[i] = hit ? (pf_int)hit[1] : -1;
  }
  free(sorted);
  *out = ghost;
  return 0;
}

/* The bins of every body whose points a stale point pair searches, and the face sets of the
 * stale face pairs, those not made yet. */
static int stale_bins(const pf_contact *c, double cell, body_bins *bins, face_set (*fs)[2]) {
  for (int k = 0; k < c->npairs; k++) {
    const pf_contact_pair *p = &c->pair[k];
    if (!c->stale[k]) continue;
    if (p->method->partners == PF_CONTACT_PARTNER_FACES) {
      for (int s = 0; s < p->nside; s++)
        if (!fs[k][s].face) PF_CALL(face_set_build(c, p, &p->side[s], &fs[k][s]));
      continue;
    }
    for (int side = 0; side < 2; side++) {
      const int b = side ? p->b : p->a;
      if (!bins[b].g.start) PF_CALL(body_bins_build(c, b, cell, &bins[b]));
    }
  }
  return 0;
}

/* The candidates of the stale pairs searched anew, the others' kept (last_gid: the last view's
 * ghosts, nlast of them). A kept partner missing from the new view (which pair_stale's rule
 * excludes) makes every pair stale and the whole list is built again, on every rank. */
static int build_candidates(pf_contact *c, const pf_points *pts, const pf_gid *last_gid, pf_int nlast) {
  double cell = 0;
  for (int k = 0; k < c->npairs; k++) cell = fmax(cell, c->pair[k].length + c->skin);
  int all = 1;
  for (int k = 0; k < c->npairs; k++) all &= c->stale[k];
  body_bins *bins = calloc((size_t)c->nbodies + 1, sizeof *bins);
  face_set(*fs)[2] = calloc((size_t)c->npairs + 1, sizeof *fs);
  if (!bins || !fs) free(bins), free(fs);
  PF_CHECK(bins && fs, PF_ERR_MEMORY, "out of memory for the contact search");
  int ierr = stale_bins(c, cell, bins, fs);
  pf_int *ghost = NULL;
  if (!ierr && !all && nlast > 0) ierr = renumber_ghosts(c, last_gid, nlast, &ghost);
  const kept_list old = {c->cand_off, c->cand, ghost, last_gid};
  const kept_list *prev = c->built ? &old : NULL; /* (kept for the pairs not stale; bonds of the others) */
  int64_t *off = NULL, cap = 0, missed = 0;
  pf_candidate *cand = NULL;
  if (!ierr) ierr = chunked_candidates(c, pts, bins, (const face_set(*)[2])fs, prev, &off, &cand, &cap, &missed);
  if (!ierr && !all && pf_max_all((double)missed) > 0) { /* (collective: every rank takes the same way) */
    free(off), free(cand);
    for (int k = 0; k < c->npairs; k++) c->stale[k] = 1;
    ierr = stale_bins(c, cell, bins, fs);
    if (!ierr) ierr = chunked_candidates(c, pts, bins, (const face_set(*)[2])fs, prev, &off, &cand, &cap, &missed);
  }
  if (!ierr) {
    free(c->cand_off), free(c->cand);
    c->cand_off = off, c->cand = cand, c->cand_cap = cap;
  }
  free(ghost);
  for (int k = 0; k < c->npairs; k++) face_set_free(&fs[k][0]), face_set_free(&fs[k][1]);
  for (int b = 0; b < c->nbodies; b++) body_bins_free(&bins[b]);
  free(fs), free(bins);
  return ierr;
}

/* Per body of one build's positions: the largest squared move, and the box of the moves
 * (-lo, hi per component, so that one MPI_MAX reduces all). */
enum { MOVE_M2, MOVE_NLO, MOVE_HI = MOVE_NLO + 3, MOVE_N = MOVE_HI + 3 };

static void body_moves(const pf_contact *c, const double *yb, double *mb) {
  const int nb = c->nbodies;
  for (int b = 0; b < nb * MOVE_N; b++) mb[b] = -INFINITY;
#pragma omp parallel for schedule(static) reduction(max : mb[:nb * MOVE_N])
  for (pf_int e = 0; e < c->nown; e++) {
    double *m = &mb[MOVE_N * c->vbody[e]], d[3], d2 = 0;
    for (int a = 0; a < 3; a++) d[a] = c->y[3 * e + a] - yb[3 * e + a], d2 += d[a] * d[a];
    m[MOVE_M2] = d2 > m[MOVE_M2] ? d2 : m[MOVE_M2]; /* (NaN positions are the guard's to report) */
    for (int a = 0; a < 3; a++) {
      m[MOVE_NLO + a] = -d[a] > m[MOVE_NLO + a] ? -d[a] : m[MOVE_NLO + a];
      m[MOVE_HI + a] = d[a] > m[MOVE_HI + a] ? d[a] : m[MOVE_HI + a];
    }
  }
}

/* 1 when the pair of bodies of reduced moves ma, mb (body_moves) keeps its candidates: every two
 * of its entities moved relative to each other by at most the skin s. Either bound suffices:
 * each moved at most s/2 (Verlet 1967); or, with the centres c and half-diagonals h of the
 * bodies' boxes of moves, |d_i - d_j| <= h_a + h_b + |c_a - c_b| <= s (2 h_a <= s within one
 * body), which holds however far the bodies moved as a whole: two clusters in flight. */
static int pair_keeps(const double *ma, const double *mb, int self, double s) {
  if (sqrt(fmax(ma[MOVE_M2], mb[MOVE_M2])) <= 0.5 * s) return 1;
  double ha = 0, hb = 0, dc = 0;
  for (int a = 0; a < 3; a++) {
    const double wa = 0.5 * (ma[MOVE_HI + a] + ma[MOVE_NLO + a]), wb = 0.5 * (mb[MOVE_HI + a] + mb[MOVE_NLO + a]);
    const double ca = 0.5 * (ma[MOVE_HI + a] - ma[MOVE_NLO + a]), cb = 0.5 * (mb[MOVE_HI + a] - mb[MOVE_NLO + a]);
    ha += wa * wa, hb += wb * wb, dc += (ca - cb) * (ca - cb);
  }
  const double bound = self ? 2 * sqrt(ha) : sqrt(ha) + sqrt(hb) + sqrt(dc);
  return bound <= s * (1 - 1e-12); /* (a margin for the rounding of the bound; NaN: rebuilt) */
}

/* The affine bound, for a pair that neither bound of pair_keeps keeps: with any a and B, each
 * entity's move d_i = a + B y_i + r_i (y_i its position at the build, r_i the rest), so two
 * entities y_b apart at the build are now at least |y_b| (1 - |B|) - 2 max |r| apart. A pair
 * farther than r_c + s then does not come within r_c while 2 max |r| + |B| (r_c + s) <= s and
 * |B| < 1; a kept partner is still within (r_c + s)(1 + |B|) + 2 max |r| <= r_c + 2 s of its
 * entity, inside the ghost margin, as with the other bounds. a and B are the least-squares fit
 * of the moves of the pair's bodies (the Frobenius norm bounds |B|); any fit gives a valid bound
 * (the 1e-12 of the skin covers a fit rounded otherwise on another rank), a good one a tight
 * one: a body that expands, stretches or turns as a whole keeps its lists while its parts move
 * little relative to that motion. Three passes over the entities, each reduced over the ranks.
 * Collective. */
enum { FIT_N, FIT_Y, FIT_D = FIT_Y + 3, FIT_SUMS = FIT_D + 3 };
enum { MOM_C, MOM_D = MOM_C + 9, MOM_N = MOM_D + 9 };

static int in_pair(const pf_contact *c, const pf_contact_pair *p, pf_int e) {
  return c->vbody[e] == p->a || c->vbody[e] == p->b;
}

/* The count and the sums of the positions at the build and of the moves, of pair k's entities. */
static void fit_sums(const pf_contact *c, int k, double *sum) {
  const pf_contact_pair *p = &c->pair[k];
  const double *yb = &c->y_build[3 * (size_t)c->nown * (size_t)k];
  for (int q = 0; q < FIT_SUMS; q++) sum[q] = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum[:FIT_SUMS])
  for (pf_int e = 0; e < c->nown; e++)
    if (in_pair(c, p, e)) {
      sum[FIT_N] += 1;
      for (int a = 0; a < 3; a++) sum[FIT_Y + a] += yb[3 * e + a], sum[FIT_D + a] += c->y[3 * e + a] - yb[3 * e + a];
    }
}

/* The second moments about the means (m: FIT_Y, FIT_D of the reduced sums over their count):
 * C = sum (y - ym)(y - ym)^T and D = sum (d - dm)(y - ym)^T. */
static void fit_moments(const pf_contact *c, int k, const double *m, double *mom) {
  const pf_contact_pair *p = &c->pair[k];
  const double *yb = &c->y_build[3 * (size_t)c->nown * (size_t)k];
  for (int q = 0; q < MOM_N; q++) mom[q] = 0;
#pragma omp parallel for schedule(static) reduction(+ : mom[:MOM_N])
  for (pf_int e = 0; e < c->nown; e++)
    if (in_pair(c, p, e)) {
      double y[3], d[3];
      for (int a = 0; a < 3; a++)
        y[a] = yb[3 * e + a] - m[FIT_Y + a], d[a] = c->y[3 * e + a] - yb[3 * e + a] - m[FIT_D + a];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) mom[MOM_C + 3 * a + b] += y[a] * y[b], mom[MOM_D + 3 * a + b] += d[a] * y[b];
    }
}

/* B = D C^-1, C regularised by 1e-9 of its trace (a flat or thin body: C is near singular); 0
 * when C is not positive definite. */
static void fit_gradient(const double *mom, double B[9]) {
  double C[3][3], inv[3][3];
  const double *D = &mom[MOM_D], tr = mom[MOM_C] + mom[MOM_C + 4] + mom[MOM_C + 8];
  memset(B, 0, 9 * sizeof *B);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) C[a][b] = mom[MOM_C + 3 * a + b] + (a == b ? 1e-9 * tr : 0);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      const int a1 = (b + 1) % 3, a2 = (b + 2) % 3, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      inv[a][b] = C[a1][b1] * C[a2][b2] - C[a1][b2] * C[a2][b1]; /* the cofactor of C[b][a] */
    }
  const double det = C[0][0] * inv[0][0] + C[0][1] * inv[1][0] + C[0][2] * inv[2][0];
  if (!(tr > 0 && det > 0 && isfinite(det))) return;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int q = 0; q < 3; q++) B[3 * a + b] += D[3 * a + q] * inv[q][b] / det;
}

/* The largest |r| of pair k's entities: r = d - dm - B (y - ym). */
static double fit_rest(const pf_contact *c, int k, const double *m, const double B[9]) {
  const pf_contact_pair *p = &c->pair[k];
  const double *yb = &c->y_build[3 * (size_t)c->nown * (size_t)k];
  double r2 = 0;
#pragma omp parallel for schedule(static) reduction(max : r2)
  for (pf_int e = 0; e < c->nown; e++)
    if (in_pair(c, p, e)) {
      double y[3], q = 0;
      for (int a = 0; a < 3; a++) y[a] = yb[3 * e + a] - m[FIT_Y + a];
      for (int a = 0; a < 3; a++) {
        const double fit = m[FIT_D + a] + B[3 * a] * y[0] + B[3 * a + 1] * y[1] + B[3 * a + 2] * y[2];
        const double r = c->y[3 * e + a] - yb[3 * e + a] - fit;
        q += r * r;
      }
      r2 = q > r2 ? q : r2; /* (NaN positions are the guard's to report) */
    }
  return sqrt(r2);
}

/* Pair k's affine bound (above) over all ranks: 1 when it keeps its lists. Collective. */
static int affine_keeps(const pf_contact *c, int k, int *ok) {
  double sum[FIT_SUMS], mom[MOM_N], B[9];
  fit_sums(c, k, sum);
  *ok &= MPI_Allreduce(MPI_IN_PLACE, sum, FIT_SUMS, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS;
  if (!(sum[FIT_N] > 0)) return 1; /* (no entity: nothing moved) */
  for (int q = 1; q < FIT_SUMS; q++) sum[q] /= sum[FIT_N];
  fit_moments(c, k, sum, mom);
  *ok &= MPI_Allreduce(MPI_IN_PLACE, mom, MOM_N, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS;
  fit_gradient(mom, B);
  double v[2] = {fit_rest(c, k, sum, B), 0}; /* the largest rest, |B| */
  for (int q = 0; q < 9; q++) v[1] += B[q] * B[q];
  v[1] = sqrt(v[1]);
  /* (both taken as their largest over the ranks, which every rank then has bit for bit: the
   * same decision everywhere, whatever rounding the sums took on the way) */
  *ok &= MPI_Allreduce(MPI_IN_PLACE, v, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS;
  const double s = c->skin;
  return v[1] < 1 && 2 * v[0] + v[1] * (c->pair[k].length + s) <= s * (1 - 1e-12); /* (NaN: rebuilt) */
}

/* Marks the pairs whose candidates must be rebuilt: two entities of the pair's bodies moved
 * relative to each other by more than the skin since the pair's last build (pair_keeps, then
 * affine_keeps). Two
 * entities that come within r_c of each other were then within r_c + skin at that build,
 * whatever their speed (Verlet 1967), and each pair's rule reads only the motion of its own
 * bodies, whose entities are all its candidates can be (the faces' nodes included: a point of a
 * face moves no more than its nodes). A pair not rebuilt keeps a list that holds every
 * interaction within r_c, like a rebuilt one, and a pair's forces depend only on those (a list
 * sorted by partner, the rest passed over), so the forces are the same bits as with a rebuild of
 * every pair. The ghosts sent at the last build stay enough: one left out was farther than
 * r_c + 2 skin from every owned entity. Returns how many are stale. Collective. */
static int pair_stale(pf_contact *c, int *nstale) {
  const int np = c->npairs, nb = c->nbodies;
  double *mv, *mb; /* [np][2][MOVE_N] each pair's two bodies' moves; [nb][MOVE_N] one build's */
  PF_MALLOC(mv, (size_t)np * 2 * MOVE_N + (size_t)nb * MOVE_N);
  mb = mv + (size_t)np * 2 * MOVE_N;
  /* one pass for each set of pairs built at the same build (the same positions at the build) */
  for (int k = 0; k < np; k++) {
    int first = 1;
    for (int q = 0; q < k; q++) first &= c->built_at[q] != c->built_at[k];
    if (!first) continue;
    body_moves(c, &c->y_build[3 * (size_t)c->nown * (size_t)k], mb);
    for (int q = k; q < np; q++)
      if (c->built_at[q] == c->built_at[k]) {
        memcpy(&mv[(size_t)q * 2 * MOVE_N], &mb[MOVE_N * c->pair[q].a], sizeof(double) * MOVE_N);
        memcpy(&mv[(size_t)q * 2 * MOVE_N + MOVE_N], &mb[MOVE_N * c->pair[q].b], sizeof(double) * MOVE_N);
      }
  }
  int ok = MPI_Allreduce(MPI_IN_PLACE, mv, np * 2 * MOVE_N, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS;
  *nstale = 0;
  for (int k = 0; k < np && ok; k++) { /* (the same decisions on every rank: they read reduced moves) */
    const double *m = &mv[(size_t)k * 2 * MOVE_N];
    const int self = c->pair[k].a == c->pair[k].b;
    *nstale += c->stale[k] = !pair_keeps(m, m + MOVE_N, self, c->skin) && !affine_keeps(c, k, &ok);
  }
  free(mv);
  PF_CHECK(ok, PF_ERR_LIB, "MPI_Allreduce failed on the contact's displacements");
  return 0;
}

int pf_contact_search(pf_contact *c, const pf_points *pts) {
  if (c->built) {
    int n = 0;
    PF_CALL(pair_stale(c, &n));
    if (n == 0) return 0;
  } else
    for (int k = 0; k < c->npairs; k++) c->stale[k] = 1;
  PF_CALL(face_sizes(c, pts));
  /* the last view's ghosts, to renumber the kept candidates' partners */
  const pf_int nlast = c->built ? c->nview - c->nown : 0;
  pf_gid *last_gid = NULL;
  if (nlast > 0) {
    PF_MALLOC(last_gid, nlast);
    memcpy(last_gid, &c->gid[c->nown], sizeof *last_gid * (size_t)nlast);
  }
  c->nview = c->nown;
  int ierr = send_lists(c);
  if (!ierr) ierr = send_ghosts(c);
  if (!ierr) map_nodes(c);
  if (!ierr) ierr = build_candidates(c, pts, last_gid, nlast);
  free(last_gid);
  if (ierr) return ierr;
  c->rebuilds++;
  for (int k = 0; k < c->npairs; k++)
    if (c->stale[k]) {
      memcpy(&c->y_build[3 * (size_t)c->nown * (size_t)k], c->y, sizeof(double) * 3 * (size_t)c->nown);
      c->built_at[k] = c->rebuilds;
    }
  c->built = 1;
  return 0;
}
