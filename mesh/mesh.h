/* perifem meshes: 8-node hexahedral meshes and their readers (gmsh, Exodus II, Pamgen), blocks,
 * node sets and side sets, and the geometry of the trilinear hexahedron (shape functions, exact
 * volume, mean gradient, faces) that the elements, the mesh checks and the contact surfaces
 * share. Depends on core/ only. */
#ifndef PF_MESH_H
#define PF_MESH_H

#include "core/core.h"

#ifndef PF_USES_MESH
#error "mesh/mesh.h is included by a module below mesh/ (docs/architecture.md: the module layers)"
#endif

/* ---- hexahedral meshes (mesh/) -------------------------------------------------- */
/* A named set of a mesh: nodes (node set) or element faces (side set). */
typedef struct {
  char name[64];
  pf_int n;
  pf_int *item;  /* [n] node indices (node set) or element indices (side set), 0-based */
  int8_t *face;  /* [n] side sets: the element's face 0..5 (Exodus HEX8 numbering); else NULL */
} pf_mesh_set;

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
  pf_mesh_set *nodeset, *sideset;
} pf_mesh;

/* The `mesh:` mapping of an FE body: a gmsh .geo (meshed at start-up into hexahedra) or .msh
 * file, an Exodus II file, or a Pamgen inline mesh. */
extern const pf_key pf_mesh_keys[];
/* Read the mesh a body's `mesh:` mapping names (file paths relative to the deck). Errors name
 * the deck position and, for bad meshes, the file and the element or node. */
int pf_mesh_read(const pf_deck *d, const pf_node *mesh, pf_mesh *m);
int pf_mesh_free(pf_mesh *m);
/* Volume of hexahedron e (exact for trilinear hexahedra: 2x2x2 Gauss of det J). */
double pf_mesh_hex_volume(const double x[8][3]);
/* Peridigm's Exodus discretization (mesh/exodus_points.c): a peridynamic body's points from the
 * SPHERE, HEX8 and TET4 element blocks of the Exodus file its `geometry: {shape: exodus}` mapping
 * names (one point per element: a SPHERE's node and `volume` attribute, a solid element's
 * centroid and volume), with the file's node sets as sets of the cloud (a node brings in every
 * element on it). Errors name the deck key, the file and the block or element. */
int pf_mesh_exodus_points_from_deck(const pf_deck *d, const pf_node *geometry, pf_point_cloud *pc);
/* A solid element as Peridigm's point (mesh/element_point.c): its centroid c and volume vol;
 * returns the least volume of the tetrahedra it is computed from (below 0: an inverted element or
 * nodes out of Exodus order). x: the nodes in Exodus order. */
double pf_mesh_tet_point(const double x[4][3], double c[3], double *vol);
double pf_mesh_hex_point(const double x[8][3], double c[3], double *vol);
/* Write a mesh as an Exodus II file (blocks, node sets, side sets): tests and conversions. */
int pf_mesh_write_exodus(const char *path, const pf_mesh *m);

/* ---- the trilinear hexahedron (mesh/hex8.c) --------------------------------------------------
 * Node order is Exodus HEX8; faces in Exodus side order (sides 1..6 as 0..5, each
 * counter-clockwise seen from outside: 0: y=-1 {0,1,5,4}, 1: x=+1 {1,2,6,5}, 2: y=+1 {2,3,7,6},
 * 3: x=-1 {0,4,7,3}, 4: z=-1 {0,3,2,1}, 5: z=+1 {4,5,6,7}); node_sign: natural coordinates, the
 * same order as gmsh's hexahedron. */
extern const double pf_hex8_node_sign[8][3];
extern const int pf_hex8_face[6][4];
void pf_hex8_gauss_point(int g, double xi[3]);
/* Gradients dN_I/dx_i at parent point xi; returns det J. */
double pf_hex8_gradients(double x[8][3], const double xi[3], double grad[8][3]);
/* Mean gradient B[I][i] (Flanagan & Belytschko 1981) of the element with nodes x; returns V. */
double pf_hex8_mean_gradient(double x[8][3], double B[8][3]);
/* The same for PF_HEX8_LANES elements at once, lane l of each array one element's (the same bits). */
#define PF_HEX8_LANES 8
void pf_hex8_mean_gradient_lanes(double x[8][3][PF_HEX8_LANES], double B[8][3][PF_HEX8_LANES],
                                 double V[PF_HEX8_LANES]);
/* pf_hex8_gradients at the eight Gauss points at once, lane g Gauss point g (the same bits);
 * det J into det. */
void pf_hex8_gauss_gradients_lanes(double x[8][3], double grad[8][3][PF_HEX8_LANES], double det[PF_HEX8_LANES]);
void pf_hex8_lumped_mass(double x[8][3], double rho, double m[8]);
double pf_hex8_char_length(double x[8][3], double V);
void pf_hex8_char_length_lanes(double x[8][3][PF_HEX8_LANES], const double V[PF_HEX8_LANES],
                               double len[PF_HEX8_LANES]);
/* The smallest det J over the eight corners (below 0: the element is tangled). */
double pf_hex8_min_corner_jacobian(double x[8][3]);

#endif
