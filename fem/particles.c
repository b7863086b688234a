/* Element-to-particle conversion (`erosion: {..., convert_to_particles: true}` of an FE body and a
 * `type: particles` body that names it; docs/theory/fem.md sec. 9b). An element the erosion limits
 * delete becomes, at the end of the step it was deleted in, one particle at its centre of mass:
 *   mass      M = sum_I w_I                (w_I its lumped-mass shares, taken off its nodes),
 *   momentum  M v_p = sum_I w_I v_I        (the shares' momenta, taken off with them),
 *   position  y_p = sum_I w_I y_I / M      (the centre of mass of the shares),
 * so that mass, momentum and the centre of mass are unchanged (to round-off). The kinetic energy
 * the averaging of the velocities removes, sum_I w_I |v_I|^2 / 2 - M |v_p|^2 / 2 >= 0 (in the
 * integrator's centred form), is booked on the particle as `conversion_loss`; the element's
 * stress work stays in the FE internal energy (the element keeps it, as an eroded one does). The
 * particle carries the element's mean stress and material state as output fields. Particles
 * have no bonds: they meet each other, FE surfaces and PD bodies by the contact pairs the deck
 * names (short-range forces, node-to-particle penalty), the way LS-DYNA's adaptive solid-to-SPH
 * particles do without SPH interaction. A particle point exists from the set-up on (one per mesh
 * element, global id gid0 + element index, at the element's reference centroid) with mass 0
 * (dormant: no force, no contact) until its element converts.
 * MPI: every rank holds the mesh-wide deleted flags; the owners of each converted element's nodes
 * contribute their shares (mass, velocity, position, the change of their centred kinetic energy)
 * and the element's owner its state; one gather gives every rank all of them, sorted by
 * (element, corner); the rank owning the particle sums them in that order. */
#include "fem/fem_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const pf_key pf_fem_particles_keys[] = {
    {"name", PF_KEY_STRING, 1, NULL, "", "body name (the Exodus block name)", NULL},
    {"type", PF_KEY_STRING, 1, NULL, "", "particles", NULL},
    {"from", PF_KEY_STRING, 1, NULL, "",
     "the finite_element body whose deleted elements become these particles (its erosion has convert_to_particles: true)",
     NULL},
    PF_KEY_END};

struct pf_fem_particles {
  char name[64], from[64];
  const pf_deck *deck;
  const pf_node *node;
  pf_fem_body *fe;     /* the source body (pf_fem_particles_link) */
  pf_gid gid0;         /* global id of element 0's particle */
  pf_int first, n;     /* owned particles of the store */
  pf_int last_first;   /* the element of the first particle made at the last conversion (-1: none) */
  pf_int *local;       /* [nelem] store index of element e's particle when owned here, else -1 */
  double cell_max;     /* the largest cube-root element volume, m */
  int ncomp;           /* 6 stress + the material's state */
};

enum { R_ELEM, R_CORNER, R_W, R_V, R_Y = R_V + 3, R_DKC = R_Y + 3, R_CORNER_WIDTH }; /* a share record */
enum { R_STATE = 2 }; /* a state record (corner 8): stress, state, then the contact radius */

int pf_fem_particles_create(const pf_deck *d, const pf_node *body, pf_fem_particles **out) {
  pf_fem_particles *p;
  PF_MALLOC(p, 1);
  const char *name = "", *from = "";
  int ierr = pf_deck_string(d, body, "name", &name);
  if (!ierr) ierr = pf_deck_string(d, body, "from", &from);
  snprintf(p->name, sizeof p->name, "%s", name);
  snprintf(p->from, sizeof p->from, "%s", from);
  p->deck = d, p->node = body;
  if (ierr) free(p), p = NULL;
  *out = p;
  return ierr;
}

int pf_fem_particles_destroy(pf_fem_particles **pp) {
  if (!*pp) return 0;
  free((*pp)->local);
  PF_FREE(*pp);
  return 0;
}

const char *pf_fem_particles_source(const pf_fem_particles *p) { return p->from; }

int pf_fem_particles_link(pf_fem_particles *p, pf_fem_body *fe) {
  if (!fe)
    return pf_deck_error(p->deck, pf_node_get(p->node, "from"), "from",
                         "body '%s': '%s' is not a finite_element body of the deck", p->name, p->from);
  if (!fe->convert)
    return pf_deck_error(p->deck, pf_node_get(p->node, "from"), "from",
                         "body '%s': the erosion of body '%s' does not convert its elements (give it erosion: "
                         "{..., convert_to_particles: true})",
                         p->name, p->from);
  if (fe->beta_fn)
    return pf_deck_error(p->deck, pf_node_get(p->node, "from"), "from",
                         "body '%s': body '%s' is blended with a peridynamic operator (not supported)", p->name, p->from);
  p->fe = fe;
  p->ncomp = 6 + fe->nstate;
  return 0;
}

