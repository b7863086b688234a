/* Private to pd/: the body structure and the material and damage plug-in tables. */
#ifndef PF_PD_IMPL_H
#define PF_PD_IMPL_H

#include "pd/pd.h"

#include <math.h>

enum { PF_PD_MAX_NO_FAIL = 8 }; /* regions in a body's damage.no_fail list */
/* Bonds that soften: a damage check in which some bond's damage grows by more than this (or a bond
 * fails) is followed by another relaxation at the same load (docs/theory/bond_failure.md §8). */
#define PF_PD_SOFT_TOL 1e-3

typedef struct pf_pd_material_ops pf_pd_material_ops;

/* How a point's internal force is formed (docs/theory/coupling.md §2). Standard: from the force
 * states of both ends of each bond. Partial stress (Silling & Seleson 2013; Littlewood 2014,
 * "Partial stress formulation"): the nonlocal divergence of nu = sum_j T<xi> (x) xi V_j. Auto:
 * partial stress at the interior points whose bond rows reach a point of another horizon (the
 * transition), standard elsewhere. Corrected: the standard force, less at the transition points
 * the ghost force it would give under their own uniform stress (§2.5). Consistent: the standard
 * (energy) form with the transition points' gradient weights corrected so that a uniform stress
 * gives no ghost force (§2.6). */
typedef enum { PF_PD_AUTO, PF_PD_STANDARD, PF_PD_PARTIAL_STRESS, PF_PD_CORRECTED, PF_PD_CONSISTENT } pf_pd_formulation;

enum { PF_PD_MAX_HISTORY_FIELDS = 8 };

/* Several materials in one body (the body's material_regions, pd/material_regions.c,
 * docs/theory/interfaces.md): part 0 is the body's own material, part q >= 1 the q-th entry's,
 * whose region claims the points it holds (later entries win). */
enum { PF_PD_MAX_PARTS = 16 };
typedef struct {
  char material[64]; /* its name under materials: */
  double density, K, G; /* kg/m^3, Pa, Pa */
  double kscale;     /* K / K of part 0: a bond-based micromodulus scales with it */
  double mscale;     /* P-wave modulus K + 4G/3 (K where G is not given) over part 0's: the
                        stable step's micromodulus scales with it */
  pf_region region;  /* the points it claims (part 0 and a block's entry: none) */
  const pf_node *block; /* its entry's `block` (the points of a block of the discretization), or NULL */
  const pf_node *node; /* its entry of material_regions (part 0: the body's `material`) */
} pf_pd_part;

/* How a bond-based micromodulus is formed across two materials (the body's interface map). */
typedef enum { PF_PD_INTERFACE_SERIES, PF_PD_INTERFACE_MEAN } pf_pd_interface_rule;

