/* The damage laws (their list and deck keys) and bond failure by critical stretch (Silling &
 * Askari 2005): a bond fails for good when its stretch exceeds min(s0_i, s0_j). s0 is either
 * constant (given, or from the energy release rate G0 through the material's closed form, e.g.
 * PMB s0 = sqrt(5 G0 / (9 K delta)), eq. 9), or follows s0 = s00 - alpha s_min (Silling &
 * Askari 2005, eq. 10), s_min being the smallest stretch among the point's intact bonds in the
 * previous step (as LAMMPS' peri/pmb). The critical-energy law is pd/damage_critical_energy.c. */
#include "pd/pd_impl.h"

#include <string.h>

const pf_key pf_pd_damage_keys[] = {
    {"law", PF_KEY_STRING, 1, NULL, "", "none | critical_stretch | silling_askari | critical_energy",
     NULL},
    {"critical_stretch", PF_KEY_REAL, 0, NULL, "", "critical_stretch: s0", NULL},
    {"energy_release_rate", PF_KEY_REAL, 0, NULL, "J/m^2",
     "critical_stretch: G0, converted to s0 by the material's closed form; critical_energy: G0, "
     "converted to the critical bond energy w_c = 4 G0 / (pi delta^4)", NULL},
    {"s00", PF_KEY_REAL, 0, NULL, "", "silling_askari: s00 in s0 = s00 - alpha s_min", NULL},
    {"alpha", PF_KEY_REAL, 0, "0.25", "", "silling_askari: alpha in s0 = s00 - alpha s_min", NULL},
    PF_KEY_END};

static int positive(const pf_deck *d, const pf_node *map, const char *key, double *v) {
  if (!pf_node_get(map, key)) return pf_deck_error(d, map, key, "this damage law needs '%s'", key);
  return pf_deck_positive(d, map, key, v);
}

static int read_none(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  (void)d, (void)map;
  b->law = PF_DAMAGE_NONE;
  b->s0_init = INFINITY;
  return 0;
}

/* Constant s0, given or from G0 through the material's closed form. */
static int read_critical_stretch(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  double s0 = INFINITY;
  b->law = PF_DAMAGE_CRITICAL_STRETCH;
  int has_s0 = pf_node_get(map, "critical_stretch") != NULL;
  int has_g0 = pf_node_get(map, "energy_release_rate") != NULL;
  if (has_s0 == has_g0)
    return pf_deck_error(d, map, "critical_stretch",
                         "give exactly one of 'critical_stretch' and 'energy_release_rate'");
  if (has_s0) PF_CALL(positive(d, map, "critical_stretch", &s0));
  else {
    double G0;
    PF_CALL(positive(d, map, "energy_release_rate", &G0));
    s0 = b->ops->critical_stretch ? b->ops->critical_stretch(b, G0) : NAN;
    if (!isfinite(s0))
      return pf_deck_error(d, pf_node_get(map, "energy_release_rate"), "energy_release_rate",
                           "no closed form s0(G0) for material '%s' with this influence "
                           "function; give 'critical_stretch'", b->ops->name);
  }
  b->s0_init = s0;
  return 0;
}

static int read_silling_askari(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  b->law = PF_DAMAGE_SILLING_ASKARI;
  PF_CALL(positive(d, map, "s00", &b->s00));
  b->alpha = 0.25;
  PF_CALL(pf_deck_real(d, map, "alpha", &b->alpha));
  b->s0_init = b->s00;
  return 0;
}

/* The damage laws, by name, with the keys of pf_pd_damage_keys each one reads. */
typedef struct {
  const char *name;
  int (*read)(const pf_deck *d, const pf_node *map, pf_pd_body *b);
  const char *keys[3];
} damage_law;
static const damage_law laws[] = {
    {"none", read_none, {NULL}},
    {"critical_stretch", read_critical_stretch, {"critical_stretch", "energy_release_rate", NULL}},
    {"silling_askari", read_silling_askari, {"s00", "alpha", NULL}},
    {"critical_energy", pf_pd_damage_critical_energy_read, {"energy_release_rate", NULL}},
};
enum { NLAWS = sizeof laws / sizeof laws[0] };

static const char *law_names(void) {
  static char known[128];
  known[0] = '\0';
  for (int k = 0; k < NLAWS; k++) {
    strcat(known, k ? ", " : "");
    strcat(known, laws[k].name);
  }
  return known;
}

/* Read the damage law and its parameters (the initial s0, or w_c). A key that belongs to
 * another law is an error naming it. */
int pf_pd_damage_read(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  const char *name = "none";
  if (map) PF_CALL(pf_deck_string(d, map, "law", &name));
  const damage_law *law = NULL;
  for (int k = 0; k < NLAWS && !law; k++)
    if (!strcmp(laws[k].name, name)) law = &laws[k];
  if (!law)
    return pf_deck_error(d, pf_node_get(map, "law"), "law", "unknown damage law '%s' (known: %s)",
                         name, law_names());
  for (const pf_key *key = pf_pd_damage_keys + 1; map && key->name; key++) {
    int used = 0;
    char takes[128] = "";
    for (int q = 0; law->keys[q]; q++) {
      used |= !strcmp(law->keys[q], key->name);
      strcat(takes, q ? ", " : "");
      strcat(takes, law->keys[q]);
    }
    if (!used && pf_node_get(map, key->name))
      return pf_deck_error(d, pf_node_get(map, key->name), key->name,
                           "not a parameter of damage law '%s' (it takes: %s)", law->name,
                           law->keys[0] ? takes : "nothing else");
  }
  return law->read(d, map, b);
}

/* The per-point s0 field: initial values when fresh; ghosts from their owners. */
int pf_pd_damage_setup(pf_pd_body *b, pf_points *pts, int fresh) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "critical_stretch", 1, PF_FIELD_GHOST | PF_FIELD_RESTART, &idx));
  b->s0 = pts->fields[idx].data;
  if (fresh)
    for (pf_int i = b->first; i < b->first + b->n; i++) b->s0[i] = b->s0_init;
  return pf_points_exchange(pts, b->s0, 1);
}

/* Silling–Askari: s0_i = s00 - alpha * s_min_i for the next step (eq. 10). */
int pf_pd_body_post_step(pf_pd_body *b, pf_points *pts) {
  if (b->law != PF_DAMAGE_SILLING_ASKARI) return 0;
  for (pf_int k = 0; k < b->n; k++)
    if (isfinite(b->smin[k])) b->s0[b->first + k] = b->s00 - b->alpha * b->smin[k];
  return pf_points_exchange(pts, b->s0, 1); /* the ghosts' s0 for the next step's bond test */
}
