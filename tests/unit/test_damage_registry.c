/* The damage-law registry (pd/damage_laws.h): every law of the list is found by its name, has
 * its required ops and its own keys are rows of the deck's damage table (assembled from them), the `law` key's description
 * names the laws in list order, and a deck naming an unknown law is refused with an error that
 * gives the file, line and column, the key, and the known names. */
#include "test_common.h"

#include <stdio.h>
#include <string.h>

#include "pd/pd_impl.h"

static const pf_pd_damage_ops *const laws[] = {
#define PF_PD_DAMAGE_LAW(id) &pf_pd_damage_##id,
#include "pd/damage_laws.h"
#undef PF_PD_DAMAGE_LAW
};
enum { NLAWS = sizeof laws / sizeof laws[0] };

/* The names of the list joined by sep into out. */
static const char *joined(const char *sep, char *out, size_t n) {
  size_t len = 0;
  out[0] = '\0';
  for (int k = 0; k < NLAWS && len < n; k++)
    len += (size_t)snprintf(out + len, n - len, "%s%s", k ? sep : "", laws[k]->name);
  return out;
}

static int is_damage_key(const char *name) {
  for (const pf_key *key = pf_pd_damage_keys; key->name; key++)
    if (!strcmp(key->name, name)) return 1;
  return 0;
}

static void each_law(void) {
  for (int k = 0; k < NLAWS; k++) {
    const pf_pd_damage_ops *law = laws[k];
    PF_TEST_TRUE(law->name && law->name[0]);
    PF_TEST_TRUE(law->read != NULL);
    PF_TEST_TRUE(pf_pd_damage_find(law->name) == law);
    for (const pf_key *key = law->keys; key && key->name; key++)
      if (!is_damage_key(key->name) || !strcmp(key->name, "law")) {
        fprintf(stderr, "damage law '%s' reads '%s', not a key of pf_pd_damage_keys\n", law->name, key->name);
        pf_test_failures++;
      }
  }
  PF_TEST_TRUE(pf_pd_damage_find("brittle") == NULL);
  PF_TEST_TRUE(pf_pd_damage_find("") == NULL);
  char names[512], bars[512];
  PF_TEST_TRUE(!strcmp(pf_pd_damage_names(), joined(", ", names, sizeof names)));
  /* the deck reference (docs/deck_keys.md) lists the laws through this description */
  PF_TEST_TRUE(!strcmp(pf_pd_damage_keys[0].name, "law"));
  if (strcmp(pf_pd_damage_keys[0].doc, joined(" | ", bars, sizeof bars))) {
    fprintf(stderr, "the description of key 'law' is '%s'; the registered laws are '%s'\n",
            pf_pd_damage_keys[0].doc, bars);
    pf_test_failures++;
  }
}

/* A deck with `law: brittle` (line 9, its value at column 12) must be refused, naming the
 * place, the key and every registered law. */
static void unknown_law(void) {
  const char *deck = "materials:\n"
                     "  glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}\n"
                     "bodies:\n"
                     "  - name: block\n"
                     "    material: glass\n"
                     "    geometry: {shape: box, lo: [0, 0, 0], hi: [0.003, 0.003, 0.003], spacing: 0.001}\n"
                     "    horizon: 0.003015\n"
                     "    damage:\n"
                     "      law: brittle\n"
                     "time: {steps: 1}\n";
  const char *path = pf_test_write_file(0, "damage_registry", deck);
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  pf_error_clear();
  pf_error_set_quiet(1);
  const int ierr = pf_sim_create(path, &opt, &sim);
  pf_error_set_quiet(0);
  char where[512], known[512], names[400];
  snprintf(where, sizeof where, "%s:9:12: key 'law': unknown damage law 'brittle'", path);
  pf_test_refused(ierr, sim != NULL, deck, where);
  snprintf(known, sizeof known, "(known: %s)", joined(", ", names, sizeof names));
  pf_test_refused(ierr, sim != NULL, deck, known);
  pf_sim_destroy(&sim);
  remove(path);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  each_law();
  unknown_law();
  return pf_test_finish();
}
