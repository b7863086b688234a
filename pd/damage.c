/* The damage laws: lookup by name in the list pd/damage_laws.h (and the laws registered at run
 * time), their deck table assembled from each law's own keys, and the body's entry points that
 * dispatch to the law's ops table (pf_pd_damage_ops, pd/pd_impl.h). The laws themselves are
 * pd/damage_<id>.c. */
#include "pd/pd_impl.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* The laws: the list of pd/damage_laws.h, then the ones registered at run time. */
static const pf_pd_damage_ops *law_list[PF_PD_MAX_LAWS] = {
#define PF_PD_DAMAGE_LAW(id) &pf_pd_damage_##id,
#include "pd/damage_laws.h"
#undef PF_PD_DAMAGE_LAW
};
static int nlaws = 0 /* (each line of the list adds 1) */
#define PF_PD_DAMAGE_LAW(id) +1
#include "pd/damage_laws.h"
#undef PF_PD_DAMAGE_LAW
    ;

const pf_pd_damage_ops *pf_pd_damage_find(const char *name) {
  for (int k = 0; k < nlaws; k++)
    if (!strcmp(law_list[k]->name, name)) return law_list[k];
  return NULL;
}

int pf_pd_damage_register(const pf_pd_damage_ops *law) {
  PF_CHECK(law && law->name && law->name[0] && law->read, PF_ERR_INPUT, "a damage law needs a name and a read");
  PF_CHECK(!pf_pd_damage_find(law->name), PF_ERR_INPUT, "damage law '%s' is already registered", law->name);
  PF_CHECK(nlaws < PF_PD_MAX_LAWS, PF_ERR_INPUT, "no room for damage law '%s' (at most %d laws)", law->name,
           PF_PD_MAX_LAWS);
  law_list[nlaws++] = law;
  return 0;
}

/* words joined by sep into out (size n), cut short rather than overflow. */
static const char *join(const char *const *words, int count, const char *sep, char *out, size_t n) {
  size_t len = 0;
  out[0] = '\0';
  for (int k = 0; k < count && len < n; k++)
    len += (size_t)snprintf(out + len, n - len, "%s%s", k ? sep : "", words[k]);
  return out;
}

/* pf_pd_damage_keys: `law`, then each law's own rows in list order (a key several laws read
 * once, its descriptions joined), assembled at first use and again after a registration. */
enum { MAX_DAMAGE_KEYS = 48 };
pf_key pf_pd_damage_key_rows[MAX_DAMAGE_KEYS + 1];

const pf_key *pf_pd_damage_key_table(void) {
  static char text[4096], laws[256];
  static int assembled = 0; /* the number of laws assembled */
  if (assembled == nlaws) return pf_pd_damage_key_rows;
  const char *names[PF_PD_MAX_LAWS];
  for (int k = 0; k < nlaws; k++) names[k] = law_list[k]->name;
  pf_key_table t = {pf_pd_damage_key_rows, MAX_DAMAGE_KEYS, 1, text, sizeof text, 0};
  t.rows[0] = (pf_key){"law", PF_KEY_STRING, 1, NULL, "", join(names, nlaws, " | ", laws, sizeof laws), NULL};
  for (int k = 0; k < nlaws; k++)
    if (pf_key_table_add(&t, law_list[k]->keys)) break; /* (full: the error is raised) */
  assembled = nlaws;
  return pf_pd_damage_key_rows;
}

const char *pf_pd_damage_names(void) {
  static char known[256];
  const char *names[PF_PD_MAX_LAWS];
  for (int k = 0; k < nlaws; k++) names[k] = law_list[k]->name;
  return join(names, nlaws, ", ", known, sizeof known);
}

int pf_pd_damage_read_required(const pf_deck *d, const pf_node *map, const char *key, double *v) {
  if (!pf_node_get(map, key)) return pf_deck_error(d, map, key, "this damage law needs '%s'", key);
  return pf_deck_positive(d, map, key, v);
}

/* Does the law read key? */
static int takes(const pf_pd_damage_ops *law, const char *key) {
  for (const pf_key *k = law->keys; k && k->name; k++)
    if (!strcmp(k->name, key)) return 1;
  return 0;
}

/* A key of pf_pd_damage_keys in the deck that the law does not read is an error naming it and
 * the keys the law does read. */
static int check_keys(const pf_deck *d, const pf_node *map, const pf_pd_damage_ops *law) {
  for (const pf_key *key = pf_pd_damage_keys + 1; map && key->name; key++) {
    if (takes(law, key->name) || !pf_node_get(map, key->name)) continue;
    const char *names[MAX_DAMAGE_KEYS];
    int n = 0;
    for (const pf_key *k = law->keys; k && k->name && n < MAX_DAMAGE_KEYS; k++) names[n++] = k->name;
    char list[256];
    return pf_deck_error(d, pf_node_get(map, key->name), key->name,
                         "not a parameter of damage law '%s' (it takes: %s)", law->name,
                         n ? join(names, n, ", ", list, sizeof list) : "nothing else");
  }
  return 0;
}

