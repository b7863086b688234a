/* The body kinds, one line each: PF_BODY_KIND(id) names the ops table pf_body_kind_<id>
 * (sim/body.h) defined in sim/body_<id>.c. For one `type:` the first kind that claims the body
 * mapping is taken, so a kind that refines another (coupled: finite_element with `peridynamic:`)
 * comes before it. Include this file with PF_BODY_KIND defined. */
PF_BODY_KIND(pd)      /* type: peridynamic (the default) */
PF_BODY_KIND(coupled) /* type: finite_element with a peridynamic: map */
PF_BODY_KIND(fe)      /* type: finite_element */
PF_BODY_KIND(particles) /* type: particles (elements converted by an FE body's erosion) */
