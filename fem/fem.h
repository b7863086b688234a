/* perifem finite elements: 8-node hexahedra with hourglass control and bulk viscosity, the
 * element stable step and erosion, and FE bodies that live in the point store beside the PD
 * bodies. Meshes are mesh/'s, materials material/'s. */
#ifndef PF_FEM_H
#define PF_FEM_H

#include "core/core.h"
#include "material/material.h"
#include "mesh/mesh.h"

#ifndef PF_USES_FEM
#error "fem/fem.h is included by a module below fem/ (docs/architecture.md: the module layers)"
#endif

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
 * then ghosts exactly the nodes of the elements of owned nodes. Fails on a node with more than
 * 216 neighbours. */
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
const pf_mesh *pf_fem_body_mesh(const pf_fem_body *b);
/* The body's `material` (material_regions may give some elements others). */
const pf_material *pf_fem_body_material(const pf_fem_body *b);
/* Each mesh node's entry of material_regions: the latest entry (1, 2, ...) that gave one of its
 * elements its material, 0 where the body's `material` holds all of them (entry[mesh nnodes]).
 * Returns 1 when the body has material_regions, 0 (every entry 0) when not. */
int pf_fem_body_node_entries(const pf_fem_body *b, uint8_t *entry);
/* The least reference density and the largest bulk modulus of the body's materials (contact's
 * penalty constants; the one material's for a body of one), kg/m^3 and Pa (fem/materials.c). */
void pf_fem_body_material_bounds(const pf_fem_body *b, double *density, double *bulk_modulus);
/* Element state as table rows (checkpoints, re-partitioning): ncomp doubles per element. */
int pf_fem_body_state_ncomp(const pf_fem_body *b);
/* Elements evaluated on this rank (those with an owned node). */
pf_int pf_fem_body_nlocal(const pf_fem_body *b);
/* The rows of the elements this rank owns: ids[k] the mesh element, data[k * ncomp] its state
 * (room for pf_fem_body_nlocal rows); returns how many. */
pf_int pf_fem_body_state_get(const pf_fem_body *b, pf_gid *ids, double *data);
/* Set every local element's state from the whole table full[nelem * ncomp] (after attach). */
void pf_fem_body_state_set(pf_fem_body *b, const double *full);
/* The elements' history (stress, material state, hourglass forces, bulk-viscosity pressure and
 * energies: the table rows above): commit the current one (restore 0), or put the committed one
 * back (restore 1). The quasi-static solver commits at each load step's start and restores before
 * each force evaluation, so that every evaluation is one increment from the last converged state
 * (docs/theory/quasi_static_failure.md §6). Element deletion is not undone. */
int pf_fem_body_history(pf_fem_body *b, int restore);
/* Restore the stable step of the last force evaluation (restart, re-partition). */
void pf_fem_body_set_stable_dt(pf_fem_body *b, double dt);
/* Fill the nodal output fields "stress" (6) and the material's state names with the
 * volume-weighted average over each owned node's elements. */
int pf_fem_body_output_fields(pf_fem_body *b, pf_points *pts);
/* ---- blending (coupling/ composes an FE body with a PD operator on the same nodes) ----------- */
/* beta(x) in [0, 1]: the other operator's weight at reference position x. */
typedef double (*pf_fem_weight_fn)(const void *ctx, const double x[3]);
/* Before attach: blend the body with another operator. Elements whose eight nodes all have
 * beta = 1 are left to it (not evaluated), and the body registers no nodal stress or state
 * fields (the nodes' are the other operator's). */
void pf_fem_body_set_blending(pf_fem_body *b, pf_fem_weight_fn beta, const void *ctx);
/* After each attach: beta at the store points; each owned element's energies are then weighted
 * by 1 - its nodes' mean beta. */
int pf_fem_body_set_blending_field(pf_fem_body *b, const double *beta);
/* Evaluate the local elements at the current positions (element forces, energies, the stable
 * step) without adding them to the nodes; t and step name a failure. pf_fem_body_force is this,
 * the erosion update and the assembly. Needs the ghosts' y and v. */
int pf_fem_body_evaluate(pf_fem_body *b, pf_points *pts, double dt, double t, long step);
/* The assembled force of the last evaluation on the body's owned node i (0 <= i < n), its
 * elements summed in ascending global element order, N; weighted (a blended body): each
 * element's share weighted by 1 - its nodes' mean beta, the weight its energies carry — the
 * forces of sum_e (1 - beta_e) W_e (the energy form). */
void pf_fem_body_node_force(const pf_fem_body *b, pf_int i, int weighted, double f[3]);
/* Blended, after pf_fem_body_set_blending_field: sum_e (beta_i - beta_e) V_e B_ei over the
 * elements of owned node i (local index), with the reference volume V_e, the reference mean
 * gradient B_ei and beta_e = 1 - the element's share: how much the weighted elements' force under
 * a uniform stress P, -P sum_e (1 - beta_e) V_e B_ei, differs from that of elements all weighted
 * 1 - beta_i (docs/theory/coupling.md §3.4). Summed in ascending global element order. */
void pf_fem_body_node_blend_vector(const pf_fem_body *b, pf_int i, double beta_i, double g[3]);
/* Lumped volume of each mesh node [nnodes], m^3. */
const double *pf_fem_body_node_volumes(const pf_fem_body *b);
/* ---- element-to-particle conversion (fem/particles.c; docs/theory/fem.md §9b) --------------- */
/* A `type: particles` body: one dormant point (mass 0) per element of the FE body it names, which
 * takes the element's mass, momentum and state when the element's erosion converts it. */
typedef struct pf_fem_particles pf_fem_particles;
extern const pf_key pf_fem_particles_keys[];
int pf_fem_particles_create(const pf_deck *d, const pf_node *body, pf_fem_particles **p);
int pf_fem_particles_destroy(pf_fem_particles **p);
/* The name of the FE body it takes elements from; link it to that body (NULL: no FE body of
 * that name: an input error, as is a body whose erosion does not convert). */
const char *pf_fem_particles_source(const pf_fem_particles *p);
int pf_fem_particles_link(pf_fem_particles *p, pf_fem_body *fe);
/* One point per mesh element at its reference centroid, with the element's volume (after link). */
int pf_fem_particles_cloud(pf_fem_particles *p, pf_point_cloud *pc);
/* Take the owned particles [first, first + n) of the store (gid0: element 0's particle). */
int pf_fem_particles_attach(pf_fem_particles *p, pf_points *pts, pf_int first, pf_int n, pf_gid gid0);
void pf_fem_particles_material(const pf_fem_particles *p, double *density, double *bulk_modulus);
/* The short-range contact's delta of the particles: three times the largest element edge, m. */
double pf_fem_particles_horizon(const pf_fem_particles *p);
/* The kinetic energy the conversions of this rank's particles removed (booked), J. */
double pf_fem_particles_loss(const pf_fem_particles *p, const pf_points *pts);
/* Add energy (J) to the booked conversion loss of the first particle made at the last
 * conversion (on the rank that owns it; nothing elsewhere). */
void pf_fem_particles_book(pf_fem_particles *p, pf_points *pts, double energy);
/* Converted elements so far (mesh-wide). */
long pf_fem_particles_count(const pf_fem_particles *p);
/* At a step's end (dt the step, t the time): the elements deleted since the last call become
 * particles; *converted gets how many (mesh-wide). Collective when some element was deleted. */
int pf_fem_particles_convert(pf_fem_particles *p, pf_points *pts, double dt, double t, long *converted);

#endif
