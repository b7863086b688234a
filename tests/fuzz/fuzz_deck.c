/* libFuzzer target for the deck loader: any bytes are written as a deck file, loaded, checked
 * against the top-level key table and each material and body against the table of its model
 * or type (as pf_sim_create does), and every scalar read back typed. Nothing may crash, leak
 * or hit undefined behaviour; bad input only returns an error. Built by scripts/fuzz.sh (clang,
 * -fsanitize=fuzzer,address,undefined); not part of the ctest run. The
 * first line "#set KEY=VALUE" of an input is also passed as a --set override. */
#include "sim/sim.h"
#include "fem/fem.h"
#include "pd/pd.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static char path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  MPI_Init(argc, argv);
  pf_error_set_quiet(1);
  pf_log_set_quiet(1);
  snprintf(path, sizeof path, "/tmp/pf_fuzz_deck_%d.yaml", (int)getpid());
  /* the part the seeds 43 and 44 include (deck composition: include:, parameters:, ${...}) */
  FILE *part = fopen("/tmp/pf_fuzz_part.yaml", "w");
  if (part) {
    fputs("materials:\n  glass:\n    model: pmb\n    density: ${rho}\n    bulk_modulus: ${K}\n", part);
    fclose(part);
  }
  return 0;
}

/* Read every scalar of a mapping as each type (exercising the typed getters on any text). */
static void read_all(const pf_deck *d, const pf_node *map) {
  for (int i = 0; i < pf_node_count(map); i++) {
    const char *key;
    const pf_node *v = pf_node_map_item(map, i, &key);
    if (!key || !v) continue;
    double r, x3[3];
    long n;
    int b;
    const char *s;
    pf_deck_real(d, map, key, &r);
    pf_deck_int(d, map, key, &n);
    pf_deck_bool(d, map, key, &b);
    pf_deck_string(d, map, key, &s);
    pf_deck_vec3(d, map, key, x3);
    read_all(d, v);
  }
}

static void check_parts(const pf_deck *d, const pf_node *root) {
  const pf_node *mats = pf_node_get(root, "materials"), *bodies = pf_node_get(root, "bodies");
  for (int k = 0; k < pf_node_count(mats); k++) {
    const char *name, *model = NULL;
    const pf_node *m = pf_node_map_item(mats, k, &name);
    if (pf_deck_string(d, m, "model", &model) || !model) continue;
    pf_deck_validate(d, m, pf_material_known(model) ? pf_material_keys : pf_pd_material_keys, "material");
  }
  for (int k = 0; k < pf_node_count(bodies); k++) {
    const pf_node *b = pf_node_item(bodies, k);
    const char *type = "peridynamic";
    pf_deck_string(d, b, "type", &type);
    pf_deck_validate(d, b, strcmp(type, "finite_element") ? pf_pd_body_keys : pf_fem_body_keys, "body");
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  fwrite(data, 1, size, f);
  fclose(f);
  /* a first line "#set KEY.PATH=VALUE" is also given as a --set override (a YAML comment) */
  char set[256] = "";
  const char *sets[1] = {set};
  if (size > 5 && !memcmp(data, "#set ", 5)) {
    size_t n = 0;
    while (5 + n < size && n + 1 < sizeof set && data[5 + n] != '\n') n++;
    memcpy(set, data + 5, n), set[n] = 0;
  }
  pf_deck *d = NULL;
  if (pf_deck_load_with(path, sets, set[0] ? 1 : 0, &d) == 0) {
    const pf_node *root = pf_deck_root(d);
    if (pf_deck_validate(d, root, pf_deck_keys, "the deck") == 0) check_parts(d, root);
    read_all(d, root);
    pf_node_hash(root);
    pf_deck_destroy(&d);
  }
  pf_error_clear();
  return 0;
}
