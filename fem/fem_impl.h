/* Private to fem/: hourglass vectors and the FE body structure. */
#ifndef PF_FEM_IMPL_H
#define PF_FEM_IMPL_H

#include "fem/fem.h"

/* ---- Flanagan-Belytschko hourglass control (fem/hourglass.c) ---- */
typedef enum { PF_HG_NONE, PF_HG_VISCOUS, PF_HG_STIFFNESS } pf_hourglass_kind;
/* gamma[a][I] = Gamma_aI - B_iI sum_J Gamma_aJ x_iJ (FB 1981, eq. 57). */
void pf_hex8_hourglass_vectors_lanes(double x[8][3][PF_HEX8_LANES], double B[8][3][PF_HEX8_LANES],
                                     double gamma[4][8][PF_HEX8_LANES]);

/* ---- FE bodies ---- */
#define PF_FEM_CHUNK 64 /* elements per batched material call */
#define PF_FEM_MAX_MATERIALS 32 /* materials of one body (`material` and `material_regions`) */
#define PF_FEM_MAX_STATE_NAMES 16 /* the output's state fields of one body */

/* One material of an FE body and the constants its elements read (fem/materials.c). */
typedef struct {
  pf_material *mat;
  double rho, K, G; /* reference density, small-strain bulk and shear moduli */
  int nstate;       /* its history variables per quadrature point (<= the body's stride) */
  int eqps;         /* the index of its "eqps" state, or -1 */
} pf_fem_material;

struct pf_fem_body {
  char name[64];
  const pf_deck *deck;
  const pf_node *node;
  pf_mesh mesh; /* the whole mesh, read on every rank */
  int nmat;                /* materials: [0] the body's `material`, then those `material_regions` add */
  pf_fem_material mats[PF_FEM_MAX_MATERIALS];
  uint8_t *mesh_entry;     /* [mesh.nelem] the material_regions entry (1, 2, ...) that gave each
                              element its material, 0 the body's `material`; NULL with one */
  uint8_t entry_mat[UINT8_MAX + 1]; /* each entry's material (entry 0: the body's, material 0) */
  int nnames;              /* the output's state fields: the union of the materials' state names */
  const char *names[PF_FEM_MAX_STATE_NAMES];
  int8_t slot[PF_FEM_MAX_MATERIALS][PF_FEM_MAX_STATE_NAMES]; /* material m's index of name k, or -1 */
  int bbar; /* 0: one-point + hourglass control; 1: selective-reduced 2x2x2 (B-bar) */
  int nqp;  /* quadrature points per element: 1 or 8 */
  int nstate; /* state stride per quadrature point: the largest of the materials' nstate */
  pf_hourglass_kind hg;
  double hg_coef;
  double bv_linear, bv_quadratic; /* bulk viscosity C_l, C_q */
  double *node_volume;            /* [mesh.nnodes] lumped nodal volume (the points' vol) */
  int64_t *mesh_node_off;         /* [mesh.nnodes + 1] CSR: the elements of each mesh node */
  pf_int *mesh_node_item;         /* ascending element indices */
  /* this rank */
  pf_gid gid0;       /* global id of mesh node 0 */
  pf_int first, n;   /* owned nodes [first, first + n) of the store */
  pf_int nel;        /* elements with an owned node, ascending global element index */
  pf_int *eid;       /* [nel] mesh element index */
  pf_int *conn;      /* [8 nel] store index of each node */
  uint8_t *own;      /* [nel] this rank owns the element (owns its node 0): sums and output */
  double *sigma;     /* [6 nqp nel] Cauchy stress */
  double *state;     /* [nstate nqp nel] material history */
  double *hgq;       /* [12 nel] hourglass generalized forces Q_ia of the last evaluation (the
                        stiffness form's state; the viscous form's, for the work's trapezoid) */
  double *bvq;       /* [nel] bulk-viscosity pressure q of the last evaluation, Pa */
  double *ref;       /* [25 nel] reference mean gradient B0 (24) and volume V0 */
  double *fe;        /* [24 nel] element nodal forces of the last evaluation */
  double *energy;    /* [3 nel] internal (stress work), hourglass, bulk-viscosity work, J */
  int64_t *node_off; /* [n + 1] CSR: elements of each owned node */
  pf_int *node_item; /* element * 8 + corner, ascending element */
  double *buf;       /* chunk scratch, one per thread (pf_fem_chunk_doubles each) */
  int nbuf;          /* threads buf has room for */
  /* blending with another operator on the same nodes (coupling/, pf_fem_body_set_blending) */
  pf_fem_weight_fn beta_fn;  /* beta(x): the other operator's weight, or NULL (no blending) */
  const void *beta_ctx;
  double *share; /* [nel] 1 - the mean beta of each element's nodes (pf_fem_body_set_blending_field),
                    or NULL (no blending) */
  /* erosion (fem/erosion.c) */
  int erosion;          /* some limit is set */
  double erode_eqps, erode_jmin, erode_jmax;
  uint8_t *mesh_eroded; /* [mesh.nelem] deleted elements, the same on every rank */
  long n_eroded;
  pf_gid *due;          /* [nel] elements found due at the last evaluation, mesh indices */
  pf_int n_due;
  /* conversion of deleted elements into particles (`convert_to_particles:`, fem/particles.c) */
  int convert;              /* deleted elements become particles */
  uint8_t *mesh_converted;  /* [mesh.nelem] deleted elements already converted (every rank) */
  double *wmass;            /* [8 nel] each local element's lumped-mass share at its corners, kg */
  pf_points *pts;           /* the store of the last attach (masses are recomputed on conversion) */
  double *committed; /* [ncomp nel] the elements' committed state (pf_fem_body_history), or NULL */
  pf_int committed_nel;
  double stable_dt;  /* from the last force evaluation */
  double t;          /* time and step of the evaluation, for error messages */
  long step;
};

