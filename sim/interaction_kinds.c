/* The registry of interaction kinds: the built-in ones of sim/interaction_kinds.h, then those a
 * program registered, in that order; building a simulation asks each kind for its instances. */
#include "sim/sim_impl.h"

static const pf_interaction_ops *const kinds[] = {
#define PF_INTERACTION_KIND(id) &pf_interaction_kind_##id,
#include "sim/interaction_kinds.h"
#undef PF_INTERACTION_KIND
};
enum { NKINDS = sizeof kinds / sizeof kinds[0], PF_MAX_EXTRA_KINDS = 8 };

/* Kinds registered at run time (a program or a test adding its own, before pf_sim_create). */
static const pf_interaction_ops *extra[PF_MAX_EXTRA_KINDS];
static int nextra;

int pf_interaction_kind_register(const pf_interaction_ops *ops) {
  for (int k = 0; k < nextra; k++)
    if (extra[k] == ops) return 0;
  PF_CHECK(ops && ops->kind && ops->build && ops->destroy, PF_ERR_INPUT,
           "pf_interaction_kind_register: an interaction kind needs a name, build and destroy");
  PF_CHECK(nextra < PF_MAX_EXTRA_KINDS, PF_ERR_INPUT, "pf_interaction_kind_register: at most %d kinds may be added",
           PF_MAX_EXTRA_KINDS);
  extra[nextra++] = ops;
  return 0;
}

int pf_interaction_kind_count(void) { return NKINDS + nextra; }
const pf_interaction_ops *pf_interaction_kind_at(int k) { return k < NKINDS ? kinds[k] : extra[k - NKINDS]; }

int pf_sim_interactions_build(pf_sim *sim) {
  for (int k = 0; k < pf_interaction_kind_count(); k++) PF_CALL(pf_interaction_kind_at(k)->build(sim));
  return 0;
}