/* One point per mesh element at its reference centroid, with the element's volume. */
int pf_fem_particles_cloud(pf_fem_particles *p, pf_point_cloud *pc) {
  const pf_mesh *m = &p->fe->mesh;
  memset(pc, 0, sizeof *pc);
  pc->n = m->nelem;
  PF_MALLOC(pc->X, 3 * (size_t)m->nelem);
  PF_MALLOC(pc->vol, m->nelem);
  PF_MALLOC(pc->cell, m->nelem);
  PF_MALLOC(pc->block, m->nelem);
  p->cell_max = 0;
  for (pf_int e = 0; e < m->nelem; e++) {
    double x[8][3], B[8][3];
    for (int I = 0; I < 8; I++)
      for (int a = 0; a < 3; a++) x[I][a] = m->X[3 * (size_t)m->conn[8 * (size_t)e + I] + a];
    for (int a = 0; a < 3; a++) {
      double c = 0;
      for (int I = 0; I < 8; I++) c += x[I][a];
      pc->X[3 * (size_t)e + a] = c / 8;
    }
    pc->vol[e] = pf_hex8_mean_gradient(x, B);
    pc->cell[e] = cbrt(pc->vol[e]);
    p->cell_max = fmax(p->cell_max, pc->cell[e]);
  }
  return 0;
}

static int register_fields(const pf_fem_particles *p, pf_points *pts) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "particle_mass", 1, PF_FIELD_RESTART, &idx));
  PF_CALL(pf_points_field_register(pts, "conversion_loss", 1, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &idx));
  PF_CALL(pf_points_field_register(pts, "conversion_time", 1, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &idx));
  PF_CALL(pf_points_field_register(pts, "particle_state", p->ncomp, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &idx));
  PF_CALL(pf_points_field_register(pts, "contact_radius", 1, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &idx));
  return 0;
}

/* Owned particles [first, first + n): a dormant one has mass 0; a converted one its mass
 * (carried in "particle_mass" through re-partitions and checkpoints). */
int pf_fem_particles_attach(pf_fem_particles *p, pf_points *pts, pf_int first, pf_int n, pf_gid gid0) {
  p->first = first, p->n = n, p->gid0 = gid0;
  PF_CALL(register_fields(p, pts));
  const double *mass = pf_points_field_get(pts, "particle_mass");
  free(p->local);
  PF_MALLOC(p->local, p->fe->mesh.nelem);
  for (pf_int e = 0; e < p->fe->mesh.nelem; e++) p->local[e] = -1;
  for (pf_int i = first; i < first + n; i++) {
    p->local[pts->gid[i] - gid0] = i;
    pts->m[i] = mass[i];
  }
  return 0;
}

void pf_fem_particles_material(const pf_fem_particles *p, double *density, double *bulk_modulus) {
  const pf_fem_material *fm = &p->fe->mats[0]; /* (a converting body has one material: fem/erosion.c) */
  *density = fm->rho, *bulk_modulus = fm->K;
}

double pf_fem_particles_horizon(const pf_fem_particles *p) { return 3 * p->cell_max; }

double pf_fem_particles_loss(const pf_fem_particles *p, const pf_points *pts) {
  const double *loss = pf_points_field_get(pts, "conversion_loss");
  double s = 0;
  for (pf_int i = p->first; i < p->first + p->n && loss; i++) s += loss[i];
  return s;
}

void pf_fem_particles_book(pf_fem_particles *p, pf_points *pts, double energy) {
  if (p->last_first < 0 || p->local[p->last_first] < 0) return;
  pf_points_field_get(pts, "conversion_loss")[p->local[p->last_first]] += energy;
}

long pf_fem_particles_count(const pf_fem_particles *p) { return p->fe->n_eroded; }

/* The centred kinetic energy of point i, m (|v|^2 - h^2 |f / m|^2) / 2 (sim/step.c). */
static double centred_ke(const pf_points *pts, pf_int i, double h) {
  const double m = pts->m[i];
  if (!(m > 0)) return 0;
  double s = 0;
  for (int a = 0; a < 3; a++) {
    const double v = pts->v[3 * (size_t)i + a], acc = pts->f[3 * (size_t)i + a] / m;
    s += v * v - h * h * acc * acc;
  }
  return 0.5 * m * s;
}

/* The distance from local element k's centre of mass (its nodes' current positions weighted by
 * their shares) to the nearest of its six face planes (through each face's centre), at least
 * 1e-6 of its reference edge: the radius of its particle in contact, so that a particle made
 * next to live elements, the other particles of the same step or a surface pressing on the
 * element starts without a contact force (contact/pairs.c). */
