/* The interaction kinds, one line each: PF_INTERACTION_KIND(id) names the ops table
 * pf_interaction_kind_<id> (sim/interaction.h) defined in sim/interaction_<id>.c. The order is
 * that of every step hook and of the forces: rigid surfaces and contact push first, walls then
 * take the normal part of the whole force, loads are added last. Include this file with
 * PF_INTERACTION_KIND defined. */
PF_INTERACTION_KIND(rigid)     /* contact: rigid_surfaces: and indenters: (contact/rigid.c) */
PF_INTERACTION_KIND(contact)   /* contact: pairs: node-to-particle, short-range, FE <-> FE (contact/) */
PF_INTERACTION_KIND(wall)      /* walls: (contact/wall.c) */
PF_INTERACTION_KIND(condition) /* boundary_conditions: prescribed velocity, displacement, body force (core/bc.c) */
