/* The body interface of the driver (docs/architecture.md §3): every kind of body (peridynamic,
 * finite-element, coupled) is an ops table registered by name in sim/body_kinds.h, and the rest of
 * sim/ calls bodies only through it. Required ops fail the set-up with the kind's name when
 * missing; optional ones (NULL) default as each comment says. Private to sim/. */
#ifndef PF_SIM_BODY_H
#define PF_SIM_BODY_H

#include "pd/pd.h"
#include "mesh/mesh.h"

/* Where a body's points sit: store body index, its owned points [first, first + n) and the
 * global id of its first point (its points' ids are gid0 + generation order). */
typedef struct {
  int index;
  pf_gid gid0;
  pf_int first, n;
} pf_body_span;

/* Energies and bond counts of a body's owned points and elements (J; counts of directed bonds). */
typedef struct {
  double elastic;   /* PD stored energy */
  double fe[3];     /* elements: stress work, hourglass energy, bulk-viscosity work */
  double bonds, broken;
  double converted; /* kinetic energy removed by converting elements into particles (booked), J */
} pf_body_energies;

/* What the body op `history` is asked. */
typedef enum { PF_HISTORY_KEPT, PF_HISTORY_COMMIT, PF_HISTORY_RESTORE } pf_history_op;

typedef struct {
  const char *type;  /* the deck's `type:` */
  const char *label; /* the kind in --check's table (PD, coupled, FE, particles) */
  /* Required. The keys of the body mapping; is this mapping of `type` this kind (NULL: yes)? */
  const pf_key *(*keys)(void);
  int (*claims)(const pf_node *body);
  int (*create)(const pf_deck *d, const pf_node *body, const pf_node *materials, void **data);
  int (*destroy)(void **data);
  /* The body's points at set-up (every rank generates them all). */
  int (*cloud)(void *data, const pf_deck *d, const pf_node *body, pf_point_cloud *pc);
  /* The rows of the span's owned points: the current ones (rows: re-partitions, checkpoints)
   * and, optionally, at set-up those found in the whole cloud (find_rows; NULL: rows). */
  int (*rows)(const void *data, const pf_points *pts, const pf_body_span *s, pf_bond_rows *rows);
  int (*find_rows)(void *data, const pf_point_cloud *pc, const pf_points *pts, const pf_body_span *s,
                   pf_bond_rows *rows);
  /* Optional: register on rows the bond fields the body's rows carry (NULL: none beyond the
   * global ids). */
  int (*bond_fields)(const void *data, pf_bond_rows *rows);
  /* Take the span's points (ghosts added; rows and local as pf_pd_body_attach). Collective. */
  int (*attach)(void *data, pf_points *pts, const pf_body_span *s, const pf_bond_rows *rows,
                const pf_int *local, int fresh);
  /* Add the internal forces to pts->f; dt the step just taken (0: initial forces). A failure that
   * must stop every rank at the step's end (an inverted element) sets *tripped and returns 0. */
  int (*force)(void *data, pf_points *pts, double dt, double t, long step, int *tripped);
  /* The stable step now, s (not collective). */
  double (*stable_dt)(const void *data, const pf_points *pts);
  /* Optional. Does the stable step change as the body deforms (NULL: no)? Do the forces read
   * the neighbours' velocities (NULL: no)? */
  int (*step_varies)(const void *data);
  int (*uses_velocity)(const void *data);
  /* Optional: after the step (damage-law state; NULL: nothing). */
  int (*post_step)(void *data, pf_points *pts);
  /* Optional: freeze (1) or thaw (0) the body's damage: frozen, its force op fails no bond and
   * degrades nothing (the quasi-static solver relaxes a load step frozen, then checks the damage
   * by one force evaluation thawed at the equilibrium reached); NULL: a body without damage,
   * nothing to do. */
  int (*freeze_damage)(void *data, const pf_points *pts, int frozen);
  /* Optional: the largest failure ratio over its owned intact bonds at the last force
   * evaluation (1: a bond at its limit; a linear body's ratio scales with its state; quasi-static
   * solver, failure: sequential); NULL with freeze_damage: the body cannot take that failure. */
  double (*failure_ratio)(const void *data, const pf_points *pts);
  /* Optional: for bonds that soften (their damage grows with their stretch), the bonds whose
   * damage grew by more than the law's tolerance, counted over the run (the quasi-static solver
   * relaxes again while it grows, as while bonds fail); -1, or NULL: no bond softens. */
  int64_t (*softened)(const void *data);
  /* Optional: the body's history (plastic and rate-form state): whether it keeps any
   * (PF_HISTORY_KEPT: returns 1 or 0), commit the current one (PF_HISTORY_COMMIT) or put the
   * committed one back (PF_HISTORY_RESTORE). A body that keeps history has the quasi-static
   * solver commit it at each load step's start and restore it before each force evaluation, and
   * reads the whole load step's increment as its velocity over a step of 1: each evaluation is
   * one increment from the last converged state. NULL, or 0 kept: the body's force keeps no
   * history, or one that the iterations advance (it reads the iteration's increment). */
  int (*history)(void *data, pf_points *pts, pf_history_op op);
  /* Optional: keep the bonds' failures as they are now (restore 0) or put the kept ones back
   * (restore 1): the quasi-static solver keeps them at each load step's start and puts them back
   * when a signal abandons the load step, so that its checkpoint is the last equilibrium's. NULL:
   * a body without bonds that fail. */
  int (*failures)(void *data, int restore);
  /* Optional: the change of stored energy when bonds failed since the last call into w[0], and
   * the part of it that is moved, not released, into w[1] (<= 0; docs/theory/pd.md §5.1), J
   * (NULL: none). */
  void (*take_damage_work)(void *data, double w[2]);
  /* Required: energies and bond counts; may write the "damage" field. */
  void (*energies)(const void *data, pf_points *pts, pf_body_energies *e);
  /* Optional: the bonds (NULL: none); their memory per directed bond, bytes. */
  const pf_family *(*family)(const void *data);
  double (*bytes_per_bond)(const void *data);
  /* Optional: directed bond evaluations per second and rank on the benchmark machine, for the
   * --check estimate (NULL: 1.5e8). */
  double (*bond_rate)(const void *data);
  /* Optional: give the bonds broken since the last call their rest length (self-contact). */
  void (*record_breaks)(void *data, const pf_points *pts);
  /* Required: density (kg/m^3) and bulk modulus (Pa); optional: the largest horizon, m. */
  void (*material)(const void *data, double *density, double *bulk_modulus);
  double (*horizon)(const void *data);
  /* Optional: store point i's own horizon, m (a variable horizon; NULL: the horizon op's). */
  double (*point_horizon)(const void *data, pf_int i);
  /* Optional: how far store point i may move in one step before the guard stops the run, and
   * what that length is called (NULL: the point's cell edge, "cell"). */
  double (*reach)(const void *data, const pf_points *pts, pf_int i);
  const char *reach_name;
  /* Optional: the hexahedral mesh (output blocks, element counts, contact surfaces of a body
   * without bonds) and its deleted elements (NULL: none). */
  const pf_mesh *(*mesh)(const void *data);
  const uint8_t *(*eroded)(const void *data, long *count);
  /* Optional: the mesh whose surface meets other bodies in contact (NULL: the body meets them by
   * its points, as particles: a PD body, and a coupled body, whose nodes are the particles that
   * fracture). */
  const pf_mesh *(*contact_surface)(const void *data);
  /* Optional: fill the body's output fields before an Exodus step. */
  int (*output_fields)(void *data, pf_points *pts);
  /* Optional: state kept per element rather than per point, as one table of `total` rows of
   * `ncomp` reals (re-partitions and checkpoints gather it whole); table_get fills this rank's
   * owned rows (room for nlocal) and returns their count; table_set restores from the whole table. */
  void (*table_shape)(const void *data, pf_gid *total, int *ncomp, pf_int *nlocal);
  pf_int (*table_get)(const void *data, pf_gid *ids, double *rows);
  void (*table_set)(void *data, const double *full);
  /* Optional: a stable step carried across re-partitions and restarts (that of the last force
   * evaluation, which the state alone does not give back). */
  void (*set_stable_dt)(void *data, double dt);
  /* Optional: bounds of the diagonal stiffness of store points first .. first + n - 1 into k,
   * the Gershgorin row sums sum_j |K_ij| of their block rows, N/m (the quasi-static solver's
   * fictitious masses; NULL: the stable-step form 4 m_i / dt_b^2, dt_b the body's stable step
   * over every rank). Collective. */
  int (*stiffness_bounds)(void *data, pf_points *pts, pf_int first, pf_int n, double *k);
  /* Optional, for tests and tools (pf_sim_body, pf_sim_fem_body): the body's PD or FE operator. */
  pf_pd_body *(*as_pd)(void *data);
  struct pf_fem_body *(*as_fem)(void *data);
  /* Optional: the body's particles made from another body's elements (sim/convert.c links them
   * to that body and converts at each step's end). */
  struct pf_fem_particles *(*as_particles)(void *data);
} pf_body_ops;

