/* perifem finite elements: hexahedral meshes (gmsh, Exodus II, Pamgen), the constitutive
 * library shared by FE and correspondence PD (elastic, neo-Hookean, J2, Johnson-Cook with a
 * Mie-Gruneisen equation of state), 8-node hexahedra with hourglass control and bulk viscosity,
 * and FE bodies that live in the point store beside the PD bodies (DESIGN.md 2-3). */
#ifndef PF_FEM_H
#define PF_FEM_H

#include "core/core.h"

/* ---- hexahedral meshes (fem/mesh*.c) -------------------------------------------------- */
/* A named set of a mesh: nodes (node set) or element faces (side set). */
typedef struct {
  char name[64];
  pf_int n;
  pf_int *item;  /* [n] node indices (node set) or element indices (side set), 0-based */
  int8_t *face;  /* [n] side sets: the element's face 0..5 (Exodus HEX8 numbering); else NULL */
} pf_fem_set;

/* A mesh of 8-node hexahedra, as read: every rank holds the whole mesh at set-up. */
typedef struct {
  pf_int nnodes;
  double *X;        /* [3 nnodes] node coordinates, m (after the deck's scale and translate) */
  pf_int nelem;
  pf_int *conn;     /* [8 nelem] node indices, Exodus HEX8 order, every element of positive volume */
  int32_t *block;   /* [nelem] block index into block_name */
  int nblocks;
  char (*block_name)[64];
  int nnodesets, nsidesets;
  pf_fem_set *nodeset, *sideset;
} pf_fem_mesh;

/* The `mesh:` mapping of an FE body: a gmsh .geo (meshed at start-up into hexahedra) or .msh
 * file, an Exodus II file, or a Pamgen inline mesh. */
extern const pf_key pf_fem_mesh_keys[];
/* Read the mesh a body's `mesh:` mapping names (file paths relative to the deck). Errors name
 * the deck position and, for bad meshes, the file and the element or node. */
int pf_fem_mesh_read(const pf_deck *d, const pf_node *mesh, pf_fem_mesh *m);
int pf_fem_mesh_free(pf_fem_mesh *m);
/* Volume of hexahedron e (exact for trilinear hexahedra: 2x2x2 Gauss of det J). */
double pf_fem_hex_volume(const double x[8][3]);
/* Write a mesh as an Exodus II file (blocks, node sets, side sets): tests and conversions. */
int pf_fem_mesh_write_exodus(const char *path, const pf_fem_mesh *m);

/* ---- constitutive library (fem/material*.c) ---------------------------------------------
 * One library for FE elements and correspondence PD points. A model advances the Cauchy stress
 * of n material points over one step, batched. Stress and rate of deformation are symmetric
 * tensors in Voigt order (xx, yy, zz, yz, xz, xy), tensor (not engineering) shear components. */
typedef struct pf_fem_material pf_fem_material;
/* Keys of a material under `materials:` whose model is an FE model. */
extern const pf_key pf_fem_material_keys[];
/* 1 when model names an FE/continuum model (elastic, neo_hookean, j2, johnson_cook). */
int pf_fem_material_known(const char *model);
/* The known model names, comma separated (for error messages). */
const char *pf_fem_material_names(void);
/* Read the material mapping `mat` (named `name` under materials:); errors name the key. */
int pf_fem_material_create(const pf_deck *d, const pf_node *mat, const char *name,
                           pf_fem_material **m);
int pf_fem_material_destroy(pf_fem_material **m);
const char *pf_fem_material_name(const pf_fem_material *m);
double pf_fem_material_density(const pf_fem_material *m);       /* reference density, kg/m^3 */
double pf_fem_material_bulk_modulus(const pf_fem_material *m);  /* small-strain K, Pa */
double pf_fem_material_shear_modulus(const pf_fem_material *m); /* small-strain G, Pa */
/* History variables per material point and their names (output fields). A model with an
 * equivalent plastic strain names it "eqps". */
int pf_fem_material_nstate(const pf_fem_material *m);
const char *pf_fem_material_state_name(const pf_fem_material *m, int k);
/* Initial state of n points: state [n * nstate] (e.g. temperature = initial temperature). */
void pf_fem_material_init(const pf_fem_material *m, pf_int n, double *state);
/* Advance n material points over dt (s):
 *   F     [9n] deformation gradient at the end of the step, row-major F_iJ = dx_i/dX_J
 *   D     [6n] rate of deformation at mid-step, 1/s
 *   sigma [6n] in: the previous Cauchy stress already rotated to the end configuration
 *              (the element applies the objective rate); out: the new Cauchy stress, Pa.
 *              Hyperelastic models compute it from F alone.
 *   state [n * nstate] history variables, updated
 *   c     [n] out: the current dilatational wave speed, m/s (for the stable step) */
