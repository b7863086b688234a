/* perifem contact (docs/architecture.md §3): rigid analytic surfaces (sphere, plane, cylinder)
 * pushing on points, rigid planar walls, and the contact of bodies with each other:
 * node-to-particle penalty with a particle-to-face check between FE and PD bodies, short-range
 * forces between PD particles (other bodies, or fragments of one body), over a binned search with a
 * skin that works across MPI ranks. */
#ifndef PF_CONTACT_H
#define PF_CONTACT_H

#include "core/core.h"
#include "mesh/mesh.h"
#include "pd/pd.h"

#ifndef PF_USES_CONTACT
#error "contact/contact.h is included by a module below contact/ (docs/architecture.md: the module layers)"
#endif

/* ---- rigid analytic surfaces (contact/rigid.c) ---------------------------------------------
 * A sphere, a plane or a cylinder with a prescribed velocity v(t), acting on the points of the
 * bodies it names (all bodies when it names none). The force on a point of depth d (how far it
 * is inside the surface) is along the surface's outward normal:
 *   law quadratic (default; the foundation's indenter, LAMMPS fix indent with PERI):
 *     F = k d^2 V_i, k in N/m^5, energy k d^3 V_i / 3;
 *   law linear: F = k d, k in N/m, energy k d^2 / 2;
 * plus regularized Coulomb friction opposing the tangential velocity of the point relative to
 * the surface: F_t = min(mu |F|, m_i |v_t| / dt) (never more than stops the sliding in one
 * step). Written under `contact: rigid_surfaces:` or (the foundation's syntax) `indenters:`. */
typedef struct pf_rigid pf_rigid;
extern const pf_key pf_rigid_keys[];
int pf_rigid_create(const pf_deck *d, const pf_node *map, int nbodies,
                    const char *const *body_names, pf_rigid **r);
int pf_rigid_destroy(pf_rigid **r);
const char *pf_rigid_name(const pf_rigid *r);
/* 1 when a and b are one surface given twice: the same shape at the same place (centre or point,
 * radius, normal or axis, length) with the same motion (the deck's velocity, as written), pushing
 * at least one body in common; they would push it twice as hard. */
int pf_rigid_same_surface(const pf_rigid *a, const pf_rigid *b);
/* Add the surface's forces to the owned points it penetrates (pts->f), with friction from the
 * mid-step velocities pts->v over the step dt (dt 0: no friction). reaction[3] gets the total
 * force of the points on the surface (N) and *energy the penalty energy (J), both summed over
 * the ranks; the friction work of this rank's points over dt is added to *dissipation (J, >= 0).
 * Collective. */
/* The same without the sums over the ranks: sums[4] gets this rank's reaction (3) and energy, to
 * be summed by the caller with the step's other sums (one reduction a step). */
int pf_rigid_force_local(pf_rigid *r, pf_points *pts, double dt, double sums[4], double *dissipation);
int pf_rigid_force(pf_rigid *r, pf_points *pts, double dt, double reaction[3], double *energy,
                   double *dissipation);
/* Quasi-static loading with friction (docs/theory/quasi_static_methods.md §8): the normal penalty as
 * pf_rigid_force_local and the tangential penalty with its stick/slip return mapping from each
 * owned point's committed slip slip[3 i] (m; the surface's motion since the start D = x - x0):
 * terms NULL: add the forces to pts->f, sums[4] this rank's reaction (3) and energy (the normal
 * penalty's and the elastic tangential part's, |F_t|^2 / (2 k_t)); terms [n_owned]: commit at
 * an equilibrium, pts->f untouched: each point's new slip into slip and the work its slip
 * increment dissipated, |F_t| |Delta s|, into terms[i]. */
int pf_rigid_force_static(const pf_rigid *r, pf_points *pts, double *slip, double *terms, double sums[4]);
/* The Coulomb coefficient; the tangential penalty k_t of the quasi-static solver (N/m; NAN: the
 * quadratic law without tangential_stiffness). */
