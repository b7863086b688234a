/* A wave across two material interfaces in one coupled PD/FE body (material_regions in a body
 * with a peridynamic: operator, docs/theory/interfaces.md §8), the shipped inputs/bimaterial_wave.yaml
 * at two resolutions.
 *
 * A bar along x, its lateral motion held (uniaxial strain), soft (aluminium-like) except stiff
 * (steel-like) for xI1 < x < xI2, both of Poisson's ratio 1/4. The first interface, xI1, lies in
 * the peridynamic part (blending weight 1, each node a correspondence point of its elements'
 * material), the second, xI2, among the elements; the overlap lies between them. A piston pushes
 * a smooth pulse v = V sin^2(pi t / tau) into the soft part. For a one-dimensional stress wave
 * meeting an interface from material a into material b, continuity of displacement and traction
 * give the transmitted and reflected stress amplitudes (Graff 1975, Wave Motion in Elastic
 * Solids, §1.4)
 *   T_ab = 2 Z_b / (Z_a + Z_b),   R_ab = (Z_b - Z_a) / (Z_a + Z_b) = T_ab - 1,   Z = rho c,
 * c the wave speed of the geometry: with the lateral motion held, the P-wave speed
 * sqrt((K + 4G/3) / rho). A pulse's momentum is its stress amplitude times its duration and area,
 * and durations do not change across an interface, so once every pulse has left the interfaces
 * (and before any reaches an end), with p the incident momentum,
 *   momentum of x < xI1:        -R_12 p           (the pulse reflected at xI1)
 *   momentum of xI1 < x < xI2:  T_12 (1 - T_21) p  (the pulse reflected back at xI2, R_21 T_12 p)
 *   momentum of x > xI2:        T_12 T_21 p        (the pulse transmitted through both),
 * so R_12 = -p1 / p, T_12 = (p2 + p3) / p, T_21 = p3 / (p2 + p3), R_21 = -p2 / (p2 + p3). The energy
 * transmission 4 Z_a Z_b / (Z_a + Z_b)^2 is the same both ways; in a travelling pulse half the
 * energy is kinetic, so the kinetic energies' shares are 1 - T_E, T_E (1 - T_E) and T_E^2.
 * Both materials have the same Poisson's ratio, so each operator of the stiff part (element,
 * correspondence point, hourglass control) is the soft part's times K2 / K1: whatever the
 * discretization makes of the long-wave modulus, Z2 / Z1 = sqrt(rho2 K2 / (rho1 K1)).
 * The first interface is measured once the pulse has crossed it and its zone (two horizons
 * either side) holds below 1e-4 of the kinetic energy, the second likewise later (then from the
 * momentum beyond the first interface alone: the reflected pulse meets the piston meanwhile).
 * The bar is long enough that no pulse has reached an end, nor the second reflection the first
 * interface, by then. Asserted within 1 % at h = 1 mm and 0.5 mm (horizon 3.015 h, two elements
 * across, a pulse of 60 mm): the four amplitudes and the two energy transmissions; the incident
 * momentum against the piston's impulse Z1 A V tau / 2. The balances, as test_fem_bimaterial and
 * test_coupling_chain hold them: the energy (kinetic plus stored against the piston's work)
 * within 1e-3, and momentum: the internal forces sum to zero (to 1e-12 of the sum of their
 * sizes, every tenth step), so that only the piston changes the momentum. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"

static const double RHO1 = PF_TEST_RHO_SOFT, K1 = PF_TEST_K_SOFT, RHO2 = PF_TEST_RHO_STIFF, K2 = PF_TEST_K_STIFF;
static const double XI1 = 0.112, XI2 = 0.208, L = 0.312, V = 0.1, TAU = 8.784e-6, W_COARSE = 2e-3;

typedef struct {
  double p[3], k[3], near[2], ends[2]; /* momenta and kinetic energies of the three parts, KE near
                                           each interface, at each end */
} sums;

static sums measure(const pf_points *p, double delta) {
  double s[10] = {0};
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double x = p->X[3 * i], mv = p->m[i] * p->v[3 * i], ke = 0.5 * mv * p->v[3 * i];
    const int part = x < XI1 - 1e-9 ? 0 : x < XI2 + 1e-9 ? 1 : 2;
    s[part] += mv, s[3 + part] += ke;
    if (fabs(x - XI1) < 2 * delta) s[6] += ke;
    if (fabs(x - XI2) < 2 * delta) s[7] += ke;
    if (x < 3 * delta) s[8] += ke;
    if (x > L - 2 * delta) s[9] += ke;
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 10, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return (sums){{s[0], s[1], s[2]}, {s[3], s[4], s[5]}, {s[6], s[7]}, {s[8], s[9]}};
}