static double face_distance(const pf_fem_body *b, const pf_points *pts, pf_int k) {
  double x[8][3], c[3] = {0, 0, 0}, W = 0, d = INFINITY;
  for (int I = 0; I < 8; I++) {
    const double w = b->wmass[8 * (size_t)k + I];
    W += w;
    for (int a = 0; a < 3; a++) x[I][a] = pts->y[3 * (size_t)b->conn[8 * (size_t)k + I] + a], c[a] += w * x[I][a];
  }
  for (int a = 0; a < 3; a++) c[a] /= W;
  for (int f = 0; f < 6; f++) {
    double fc[3] = {0, 0, 0}, u[3], v[3], n[3];
    const int *q = pf_hex8_face[f];
    for (int j = 0; j < 4; j++)
      for (int a = 0; a < 3; a++) fc[a] += 0.25 * x[q[j]][a];
    for (int a = 0; a < 3; a++) u[a] = x[q[2]][a] - x[q[0]][a], v[a] = x[q[3]][a] - x[q[1]][a];
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0) d = fmin(d, fabs((c[0] - fc[0]) * n[0] + (c[1] - fc[1]) * n[1] + (c[2] - fc[2]) * n[2]) / len);
  }
  return fmax(d, 1e-6 * cbrt(b->ref[25 * (size_t)k + 24]));
}

/* This rank's records of the elements deleted and not yet converted (flag `fresh`): a share
 * record per corner whose node it owns, a state record per element it owns. The masses of its
 * owned nodes are recomputed without them; each node's change of centred kinetic energy goes
 * into its first share record. */
static int local_records(pf_fem_particles *p, pf_points *pts, const uint8_t *fresh, double h, int W, double **rec,
                         int *nrec) {
  pf_fem_body *b = p->fe;
  int n = 0;
  for (pf_int k = 0; k < b->nel; k++)
    if (fresh[b->eid[k]]) {
      for (int I = 0; I < 8; I++) {
        const pf_int i = b->conn[8 * (size_t)k + I];
        n += i >= b->first && i < b->first + b->n;
      }
      n += b->own[k];
    }
  double *r;
  int64_t *first_rec;
  PF_MALLOC(r, (size_t)W * n);
  PF_MALLOC(first_rec, b->n);
  for (pf_int i = 0; i < b->n; i++) first_rec[i] = -1;
  int q = 0;
  for (pf_int k = 0; k < b->nel; k++) {
    const pf_int e = b->eid[k];
    if (!fresh[e]) continue;
    for (int I = 0; I < 8; I++) {
      const pf_int i = b->conn[8 * (size_t)k + I];
      if (i < b->first || i >= b->first + b->n) continue;
      double *x = &r[(size_t)W * q];
      x[R_ELEM] = e, x[R_CORNER] = I, x[R_W] = b->wmass[8 * (size_t)k + I];
      for (int a = 0; a < 3; a++) x[R_V + a] = pts->v[3 * (size_t)i + a], x[R_Y + a] = pts->y[3 * (size_t)i + a];
      if (first_rec[i - b->first] < 0) first_rec[i - b->first] = q, x[R_DKC] = centred_ke(pts, i, h);
      q++;
    }
    if (b->own[k]) { /* the element's mean stress and state over its quadrature points */
      double *x = &r[(size_t)W * q++];
      x[R_ELEM] = e, x[R_CORNER] = 8;
      x[R_STATE + p->ncomp] = face_distance(b, pts, k);
      for (int g = 0; g < b->nqp; g++) {
        for (int c = 0; c < 6; c++) x[R_STATE + c] += b->sigma[6 * ((size_t)b->nqp * k + g) + c] / b->nqp;
        for (int c = 0; c < b->nstate; c++)
          x[R_STATE + 6 + c] += b->state[(size_t)b->nstate * ((size_t)b->nqp * k + g) + c] / b->nqp;
      }
    }
  }
  for (pf_int e = 0; e < b->mesh.nelem; e++) b->mesh_converted[e] |= fresh[e];
  pf_fem_lumped_masses(b, pts);
  for (pf_int k = 0; k < b->nel; k++) /* the converted elements' nodal forces leave with them (they sum to 0) */
    for (int I = 0; I < 8 && fresh[b->eid[k]]; I++) {
      const pf_int i = b->conn[8 * (size_t)k + I];
      if (i >= b->first && i < b->first + b->n)
        for (int a = 0; a < 3; a++) pts->f[3 * (size_t)i + a] -= b->fe[24 * (size_t)k + 3 * I + a];
    }
  for (pf_int i = 0; i < b->n; i++)
    if (first_rec[i] >= 0) r[(size_t)W * first_rec[i] + R_DKC] -= centred_ke(pts, b->first + i, h);
  free(first_rec);
  *rec = r, *nrec = n;
  return 0;
}