double pf_rigid_friction(const pf_rigid *r);
double pf_rigid_tangential_stiffness(const pf_rigid *r);
/* Move the surface from t to t + dt with its prescribed velocity v(t + dt/2): dx[3] gets the
 * motion dt v(t + dt/2), m (the work it does on the points is booked by the caller: the
 * trapezoidal rule of sim/ledger.h). */
void pf_rigid_advance(pf_rigid *r, double t, double dt, double dx[3]);
/* Refuse a velocity expression that is not finite over [0, t_end] (nt + 1 times). Collective. */
int pf_rigid_check_finite(const pf_rigid *r, double t_end, int nt);
/* The stable step the penalty allows the owned points it may touch, 2 sqrt(m_min / k) for the
 * linear law (INFINITY for the quadratic law, whose stiffness grows from zero with the depth,
 * and when it touches no body). Collective. */
double pf_rigid_stable_dt(const pf_rigid *r, const pf_points *pts);
/* Quasi-static loading: add to k[i] (N/m) a bound of the row sums of the 3 x 3 penalty stiffness
 * H = k_n n n^T - k_t (I - n n^T) on each owned point it acts on within one cell edge c_i of the
 * surface, at the depth d_b = max(d_i, 0) + c_i (d_i at the current positions): k_n = dF/dd
 * (2 k d_b V_i quadratic, k linear) and k_t = F / rho, the normal's turn over the distance rho
 * = max(R - d_b, R/2) from the centre or axis (0 on a plane); a row of n n^T sums to at most
 * |n|_inf |n|_1 <= sqrt(3), of I - n n^T to at most 1 + sqrt(3):
 *   k_i += sqrt(3) k_n + (1 + sqrt(3)) k_t. */
void pf_rigid_stiffness_bounds(const pf_rigid *r, const pf_points *pts, double *k);
/* Current position (sphere centre, plane point, point of the cylinder axis); restart. */
void pf_rigid_position(const pf_rigid *r, double x[3]);
void pf_rigid_set_position(pf_rigid *r, const double x[3]);

/* ---- rigid, fixed, frictionless walls for FE nodes (contact/wall.c) ------------------------ */
typedef struct pf_wall pf_wall;
extern const pf_key pf_wall_keys[];
int pf_wall_create(const pf_deck *d, const pf_node *map, int nbodies, const char *const *body_names,
                   pf_wall **w);
int pf_wall_destroy(pf_wall **w);
const char *pf_wall_name(const pf_wall *w);
/* After the drift: owned points behind the plane go back onto it and lose their inward normal
 * velocity; the kinetic energy removed is added to *loss (J), the momentum given to impulse[3]
 * (N s, this rank's points). */
void pf_wall_enforce_position(const pf_wall *w, pf_points *pts, double *loss, double impulse[3]);
/* After the forces: points on the plane lose the inward normal part of their force;
 * reaction[3] gets the total force on the wall over all ranks (N). Collective. */
void pf_wall_enforce_force(const pf_wall *w, pf_points *pts, double reaction[3]);
/* The same with this rank's share of the reaction only (the caller sums it over the ranks). */
void pf_wall_enforce_force_local(const pf_wall *w, pf_points *pts, double reaction[3]);

/* ---- contact between bodies (contact/contact.c, search.c, surface.c, pairs.c) --------------- */
typedef struct pf_contact pf_contact;
extern const pf_key pf_contact_keys[];      /* the `contact:` mapping */
extern const pf_key pf_contact_pair_keys[]; /* one entry of `contact: pairs:` */

/* What the contact module needs to know of a body. */
typedef struct {
  const char *name;
  int is_fe;
  double bulk_modulus; /* Pa */
  double density;      /* kg/m^3 */
  double horizon;      /* PD: the horizon, m (FE: 0) */
  double spacing;      /* the largest cell edge of the body's points (FE nodes: cube root of the nodal volume), m */
  pf_gid gid0;         /* global id of the body's first point (FE: of mesh node 0) */
  pf_int first, n;     /* the body's owned points [first, first + n) of the store */
  const pf_mesh *mesh; /* FE: the whole mesh (every rank) */
  /* FE: the mesh's deleted elements now (flags [nelem], their count in *count), which change the
   * surface, or NULL when the body deletes none */
  const uint8_t *(*eroded)(const void *ctx, long *count);
  const void *eroded_ctx;
  const pf_family *fam;    /* PD: the family of the owned points (for bonded-pair exclusion) */
} pf_contact_body;