struct pf_pd_body {
  char name[64];
  char material[64];   /* its name under materials: */
  const pf_deck *deck; /* for error messages naming the deck position */
  const pf_node *node; /* this body's mapping in the deck */
  pf_int first, n;     /* owned points [first, first + n) of the store */
  int partial;         /* partial-volume fractions */
  int ncracks;
  pf_precrack *cracks;
  double horizon, density; /* horizon: the constant one, or the largest of a variable one */
  pf_expr *hz_expr;        /* a variable horizon delta(x, y, z, d_fe), or NULL */
  int coupled;             /* the nodes of an FE body (its `peridynamic:` map) */
  int uses_dfe;            /* coupled: the horizon expression names d_fe */
  pf_pd_distance_fn fe_distance; /* coupled: d_fe, the distance to where the elements act */
  const void *fe_ctx;
  pf_pd_fe_vector_fn fe_vector; /* coupled, energy form: the elements' uniform-stress vector */
  const void *fe_vector_ctx;
  pf_pd_formulation form;
  double *hz;              /* field "horizon" [store]: each point's own horizon, ghosts too */
  double *shortfall;       /* field "family_shortfall" [store] (family_stiffness materials, else
                              NULL): g_i = rho_top / rho_i >= 1, rho_i = m_i / m_whole(delta_i),
                              rho_top the body's fullest (at least 0.9) */
  double *region;          /* field "region" [store]: bit 0 (1) the partial-stress force, bit 1
                              (2) an overlap point (blending weight < 1), bit 2 (4) the
                              ghost-corrected standard force, bit 3 (8) the consistent
                              weights; 0: the PD region */
  const double *blend;     /* coupled to FE elements: each store point's blending weight, or NULL */
  int blend_states;        /* 1: each point's force state carries its blending weight (energy form) */
  uint8_t *idle;           /* [n] coupled: 1 where beta = 0 at the point and its whole row (no PD
                              force is wanted there, nor its state by a neighbour), or NULL */
  int one_sided;           /* rows may hold bonds outside a point's own family (variable
                              horizon, or the element neighbours of a coupled body's nodes) */
  double dt;           /* the step just taken, set by pf_pd_body_force (rate-form materials) */
  int fresh;           /* set by attach for the material's setup: 1 at t = 0, 0 after a re-partition
                          or a restart (the material's restart fields came with the points) */
  double bulk_modulus, shear_modulus;
  /* several materials: nparts >= 2 with material_regions, and then part (field "material",
   * ghosted: each store point's part index) is set at attach; nparts 1 and part NULL otherwise */
  int nparts;
  pf_pd_part parts[PF_PD_MAX_PARTS];
  double *part;
  uint8_t *block_part; /* [cloud size] by block entries: the part of each point of the body's cloud
                          (index gid - the body's first gid), 0 where no block entry claims it; NULL
                          without block entries. Coupled: each mesh node's part, from its elements
                          (pf_pd_body_set_node_parts), the regions then not tested */
  pf_gid nblock_part;
  pf_pd_interface_rule interface;
  /* the interface's own damage law (interface: damage:), for the bonds between two materials,
   * which then take it instead of the body's: */
  int interface_law;        /* 1: there is one */
  double interface_s0;      /* critical_stretch: their stretch limit (INFINITY: none) */
  double interface_wc;      /* critical_energy: their energy limit w_c, J/m^6 (INFINITY: none),
                               filled into wc_bond at attach (INFINITY for the other bonds) */
  pf_influence influence;
  pf_family fam;
  const pf_pd_material_ops *ops;
  void *mat; /* the material's own data */
  /* damage */
  const pf_pd_damage_ops *damage; /* the law (pd/damage_laws.h); "none" when the deck gives none */
  void *damage_data; /* the law's own parameters, or NULL (allocated by its read, freed with the body) */
  double s0_init;    /* initial critical stretch (INFINITY: no stretch limit; pf_pd_damage_ops) */
  int n_no_fail;     /* the deck's damage.no_fail: regions whose points start with s0 = INFINITY */
  pf_region no_fail[PF_PD_MAX_NO_FAIL];
  double critical_energy; /* the energy limit w_c, J/m^6 (INFINITY: none; pf_pd_damage_ops) */
  double *wc_bond;        /* [bonds] each bond's own w_c (critical_energy, calibration: family),
                             or NULL: every bond has critical_energy */
  double *s0;        /* field "critical_stretch": per point, used by the force kernels */
  /* A law whose bonds soften (law softening, pd/softening.c): s1 / s0 > 1, or 0 when the bonds
   * fail at once. Each bond's state (fam.state, nstate 2) is its largest stretch s_max and its
   * damage d, and it acts with the weight 1 - d (pf_pd_soft_weight). */
  double soft_ratio;
  double *soft_lost;   /* [n] LPS: sum_j d omega |xi|^2 V_j over each point's intact bonds (the
                          weighted volume the softening took; pf_pd_dilatation_moment) */
  int64_t soft_grown;  /* the bonds whose damage grew by more than PF_PD_SOFT_TOL, counted over the
                          run (the quasi-static solver relaxes again while it grows) */
  /* Under the quasi-static solver (pd/softening.c, pd/failures_kept.c): the bonds' state at the
   * load step's start (put back when a signal abandons it) and at the pass's start (the last
   * check's), each owned point's dilatation there (theta_stale: to be taken at the next
   * evaluation), and the pass: 0 dynamics, 1 the load step's first relaxation (the weights stay),
   * 2 a relaxation after a check (each evaluation's damage from the pass's start and the stretch
   * now, booked by the next check). */
  struct {
    double *kept, *base, *theta;
    int64_t n;      /* 2 x the bonds */
    pf_int npoints; /* the owned points of theta */
    int pass, theta_stale;
  } soft_qs;
  double *smin;      /* [n] smallest stretch of each point's intact bonds this step */
  double *lost_volume; /* field "lost_weighted_volume" of the LPS family (lps, elastic_plastic):
                          sum of omega |xi|^2 V_j over each point's failed bonds, added to by
                          pf_pd_lps_release; NULL for the other materials */
  uint8_t *lost;     /* [n] scratch of the threaded bond loops: 1 where the point's row has
                        PF_BOND_FRESH bonds, whose energy a serial pass then books */
  int rest_at_break; /* 1 once the body is in self-contact (pf_pd_body_record_breaks): the
                        releases of PMB and LPS give a failing bond its rest length at once */
  double damage_work; /* change of the stored energy when this rank's points lost bonds (the
                         energy with them less without, at the same positions) since it was last
                         taken (pf_pd_body_take_damage_work), J */
  double damage_redistribution; /* the part of damage_work that is not released but moved: the
                                   LPS dilatation's cross term where negative (docs/theory/pd.md
                                   §5.1), J, <= 0; taken by pf_pd_body_take_damage_redistribution */
  /* The material's history (pd/history.c): the point fields its force advances, by index, and
   * (with fam.nstate > 0) the bonds' state, committed by pf_pd_body_history into committed[]. */
  struct {
    int field[PF_PD_MAX_HISTORY_FIELDS], nfields;
    double *committed;
    size_t n;
  } history;
  /* The bonds' failures kept at a quasi-static load step's start (pd/failures_kept.c). */
  struct {
    uint8_t *broken;
    float *rest;
    uint64_t *recorded;
    int64_t nbonds;
  } kept;
  /* The law's limits while the damage is frozen (pf_pd_body_freeze_damage): the body then holds
   * none (s0 the all-INFINITY none_s0 [none_n], no energy limit), so no kernel fails a bond. */
  struct {
    int on;
    double *s0, s0_init, critical_energy, *wc_bond, interface_s0;
    double *none_s0;
    pf_int none_n;
  } frozen;
};

