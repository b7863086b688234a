/* perifem contact: rigid analytic indenters (sphere, plane) pushing on points. (The penalty
 * node-to-particle and particle-particle contact of the contact issue will live here too.) */
#ifndef PF_CONTACT_H
#define PF_CONTACT_H

#include "core/core.h"

typedef struct pf_indenter pf_indenter;
extern const pf_key pf_indenter_keys[];

int pf_indenter_create(const pf_deck *d, const pf_node *map, pf_indenter **ind);
int pf_indenter_destroy(pf_indenter **ind);
const char *pf_indenter_name(const pf_indenter *ind);
/* Add the indenter's repulsive force to the points it penetrates (pts->y); the force on the
 * indenter (the reaction, N) goes to reaction[3] and the penalty energy (J) to *energy. */
int pf_indenter_force(pf_indenter *ind, pf_points *pts, double reaction[3], double *energy);
/* Move the indenter from t to t + dt with its prescribed velocity v(t) (midpoint rule) and
 * accumulate the work done on the points, -reaction . v dt, into *work. */
void pf_indenter_advance(pf_indenter *ind, double t, double dt, const double reaction[3],
                         double *work);
/* Current position (sphere centre or plane point). */
void pf_indenter_position(const pf_indenter *ind, double x[3]);
/* Move the indenter to x (restart). */
void pf_indenter_set_position(pf_indenter *ind, const double x[3]);

/* A rigid, fixed, frictionless plane that points cannot cross (contact/wall.c). */
typedef struct pf_wall pf_wall;
extern const pf_key pf_wall_keys[];
int pf_wall_create(const pf_deck *d, const pf_node *map, int nbodies, const char *const *body_names,
                   pf_wall **w);
int pf_wall_destroy(pf_wall **w);
const char *pf_wall_name(const pf_wall *w);
/* After the drift: owned points behind the plane go back onto it and lose their inward normal
 * velocity; the kinetic energy removed is added to *loss (J). */
void pf_wall_enforce_position(const pf_wall *w, pf_points *pts, double *loss);
/* After the forces: points on the plane lose the inward normal part of their force;
 * reaction[3] gets the total force on the wall over all ranks (N). Collective. */
void pf_wall_enforce_force(const pf_wall *w, pf_points *pts, double reaction[3]);

#endif
