/* Private to the contact module (the files of contact/). */
#ifndef PF_CONTACT_IMPL_H
#define PF_CONTACT_IMPL_H

#include "contact/contact.h"

#include <math.h>

typedef struct pf_contact_pair pf_contact_pair;
typedef struct pf_contact_side pf_contact_side;
typedef struct pf_contact_eval pf_contact_eval;

/* The two bodies of a pair, of which a method claims one: two PD bodies (or a PD body with
 * itself), an FE body and a PD body (the pair's body a the FE one), two FE bodies. */
typedef enum { PF_CONTACT_PD_PD, PF_CONTACT_FE_PD, PF_CONTACT_FE_FE, PF_CONTACT_NCASES } pf_contact_case;

/* A method's candidates: view entities of the pair's other body (binned with the view), or
 * faces of the side the entity's body faces (binned in the face sets of search.c). */
typedef enum { PF_CONTACT_PARTNER_POINTS, PF_CONTACT_PARTNER_FACES } pf_contact_partner;

/* A contact method (how the two bodies of a pair push on each other): one file
 * contact/method_<id>.c defining pf_contact_method_<id>, and one line in contact/methods.h. The
 * generic code (contact.c: the deck, the stable step, the gap; search.c: the candidates; pairs.c:
 * the loop over each entity's candidates, the sums, the FE nodes' shares) reads the method's
 * flags and calls its ops, never its name. Required: id, claims, read, evaluate, stable_w2.
 * Optional (their defaults applied by one dispatcher each, contact.c): name (NULL: the method
 * takes no `method:` key), length (r_c), self_rest_lengths (0), side_rebuilt (nothing), the flags
 * (0). */
typedef struct {
  const char *id;        /* the <id> (messages, tests) */
  const char *name;      /* the deck's `method:` value that picks it for its case (one name may
                          * serve several cases: `surface`); NULL: no `method:` key */
  pf_contact_case claims;
  pf_contact_partner partners;
  int fe_entities;       /* 1: an FE node of the pair has candidates too (each FE body's nodes meet
                          * the other's faces); 0: a particle's owner computes each of its
                          * interactions with FE nodes, whose shares travel to the nodes' owners */
  int bonds;             /* 1: a candidate of the entity's own body carries the bond of the
                          * entity's family to it, resolved at each build (pf_candidate.bond) */
  int signed_gap;        /* 1: the gap is a signed distance from a surface (pf_contact_gap.surface) */
  int candidate_work;    /* the cost of one candidate at a force evaluation, in the bond
                          * evaluations of the partition's weights (pf_contact_work; 0: 1) */
  int pushes;            /* 1: its forces go through pf_contact_push, whose friction the quasi-static
                          * solver takes as a tangential penalty on the committed slip */
  int holds_offsets;     /* 1: against the surface of a body that deletes elements, a particle
                          * keeps the penetration it had when a face was uncovered under it (the
                          * point fields "contact_offset", "contact_reach": pairs.c) */
  /* Read the pair's keys from its `pairs:` entry map (bodies, name and friction are read by
   * contact.c) and set p's radius, stiffness, sides and what else it reads; refuse the keys of
   * other methods. a, b: the pair's bodies (FE <-> PD: a the FE body). When the deck's `method:`
   * names no method of the pair's case and the case has at most one method with a name, the
   * case's first method reads the pair and refuses the value in its own words. */
  int (*read)(const pf_deck *d, const pf_node *map, const pf_contact_body *a, const pf_contact_body *b,
              pf_contact_pair *p);
  /* The interactions of owned entities [e0, e1), in turn, with their candidates of pair k among
   * [q0, q1) (c->cand; each entity's sorted by partner, pf_contact_entity_candidates): add the
   * force on each to c->force, the shares of FE nodes it pushes (pf_contact_push), and the
   * energy, dissipation, pair force and gap to w's sums. The pair loop (pairs.c) calls it once for
   * a run of entities whose candidates are all of pair k, else once for an entity and a pair: the
   * loops over the entities and the candidates are the method's. */
  int (*evaluate)(pf_contact *c, int k, pf_int e0, pf_int e1, int64_t q0, int64_t q1, double dt,
                  pf_contact_eval *w);
  /* omega^2 of the stiffest contact a point of the pair can see (the stable step is 2 / omega).
   * Collective. */
  double (*stable_w2)(const pf_contact *c, const pf_contact_pair *p, const pf_points *pts);
  /* The scale of the pair's gap (pf_contact_pair_gap) and its share of the default skin, m. */
  double (*length)(const pf_contact *c, const pf_contact_pair *p);
  /* 1 when the pair, a body with itself, needs the rest lengths of its broken bonds. */
  int (*self_rest_lengths)(const pf_contact_pair *p);
  /* After the faces of side sd of FE body fe were rebuilt (elements deleted): the side's data of
   * the method's own. */
  int (*side_rebuilt)(const pf_contact_body *fe, pf_contact_side *sd);
} pf_contact_method;