/* A material's setup names a point field its force advances as history (plastic or rate-form
 * state: pf_pd_body_history commits and restores it for the quasi-static solver); the bonds'
 * material state (fam.nstate > 0) is history without being named. */
int pf_pd_body_keep_history(pf_pd_body *b, int field);

/* A bond a force kernel fails is first marked PF_BOND_FRESH, so that the kernel can book the
 * energy it released (the point's stored energy with the bond less without it, at the same
 * positions) before marking it PF_BOND_BROKEN, all within one force pass. */
enum { PF_BOND_BROKEN = 1, PF_BOND_FRESH = 2 };

/* A material: one file, one line in pd/materials.h (docs/architecture.md §5). Required: create,
 * force, energy. Optional: setup (NULL: nothing to precompute), micromodulus (NULL: the
 * bulk-modulus estimate 18 K / (pi delta^4) is used for the time step). */
struct pf_pd_material_ops {
  const char *name;
  int (*create)(const pf_deck *d, const pf_node *mat, pf_pd_body *b);
  int (*setup)(pf_pd_body *b, pf_points *pts);
  int (*force)(pf_pd_body *b, pf_points *pts);
  double (*energy)(const pf_pd_body *b, const pf_points *pts);
  double (*micromodulus)(const pf_pd_body *b, double delta); /* c for the stable step */
  /* the body's current stable step, for a material whose step changes as it deforms (then
   * micromodulus is unused and the time loop asks for it every step); NULL: fixed */
  double (*stable_dt)(const pf_pd_body *b, const pf_points *pts);
  /* the points' own stable steps at the last evaluation, a store array whose owned entries are
   * set, where the material has them (they bound a point's stiffness where its family is cut
   * short: the quasi-static masses take them, pf_pd_body_stiffness_bounds); NULL: none */
  double *(*point_steps)(pf_pd_body *b);
  double (*critical_stretch)(const pf_pd_body *b, double G0); /* from G0, or NULL */
  void (*destroy)(pf_pd_body *b);
  int partial_stress; /* 1: takes a variable horizon and the partial-stress form */
  /* What else the material offers, asked by the body and the laws instead of which it is: */
  int gradient_forms; /* 1: takes the corrected and consistent forms (a deformation gradient) */
  int uses_velocity;  /* 1: its forces read the neighbours' velocities (a rate form) */
  int bond_energy;    /* 1: its force kernel evaluates each bond's energy (critical_energy law) */
  int family_stiffness; /* 1: a bond's stiffness goes as 1 / m of its ends' families (an ordinary
                           state: 15 G / m_i), so a bond of a family a face cuts short is stiffer
                           than a whole family's: the explicit step and the quasi-static
                           masses take it (pf_pd_stable_dt_point, pf_pd_body_stiffness_bounds) */
  /* With bond_energy: the energy per V_i V_j of bond k of owned point i (extension ext > 0, rest
   * length r0) at the last force evaluation's state, as its kernel's energy test evaluates it
   * (pf_pd_body_failure_ratio). */
  double (*bond_energy_at)(const pf_pd_body *b, pf_int i, int64_t k, double r0, double ext);
  int several_materials; /* 1: its kernels read each point's constants (pf_pd_K, pf_pd_G,
                            pf_pd_bond_stiffness): the body may have material_regions */
  int records_rest;   /* 1: every bond its kernels fail passes through its release, which gives
                         it its rest length (pf_pd_body_rest_at_break): pf_pd_body_record_breaks
                         scans only once */
  /* Read part q's material, the mapping mat named name under materials: (several materials;
   * optional, NULL: the keys density, bulk_modulus and shear_modulus of a model that must be the
   * body's): fill part's density, K and G, keep what else the material needs of it. */
  int (*read_part)(const pf_deck *d, const pf_node *mat, const char *name, pf_pd_body *b, int q, pf_pd_part *part);
  /* directed bond evaluations per second and rank measured on the project's 2-core benchmark
   * machine (87 451-point target, 150 steps), for perifem --check's run-time estimate; 0: the
   * rate of the other models, 1.5e8 */
  double bond_rate;
  const char *const *body_keys; /* keys of the body mapping only it reads (NULL-ended), or NULL */
  /* Its own rows of the material mapping besides model, density, bulk_modulus and shear_modulus
   * (PF_KEY_END-ended, or NULL; each description starts "<id>: "), assembled into
   * pf_pd_material_keys in list order. */
  const pf_key *keys;
};
/* Does material m read body key `key` (one of its body_keys)? */
int pf_pd_material_reads_key(const pf_pd_material_ops *m, const char *key);
/* The registered materials whose flag at byte offset `flag` of pf_pd_material_ops is set, comma
 * separated (for messages: "pmb, lps"). */