/* fem/materials.c: the body's `material` and `material_regions` (each element's material, the
 * union of the state names); element e's (local) material; the initial state of the local
 * elements; the batched constitutive update of chunk elements [e0, e0 + ne), one
 * pf_material_update per run of elements of one material (scratch: room for
 * PF_FEM_CHUNK nqp nstate doubles). */
extern const pf_key pf_fem_material_region_keys[];
int pf_fem_materials_read(pf_fem_body *b, const pf_deck *d, const pf_node *body, const pf_node *materials);
int pf_fem_materials_regions(pf_fem_body *b, const pf_deck *d, const pf_node *body, const pf_node *materials);
void pf_fem_materials_destroy(pf_fem_body *b);
static inline int pf_fem_mesh_material(const pf_fem_body *b, pf_int ge) { /* mesh element ge's material */
  return b->mesh_entry ? b->entry_mat[b->mesh_entry[ge]] : 0;
}
static inline const pf_fem_material *pf_fem_element_material(const pf_fem_body *b, pf_int e) {
  return &b->mats[pf_fem_mesh_material(b, b->eid[e])];
}
int pf_fem_materials_init(pf_fem_body *b);
void pf_fem_materials_update(pf_fem_body *b, pf_int e0, pf_int ne, double dt, const double *F, const double *D,
                             double *c, double *scratch);

/* fem/erosion.c: the `erosion:` map; whether element e (local) has reached a limit at volume
 * ratio J; every rank's due elements merged into mesh_eroded (collective). */
extern const pf_key pf_fem_erosion_keys[];
int pf_fem_erosion_read(pf_fem_body *b, const pf_deck *d, const pf_node *body);
int pf_fem_erosion_due(const pf_fem_body *b, pf_int e, double J);
int pf_fem_erosion_sync(pf_fem_body *b);
/* fem/body_assembly.c: the owned nodes' lumped masses from the elements not converted into
 * particles, each node summing its elements' shares in ascending element order. */
void pf_fem_lumped_masses(const pf_fem_body *b, pf_points *p);
static inline int pf_fem_element_eroded(const pf_fem_body *b, pf_int e) {
  return b->erosion && b->mesh_eroded[b->eid[e]];
}

/* fem/element_force.c: element forces of the body's local elements into b->fe, energies and
 * the stable step; returns 0 or an error naming a negative-Jacobian element. */
int pf_fem_elements_evaluate(pf_fem_body *b, const pf_points *pts, double dt);

size_t pf_fem_chunk_doubles(int nqp, int nstate);

#endif
