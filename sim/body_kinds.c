/* The registry of body kinds (sim/body_kinds.h), the choice of a deck body's kind, and the deck
 * rules that read the kinds' own maps (statics-only transition forms in a dynamic run). */
#include "sim/body.h"

#include <string.h>

#define PF_BODY_KIND(id) extern const pf_body_ops pf_body_kind_##id;
#include "sim/body_kinds.h"
#undef PF_BODY_KIND

static const pf_body_ops *const kinds[] = {
#define PF_BODY_KIND(id) &pf_body_kind_##id,
#include "sim/body_kinds.h"
#undef PF_BODY_KIND
};
enum { NKINDS = sizeof kinds / sizeof kinds[0] };


int pf_body_kind_count(void) { return NKINDS; }

const pf_body_ops *pf_body_kind_at(int k) { return kinds[k]; }

int pf_body_kind_first_of_type(int k) {
  for (int q = 0; q < k; q++)
    if (!strcmp(kinds[q]->type, kinds[k]->type)) return 0;
  return 1;
}

/* The distinct type names, comma separated, in list order. */
static const char *type_names(void) {
  static char names[256];
  if (names[0]) return names;
  for (int k = 0; k < NKINDS; k++) {
    if (!pf_body_kind_first_of_type(k)) continue;
    size_t len = strlen(names);
    snprintf(names + len, sizeof names - len, "%s%s", len ? ", " : "", kinds[k]->type);
  }
  return names;
}

int pf_body_kind(const pf_deck *d, const pf_node *body, const pf_body_ops **ops) {
  const char *type = "peridynamic";
  *ops = NULL;
  if (pf_node_get(body, "type")) PF_CALL(pf_deck_string(d, body, "type", &type));
  for (int k = 0; k < NKINDS && !*ops; k++)
    if (!strcmp(kinds[k]->type, type) && (!kinds[k]->claims || kinds[k]->claims(body))) *ops = kinds[k];
  if (!*ops)
    return pf_deck_error(d, pf_node_get(body, "type"), "type", "unknown body type '%s' (known: %s)", type,
                         type_names());
  const pf_body_ops *o = *ops; /* the required ops */
  PF_CHECK(o->label && o->keys && o->create && o->destroy && o->cloud && o->rows && o->attach && o->force &&
               o->stable_dt && o->energies && o->material,
           PF_ERR_RUN, "body kind '%s' lacks a required op (sim/body.h)", o->type);
  return 0;
}

/* The transition forms auto, partial_stress and corrected are statics and patch-test tools: the
 * partial-stress force is a strong form and the corrected force a non-symmetric term, so neither
 * conserves energy (docs/theory/coupling.md §2.4-2.5; a tapered coupled bar gains 136 times its
 * energy in 25 us). An explicit run that takes a step refuses them unless the same map says
 * allow_in_dynamics: true. map: a PD body, or an FE body's `peridynamic:` map. */
static int check_dynamic_form(const pf_deck *d, const pf_node *map, const char *body) {
  const char *form = NULL;
  int allow = 0;
  PF_CALL(pf_deck_string(d, map, "formulation", &form));
  PF_CALL(pf_deck_bool(d, map, "allow_in_dynamics", &allow));
  if (!form || allow || (strcmp(form, "auto") && strcmp(form, "partial_stress") && strcmp(form, "corrected")))
    return 0;
  return pf_deck_error(d, pf_node_get(map, "formulation"), "formulation",
                       "body '%s': formulation %s is a statics form that conserves no energy in an explicit run "
                       "(docs/theory/coupling.md §2.4-2.5); use formulation: consistent (correspondence) or "
                       "standard, which conserve it, the solver type quasi_static, or say allow_in_dynamics: "
                       "true beside it to run it anyway", body, form);
}

int pf_body_kinds_check_dynamic_forms(const pf_deck *d, long nsteps, const char *const *names) {
  const pf_node *bodies = pf_node_get(pf_deck_root(d), "bodies");
  if (nsteps == 0) return 0; /* forces at t = 0 only (patch tests): no energy to gain */
  for (int b = 0; b < pf_node_count(bodies); b++) {
    const pf_node *body = pf_node_item(bodies, b), *pd = pf_node_get(body, "peridynamic");
    PF_CALL(check_dynamic_form(d, pd ? pd : body, names[b]));
  }
  return 0;
}