const char *pf_pd_material_names_with(size_t flag);

/* A damage law (bond failure): one file pd/damage_<id>.c defining pf_pd_damage_<id>, and one
 * line in pd/damage_laws.h (or, in a test, pf_pd_damage_register). A law owns its test by the
 * LIMITS it leaves in the body, which every force kernel compares against (pf_pd_stretch_fails,
 * pf_pd_energy_limit below), whatever the law:
 *   stretch: a bond fails when its stretch exceeds min(s0_i, s0_j) (both ends, as LAMMPS' peri
 *     pair styles), s0 the point field "critical_stretch" (b->s0), starting at b->s0_init or
 *     filled by attach, evolving by post_step; INFINITY where there is no limit;
 *   energy: a bond in tension fails when its energy per V_i V_j exceeds b->critical_energy, or
 *     the bond's own b->wc_bond[k]; INFINITY (and wc_bond NULL) when there is none. The
 *     material's force kernel evaluates the energy (pf_pd_material_ops.bond_energy).
 * The kernels never read the law. Required: name, read. Optional: keys (NULL: none besides
 * `law`), attach (NULL: every owned point starts at b->s0_init), post_step (NULL: s0 stays). */
struct pf_pd_damage_ops {
  const char *name; /* the deck's `law:` value (the <id>) */
  /* Its own rows of the `damage:` mapping besides `law` (PF_KEY_END-ended, or NULL; each
   * description starts "<id>: "), assembled into pf_pd_damage_keys; any other key of that table
   * in the deck is an error naming it. A key that several laws read is a row in each (the same
   * type, default and units), their descriptions joined in list order. */
  const pf_key *keys;
  /* Read its parameters from the body's `damage:` mapping (NULL when the deck has none; the
   * material is created): set its limits, b->s0_init (a finite value: the body has a stretch
   * limit) and b->critical_energy (finite: an energy limit), both INFINITY until it does, and
   * b->damage_data for parameters of its own. */
  int (*read)(const pf_deck *d, const pf_node *map, pf_pd_body *b);
  /* At attach, the field "critical_stretch" (b->s0) registered: when fresh, fill the owned
   * points' initial s0 (their ghosts follow); register any field of its own, or fill
   * b->wc_bond [bonds + PF_FAMILY_SLACK] (freed with the body). */
  int (*attach)(pf_pd_body *b, pf_points *pts, int fresh);
  /* After each step: update s0 from the step's b->smin, ghosts included. Collective. */
  int (*post_step)(pf_pd_body *b, pf_points *pts);
};

#define PF_PD_DAMAGE_LAW(id) extern const pf_pd_damage_ops pf_pd_damage_##id;
#include "pd/damage_laws.h"
#undef PF_PD_DAMAGE_LAW

/* The limits as the kernels read them, once per call (to choose a specialized loop): has the
 * body a stretch limit, an energy limit? */
