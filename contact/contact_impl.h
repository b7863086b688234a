/* Private to contact/contact.c, search.c and pairs.c. */
#ifndef PF_CONTACT_IMPL_H
#define PF_CONTACT_IMPL_H

#include "contact/contact.h"

/* SURFACE: PD particles against an FE surface; NODES: PD particles against FE surface nodes;
 * SURFACES: two FE bodies, each one's surface nodes against the other's surface (two-pass). */
typedef enum { PF_PAIR_SHORT_RANGE, PF_PAIR_SURFACE, PF_PAIR_NODES, PF_PAIR_SURFACES } pf_pair_kind;

/* The surface of an FE body in a pair: its faces (mesh node indices). */
typedef struct {
  int body;
  int sideset;       /* the side set of the body's mesh, or -1: its whole boundary */
  pf_contact_face *face;
  pf_int nface;
  double size;       /* largest node-to-node distance of a face at the last build, m */
  pf_int *node_off;  /* SURFACES: [nnodes + 1] CSR of the faces of each mesh node */
  pf_int *node_face;
  uint8_t *fresh;    /* [nface] or NULL: 1 for a face a deletion uncovered at this evaluation */
} pf_contact_side;

/* One entry of `contact: pairs:`. */
typedef struct {
  char name[64];
  pf_pair_kind kind;
  int a, b;          /* bodies; SURFACE / NODES: a the FE body, b the PD body */
  int all_points;    /* short range: also between bonded points */
  double radius;     /* contact radius r_c, m */
  double stiffness;  /* short range: C in f = C (r_c - r) V_i V_j (N/m^7); FE: k in f = k (r_c - g) (N/m) */
  double friction;   /* Coulomb coefficient */
  int nside;         /* SURFACE / NODES: 1 (body a's surface); SURFACES: 2 (a's, then b's) */
  pf_contact_side side[2];
  double force[3];   /* total force on body a at the last evaluation (all ranks), N */
  double gap;        /* smallest gap of this rank's interactions at the last evaluation over the
                      * pair's length (surface pairs: signed, negative behind the surface;
                      * point pairs: centre distance over r_c); INFINITY: none within reach */
  double length;     /* the gap's scale: r_c, or half the finer spacing when r_c = 0 (FE <-> FE) */
} pf_contact_pair;

/* The side of pair p whose faces the entities of body `body` meet: the other body's
 * (SURFACES), else the FE body's. */
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
  double margin;          /* ghost margin of the last build, m */
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
  double *X;              /* [3 nview] reference positions (short range within a body) */
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
/* Rebuild when some entity of a pair's bodies moved more than half the skin since the pair's
 * last build (or never built): the ghosts, and the candidate lists of those pairs. Collective. */
int pf_contact_search(pf_contact *c, const pf_points *pts);
/* Owned entities from the bodies' owned ranges (after attach). */
int pf_contact_collect_owned(pf_contact *c, const pf_points *pts);

/* contact/pairs.c */
/* Regularized Coulomb friction (pairs.c file head) on the side moving at vrel relative to the
 * other, pressed with the normal force Fn >= 0 along the unit normal n, m the (reduced) mass:
 * the tangential force into ft[3] (zero when mu, dt or the sliding is zero); returns the work
 * dissipated over dt, |F_t| |v_t| dt. Used by the pairs and the rigid surfaces. */
double pf_contact_friction(double mu, double Fn, const double n[3], const double vrel[3], double m, double dt,
                           double ft[3]);
int pf_contact_pairs_evaluate(pf_contact *c, double dt, double *energy, double *dissipation);

#endif
