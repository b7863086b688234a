/* perifem coupling: the coupled body, an FE body and a peridynamic operator on the same nodes
 * composed by blending forces or energies over an overlap (docs/theory/coupling.md §3), with the horizon
 * field's distance to the FE region (d_fe). The transition forms of the PD operator itself
 * (partial stress, corrected, consistent) are kernels of its force pass and live in pd/
 * (docs/architecture.md says why). Depends on core/, material/, mesh/, pd/ and fem/. */
#ifndef PF_COUPLING_H
#define PF_COUPLING_H

#include "core/core.h"
#include "fem/fem.h"
#include "pd/pd.h"

#ifndef PF_USES_COUPLING
#error "coupling/coupling.h is included by a module below coupling/ (docs/architecture.md: the module layers)"
#endif

typedef struct pf_coupled_body pf_coupled_body;

/* The keys of a `type: finite_element` body: the FE body's, with the optional `peridynamic:`
 * map (pf_pd_coupled_keys) that makes it a coupled body. */
const pf_key *pf_coupled_body_keys(void);
/* 1 when the body mapping asks for a coupled body (a finite_element body with `peridynamic:`). */
int pf_coupled_body_requested(const pf_node *body);
/* Read the FE body, its PD operator and the blending weight beta(x) (every rank checks that
 * beta lies in [0, 1] at every mesh node); errors name the deck position. */
int pf_coupled_body_create(const pf_deck *d, const pf_node *body, const pf_node *materials,
                           pf_coupled_body **c);
int pf_coupled_body_destroy(pf_coupled_body **c);
pf_fem_body *pf_coupled_body_fem(const pf_coupled_body *c);
pf_pd_body *pf_coupled_body_pd(const pf_coupled_body *c);
/* Append the rows of store points [first, first+n), nodes of the body (gid0 the global id of
 * mesh node 0): each node's PD family (searched in the whole mesh before the first attach; its
 * current bonds, broken ones included, afterwards) merged with its element neighbours. */
int pf_coupled_body_rows(const pf_coupled_body *c, const pf_points *pts, pf_int first, pf_int n,
                         pf_gid gid0, pf_bond_rows *rows);
/* Attach the FE body (store body index `body`), the blending field "blending_weight", the
 * masses rho V of every node, and the PD operator (rows, local, fresh as pf_pd_body_attach).
 * Collective. */
int pf_coupled_body_attach(pf_coupled_body *c, int body, pf_points *pts, pf_int first, pf_int n,
                           pf_gid gid0, const pf_bond_rows *rows, const pf_int *local, int fresh);
/* Add the blended force (overlap: force, f = beta f_PD + (1 - beta) f_FE; overlap: energy, the
 * forces of beta W_PD + (1 - beta) W_FE) to the owned nodes' pts->f; the stable step becomes the
 * smaller of the elements' and the PD operator's. t and step name an element failure. */
int pf_coupled_body_force(pf_coupled_body *c, pf_points *pts, double dt, double t, long step);

#endif