static inline int pf_pd_stretch_limited(const pf_pd_body *b) { return isfinite(b->s0_init); }
static inline int pf_pd_energy_limited(const pf_pd_body *b) { return isfinite(b->critical_energy) || b->wc_bond; }
/* Does the bond i - j of stretch s exceed its stretch limit min(s0_i, s0_j), or, between two
 * materials of a body whose interface has its own law, the interface's? */
static inline int pf_pd_stretch_fails(const pf_pd_body *b, pf_int i, pf_int j, double s) {
  if (b->interface_law && b->part[i] != b->part[j]) return s > b->interface_s0;
  return s > fmin(b->s0[i], b->s0[j]);
}
/* The energy limit of bond k (per V_i V_j, J/m^6): its own, or the body's. */
static inline double pf_pd_energy_limit(const pf_pd_body *b, int64_t k) {
  return b->wc_bond ? b->wc_bond[k] : b->critical_energy;
}

/* pd/damage.c: the storage of pf_pd_damage_keys, for the body tables that nest it (filled by
 * pf_pd_damage_key_table, which every reader of those tables calls first). */
extern pf_key pf_pd_damage_key_rows[];
/* pd/damage.c: the law named name, or NULL; the known names, comma separated. */
const pf_pd_damage_ops *pf_pd_damage_find(const char *name);
const char *pf_pd_damage_names(void);
/* Read the body's damage law and its parameters (b->damage and what its read sets). */
int pf_pd_damage_read(const pf_deck *d, const pf_node *map, pf_pd_body *b);
/* The per-point s0 field: initial values when fresh (the law's attach); ghosts from owners. */
int pf_pd_damage_setup(pf_pd_body *b, pf_points *pts, int fresh);
/* The positive real *v of key, which this law requires (an error naming the key if absent). */
int pf_pd_damage_read_required(const pf_deck *d, const pf_node *map, const char *key, double *v);
/* pd/damage_critical_energy.c: the critical bond energy w_c = 4 G0 / (pi delta^4) (J/m^6). */
double pf_pd_critical_energy(double G0, double delta);

/* Non-ordinary correspondence (pd/material_correspondence.c): the body's material is a
 * continuum model of the constitutive library (fem/), not a name in pd/materials.h. */
extern const pf_pd_material_ops pf_pd_material_correspondence;
extern const pf_key pf_pd_hourglass_keys[];

#define PF_PD_MATERIAL(id) extern const pf_pd_material_ops pf_pd_material_##id;
#include "pd/materials.h"
#undef PF_PD_MATERIAL

/* Is the bond i -> j (reference length r0) in i's own family? Always, for a constant horizon;
 * with a variable one the rows also hold the bonds only j's family has (one-sided). Every kernel
 * computes r0 as sqrt of the same sum of squares, so all decide alike. */
static inline int pf_pd_in_family(const pf_pd_body *b, pf_int i, double r0) {
  return !b->one_sided || r0 <= b->hz[i];
}

/* Does store point i take the partial-stress force? The ghost-corrected one? */
static inline int pf_pd_partial_stress_at(const pf_pd_body *b, pf_int i) { return (int)b->region[i] & 1; }
static inline int pf_pd_corrected_at(const pf_pd_body *b, pf_int i) { return (int)b->region[i] & 4; }
static inline int pf_pd_consistent_at(const pf_pd_body *b, pf_int i) { return (int)b->region[i] & 8; }

/* May the damage law fail the bond i - j? Only between points of the standard force: the
 * partial-stress transition carries no damage (Littlewood 2014: "not a good candidate for modeling
 * material failure"). */
static inline int pf_pd_may_fail(const pf_pd_body *b, pf_int i, pf_int j) {
  return b->region[i] == 0 && b->region[j] == 0;
}

/* The weight of point i's energy: its blending weight beta_i when coupled in the energy form
 * (docs/theory/coupling.md §3.4), else 1. */
static inline double pf_pd_energy_weight(const pf_pd_body *b, pf_int i) {
  return b->blend && b->blend_states ? b->blend[i] : 1.0;
}

/* The material constants of store point i: its part's (several materials), else the body's. */
static inline const pf_pd_part *pf_pd_part_at(const pf_pd_body *b, pf_int i) {
  return &b->parts[b->part ? (int)b->part[i] : 0];
}
static inline double pf_pd_K(const pf_pd_body *b, pf_int i) { return b->part ? pf_pd_part_at(b, i)->K : b->bulk_modulus; }
static inline double pf_pd_G(const pf_pd_body *b, pf_int i) { return b->part ? pf_pd_part_at(b, i)->G : b->shear_modulus; }
static inline double pf_pd_density(const pf_pd_body *b, pf_int i) {
  return b->part ? pf_pd_part_at(b, i)->density : b->density;
}
/* The bond-based micromodulus factor of the bond i - j across materials, c_ij = c k (k the
 * parts' kscale): series 2 k_i k_j / (k_i + k_j) (the two half-bonds as springs in series) or
 * the mean (k_i + k_j) / 2; the same bits from either end. 1 within one material. */