/* A body of the simulation. */
typedef struct {
  const pf_body_ops *ops;
  void *data;
  const char *name;
} pf_body;

/* The kind of the deck's body mapping (by `type:`, default peridynamic, then by claims); an
 * unknown type is an input error listing the known ones. */
int pf_body_kind(const pf_deck *d, const pf_node *body, const pf_body_ops **ops);
/* An explicit run of nsteps > 0 steps refuses the statics-only transition forms (auto,
 * partial_stress, corrected) of a PD body or of an FE body's peridynamic: map unless the same
 * map says allow_in_dynamics: true (sim/body_kinds.c). names: the bodies' names. */
int pf_body_kinds_check_dynamic_forms(const pf_deck *d, long nsteps, const char *const *names);
/* The registered kinds in list order; is kind k the first of its type (whose keys are the
 * type's: the kinds of one type share one key table)? */
int pf_body_kind_count(void);
const pf_body_ops *pf_body_kind_at(int k);
int pf_body_kind_first_of_type(int k);
/* Bytes a point and a bond cost at the peak of the set-up: measured on a 227 000-point PMB
 * box, 5.1 KB per point at 3.015 spacings (123 bonds a point) and 18.5 KB at 5.015 (515 bonds):
 * about 1 KB + 34 bytes a bond; 40 bytes allowed. */
