/* perifem peridynamic core: families (bonds), influence functions, materials, bond failure
 * and damage, the critical time step. */
#ifndef PF_PD_H
#define PF_PD_H

#include "core/core.h"

#ifndef PF_USES_PD
#error "pd/pd.h is included by a module below pd/ (docs/architecture.md: the module layers)"
#endif

typedef struct pf_pd_body pf_pd_body;

/* CSR family of the points [first, first + n) of the point store. Full lists (each bond seen
 * from both ends), each row sorted by the neighbour's global id. neighbor, broken and vfrac
 * have PF_FAMILY_SLACK zero entries past the last bond, so that a batched bond loop may read a
 * whole batch at a row's end. broken, vfrac, rest and state travel in the bond rows as the bond
 * fields of those names (pf_pd_family_register_fields): filled from the rows by
 * pf_pd_family_from_rows, written back by pf_pd_family_to_rows. */
enum { PF_FAMILY_SLACK = 8 };
typedef struct {
  pf_int first, n;
  int64_t *offset;  /* [n + 1] */
  pf_int *neighbor; /* [nbonds] local index into the point store */
  uint8_t *broken;  /* [nbonds] 1 once the bond has failed */
  float *vfrac;     /* [nbonds] partial-volume fraction of the neighbour, or NULL */
  float *rest;      /* [nbonds] a broken bond's length when it broke (the contact rest length of
                       its ends, pf_pd_body_record_breaks), 0 while intact or not recorded */
  uint64_t *recorded; /* [nbonds / 64 + 1] bit k % 64 of word k / 64: rest[k] > 0, so that
                         pf_pd_body_record_breaks finds the new breaks without reading rest */
  int nstate;       /* reals of material state per bond: set by the material's create (0: none) */
  double *state;    /* [nbonds * nstate] the material's per-bond state, or NULL; it travels with
                       the rows (re-partition, checkpoint). Freed by the material's destroy. */
} pf_family;

/* Bond filters applied while building families: planar pre-cracks. */
typedef enum { PF_CRACK_RECTANGLE, PF_CRACK_DISK } pf_crack_kind;
typedef struct {
  pf_crack_kind kind;
  double p0[3], a[3], b[3]; /* rectangle: corner p0, edges a and b */
  double center[3], normal[3], radius; /* disk */
} pf_precrack;

/* The points a body's bonds may reach: the whole body (every rank generates it at set-up);
 * point j of the cloud has global id gid0 + j. */
typedef struct {
  const double *X;    /* [3n] */
  const double *cell; /* [n] */
  pf_int n;
  pf_gid gid0;
} pf_pd_cloud;

/* Register in rows the bond fields a family keeps (core/ carries them through migration and
 * checkpoints): "broken" (uint8, 1 once failed), "rest" (float, m), with partial volumes
 * "vfrac" (float, init 1), and with nstate > 0 "state" (nstate doubles). */
/* A checkpoint of format 3 or older kept the correspondence record's matrices (P K^-1, Fbar,
 * Fbar dot) by rows: transpose them into this version's columns (no-op without the field). */
void pf_pd_correspondence_upgrade(pf_points *pts);
int pf_pd_family_register_fields(pf_bond_rows *rows, int partial_volumes, int nstate);
/* Append to rows the bonds of points [first, first+n) of pts (which are points of the cloud)
 * to every cloud point within `horizon` (|xi| <= horizon), each row ascending in global id.
 * With hz (each cloud point's own horizon; then `horizon` is their largest), the rows hold
 * every pair with |xi| <= max(hz_i, hz_j): j in i's family, or i in j's (a one-sided bond),
 * so that the rows stay symmetric; the kernels tell the two apart (pf_pd_in_family).
 * With partial_volumes, neighbours whose cell only partly lies in the horizon sphere are kept
 * with the fraction of the cell inside (16^3 sub-cell midpoint rule, as Peridigm). Bonds
 * crossing a pre-crack are left out. O(n) cell-list search. The family's bond fields are
 * registered in rows (without "state": the new bonds have none yet). */
int pf_pd_family_build(const pf_pd_cloud *src, const pf_points *pts, pf_int first, pf_int n,
                       double horizon, const double *hz, int partial_volumes, int ncracks,
                       const pf_precrack *cracks, pf_bond_rows *rows);
/* The family of the owned points [first, first+n) from their rows (row i of rows is store
 * point i), local[] giving the store index of each bond's neighbour. fam->nstate is kept: the
 * first fam->nstate reals of each bond's state are taken from the rows (zero beyond theirs). */
int pf_pd_family_from_rows(const pf_bond_rows *rows, const pf_int *local, pf_int first, pf_int n,
                           int partial_volumes, pf_family *fam);
/* Append the family's rows (neighbours by global id, with their state, per-bond reals
 * included) to rows, registering the family's bond fields in rows first. */
