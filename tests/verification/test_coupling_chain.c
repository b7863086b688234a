/* An elastic pulse through the whole chain PD -> transition -> overlap -> FE, back from the free
 * end and on, over 200 us, with the default coupling (the consistent form and the energy overlap,
 * docs/theory/coupling.md §2.6, §3.4): the conservation test of the coupled system.
 * One mesh of 1 mm hexahedra, NX x NY x NY mm, neo-Hookean steel (E = 200 GPa, nu = 0,
 * rho = 7800: c = sqrt(E/rho) = 5064 m/s), whose nodes carry the correspondence operator:
 *   PD x < X_TAPER (horizon 3.01 mm), the horizon tapering to 1.01 mm over 20 mm, then the
 *   overlap (beta 1 -> 0 over 20 mm), elements beyond, to the free end x = NX mm.
 * The pulse u_x = U exp(-((x - x0)/s)^2), s = 8 mm, starts at x0 = 30 mm travelling right
 * (v = -c du/dx). The references are the laws and an independent bar:
 * - energy: no external force acts, so kinetic plus stored energy (the booked, blended stored
 *   energies) stays at its initial value. Its largest excursion over the run is the time
 *   integration's own, bounded and first order in the step: 2.2e-6 of the pulse's energy at the
 *   default step (safety factor 0.8), 1.1e-6 at half of it (run `test_coupling_chain 0.4`;
 *   docs/theory/coupling.md §3.4). Asserted: 3e-6 at the default step, and 1e-6 in the slow
 *   run `verification/test_coupling_chain_fine` at safety factor 0.35;
 * - linear momentum: stays at its initial value to round-off, 1e-12 of sum m |v|;
 * - reflection at the interfaces: once the pulse is in the elements (T_REFL), the left-going
 *   energy in x < X_TAPER - 5 mm (per 1 mm slab, cross-section means, w = (v + c eps) / 2,
 *   energy M w^2, less its value at t = 0; as tests/verification/test_coupling_wave.c), over the
 *   pulse's energy, less the same in the all-FE bar (beta = 0, no PD) at the same time:
 *   below 5e-4. The all-FE bar's own value is the measure's floor (the pulse as sampled on the
 *   grid). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"

enum { NX = 160, NY = 4, NSLAB = NX + 1 };
static const double C_BAR = 5063.6965, SLAB = 1e-3, X_TAPER = 0.050, T_REFL = 18.0e-6, T_END = 200.0e-6;

static double safety = 0.8; /* the step's safety factor (argument 1 may change it, to measure how
                               the energy's excursion scales with the step) */

static pf_sim *bar(const char *tag, const char *beta, double final_time) {
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials: {steel: {model: neo_hookean, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.0}}\n"
           "bodies:\n"
           "  - name: bar\n"
           "    type: finite_element\n"
           "    material: steel\n"
           "    hourglass: {type: stiffness, coefficient: 0.05}\n"
           "    bulk_viscosity: {linear: 0, quadratic: 0}\n"
           "    initial_displacement: [\"1e-6 * exp(-((x - 0.03) / 0.008)^2)\", \"0\", \"0\"]\n"
           "    initial_velocity: [\"5063.6965 * 2e-6 * (x - 0.03) / 0.008^2 * exp(-((x - 0.03) / 0.008)^2)\", \"0\", \"0\"]\n"
           "    peridynamic:\n"
           "      horizon: \"3.01e-3 - 2.0e-3 * min(max((x - %g) / 0.02, 0), 1)\"\n"
           "      blending: \"%s\"\n"
           "      hourglass: {type: none}\n"
           "%s"
           "time: {final_time: %g, safety_factor: %g}\n",
           X_TAPER, beta, pf_test_pamgen_box(NX, NY, NY, (const double[3]){0, 0, 0}, (const double[3]){NX * 1e-3, NY * 1e-3, NY * 1e-3}),
           final_time, safety);
  return pf_test_sim(tag, deck);
}