/* Read `contact:` (pairs, skin): bodies named by pairs must exist and a pair of two FE bodies
 * is refused. Returns *c = NULL when the deck has no pair. */
int pf_contact_create(const pf_deck *d, const pf_node *map, int nbodies,
                      const pf_contact_body *bodies, pf_contact **c);
int pf_contact_destroy(pf_contact **c);
/* Give the contact the bodies' current owned ranges and families (after every (re)partition);
 * the next search (pf_contact_prepare or pf_contact_force) is built anew. */
int pf_contact_attach(pf_contact *c, const pf_contact_body *bodies);
/* Add the contact forces at the current positions pts->y (friction from the mid-step velocities
 * pts->v over the step dt; dt 0: none) to the owned points, each point summing its
 * interactions in an order independent of the partition. sums[pf_contact_nsums] gets this
 * rank's part of the pairs' forces and of the penalty energy, which the caller sums over the
 * ranks (with the step's other sums, in one reduction) and hands back to pf_contact_sums_take;
 * the friction work of this rank over dt is added to *dissipation. The per-point contact force
 * goes to the output field "contact_force". Collective (the search's exchanges). */
int pf_contact_nsums(const pf_contact *c);
/* The search (the contact ghosts' positions and the candidates) ahead of the next pf_contact_force
 * at the same positions and velocities (the store's ghosts' positions exchanged: a face's size
 * reads them), which then only evaluates the pairs: called before the bodies' forces, its
 * exchanges and reductions meet the ranks together instead of waiting for the slowest rank's
 * bodies. On one rank it leaves the search to pf_contact_force. Collective. */
int pf_contact_prepare(pf_contact *c, pf_points *pts);
/* Build the search anew at the next pf_contact_prepare or pf_contact_force (points took or lost
 * mass: a point of mass 0 takes no part in contact). */
void pf_contact_rebuild(pf_contact *c);
/* After a restart restored the deleted elements: the surfaces without them, none of their faces
 * fresh (they were uncovered before the checkpoint). */
int pf_contact_restored(pf_contact *c);
int pf_contact_force(pf_contact *c, pf_points *pts, double dt, double *sums, double *dissipation);
/* The sums over the ranks: keep the pairs' forces (pf_contact_pair_force); *energy gets the
 * penalty energy, J. */
void pf_contact_sums_take(pf_contact *c, const double *sums, double *energy);
/* The stable step the penalties allow (2 / omega of the stiffest contact a point can see).
 * Collective. */
double pf_contact_stable_dt(const pf_contact *c, const pf_points *pts);
/* Lower the stiffness of each pair with `soft: true` until its stable step is the smaller of its
 * two bodies' (body_dt[b], over all ranks), logging each change; pairs whose step is not below
 * keep theirs (docs/theory/contact.md §4a). Set-up, before the time step is chosen; collective. */
int pf_contact_soften(pf_contact *c, const pf_points *pts, const double *body_dt, const char *const *body_name);
/* The soft pairs' count, whether pair k is one, and their stiffnesses in pair order (set: a
 * restart's, which keeps the run's). */
int pf_contact_nsoft(const pf_contact *c);
int pf_contact_pair_soft(const pf_contact *c, int k);
void pf_contact_soft_stiffness_get(const pf_contact *c, double *v);
void pf_contact_soft_stiffness_set(pf_contact *c, const double *v);
/* Quasi-static loading (the solver's open): the pairs with friction take it as a tangential penalty
 * on each point's slip relative to the surface point it meets (docs/theory/quasi_static_methods.md
 * §8), kept in the point field "contact_slip" (registered here; carried by re-partitions and
 * checkpoints); a short-range pair's friction is refused (an error naming the key of `map`, the
 * deck's `contact:`). */
int pf_contact_quasi_static(pf_contact *c, const pf_deck *d, const pf_node *map, pf_points *pts);
/* Quasi-static loading, at a load step's equilibrium: each owned point's slip takes what the
 * elastic part of its friction does not hold (a point that nothing pushes: its displacement
 * relative to the nearest surface point within the search's reach; none beyond it), and terms[i]
 * (over the owned points) the work of its slip increment, J. Collective. */