int pf_pd_family_to_rows(const pf_family *fam, const pf_points *pts, pf_bond_rows *rows);
int pf_pd_family_free(pf_family *fam);
int64_t pf_pd_family_nbonds(const pf_family *fam);
/* Volume fraction of the cube (centre c, edge h) inside the sphere (centre x, radius delta). */
double pf_pd_partial_volume(const double x[3], const double c[3], double h, double delta);

/* Influence functions omega(|xi|), registered by name (pd/influence.c). */
typedef enum { PF_INFLUENCE_CONSTANT, PF_INFLUENCE_INVERSE_DISTANCE, PF_INFLUENCE_GAUSSIAN } pf_influence_kind;
typedef struct {
  pf_influence_kind kind;
  double length; /* Gaussian: sigma in exp(-r^2 / sigma^2) */
} pf_influence;
int pf_pd_influence_by_name(const char *name, pf_influence_kind *kind);
const char *pf_pd_influence_names(void);
/* 4 pi * int_0^delta omega(r) r^p dr, by Gauss-Legendre quadrature (exact for the polynomial
 * cases): the moments that calibrate micromoduli and critical stretches. */
double pf_pd_influence_moment(const pf_influence *w, double delta, int p);

/* Closed forms. */
/* PMB micromodulus c = 18 K / (pi delta^4) for omega = 1 (Silling & Askari 2005, eq. 7);
 * in general c = 18 K / (4 pi int omega r^3 dr). */
double pf_pd_pmb_micromodulus(double bulk_modulus, const pf_influence *w, double delta);
/* Critical stretch from the energy release rate: PMB s0 = sqrt(5 G0 / (9 K delta))
 * (Silling & Askari 2005, eq. 9). */
double pf_pd_pmb_critical_stretch(double G0, double bulk_modulus, double delta);

/* A body of peridynamic points, read from the deck (`bodies[i]`, with its material from
 * `materials`): material, horizon, influence function, damage law, pre-cracks. Its deck tables
 * are assembled at first use from the lists pd/materials.h and pd/damage_laws.h: each material
 * and each law gives its own rows (pf_pd_material_ops.keys, pf_pd_damage_ops.keys), so that
 * adding one edits no table here. The names read as the tables. */
const pf_key *pf_pd_body_key_table(void);
const pf_key *pf_pd_material_key_table(void);
const pf_key *pf_pd_damage_key_table(void);
#define pf_pd_body_keys (pf_pd_body_key_table())
#define pf_pd_material_keys (pf_pd_material_key_table())
#define pf_pd_damage_keys (pf_pd_damage_key_table())
/* Add a damage law to the list of pd/damage_laws.h at run time (a law defined in a test, as
 * PETSc's PCRegister): law (pf_pd_damage_ops, pd/pd_impl.h; kept, not copied) is found by its
 * name from then on. An error when the name is taken, or the list is full (PF_PD_MAX_LAWS). Not
 * thread safe: register before reading a deck. */
typedef struct pf_pd_damage_ops pf_pd_damage_ops;
enum { PF_PD_MAX_LAWS = 16 };
int pf_pd_damage_register(const pf_pd_damage_ops *law);
/* 1 when model names a peridynamic material; the known names, comma separated. */
int pf_pd_material_known(const char *model);
const char *pf_pd_material_names(void);
int pf_pd_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials,
                      pf_pd_body **b);
/* The body's points as its set-up cloud holds them (every point, in global-id order from the
 * body's first): the material_regions entries that name a block (pd/material_regions.c) take the
 * points of that block; an entry whose block the cloud does not hold is an error naming its key. */
int pf_pd_body_take_blocks(pf_pd_body *b, const pf_point_cloud *pc);
/* A peridynamic operator over the nodes of a finite-element body (docs/theory/coupling.md §3):
 * its keys from map (pf_pd_coupled_keys, an FE body's `peridynamic:`), its name and material from
 * the FE body's mapping owner: a correspondence body of the FE body's continuum model. */
const pf_key *pf_pd_coupled_key_table(void);
#define pf_pd_coupled_keys (pf_pd_coupled_key_table())
int pf_pd_body_create_coupled(const pf_deck *d, const pf_node *owner, const pf_node *map,
                              const pf_node *materials, pf_pd_body **b);
/* Coupled with material_regions (read from the owner's mapping, one part per entry): the part of
 * each mesh node, entry[k] for node k (global id: the body's first + k), from the entries of its
 * elements (pf_fem_body_node_entries); copied. The entries' regions are then not tested at the
 * nodes. The density of part q (0: the body's material). */