#define PF_PD_BYTES_PER_POINT 1024.0
#define PF_PD_BYTES_PER_BOND 40.0
/* sim/body_pd.c: the directed bonds a point has with a horizon of m spacings, 4/3 pi m^3
 * (at most points - 1), and the memory a PD body of that many points takes at the peak of the
 * set-up, bytes (about 1 KB a point and 40 bytes a bond, measured). */
double pf_body_pd_bonds_per_point(double points, double m);
double pf_body_pd_bytes(double points, double m);
/* An optional flag op that is always true (step_varies, uses_velocity). */
int pf_body_always(const void *data);

/* The optional ops, each with its default (the comments of pf_body_ops): sim/ calls these, never
 * an optional op directly. pf_body_table_shape returns 0 for a body without a state table;
 * pf_body_eroded_count the elements its erosion deleted (-1: it deletes none); pf_body_carries_stable_dt
 * whether it keeps a stable step across re-partitions and restarts. */
int pf_body_find_rows(const pf_body *b, const pf_point_cloud *pc, const pf_points *pts, const pf_body_span *s,
                      pf_bond_rows *rows);
int pf_body_bond_fields(const pf_body *b, pf_bond_rows *rows);
int pf_body_step_varies(const pf_body *b);
int pf_body_uses_velocity(const pf_body *b);
int pf_body_post_step(const pf_body *b, pf_points *pts);
int pf_body_freeze_damage(const pf_body *b, const pf_points *pts, int frozen);
double pf_body_failure_ratio(const pf_body *b, const pf_points *pts); /* 0 without the op */
int pf_body_fails_without_ratio(const pf_body *b); /* freeze_damage without failure_ratio */
int64_t pf_body_softened(const pf_body *b);        /* -1 without the op */
int pf_body_keeps_history(const pf_body *b, pf_points *pts);
int pf_body_history(const pf_body *b, pf_points *pts, pf_history_op op);
int pf_body_failures(const pf_body *b, int restore);
/* The body's stable step now, the smallest over all ranks (s). Collective. */
double pf_body_stable_dt_all(const pf_body *b, const pf_points *pts);
/* The failed directed bonds of the body's owned rows (0 for a body without bonds). */
int64_t pf_body_broken_bonds(const pf_body *b);
void pf_body_take_damage_work(const pf_body *b, double w[2]);
const pf_family *pf_body_family(const pf_body *b);
double pf_body_bytes_per_bond(const pf_body *b);
double pf_body_bond_rate(const pf_body *b);
void pf_body_record_breaks(const pf_body *b, const pf_points *pts);
double pf_body_horizon(const pf_body *b);
double pf_body_point_horizon(const pf_body *b, pf_int i);
double pf_body_reach(const pf_body *b, const pf_points *pts, pf_int i);
const char *pf_body_reach_name(const pf_body *b);
const pf_mesh *pf_body_mesh(const pf_body *b);
const pf_mesh *pf_body_contact_surface(const pf_body *b);
long pf_body_eroded_count(const pf_body *b);
int pf_body_output_fields(const pf_body *b, pf_points *pts);
int pf_body_table_shape(const pf_body *b, pf_gid *total, int *ncomp, pf_int *nlocal);
void pf_body_table_set(const pf_body *b, const double *full);
int pf_body_carries_stable_dt(const pf_body *b);
void pf_body_set_stable_dt(const pf_body *b, double dt);
/* The stiffness bound of the body's owned points first .. first + n - 1 into k[0 .. n-1], N/m
 * (the op's, or its default). Collective (the default's stable step is the minimum over ranks). */
int pf_body_stiffness_bounds(const pf_body *b, pf_points *pts, pf_int first, pf_int n, double *k);
pf_pd_body *pf_body_as_pd(const pf_body *b);
struct pf_fem_body *pf_body_as_fem(const pf_body *b);
struct pf_fem_particles *pf_body_as_particles(const pf_body *b);

#endif