static inline double pf_pd_bond_stiffness(const pf_pd_body *b, pf_int i, pf_int j) {
  const double ki = pf_pd_part_at(b, i)->kscale, kj = pf_pd_part_at(b, j)->kscale;
  if (ki == kj) return ki;
  return b->interface == PF_PD_INTERFACE_SERIES ? 2 * ki * kj / (ki + kj) : 0.5 * (ki + kj);
}
/* pd/material_regions.c: read the body's material_regions and interface (after its own material
 * and its damage law); at attach, each store point's part into the field "material". */
int pf_pd_parts_read(const pf_deck *d, const pf_node *body, const pf_node *materials, pf_pd_body *b);
int pf_pd_parts_attach(pf_pd_body *b, pf_points *pts, int fresh);
void pf_pd_parts_free(pf_pd_body *b);
/* The default of pf_pd_material_ops.read_part: the material mapping mat (named name) must be of the
 * body's model; its density, bulk_modulus and shear_modulus into part (checked by the caller). */
int pf_pd_part_read_constants(const pf_deck *d, const pf_node *mat, const char *name, const pf_pd_body *b,
                              pf_pd_part *part);

/* omega(r), inlined in the bond loops. */
static inline double pf_pd_omega(const pf_influence *w, double r) {
  switch (w->kind) {
  case PF_INFLUENCE_CONSTANT: return 1.0;
  case PF_INFLUENCE_INVERSE_DISTANCE: return 1.0 / r;
  case PF_INFLUENCE_GAUSSIAN: return exp(-r * r / (w->length * w->length));
  }
  return 1.0;
}

/* LPS's stable-step micromodulus (the PMB one of equal P-wave modulus) and its critical stretch
 * from G0 (Madenci & Oterkus 2014), shared by elastic_plastic (pd/material_lps.c). */
double pf_pd_lps_micromodulus(const pf_pd_body *b, double delta);
double pf_pd_lps_critical_stretch(const pf_pd_body *b, double G0);
/* The LPS strain energy per reference volume of store point i (Silling et al. 2007, eq. 92),
 * with the deviatoric extensions less ep[stride k] when ep is given (elastic_plastic), from the
 * batch records rec of every store point (pd/bond_batch.h, filled with the current positions). */
double pf_pd_lps_energy_density(const pf_pd_body *b, const double *rec, pf_int i, double theta, double m,
                                const double *ep, int stride);
/* The change of stored energy (J) when point i loses its PF_BOND_FRESH bonds, V_i (W_i - W_i'),
 * W_i' the LPS energy (with ep, as above) without them and with the dilatation they no longer
 * carry; its negative cross term (docs/theory/pd.md §5.1) is also added to
 * b->damage_redistribution. Marks them PF_BOND_BROKEN. */
double pf_pd_lps_release(pf_pd_body *b, const pf_points *pts, pf_int i, double m, const double *ep,
                         int stride);
/* The same, but the cross term into *redistribution instead of b->damage_redistribution: it
 * writes only point i's data (its row's flags, lost_volume[i]), so threads may call it for their
 * own points and add the two parts in point order after. */
double pf_pd_lps_release_point(pf_pd_body *b, const pf_points *pts, pf_int i, double m, const double *ep,
                               int stride, double *redistribution);

/* The batched LPS loops (pd/lps_batched.c), for a body of one horizon whose points all take
 * the standard force. Pass 1: theta of every owned point from records with s0 in REC_AUX
 * (pd/bond_batch.h), failing bonds on the critical stretch and booking the energy they held.
 * Pass 2: the forces, from records with Q = (3K - 5G) theta in REC_AUX and rm = 1 / m (store
 * points); fails bonds on the energy limit when the body has one and returns their number. */
void pf_pd_lps_batched_dilatation(pf_pd_body *b, const pf_points *pts, const double *rec, const double *m,
                                  double *theta);
int64_t pf_pd_lps_batched_force(pf_pd_body *b, pf_points *pts, const double *rec, const double *rm);