#define PF_CONTACT_METHOD(id) extern const pf_contact_method pf_contact_method_##id;
#include "contact/methods.h"
#undef PF_CONTACT_METHOD

/* The surface of an FE body in a pair: its faces (mesh node indices). */
struct pf_contact_side {
  int body;
  int sideset;       /* the side set of the body's mesh, or -1: its whole boundary */
  pf_contact_face *face;
  pf_int nface;
  double size;       /* largest node-to-node distance of a face at the last build, m */
  pf_int *node_off;  /* method surfaces: [nnodes + 1] CSR of the faces of each mesh node */
  pf_int *node_face;
  uint8_t *fresh;    /* [nface] or NULL: 1 for a face a deletion uncovered at this evaluation */
};

/* One entry of `contact: pairs:`. */
struct pf_contact_pair {
  char name[64];
  const pf_contact_method *method;
  int a, b;          /* bodies; FE <-> PD: a the FE body, b the PD body */
  int all_points;    /* short range: also between bonded points */
  double radius;     /* contact radius r_c, m */
  double stiffness;  /* short range: C in f = C (r_c - r) V_i V_j (N/m^7); FE: k in f = k (r_c - g) (N/m) */
  double friction;   /* Coulomb coefficient */
  double tangential; /* quasi-static friction: the tangential penalty k_t, N/m (methods that push) */
  int soft;          /* the stiffness lowered, at set-up, until the pair's stable step is its bodies'
                      * (pf_contact_soften) */
  int nside;         /* 0 (short range), 1 (FE <-> PD: body a's surface), 2 (FE <-> FE: a's, then b's) */
  pf_contact_side side[2];
  double force[3];   /* total force on body a at the last evaluation (all ranks), N */
  double gap;        /* smallest gap of this rank's interactions at the last evaluation over the
                      * pair's length (surface pairs: signed, negative behind the surface;
                      * point pairs: centre distance over r_c); INFINITY: none within reach */
  double length;     /* the gap's scale: r_c, or half the finer spacing when r_c = 0 (FE <-> FE) */
};

/* The side of pair p whose faces the entities of body `body` meet: the other body's
 * (two sides), else the FE body's. */
static inline const pf_contact_side *pf_contact_facing(const pf_contact_pair *p, int body) {
  return p->nside == 2 && body == p->a ? &p->side[1] : &p->side[0];
}

/* A uniform grid of bins over a set of points (counting sort, O(n + bins)). */
typedef struct {
  double lo[3], cell;
  int dim[3];
  pf_int *start; /* [nbins + 1] */
  pf_int *item;  /* [n] */
} pf_grid;

/* Per owned entity: the candidates found at the last build, sorted by (pair, partner gid). The
 * sort key is needed only while the list is built and sorted; then a short-range candidate holds
 * in its place the bond that joins the two points, resolved once a build (search.c), so that the
 * force evaluation of each step reads the bond's broken flag instead of searching the family. */
typedef struct {
  int32_t pair;
  pf_int j;        /* view index (short range, nodes) or face index of the pair (surface) */
  union {
    pf_gid key;    /* during the build: partner gid (short range, nodes) or face index (surface) */
    int64_t bond;  /* after it, short range: the bond of the owned particle's family to the
                    * partner (-1: another body, or never bonded) */
  };
} pf_candidate;