int pf_pd_body_set_node_parts(pf_pd_body *b, const uint8_t *entry, pf_gid nnodes);
double pf_pd_body_part_density(const pf_pd_body *b, int q);
/* Each store point's blending weight (FE-coupled bodies), read at attach: points with beta < 1
 * are overlap points (no damage). weight_states 0: the caller weights the operator's net force
 * at each point by beta (force blending); 1: each point's force state is weighted by its own
 * beta, the forces of the energy sum_i beta_i W_i V_i (the energy form, docs/theory/coupling.md
 * §3.4), which conserve linear and angular momentum pair by pair. */
void pf_pd_body_set_blending(pf_pd_body *b, const double *beta, int weight_states);
/* Coupled: the horizon expression's d_fe at x, the distance to the region where the elements act,
 * is distance(ctx, x) (coupling/ gives it; without it d_fe is infinite). Does the body's horizon
 * expression name d_fe? */
typedef double (*pf_pd_distance_fn)(const void *ctx, const double x[3]);
void pf_pd_body_set_fe_distance(pf_pd_body *b, pf_pd_distance_fn distance, const void *ctx);
int pf_pd_body_uses_fe_distance(const pf_pd_body *b);
/* Coupled in the energy form: the elements' part of the uniform-stress vector at owned store
 * point i, sum_e (beta_i - beta_e) V_e B_ei over its elements (reference volume and mean gradient,
 * beta_e the mean of the element's nodes), into out; the consistent form takes it into the
 * targets of its weight corrections at the overlap's kinks (docs/theory/coupling.md §3.4). */
typedef void (*pf_pd_fe_vector_fn)(const void *ctx, pf_int i, double out[3]);
void pf_pd_body_set_fe_vector(pf_pd_body *b, pf_pd_fe_vector_fn vector, const void *ctx);
/* Append to rows the bonds of store points [first, first+n), points of this body, found in
 * the body's whole cloud (with a variable horizon, each point's own horizon: rows hold the
 * pairs either end's family has). */
int pf_pd_body_find_bonds(pf_pd_body *b, const pf_pd_cloud *cloud, const pf_points *pts,
                          pf_int first, pf_int n, pf_bond_rows *rows);
/* Give the body its owned points [first, first+n) and their family (rows of those points, with
 * local[] the store index of each neighbour). When fresh: masses, initial critical stretch,
 * the material's per-point set-up. Otherwise (after a re-partition) the migrated fields are
 * kept. Collective (halo exchanges); fails on every rank alike when the body has no bond. */
int pf_pd_body_attach(pf_pd_body *b, pf_points *pts, pf_int first, pf_int n,
                      const pf_bond_rows *rows, const pf_int *local, int fresh);
/* Append the rows of the body's owned points (neighbours by global id) to rows. */
int pf_pd_body_bond_rows(const pf_pd_body *b, const pf_points *pts, pf_bond_rows *rows);
/* Register in rows the bond fields the body's rows carry (pf_pd_family_register_fields), as
 * its rows would: before reading a checkpoint into them. */
int pf_pd_body_bond_fields(const pf_pd_body *b, pf_bond_rows *rows);
int pf_pd_body_destroy(pf_pd_body **b);
double pf_pd_body_density(const pf_pd_body *b);
double pf_pd_body_horizon(const pf_pd_body *b); /* the constant one, or the largest */
double pf_pd_body_point_horizon(const pf_pd_body *b, pf_int i); /* store point i's own */
double pf_pd_body_bulk_modulus(const pf_pd_body *b); /* Pa */
const pf_family *pf_pd_body_family(const pf_pd_body *b);
/* Add the body's internal forces (N) to pts->f; fails bonds per the damage law. dt is the step
 * just taken (0 for the initial forces): rate-form materials advance their stress over it. */
int pf_pd_body_force(pf_pd_body *b, pf_points *pts, double dt);
/* 1 when the body's forces depend on the neighbours' velocities (rate-form correspondence). */
int pf_pd_body_uses_velocity(const pf_pd_body *b);
/* After the step: update damage-law state (e.g. Silling–Askari s0 from the step's s_min). */
int pf_pd_body_post_step(pf_pd_body *b, pf_points *pts);
/* Freeze (1) or thaw (0) the body's damage. Frozen, the body fails no bond: the force kernels,
 * which only compare against the limits the law leaves (pd/pd_impl.h), read none (every point's
 * critical stretch INFINITY, no energy limit); thawed, the law's limits are back as they were.
 * The quasi-static solver freezes the damage while it relaxes a load step and checks it at the
 * equilibrium reached (docs/theory/quasi_static_failure.md §5). Nothing may re-attach the body while
 * frozen. */
int pf_pd_body_freeze_damage(pf_pd_body *b, const pf_points *pts, int frozen);
/* The largest failure ratio over the owned points' intact bonds at the last force evaluation's
 * state: s / s_lim or sqrt(w / w_c), against the law's limits (also while frozen); 1 at the
 * limit, 0 without one (pd/failure_ratio.c). */