static double balance(pf_sim *sim) {
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  return (g.kinetic_centred + g.elastic + g.fe_internal + g.hourglass + g.bulk_viscosity) / g.external_work - 1;
}

/* Ten steps; the measures after them into s, the largest |sum of the internal forces| over the sum of
 * their sizes (along x; zero for forces in equal and opposite pairs) into *fsum. Returns the time. */
static double advance(pf_sim *sim, const pf_points *pts, double delta, sums *s, double *fsum) {
  PF_TEST_OK(pf_sim_step(sim, 10));
  *s = measure(pts, delta);
  double f[2] = {0, 0}; /* the internal forces' sum and the sum of their sizes, along x */
  for (pf_int i = 0; i < pts->n_owned; i++) f[0] += pts->f[3 * i], f[1] += fabs(pts->f[3 * i]);
  MPI_Allreduce(MPI_IN_PLACE, f, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  *fsum = fmax(*fsum, fabs(f[0]) / f[1]);
  pf_sim_globals g;
  PF_TEST_OK(pf_sim_globals_get(sim, &g));
  if (getenv("PF_TEST_TRACE") && pf_comm_rank() == 0) {
    const double k = s->k[0] + s->k[1] + s->k[2];
    printf("t %.2f us p %.4e %.4e %.4e k %.3e %.3e %.3e near %.2e %.2e ends %.2e %.2e\n", g.time * 1e6, s->p[0], s->p[1],
           s->p[2], s->k[0], s->k[1], s->k[2], s->near[0] / k, s->near[1] / k, s->ends[0] / k, s->ends[1] / k);
  }
  return g.time;
}

/* The reference density of the node nearest to x, over the ranks (the deck's materials are the
 * closed form's). */
static double density_at(const pf_points *p, double x, double h) {
  double rho = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    if (fabs(p->X[3 * i] - x) < 0.5 * h) rho = p->m[i] / p->vol[i];
  return pf_max_all(rho);
}

/* One run at spacing h (the deck's 1 mm, or its variant), named "coarse" or "fine". */
static void run(double h, const char *name) {
  const double delta = 3.015 * h, W = W_COARSE * (h / 1e-3); /* two elements across */
  const char *deck = "../inputs/bimaterial_wave.yaml";
  if (h != 1e-3) {
    char lines[4][256];
    snprintf(lines[0], sizeof lines[0], "            nx = %d", (int)lround(L / h));
    snprintf(lines[1], sizeof lines[1], "            gmax = %.17g %.17g %.17g", L, W, W);
    snprintf(lines[2], sizeof lines[2], "      horizon: %.17g", delta);
    snprintf(lines[3], sizeof lines[3], "  - {name: piston, region: {shape: box, lo: [-1, -1, -1], hi: [%.17g, 1, 1]}, "
             "velocity: [\"t < %.17g ? %g * sin(_pi * t / %.17g)^2 : 0\", \"0\", \"0\"]}", 2.5 * h, TAU, V, TAU);
    const char *keys[4] = {"nx =", "gmax =", "horizon:", "name: piston"};
    const char *l[4] = {lines[0], lines[1], lines[2], lines[3]};
    deck = pf_test_deck_variant(deck, 4, keys, l);
  }
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  PF_TEST_OK(pf_sim_create(deck, &opt, &sim));
  if (h != 1e-3) pf_test_remove_shared(deck);
  if (!sim) return;
  const pf_points *pts = pf_sim_points(sim);
  const double M1 = K1 + 4 * 0.6 * K1 / 3, c1 = sqrt(M1 / RHO1); /* (G = 0.6 K, as the deck's) */
  const double end = 2 * L / c1;
  double t = 0, fsum = 0;
  sums s1, s2;
  PF_TEST_OK(pf_sim_step(sim, 0));
  /* 1: until the piston has stopped, the pulse has crossed the first interface (the parts beyond
   * hold more than half the momentum) and left it */
  do
    t = advance(sim, pts, delta, &s1, &fsum);
  while (t < end && (t < TAU || s1.p[1] + s1.p[2] < 0.5 * (s1.p[0] + s1.p[1] + s1.p[2]) ||
                     s1.near[0] > 1e-4 * (s1.k[0] + s1.k[1] + s1.k[2])));
  /* 2: until the transmitted pulse has crossed the second interface and left it */
  s2 = s1;
  while (t < end && (s2.p[2] < 0.5 * (s2.p[1] + s2.p[2]) || s2.near[1] > 1e-4 * (s2.k[0] + s2.k[1] + s2.k[2])))
    t = advance(sim, pts, delta, &s2, &fsum);
  const double z = sqrt(RHO2 * K2 / (RHO1 * K1)); /* Z2 / Z1 */
  const double R12 = (z - 1) / (1 + z), T12 = 2 * z / (1 + z), R21 = (1 - z) / (1 + z), T21 = 2 / (1 + z);
  const double TE = 4 * z / ((1 + z) * (1 + z));
  const double p = s1.p[0] + s1.p[1] + s1.p[2], k = s1.k[0] + s1.k[1] + s1.k[2], k2 = s2.k[0] + s2.k[1] + s2.k[2];
  const double beyond = s2.p[1] + s2.p[2]; /* the momentum beyond the first interface at the second measure */
  const double r12 = -s1.p[0] / p, t12 = (s1.p[1] + s1.p[2]) / p, t21 = s2.p[2] / beyond, r21 = -s2.p[1] / beyond;
  const double te1 = (s1.k[1] + s1.k[2]) / k, te2 = s2.k[2] / (s2.k[1] + s2.k[2]);
  const double A = W * W, impulse = RHO1 * c1 * A * V * TAU / 2, bal = balance(sim);
  PF_TEST_TRUE(t < end);
  PF_TEST_CLOSE(density_at(pts, 0.5 * XI1, h), RHO1, 1e-12, 0);
  PF_TEST_CLOSE(density_at(pts, 0.5 * (XI1 + XI2), h), RHO2, 1e-12, 0);
  PF_TEST_TRUE(s1.ends[0] < 1e-3 * k);                      /* the reflected pulse not at the piston yet */
  PF_TEST_TRUE(s2.ends[1] < 1e-3 * k2 && s2.near[0] < 1e-3 * k2); /* nor the others at the far end and back at xI1 */
  PF_TEST_CLOSE(r12, R12, 0.01, 0);
  PF_TEST_CLOSE(t12, T12, 0.01, 0);
  PF_TEST_CLOSE(r21, R21, 0.01, 0);
  PF_TEST_CLOSE(t21, T21, 0.01, 0);
  PF_TEST_CLOSE(te1, TE, 0.01, 0);
  PF_TEST_CLOSE(te2, TE, 0.01, 0);
  PF_TEST_CLOSE(p, impulse, 0.01, 0);
  PF_TEST_TRUE(fabs(bal) < 1e-3);
  PF_TEST_TRUE(fsum < 1e-12);
  char key[96];
  const char *what[6] = {"reflection_pd", "transmission_pd", "reflection_fe", "transmission_fe",
                         "energy_transmission_pd", "energy_transmission_fe"};
  const double got[6] = {r12, t12, r21, t21, te1, te2}, want[6] = {R12, T12, R21, T21, TE, TE};
  for (int q = 0; q < 6; q++) snprintf(key, sizeof key, "%s_%s_error", what[q], name), pf_test_measure(key, got[q] / want[q] - 1, "1");
  snprintf(key, sizeof key, "energy_balance_%s", name), pf_test_measure(key, bal, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0) {
    printf("h %g mm, t = %.2f us:\n", h * 1e3, t * 1e6);
    for (int q = 0; q < 6; q++)
      printf("  %-24s %.5f (closed form %.5f, %+.3f %%)\n", what[q], got[q], want[q], 100 * (got[q] / want[q] - 1));
    printf("  incident momentum / impulse %.5f, energy balance %.2e, force sum %.2e, piston end %.2e, back at xI1 "
           "%.2e\n", p / impulse, bal, fsum, s1.ends[0] / k, s2.near[0] / k2);
  }
  pf_test_print_digest(name, sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  run(1e-3, "coarse");
  run(0.5e-3, "fine");
  return pf_test_finish();
}