void pf_fem_material_update(const pf_fem_material *m, pf_int n, double dt,
                            const double *restrict F, const double *restrict D,
                            double *restrict sigma, double *restrict state, double *restrict c);

/* The deformation-gradient estimate of n points changed from F_from [9n] to F_to [9n] without
 * the material moving (a correspondence point that lost bonds): the model re-expresses its
 * history so that its elastic state, and so its stress, stays what it was (docs/theory/
 * materials.md §2.7). A model whose stress follows F only through D needs nothing. */
void pf_fem_material_rereference(const pf_fem_material *m, pf_int n, const double *F_from,
                                 const double *F_to, double *state);

/* ---- FE bodies (fem/body.c): a hexahedral mesh whose nodes are points of the store ---------- */
typedef struct pf_fem_body pf_fem_body;
extern const pf_key pf_fem_body_keys[];
/* Read an FE body (`bodies[i]` with `type: finite_element`): its mesh (whole, on every rank),
 * material, element options. */
int pf_fem_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials,
                       pf_fem_body **b);
int pf_fem_body_destroy(pf_fem_body **b);
/* The mesh nodes as a point cloud (positions, lumped nodal volumes, cell = cbrt(volume)) for the
 * decomposition; free with pf_point_cloud_free. Node k gets global id gid0 + k. */
int pf_fem_body_cloud(const pf_fem_body *b, pf_point_cloud *pc);
/* Append to rows, for store points [first, first+n) (nodes of this body, gid0 the global id of
 * node 0), every node that shares an element with it, ascending global id: the decomposition
 * then ghosts exactly the nodes of the elements of owned nodes. */
int pf_fem_body_node_rows(const pf_fem_body *b, const pf_points *pts, pf_int first, pf_int n,
                          pf_gid gid0, pf_bond_rows *rows);
/* Give the body its owned nodes [first, first+n) (store body index `body`, ghosts already
 * added): local elements (those with an owned node, computed redundantly by every rank that
 * has one), lumped masses, initial material state. */
int pf_fem_body_attach(pf_fem_body *b, int body, pf_points *pts, pf_int first, pf_int n,
                       pf_gid gid0);
/* Add the internal forces (stress, hourglass, bulk viscosity) of the body's elements to the
 * owned nodes, each node summing its elements in ascending global element order (the same sum
 * on any number of ranks). Needs the ghosts' y and v. t and step name the failure time. */
int pf_fem_body_force(pf_fem_body *b, pf_points *pts, double dt, double t, long step);
/* Stable step of the last force evaluation (before any: the reference elements'), s. */
double pf_fem_body_stable_dt(const pf_fem_body *b);
/* Energies of the elements this rank owns: [0] stress work (internal energy), [1] hourglass,
 * [2] bulk-viscosity work, J. */
void pf_fem_body_energies(const pf_fem_body *b, double e[3]);
/* The mesh-wide flags of deleted elements (`erosion:`; the same on every rank) and their count;
 * NULL when the body has no erosion (fem/erosion.c). */
const uint8_t *pf_fem_body_eroded(const pf_fem_body *b, long *count);
/* Element count of the mesh; the mesh (for output connectivity). */
const pf_fem_mesh *pf_fem_body_mesh(const pf_fem_body *b);
const pf_fem_material *pf_fem_body_material(const pf_fem_body *b);
/* Element state as table rows (checkpoints, re-partitioning): ncomp doubles per element. */
int pf_fem_body_state_ncomp(const pf_fem_body *b);
/* Elements evaluated on this rank (those with an owned node). */
pf_int pf_fem_body_nlocal(const pf_fem_body *b);
/* The rows of the elements this rank owns: ids[k] the mesh element, data[k * ncomp] its state
 * (room for pf_fem_body_nlocal rows); returns how many. */
pf_int pf_fem_body_state_get(const pf_fem_body *b, pf_gid *ids, double *data);
/* Set every local element's state from the whole table full[nelem * ncomp] (after attach). */
void pf_fem_body_state_set(pf_fem_body *b, const double *full);
/* Restore the stable step of the last force evaluation (restart, re-partition). */
void pf_fem_body_set_stable_dt(pf_fem_body *b, double dt);
/* Fill the nodal output fields "stress" (6) and the material's state names with the
 * volume-weighted average over each owned node's elements. */
int pf_fem_body_output_fields(pf_fem_body *b, pf_points *pts);
/* The peridynamic operator coupled to the body's nodes (a `peridynamic:` map), or NULL
 * (fem/body_coupling.c). Its attach follows the body's, with the same rows; then
 * pf_fem_body_coupling_ready takes its stable step into the body's. */
struct pf_pd_body *pf_fem_body_pd(const pf_fem_body *b);
int pf_fem_body_coupling_ready(pf_fem_body *b, pf_points *pts);

#endif