/* Ordinary state-based materials (LPS, elastic-plastic): the weighted volume
 * m_i = sum_j omega |xi|^2 V_j of the owned points (Silling et al. 2007, eq. 90) into m, then the
 * ghosts' values; an isolated point is an input error naming it (pd/body.c). */
/* Bond k of owned point i, failed in this force pass: in a body in self-contact, its rest length
 * now, the length pf_pd_body_record_breaks would give it at the contact's evaluation of the same
 * positions, where the bond's neighbour is still in cache. Threads may call it for their own rows. */
void pf_pd_body_rest_at_break(const pf_pd_body *b, const pf_points *pts, pf_int i, int64_t k);
int pf_pd_weighted_volumes(const pf_pd_body *b, pf_points *pts, double *m);
/* sum_i term(i) over the owned points, the terms evaluated by the threads and summed in point
 * order: the same bits for every thread count (NAN when out of memory). */
typedef double (*pf_pd_point_term)(const pf_pd_body *b, const pf_points *pts, pf_int i);
double pf_pd_body_point_sum(const pf_pd_body *b, const pf_points *pts, pf_pd_point_term term);

/* Partial stress (pd/partial_stress.c, docs/theory/coupling.md §2). The inverse shape tensor
 * of store point i over its own intact family into Ki (row-major); 0 (and Ki = 0) when its
 * bonds do not span space. */
double pf_pd_shape_tensor_inverse(const pf_pd_body *b, const pf_points *pts, pf_int i, double Ki[9]);
/* f_i += V_i div nu: the nonlocal divergence of the partial stress nu (row-major 3x3 at
 * nu[stride * j], for i and every neighbour, ghosts included) over i's own family. */
void pf_pd_partial_stress_force(const pf_pd_body *b, pf_points *pts, pf_int i, const double *nu,
                                int stride, const double Ki[9]);

/* Is store point i's own family complete (no free surface within its horizon: its first moment
 * |sum_j V_j xi| is at most 1 % of sum_j V_j |xi|)? S gets the first moment (pd/body.c). */
int pf_pd_family_complete(const pf_pd_body *b, const pf_points *pts, pf_int i, double S[3]);

/* The consistent form (pd/consistent.c; docs/theory/coupling.md §2.6). A transition point i (region
 * bit 8) forms Fbar_i = sum_k (y_k - y_i) (x) g_ik over its whole row, with
 *   g_ik = w V_k K_i^-1 xi [k in H_i] + h_ik,   h_ik = w V_k (Lambda_i xi + b_i V_i (mu_k - mu_i)),
 * w = omega(|xi|), and the force is the energy's: f_i += b_i V_i P_i g_ij - b_j V_j P_j g_ji, with b
 * the energy's weight (pf_pd_energy_weight: beta coupled in the energy form, else 1; the call's
 * Vi is b_i V_i). The multipliers
 * (PF_CONSISTENT_NLM reals per point: Lambda row-major, then mu) are a ghosted point field,
 * solved for once at t = 0 so that sum_k xi (x) h_ik = 0 at every transition point (Fbar stays
 * exact for a linear motion) and a uniform stress gives the force of a constant horizon
 * (pf_pd_consistent_solve; collective). t: each owned point's target of (C) (V_i d_i with d_i
 * the corrected form's ghost vector, §2.5, plus the blending's part in the energy form, §3.4). */
enum { PF_CONSISTENT_NLM = 12 };
int pf_pd_consistent_solve(const pf_pd_body *b, const pf_points *pts, const double *t, double *lm);
static inline void pf_pd_consistent_h(const double *restrict lmi, const double *restrict lmk, double w,
                                      double Vi, const double xi[3], double h[3]) {
  for (int a = 0; a < 3; a++)
    h[a] = w * (lmi[3 * a] * xi[0] + lmi[3 * a + 1] * xi[1] + lmi[3 * a + 2] * xi[2] + Vi * (lmk[9 + a] - lmi[9 + a]));
}

/* The volumetric coefficient of the LPS force state, t = w (a |xi| + alpha (e^d - e^dp)):
 * a = 3 K theta / m - alpha M / m with alpha = 15 G / m and M the dilatation moment of the
 * bonds that stay (docs/theory/materials.md §1, "Failed bonds"; 0 while a point has lost no bond, so that
 * a = 3 K theta / m bitwise, Silling et al. 2007). */
static inline double pf_pd_lps_volumetric(double K, double G, double theta, double M, double m) {
  return M == 0.0 ? 3 * K * theta / m : (3 * K * theta - 15 * G * M / m) / m;
}
/* Register the fields "lost_weighted_volume" (restarted; into b->lost_volume) and
 * "dilatation_moment" (ghosted; returned in *mom). */
