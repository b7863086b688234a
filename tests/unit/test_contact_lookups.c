/* The cost of short-range self-contact does not depend on the regularity of the lattice
 * (issue 33). On a regular lattice of spacing h with contact radius 0.9 h no two points are
 * within reach, so no pair asks whether it is bonded; on a lattice whose points are moved by up
 * to 0.1 h per component about one pair in eight of the nearest neighbours comes within 0.9 h,
 * and each of those must be found bonded (and intact) to be skipped. A binary search of the
 * family every step for each such pair (about 5 family entries read, each a random access) took
 * the contact from 15 % to 32 % of the loop on the bench cylinder. The bonds are now resolved
 * once per search build, and a step reads one broken flag per close pair.
 *
 * Checked from the contact module's work counters (pf_contact_counts) on an n^3 PMB box at rest
 * (n = 12, h = 1 mm, horizon 3 h, radius 0.9 h, default skin 0.9 h, 20 steps), over the steps
 * after the first (the points do not move: no search rebuild in them):
 *  - the regular lattice: each point's candidates are the lattice points within 1.8 h, the
 *    3 x 3 x 3 block around it (sqrt 3 h < 1.8 h < 2 h), so a step tests (3n - 2)^3 - n^3
 *    ordered pairs (hand count), and reads no family entry (no pair within 0.9 h);
 *  - the jittered lattice (perturbation 0.1): a step reads exactly one family entry per ordered
 *    pair of points closer than 0.9 h (all bonded: 0.9 h < 3 h), those pairs counted here by
 *    brute force over the points; a search would read several;
 *  - the jittered lattice's work a step (pairs tested + family entries read) is within 10 % of
 *    the regular lattice's. */
#include "test_common.h"

#include "contact/contact.h"

#include <stdio.h>
#include <stdlib.h>

enum { N = 12, STEPS = 20 };
static const double H = 1e-3;

/* Ordered pairs (i owned, j any point of the store) closer than r, summed over the ranks. */
static double close_pairs(const pf_points *p, double r) {
  double n = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    for (pf_int j = 0; j < p->n_total; j++) {
      const double *a = &p->y[3 * i], *b = &p->y[3 * j];
      const double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
      n += j != i && d0 * d0 + d1 * d1 + d2 * d2 < r * r;
    }
  return pf_sum_all(n);
}

typedef struct {
  long steps;            /* steps counted */
  double tested, reads;  /* over those steps, all ranks */
  double close;          /* ordered pairs closer than the contact radius */
} work;

static work work_of(const char *tag, double perturbation) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
           "bodies:\n"
           "  - name: block\n"
           "    material: glass\n"
           "    horizon: 3.0001e-3\n"
           "    geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %g,"
           " perturbation: %g}\n"
           "contact:\n  pairs:\n    - {bodies: [block, block]}\n"
           "time: {steps: %d, dt: 1e-8}\n",
           (N - 1) * H, (N - 1) * H, (N - 1) * H, H, perturbation, STEPS);
  pf_sim *sim = pf_test_sim(tag, deck);
  PF_TEST_TRUE(pf_sim_points(sim)->n_global == N * N * N);
  pf_contact *c = pf_sim_contact(sim);
  work w = {0, 0, 0, 0};
  PF_TEST_TRUE(c != NULL);
  if (c) {
    int64_t t0, r0, t1, r1;
    PF_TEST_OK(pf_sim_step(sim, 1)); /* the forces at t = 0 and the first step */
    pf_contact_counts(c, &t0, &r0);
    for (; !pf_sim_finished(sim); w.steps++) PF_TEST_OK(pf_sim_step(sim, 1)); /* one evaluation each */
    pf_contact_counts(c, &t1, &r1);
    w.tested = pf_sum_all((double)(t1 - t0)), w.reads = pf_sum_all((double)(r1 - r0));
    w.close = close_pairs(pf_sim_points(sim), 0.9 * H);
  }
  pf_sim_destroy(&sim);
  return w;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const work reg = work_of("contact_regular", 0.0), jit = work_of("contact_jittered", 0.1);
  const double pairs = (double)(3 * N - 2) * (3 * N - 2) * (3 * N - 2) - (double)N * N * N;
  PF_TEST_TRUE(reg.steps == STEPS - 1 && jit.steps == STEPS - 1);
  PF_TEST_TRUE(reg.close == 0);
  PF_TEST_TRUE(jit.close > 0.05 * N * N * N); /* the jitter brings pairs within reach */
  if (reg.tested != reg.steps * pairs || reg.reads != 0) {
    printf("regular lattice: %.0f pairs tested and %.0f family entries read over %ld steps, expected %.0f and 0\n",
           reg.tested, reg.reads, reg.steps, reg.steps * pairs);
    pf_test_failures++;
  }
  if (jit.reads != jit.steps * jit.close) {
    printf("jittered lattice: %.0f family entries read over %ld steps, expected one per close pair, %.0f\n",
           jit.reads, jit.steps, jit.steps * jit.close);
    pf_test_failures++;
  }
  const double w0 = reg.tested + reg.reads, w1 = jit.tested + jit.reads;
  pf_test_measure("regular_tested", reg.tested, "pairs");
  pf_test_measure("regular_reads", reg.reads, "reads");
  pf_test_measure("jittered_close", jit.close, "pairs");
  pf_test_measure("jittered_reads", jit.reads, "reads");
  pf_test_measure("work_ratio", w1 / w0, "1");
  if (pf_comm_rank() == 0 && (getenv("PF_TEST_VERBOSE") || !(w1 <= 1.10 * w0)))
    printf("contact work over %ld steps: regular %.0f pairs tested + %.0f family reads, jittered %.0f + %.0f"
           " (%.0f close pairs; %.3f x)\n",
           reg.steps, reg.tested, reg.reads, jit.tested, jit.reads, jit.close, w1 / w0);
  if (!(w1 <= 1.10 * w0)) {
    printf("the jittered lattice's contact does more than 1.10 x the regular one's work\n");
    pf_test_failures++;
  }
  return pf_test_finish();
}
