/* The registry of body kinds (sim/body_kinds.h) and the choice of a deck body's kind. */
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