int pf_pd_lost_volume_fields(pf_pd_body *b, pf_points *pts, double **mom);
/* The dilatation moment M_i = theta_i m^lost_i / 3 - sum_j w |xi| e^dp V_j of point i (the
 * second term given as pm), times beta (docs/theory/materials.md §1, "Failed bonds"); 0 while i lost no bond. */
static inline double pf_pd_dilatation_moment(const pf_pd_body *b, pf_int i, double theta, double pm,
                                             double beta) {
  const double ml = b->soft_lost ? b->lost_volume[i] + b->soft_lost[i - b->first] : b->lost_volume[i];
  return ml > 0 ? beta * (theta * ml / 3 - pm) : 0.0;
}

/* The weight 1 - d of bond k in a body whose bonds soften (its damage d in fam.state), else 1. */
static inline double pf_pd_soft_weight(const pf_pd_body *b, int64_t k) {
  return b->soft_ratio > 0 ? 1.0 - b->fam.state[2 * k + 1] : 1.0;
}
/* pd/softening.c (docs/theory/bond_failure.md §8). Before a force evaluation of a body whose bonds
 * soften: in dynamics and at a quasi-static damage check, each intact bond's s_max and d from the
 * current stretch (at a check, from the pass's start), the bonds at d = 1 failed, and the energy the
 * change dissipates booked into damage_work, each bond's dW/d(1 - d) integrated along its envelope
 * (PMB: m and theta NULL, c its micromodulus, the bond law's closed form; LPS: m the weighted
 * volumes, theta the dilatations of the last evaluation); in a quasi-static relaxation after a
 * check, the damage of this evaluation's stretch from the pass's start, nothing failed or booked;
 * in the load step's first relaxation, nothing. */
int pf_pd_softening_update(pf_pd_body *b, const pf_points *pts, double c, const double *m, const double *theta);
/* The PMB forces of a body whose bonds soften: f = (1 - d) c omega s V_j e / r, added to pts->f. */
void pf_pd_softening_pmb_force(pf_pd_body *b, pf_points *pts, double c);
/* Read s_c (from critical_stretch or from energy_release_rate through the material's closed form)
 * into b->s0_init: the stretch laws' common key pair (pd/damage_critical_stretch.c). */
int pf_pd_damage_read_stretch(const pf_deck *d, const pf_node *map, pf_pd_body *b);

/* The positions of the last force evaluation (PF_PREVIOUS_POSITIONS), or the current ones where
 * the integrator keeps none (a kernel driven alone, as in the unit tests). */
static inline const double *pf_pd_previous_positions(const pf_points *pts) {
  const double *yp = pf_points_field_get(pts, PF_PREVIOUS_POSITIONS);
  return yp ? yp : pts->y;
}

/* Bond geometry: reference length r0, current length r, current bond vector e[3]. The same
 * operations from either end give bitwise the same r0 and r. */
static inline void pf_pd_bond_lengths(const double *restrict X, const double *restrict Y, pf_int i,
                                      pf_int j, double *r0, double *r, double e[3]) {
  double d2 = 0, e2 = 0;
  for (int a = 0; a < 3; a++) {
    double d = X[3 * j + a] - X[3 * i + a];
    e[a] = Y[3 * j + a] - Y[3 * i + a];
    d2 += d * d, e2 += e[a] * e[a];
  }
  *r0 = sqrt(d2), *r = sqrt(e2);
}

/* Volume of bond b's neighbour j as seen from its owner: V_j times the partial-volume fraction. */
static inline double pf_pd_bond_volume(const pf_family *fam, const double *vol, int64_t b,
                                       pf_int j) {
  return fam->vfrac ? vol[j] * fam->vfrac[b] : vol[j];
}

/* Reference geometry of bond k (point i -> its neighbour j) if it is intact and in i's own
 * family: xi into xi[3], its length into *r0, its weight omega(|xi|) V_j into *w; else 0. */
static inline int pf_pd_own_bond(const pf_pd_body *b, const pf_points *pts, pf_int i, int64_t k,
                                 double xi[3], double *r0, double *w) {
  const pf_family *fam = &b->fam;
  if (fam->broken[k]) return 0;
  const pf_int j = fam->neighbor[k];
  double r02 = 0;
  for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r02 += xi[a] * xi[a];
  *r0 = sqrt(r02);
  if (!pf_pd_in_family(b, i, *r0)) return 0;
  *w = pf_pd_omega(&b->influence, *r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
  return 1;
}

#endif