double pf_pd_body_failure_ratio(const pf_pd_body *b, const pf_points *pts);
/* Bonds that soften (law softening): the bonds whose damage grew by more than its tolerance at
 * the evaluations with the damage thawed, counted over the run; -1 for a body whose bonds do not
 * soften. */
int64_t pf_pd_body_softened(const pf_pd_body *b);
/* 1 when the body's material keeps history (a plastic or rate-form state its force advances). */
int pf_pd_body_keeps_history(const pf_pd_body *b);
/* Commit the body's history (restore 0: the material's history fields of its owned points and
 * its bonds' state as they are now) or put the committed one back (restore 1). The
 * quasi-static solver commits at each load step's start and restores before each force
 * evaluation (docs/theory/quasi_static_failure.md §6). */
int pf_pd_body_history(pf_pd_body *b, pf_points *pts, int restore);
/* Keep the bonds' failures as they are now (restore 0: broken flags, the contact's rest lengths
 * and their record bits) or put the kept ones back (restore 1). The quasi-static solver keeps
 * them at each load step's start and puts them back when a signal abandons the load step
 * (pd/failures_kept.c). */
int pf_pd_body_failures(pf_pd_body *b, int restore);
void pf_pd_body_failures_free(pf_pd_body *b);
/* Stored elastic energy (J) of the body's owned points. */
double pf_pd_body_energy(const pf_pd_body *b, const pf_points *pts);
/* The change of stored energy (J) of the body's owned points when bonds failed since the last
 * call (the energy with them less without, at the same positions), and restart the count. Of it,
 * _redistribution (pd/damage.c) is the part that is not released but moved (<= 0: the LPS
 * dilatation's cross term; docs/theory/pd.md §5.1); the rest, the damage dissipation, is >= 0. */
double pf_pd_body_take_damage_work(pf_pd_body *b);
double pf_pd_body_take_damage_redistribution(pf_pd_body *b);
/* Give each bond of the owned rows that broke since the last call its rest length: its length
 * at the current positions, rounded down to a float. Below it the bond's two points are in
 * contact (short-range self-contact, contact/pairs.c), so a bond that breaks in compression sets
 * no contact force free. Call after the forces that broke it and before the contact forces. */
void pf_pd_body_record_breaks(pf_pd_body *b, const pf_points *pts);
/* Point damage phi = 1 - intact bond volume / family volume into the "damage" field;
 * returns the number of broken directed bonds. */
int64_t pf_pd_body_damage(const pf_pd_body *b, pf_points *pts);
/* Critical time step of the body: Silling–Askari's min_i sqrt(2 rho / sum_j V_j c / |xi|), or,
 * for a body whose step changes as it deforms (correspondence), its current step. */
double pf_pd_body_stable_dt(const pf_pd_body *b, const pf_points *pts);
/* Does the body's stable step change as it deforms (then the time loop asks every step)? */
int pf_pd_body_step_varies(const pf_pd_body *b);
/* Number of directed bonds (intact or broken) of the body. */
int64_t pf_pd_body_nbonds(const pf_pd_body *b);
/* Bytes the body keeps per directed bond: neighbour index, broken flag, partial-volume
 * fraction (when on) and the material's bond state. */
double pf_pd_body_bytes_per_bond(const pf_pd_body *b);
/* Directed bond evaluations per second and rank of its model on the benchmark machine (--check). */
double pf_pd_body_bond_rate(const pf_pd_body *b);

/* Stable step of store point i of body b: sqrt(2 rho / sum_j V_j c omega / |xi|) over its own
 * family (Silling & Askari 2005, eq. 15 with the Peridigm form); for LPS and elastic-plastic each
 * term times max(1, (g_i + g_j) / 4), g the family shortfalls (docs/theory/pd.md §4). */
double pf_pd_stable_dt_point(const pf_pd_body *b, const pf_points *pts, pf_int i, double c);
/* The Gershgorin bounds of store points first .. first + n - 1's block rows of the linearised
 * stiffness into k[0 .. n-1], N/m: sum_j |K_ij| <= 2 V_i sum_j V_j c_ij omega / |xi| = 4 m_i / dt_i^2,
 * c the micromodulus of the point's horizon (for LPS, elastic-plastic and correspondence the
 * PMB-equivalent of the body's bulk modulus), times the mean family shortfall of the bond's ends
 * beyond a factor 2 for LPS and elastic-plastic; dt_i no more than the smallest own stable step
 * over the point's family for correspondence; 0 for a point without bonds
 * (docs/theory/quasi_static.md §2).
 * Collective (the own steps' ghosts are exchanged). */
int pf_pd_body_stiffness_bounds(pf_pd_body *b, pf_points *pts, pf_int first, pf_int n, double *k);

#endif
