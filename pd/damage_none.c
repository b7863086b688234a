/* Damage law "none": no bond fails (the default when a body has no `damage:` mapping). A law of
 * its own rather than the absence of one, so that every body has a law and the known names come
 * from the list alone. It sets no limit: s0 and the critical energy stay infinite, so the
 * kernels' comparisons never fail a bond. */
#include "pd/pd_impl.h"

static int read_none(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  (void)d, (void)map;
  b->s0_init = INFINITY;
  return 0;
}

const pf_pd_damage_ops pf_pd_damage_none = {
    .name = "none",
    .read = read_none,
};