struct pf_contact {
  int npairs;
  pf_contact_pair *pair;
  int nbodies;
  pf_contact_body *body;  /* [nbodies] */
  uint8_t *body_used;     /* [nbodies] the body takes part in some pair */
  uint8_t **surface_node; /* [nbodies] FE bodies: [nnodes] 1 when on a pair's surface */
  long *eroded_seen;      /* [nbodies] FE bodies: deleted elements when the surfaces were built */
  double skin;
  int has_fe;             /* some pair is FE <-> PD: node shares travel between ranks */
  /* the view: owned entities (points of contact bodies: PD particles, FE surface nodes), then
   * ghosts received from other ranks at the last build */
  pf_int nown, nview;
  pf_int *local;          /* [nown] store index of each owned entity */
  pf_gid *gid;            /* [nview] */
  int32_t *vbody;         /* [nview] body index */
  int *rank;              /* [nview] owner rank */
  double *y, *v, *vol, *m; /* [3 nview], [3 nview], [nview], [nview] */
  double *offset; /* the point field "contact_offset" (NULL: no pair meets a surface that deletes
                   * elements): a particle's penetration held at its birth (pairs.c surface) */
  double *reach;  /* the point field "contact_reach" (2 a point: in reach of such a surface at the
                   * previous evaluation, at this one) */
  double *rad; /* [nview] a point's own contact radius (the point field "contact_radius" where
                  positive: a particle made from an element, fem/particles.c), else INFINITY */
  double *X;              /* [3 nview] reference positions (short range within a body; the
                           * relative displacement of quasi-static friction) */
  /* quasi-static friction (pf_contact_quasi_static): the point field "contact_slip" at this
   * evaluation (4 a point: the committed slip relative to the surface point it meets, and 1 when
   * set, 0 while the point has been near no surface at a load step's equilibrium), else NULL;
   * while the slips are committed, PF_CONTACT_COMMIT doubles an owned entity (else NULL): the
   * sums of its pushes' new slips weighted by their normal forces, and of their slip increments'
   * work, then its displacement relative to the nearest surface point within the search's reach
   * that does not push it, and that point's distance */
  int static_friction;
  double *slip, *commit;
  double *y_build;        /* [npairs][3 nown] positions at each pair's last build */
  uint8_t *stale;         /* [npairs] the pair's candidates are rebuilt at this build */
  long *built_at;         /* [npairs] the build (rebuilds count) that last rebuilt the pair */
  pf_int cap;             /* room in the view arrays */
  /* ghost exchange lists of the last build */
  int nranks;
  int *scount, *sdispl, *rcount, *rdispl; /* [nranks] entities */
  pf_int *send;           /* [sum scount] view index of each entity sent */
  pf_exchange *exchange;  /* the plan of those sends (core/exchange.c) */
  /* FE nodes: view index of each mesh node of each FE body in a pair (-1: not in the view) */
  pf_int **node_view;     /* [nbodies][nnodes] */
  /* candidates of each owned entity: CSR */
  int64_t *cand_off;      /* [nown + 1] */
  pf_candidate *cand;
  int64_t cand_cap;
  int built;
  int prepared; /* the search was done ahead of this force evaluation (pf_contact_prepare) */
  /* work counters (pf_contact_counts): candidate pairs tested at the force evaluations, and
   * family entries read to tell whether a pair is bonded (at the builds and the evaluations) */
  int64_t pairs_tested, family_reads;
  /* results */
  double *force;          /* [3 nown] contact force of the last evaluation */
  long rebuilds;
  double seconds;
};

/* contact/search.c */
int pf_contact_grid_build(pf_grid *g, pf_int n, const double *x, double cell);
void pf_contact_grid_free(pf_grid *g);
/* The bins overlapping the box [p - r, p + r]: lo/hi bin ranges (inclusive), clamped. */
void pf_contact_grid_range(const pf_grid *g, const double p[3], double r, int lo[3], int hi[3]);
/* Refresh the owned entities' y, v from the store and the ghosts' from their owners. */
int pf_contact_exchange(pf_contact *c, const pf_points *pts);
/* Rebuild when two entities of a pair's bodies may have moved relative to each other by more
 * than the skin since the pair's last build (or never built): the ghosts, and the candidate
 * lists of those pairs. Collective. */
int pf_contact_search(pf_contact *c, const pf_points *pts);
/* Owned entities from the bodies' owned ranges (after attach). */
int pf_contact_collect_owned(pf_contact *c, const pf_points *pts);

/* contact/pairs.c */
/* The commit scratch of an entity (pf_contact.commit): new slips x normal force (3), normal force,
 * slip work, relative displacement to the nearest surface point out of contact (3), its distance. */
enum { PF_CONTACT_COMMIT_WORK = 4, PF_CONTACT_COMMIT_NEAR = 5, PF_CONTACT_COMMIT_DIST = 8, PF_CONTACT_COMMIT = 9 };
/* While the slips are committed: entity e is distance d from the surface point sum_q wt_q x_q
 * (view entities nv[nn]) of a pair with friction, beyond its contact radius; the nearest such
 * point gives its slip when nothing pushes it (it then starts to stick from there). */
void pf_contact_slip_near(pf_contact *c, pf_int e, const pf_int *nv, int nn, const double *wt, double d);
/* Regularized Coulomb friction (pairs.c file head) on the side moving at vrel relative to the
 * other, pressed with the normal force Fn >= 0 along the unit normal n, m the (reduced) mass:
 * the tangential force into ft[3] (zero when mu, dt or the sliding is zero); returns the work
 * dissipated over dt, |F_t| |v_t| dt. Used by the pairs and the rigid surfaces. */
double pf_contact_friction(double mu, double Fn, const double n[3], const double vrel[3], double m, double dt,
                           double ft[3]);
int pf_contact_pairs_evaluate(pf_contact *c, double dt, double *energy, double *dissipation);

/* A chunk's sums (pairs.c): sums[PF_CONTACT_SUM_ENERGY], sums[PF_CONTACT_SUM_DISSIPATION], pair
 * k's force at sums[PF_CONTACT_SUM_FORCE + 3 k], and after the forces pair k's smallest gap over
 * its length at sums[PF_CONTACT_SUM_FORCE + 3 npairs + k] (a minimum, not a sum). */