static int gather_records(const double *mine, int n, int W, double **all, int *total) {
  int R = pf_comm_size(), *cnt, *dis, ierr;
  PF_MALLOC(cnt, 2 * R);
  dis = cnt + R;
  int nd = n * W;
  ierr = MPI_Allgather(&nd, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  int t = 0;
  for (int r = 0; r < R; r++) dis[r] = t, t += cnt[r];
  *all = malloc(sizeof(double) * ((size_t)t + 1));
  if (!*all) ierr = PF_ERR_MEMORY;
  if (!ierr) ierr = MPI_Allgatherv(mine, nd, MPI_DOUBLE, *all, cnt, dis, MPI_DOUBLE, MPI_COMM_WORLD);
  free(cnt);
  *total = t / W;
  PF_CHECK(!ierr, PF_ERR_LIB, "gathering the converted elements' records failed");
  return 0;
}

static int by_element_corner(const void *a, const void *b) {
  const double *x = a, *y = b;
  if (x[R_ELEM] != y[R_ELEM]) return x[R_ELEM] < y[R_ELEM] ? -1 : 1;
  return (x[R_CORNER] > y[R_CORNER]) - (x[R_CORNER] < y[R_CORNER]);
}

/* Element e's particle from its records rec[0 .. n) (sorted by corner, the state record last). */
static void make_particle(pf_fem_particles *p, pf_points *pts, pf_int i, const double *rec, int n, int W, double t) {
  double M = 0, P[3] = {0, 0, 0}, Y[3] = {0, 0, 0}, dkc = 0;
  for (int k = 0; k < n; k++) {
    const double *x = &rec[(size_t)W * k];
    if (x[R_CORNER] > 7) continue;
    M += x[R_W], dkc += x[R_DKC];
    for (int a = 0; a < 3; a++) P[a] += x[R_W] * x[R_V + a], Y[a] += x[R_W] * x[R_Y + a];
  }
  pts->m[i] = M;
  double ke = 0;
  for (int a = 0; a < 3; a++) {
    const double v = P[a] / M, y = Y[a] / M;
    pts->v[3 * (size_t)i + a] = v, pts->y[3 * (size_t)i + a] = y;
    pts->u[3 * (size_t)i + a] = y - pts->X[3 * (size_t)i + a];
    pts->f[3 * (size_t)i + a] = 0;
    ke += 0.5 * M * v * v;
  }
  pf_points_field_get(pts, "particle_mass")[i] = M;
  pf_points_field_get(pts, "conversion_loss")[i] = dkc - ke;
  pf_points_field_get(pts, "conversion_time")[i] = t;
  double *offset = pf_points_field_get(pts, "contact_offset"); /* new: its overlap with a surface is held (contact/pairs.c) */
  if (offset) offset[i] = -1;
  const double *last = &rec[(size_t)W * (n - 1)];
  if (last[R_CORNER] == 8) {
    memcpy(&pf_points_field_get(pts, "particle_state")[(size_t)p->ncomp * i], &last[R_STATE], sizeof(double) * p->ncomp);
    pf_points_field_get(pts, "contact_radius")[i] = last[R_STATE + p->ncomp];
  }
}

int pf_fem_particles_convert(pf_fem_particles *p, pf_points *pts, double dt, double t, long *converted) {
  pf_fem_body *b = p->fe;
  *converted = 0;
  long done = 0;
  for (pf_int e = 0; e < b->mesh.nelem; e++) done += b->mesh_converted[e];
  if (done == b->n_eroded) return 0; /* (the same on every rank: no collective call) */
  uint8_t *fresh;
  PF_MALLOC(fresh, b->mesh.nelem);
  for (pf_int e = 0; e < b->mesh.nelem; e++) fresh[e] = b->mesh_eroded[e] && !b->mesh_converted[e];
  const int W = R_STATE + p->ncomp + 1 > R_CORNER_WIDTH ? R_STATE + p->ncomp + 1 : R_CORNER_WIDTH;
  double *mine = NULL, *all = NULL;
  int n = 0, total = 0;
  int ierr = local_records(p, pts, fresh, 0.5 * dt, W, &mine, &n);
  free(fresh);
  if (!ierr) ierr = gather_records(mine, n, W, &all, &total);
  free(mine);
  if (ierr) return ierr;
  qsort(all, (size_t)total, sizeof(double) * W, by_element_corner);
  p->last_first = total > 0 ? (pf_int)all[R_ELEM] : -1;
  for (int k = 0, e; k < total; k = e) {
    for (e = k + 1; e < total && all[(size_t)W * e + R_ELEM] == all[(size_t)W * k + R_ELEM]; e++) {}
    const pf_int i = p->local[(pf_int)all[(size_t)W * k + R_ELEM]];
    if (i >= 0) make_particle(p, pts, i, &all[(size_t)W * k], e - k, W, t);
    (*converted)++;
  }
  free(all);
  return 0;
}
