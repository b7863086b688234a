/* The run summary's "bytes each" per directed bond (pf_pd_body_bytes_per_bond) against a count
 * made here: every per-bond array of the family the body stores (neighbour index, broken flag,
 * the broken bond's rest length, the partial-volume fraction, the material's bond state), the
 * size of its element times the number of bonds, and, for each array that exists, malloc's
 * usable size of its block at least that much (so the arrays counted really are per-bond
 * arrays). PMB, PMB with partial volumes, elastic_plastic (bond state) and correspondence. */
#include "test_common.h"

#include <malloc.h>
#include <stdio.h>

/* sizeof of each per-bond array that exists times bonds, and the allocation check. */
static double counted_bytes(const pf_family *f, int64_t nb, const char *tag) {
  double total = 0;
  struct {
    const void *p;
    size_t elem;
    const char *name;
  } arr[] = {{f->neighbor, sizeof f->neighbor[0], "neighbor"},
             {f->broken, sizeof f->broken[0], "broken"},
             {f->rest, sizeof f->rest[0], "rest"},
             {f->vfrac, sizeof f->vfrac[0], "vfrac"},
             {f->state, (size_t)f->nstate * sizeof(double), "state"}};
  for (size_t a = 0; a < sizeof arr / sizeof arr[0]; a++) {
    if (!arr[a].p || !arr[a].elem) continue;
    const double bytes = (double)arr[a].elem * (double)nb;
    if ((double)malloc_usable_size((void *)arr[a].p) < bytes) {
      printf("%s: the %s block holds %zu bytes, less than %.0f bonds x %zu\n", tag, arr[a].name,
             malloc_usable_size((void *)arr[a].p), (double)nb, arr[a].elem);
      pf_test_failures++;
    }
    total += bytes;
  }
  return total;
}

static void check(const char *tag, const char *material, const char *body_extra, double want_per_bond) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: %s}\n"
           "bodies:\n  - {name: b, material: m, horizon: 3.0001e-3,%s\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [7e-3, 7e-3, 7e-3], spacing: 1e-3}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           material, body_extra);
  pf_sim *sim = pf_test_sim(tag, deck);
  pf_pd_body *b = pf_sim_body(sim, 0);
  const pf_family *f = pf_pd_body_family(b);
  const int64_t nb = pf_pd_body_nbonds(b);
  PF_TEST_TRUE(nb > 0);
  const double counted = counted_bytes(f, nb, tag), summary = pf_pd_body_bytes_per_bond(b) * (double)nb;
  pf_test_measure(tag, pf_pd_body_bytes_per_bond(b), "bytes");
  if (summary != counted || counted != want_per_bond * (double)nb) {
    printf("%s: summary %.0f bytes, counted %.0f (%.3g a bond), expected %.3g a bond\n", tag, summary, counted,
           counted / (double)nb, want_per_bond);
    pf_test_failures++;
  }
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *pmb = "{model: pmb, density: 1000, bulk_modulus: 1.0e9}";
  /* int32 neighbour, byte flag, float rest length: 9 bytes */
  check("pmb", pmb, "", sizeof(pf_int) + 1 + 4);
  check("pmb_partial", pmb, " partial_volumes: true,", sizeof(pf_int) + 1 + 4 + 4);
  check("elastic_plastic",
        "{model: elastic_plastic, density: 1000, bulk_modulus: 1.0e9, shear_modulus: 0.6e9, yield_stress: 1.0e7}", "",
        sizeof(pf_int) + 1 + 4 + 2 * 8); /* the plastic extension at each end, two doubles */
  check("correspondence", "{model: elastic, density: 1000, youngs_modulus: 1.0e9, poissons_ratio: 0.25}", "",
        sizeof(pf_int) + 1 + 4);
  return pf_test_finish();
}