/* The left-going energy in x < xmax (header). */
static double left_going(pf_sim *sim, double xmax) {
  const pf_points *p = pf_sim_points(sim);
  static double s[3][NSLAB]; /* mass, mass-weighted u_x and v_x per slab */
  memset(s, 0, sizeof s);
  for (pf_int i = 0; i < p->n_owned; i++) {
    const long k = lround(p->X[3 * i] / SLAB);
    if (k < 0 || k >= NSLAB) continue;
    s[0][k] += p->m[i], s[1][k] += p->m[i] * p->u[3 * i], s[2][k] += p->m[i] * p->v[3 * i];
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 3 * NSLAB, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double e = 0;
  for (int k = 1; k + 1 < NSLAB && k * SLAB < xmax; k++) {
    const double eps = (s[1][k + 1] / s[0][k + 1] - s[1][k - 1] / s[0][k - 1]) / (2 * SLAB);
    const double w = 0.5 * (s[2][k] / s[0][k] + C_BAR * eps);
    e += s[0][k] * w * w;
  }
  return e;
}

static double total_energy(pf_sim *sim) {
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  return g.kinetic_centred + g.elastic + g.fe_internal + g.hourglass + g.bulk_viscosity;
}

/* Sum of m |v| over the bar: the momentum's scale (the pulse's own momentum is about zero). */
static double momentum_scale(pf_sim *sim) {
  const pf_points *p = pf_sim_points(sim);
  double s = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    s += p->m[i] * sqrt(pow(p->v[3 * i], 2) + pow(p->v[3 * i + 1], 2) + pow(p->v[3 * i + 2], 2));
  return pf_sum_all(s);
}

/* Step until time t (or the end); 0 or the step's error. */
static int run_to(pf_sim *sim, double t, double e0, double p0[3], double *de, double *dp) {
  pf_sim_globals g;
  int ierr = 0;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  while (!ierr && !pf_sim_finished(sim) && g.time < t - 1e-12) {
    ierr = pf_sim_step(sim, 1);
    PF_TEST_OK(pf_sim_globals_get(sim, &g));
    if (de) *de = fmax(*de, fabs(total_energy(sim) - e0));
    for (int a = 0; a < 3 && dp; a++) *dp = fmax(*dp, fabs(g.momentum[a] - p0[a]));
  }
  return ierr;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  if (argc > 1) safety = atof(argv[1]);
  const char *chain_beta = argc > 2 ? argv[2] : NULL; /* (another blending, to compare) */
  /* the all-FE bar, to the reflection's time */
  pf_sim *fe = bar("all_fe", "0", T_REFL);
  PF_TEST_OK(pf_sim_step(fe, 0));
  const double kfe = total_energy(fe), lfe0 = left_going(fe, X_TAPER - 0.005);
  PF_TEST_OK(run_to(fe, T_REFL, 0, NULL, NULL, NULL));
  const double r_fe = (left_going(fe, X_TAPER - 0.005) - lfe0) / kfe;
  pf_sim_destroy(&fe);

  /* the chain, with the default forms */
  char beta[128];
  snprintf(beta, sizeof beta, "1 - min(max((x - %g) / 0.02, 0), 1)", X_TAPER + 0.02);
  pf_sim *sim = bar("chain", chain_beta ? chain_beta : beta, T_END);
  PF_TEST_OK(pf_sim_step(sim, 0));
  pf_sim_globals g0;
  PF_TEST_OK(pf_sim_globals_get(sim, &g0));
  const double e0 = total_energy(sim), l0 = left_going(sim, X_TAPER - 0.005), mscale = momentum_scale(sim);
  double de = 0, dp = 0;
  int ierr = run_to(sim, T_REFL, e0, g0.momentum, &de, &dp);
  const double r_chain = ierr ? NAN : (left_going(sim, X_TAPER - 0.005) - l0) / e0;
  if (!ierr) ierr = run_to(sim, T_END, e0, g0.momentum, &de, &dp);
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  if (!ierr) pf_test_print_digest("chain", sim);
  pf_sim_destroy(&sim);
  pf_test_measure("energy_excursion", de / e0, "1");
  pf_test_measure("momentum_error", dp / mscale, "1");
  pf_test_measure("reflection_chain", r_chain, "1");
  pf_test_measure("reflection_fe", r_fe, "1");
  pf_test_measure("reflection_difference", r_chain - r_fe, "1");
  if (pf_comm_rank() == 0)
    printf("chain PD -> taper -> overlap -> FE, defaults, to %.1f us: energy %.2e of the pulse's (largest excursion), "
           "momentum %.2e of sum m|v|; reflected at %.0f us %.2e of the pulse (all-FE bar %.2e, difference %.2e)\n",
           g.time * 1e6, de / e0, dp / mscale, T_REFL * 1e6, r_chain, r_fe, r_chain - r_fe);
  PF_TEST_TRUE(!ierr);
  PF_TEST_TRUE(g.time >= T_END - 1e-9);
  PF_TEST_TRUE(de / e0 < (safety <= 0.35 ? 1e-6 : 3e-6 * safety / 0.8)); /* (1e-6: the slow _fine run) */
  PF_TEST_TRUE(dp / mscale < 1e-12);
  PF_TEST_TRUE(fabs(r_chain - r_fe) < 5e-4);
  return pf_test_finish();
}