/* Read the damage law and its parameters (the initial s0, or w_c). A key that belongs to
 * another law is an error naming it. */
int pf_pd_damage_read(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  const char *name = "none";
  if (map) PF_CALL(pf_deck_string(d, map, "law", &name));
  const pf_pd_damage_ops *law = pf_pd_damage_find(name);
  if (!law)
    return pf_deck_error(d, pf_node_get(map, "law"), "law", "unknown damage law '%s' (known: %s)",
                         name, pf_pd_damage_names());
  PF_CALL(check_keys(d, map, law));
  b->damage = law;
  b->s0_init = b->critical_energy = INFINITY; /* no limit until the law sets one */
  PF_CALL(law->read(d, map, b));
  if (pf_pd_energy_limited(b) && !b->ops->bond_energy) /* (the force kernel evaluates the energy) */
    return pf_deck_error(d, pf_node_get(map, "law"), "law",
                         "law '%s' needs the bond energy from the material's force kernel; material "
                         "model '%s' does not provide it (it does: %s)", law->name, b->ops->name,
                         pf_pd_material_names_with(offsetof(pf_pd_material_ops, bond_energy)));
  const pf_node *nf = map ? pf_node_get(map, "no_fail") : NULL;
  b->n_no_fail = nf ? pf_node_count(nf) : 0;
  if (b->n_no_fail > PF_PD_MAX_NO_FAIL)
    return pf_deck_error(d, nf, "no_fail", "at most %d regions (got %d)", PF_PD_MAX_NO_FAIL, b->n_no_fail);
  for (int k = 0; k < b->n_no_fail; k++)
    PF_CALL(pf_region_from_deck(d, pf_node_item(nf, k), NULL, -1, &b->no_fail[k]));
  return 0;
}

/* The per-point s0 field: initial values when fresh (INFINITY in the no-fail region); ghosts
 * from their owners. */
int pf_pd_damage_setup(pf_pd_body *b, pf_points *pts, int fresh) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "critical_stretch", 1, PF_FIELD_GHOST | PF_FIELD_RESTART, &idx));
  b->s0 = pts->fields[idx].data;
  if (b->damage->attach) PF_CALL(b->damage->attach(b, pts, fresh));
  else if (fresh)
    for (pf_int i = b->first; i < b->first + b->n; i++) b->s0[i] = b->s0_init;
  for (int k = 0; fresh && k < b->n_no_fail; k++) /* (later, s0 comes with the points) */
    for (pf_int i = b->first; i < b->first + b->n; i++)
      if (pf_region_selects(&b->no_fail[k], pts, i)) b->s0[i] = INFINITY;
  return pf_points_exchange(pts, b->s0, 1);
}

/* Frozen: the law's limits kept aside, the body's replaced by none (an all-INFINITY s0 over the
 * store, owned points and ghosts; no energy limit), so every kernel takes its loop without a
 * limit and fails nothing. Thawed: the kept limits back. */
int pf_pd_body_freeze_damage(pf_pd_body *b, const pf_points *pts, int frozen) {
  if (!frozen == !b->frozen.on) return 0;
  if (!frozen) {
    b->s0 = b->frozen.s0, b->s0_init = b->frozen.s0_init;
    b->critical_energy = b->frozen.critical_energy, b->wc_bond = b->frozen.wc_bond;
    b->interface_s0 = b->frozen.interface_s0;
    b->frozen.on = 0;
    return 0;
  }
  if (b->frozen.none_n < pts->n_total) {
    free(b->frozen.none_s0);
    b->frozen.none_n = 0;
    PF_MALLOC(b->frozen.none_s0, pts->n_total);
    b->frozen.none_n = pts->n_total;
  }
  for (pf_int i = 0; i < pts->n_total; i++) b->frozen.none_s0[i] = INFINITY;
  b->frozen.s0 = b->s0, b->frozen.s0_init = b->s0_init;
  b->frozen.critical_energy = b->critical_energy, b->frozen.wc_bond = b->wc_bond;
  b->frozen.interface_s0 = b->interface_s0;
  b->s0 = b->frozen.none_s0, b->s0_init = b->critical_energy = INFINITY, b->wc_bond = NULL;
  b->interface_s0 = INFINITY;
  b->frozen.on = 1;
  return 0;
}

int pf_pd_body_post_step(pf_pd_body *b, pf_points *pts) {
  return b->damage->post_step ? b->damage->post_step(b, pts) : 0;
}

int64_t pf_pd_body_softened(const pf_pd_body *b) { return b->soft_ratio > 0 ? b->soft_grown : -1; }

double pf_pd_body_take_damage_redistribution(pf_pd_body *b) {
  const double r = b->damage_redistribution;
  b->damage_redistribution = 0;
  return r;
}