enum { PF_CONTACT_SUM_ENERGY, PF_CONTACT_SUM_DISSIPATION, PF_CONTACT_SUM_FORCE };

/* Pair k's smallest gap over its length in a chunk's sums: takes gap if it is smaller. */
static inline void pf_contact_gap_note(double *sums, const pf_contact *c, int k, double gap) {
  double *slot = &sums[PF_CONTACT_SUM_FORCE + 3 * c->npairs + k];
  *slot = fmin(*slot, gap);
}
/* What a method's evaluate adds to, for a chunk of owned entities (pairs.c). */
typedef struct pf_contact_shares pf_contact_shares;
struct pf_contact_eval {
  double *sums;               /* the chunk's sums (above) */
  pf_contact_shares *shares;  /* the FE nodes' shares of the forces (pf_contact_push) */
  int64_t tested, reads;      /* work counters (pf_contact_counts) */
};
/* The candidates [*s, *t) of entity e of an evaluate call over candidates [q0, q1). */
static inline void pf_contact_entity_candidates(const pf_contact *c, pf_int e, int64_t q0, int64_t q1, int64_t *s,
                                                int64_t *t) {
  *s = c->cand_off[e] > q0 ? c->cand_off[e] : q0;
  *t = c->cand_off[e + 1] < q1 ? c->cand_off[e + 1] : q1;
}
/* Push entity e by f = k (r_c - g) n + friction against a surface point of body `body` with
 * weights wt on the view entities nv[nn] (n outward of that body, towards e); the nodes' shares
 * go to the evaluation's list. The pair's force is the force on its body a: e's when e belongs to
 * a, else the nodes'. */
int pf_contact_push(pf_contact *c, int k, int body, pf_int e, const pf_int *nv, int nn, const double *wt, double g,
                    const double n[3], double dt, pf_contact_eval *w);
/* Entity e (a particle, or with fe_node an FE node of a pair of FE bodies) against the closest
 * face among its candidates [q0, q1) of pair k, pushed by pf_contact_push when within r_c;
 * may_uncover: faces of a body that deletes elements hold the penetration of the particles
 * they are uncovered under (the pair's method holds_offsets). */
int pf_contact_closest_face(pf_contact *c, int k, pf_int e, int64_t q0, int64_t q1, double dt, pf_contact_eval *ev,
                            int fe_node, int may_uncover);

/* contact/contact.c: helpers of the methods' readers and stable steps */
/* The faces of FE body `fe` (index b) in contact: the side set named by the scalar `node` under
 * `key`, or the whole boundary when node is NULL. */
int pf_contact_side_read(const pf_deck *d, const pf_node *node, const char *key, const pf_contact_body *fe, int b,
                         pf_contact_side *side);
/* The first of keys[] (NULL-ended) present in map is an error: "'<key>' is <why>". */
int pf_contact_refuse_keys(const pf_deck *d, const pf_node *map, const char *const *keys, const char *why);
/* Smallest mass of the owned points of body b over the ranks (a dormant point counts with
 * density times volume). Collective. */
double pf_contact_min_mass(const pf_contact_body *b, const pf_points *pts);
/* omega^2 of a point of mass m and spacing h pressed with stiffness k on a face of spacing l
 * whose node of mass m_f carries up to (sqrt 2 l / h)^2 such points. */
double pf_contact_node_on_face_w2(double k, double m, double h, double mf, double l);

/* The reader and the stable step of the FE <-> PD methods (surface, nodes): body a's surface (the
 * side set under `surface`, default its whole boundary), r_c = h/2 and k = K h of the PD body. */
int pf_contact_fe_pd_read(const pf_deck *d, const pf_node *map, const pf_contact_body *fe, const pf_contact_body *pd,
                          pf_contact_pair *p);
double pf_contact_fe_pd_stable_w2(const pf_contact *c, const pf_contact_pair *p, const pf_points *pts);
/* The keys only short-range pairs read (contact/method_short_range.c), NULL-ended. */
extern const char *const pf_contact_short_range_keys[];

/* The dispatchers of the methods' optional ops (contact.c), each applying the op's default. */
double pf_contact_method_length(const pf_contact *c, const pf_contact_pair *p);
int pf_contact_method_self_rest_lengths(const pf_contact_pair *p);
int pf_contact_method_side_rebuilt(const pf_contact_method *m, const pf_contact_body *fe, pf_contact_side *sd);
/* The registered methods (contact/methods.h), in list order, and their count; the method that
 * `method:` value name (NULL: none given) picks for case cs, or NULL. */
extern const pf_contact_method *const pf_contact_methods[];
extern const int pf_contact_nmethods;
const pf_contact_method *pf_contact_method_find(pf_contact_case cs, const char *name);

#endif