int pf_contact_commit_slips(pf_contact *c, pf_points *pts, double *terms);
/* Quasi-static: add to k[i] (N/m, owned points) a bound of the row sums of the pairs' penalty
 * stiffness at point i (the fictitious masses). Collective. */
void pf_contact_stiffness_bounds(const pf_contact *c, const pf_points *pts, double *k);
/* 1 when body b is in short-range contact with itself between unbonded points (the default, not
 * all_points): its broken bonds then need their rest lengths (pf_pd_body_record_breaks). */
int pf_contact_self_pair(const pf_contact *c, int b);
/* The pairs: count, names (history columns) and the total force on the pair's first body (the
 * FE body of an FE <-> PD pair) at the last evaluation, N. */
int pf_contact_npairs(const pf_contact *c);
const char *pf_contact_pair_name(const pf_contact *c, int k);
void pf_contact_pair_force(const pf_contact *c, int k, double f[3]);
/* Pair k's smallest gap among this rank's interactions at the last force evaluation, over
 * info->length (INFINITY: no interaction within reach): for a pair against an FE surface the
 * signed distance of a point from the surface (negative: behind it, inside the body), for
 * point pairs (short range, nodes) the distance of the two centres over the contact radius;
 * info gets the pair's bodies, kind and length (m): r_c, or half the finer spacing of an FE <-> FE
 * pair with r_c = 0. Read by the run-health monitor; not collective. */
typedef struct {
  int a, b;    /* the bodies (an FE <-> PD pair: a the FE body) */
  int surface; /* 1: against a surface (signed gap) */
  double length;
} pf_contact_gap;
double pf_contact_pair_gap(const pf_contact *c, int k, pf_contact_gap *info);
/* Set it back (restart: the history row of the restarted step shows the force last evaluated). */
void pf_contact_pair_force_set(pf_contact *c, int k, const double f[3]);
/* Search statistics: rebuilds so far, and the contact share of the time (seconds spent). */
void pf_contact_stats(const pf_contact *c, long *rebuilds, double *seconds);
/* Work done so far on this rank: short-range candidate pairs tested at the force evaluations,
 * and family entries read to tell bonded pairs from unbonded ones (at the search builds, and the
 * broken flags read at the evaluations). Deterministic, for tests of the contact's cost. */
void pf_contact_counts(const pf_contact *c, int64_t *pairs_tested, int64_t *family_reads);
/* Add to w[i] (owned points) the work the force evaluation spends on point i's candidates of the
 * last build, in bond evaluations (each method's cost of a candidate; for re-partitioning). */
void pf_contact_work(const pf_contact *c, int *w);

/* ---- geometry of FE surfaces (contact/surface.c) ----------------------------------------- */
/* A boundary face of a hexahedral mesh: its 4 mesh nodes ordered so that the right-hand rule
 * gives the outward normal, and the element and face (0..5) it comes from. */
typedef struct {
  pf_int node[4];
  pf_int elem;
  int face;
} pf_contact_face;
/* The boundary faces of a mesh (faces of exactly one element), or the sides of side set
 * `sideset` (index into m->sideset; -1: the whole boundary), leaving out the elements flagged in
 * dead[nelem] (deleted by erosion; NULL: none), whose neighbours' faces then become boundary.
 * Sorted by (elem, face). */
int pf_contact_surface_faces(const pf_mesh *m, int sideset, const uint8_t *dead, pf_contact_face **faces,
                             pf_int *nfaces);
/* The point of quadrilateral face x[4] closest to p, the face taken as the four triangles
 * (x_a, x_a+1, centre), exact for a flat face. Returns the signed distance (positive on the
 * outward side); c[3] the closest point; w[4] the node weights of c (sum 1, >= 0); n[3] the unit
 * outward contact normal at c (from c towards p when p is outside, away from p when inside; the
 * triangle normal when p lies on the face). */
double pf_contact_face_closest(const double x[4][3], const double p[3], double c[3], double w[4],
                               double n[3]);

#endif
