/* The law softening (docs/theory/bond_failure.md §8) on two points one unit apart (V = 1, omega = 1,
 * horizon 1.5), s_c = 0.01, r = 4: s0 = 0.005, s1 = 0.02, the bond stretched along x through
 * s = 0.004, 0.01, 0.005 (unloading), 0.01, 0.015, 0.025, against the closed forms:
 *  - PMB, c = 18 K / (pi delta^4): the force c (1 - d) s with (1 - d) s_max = s0 (s1 - s_max) / (s1 - s0)
 *    on the envelope and d fixed below s_max (the secant); the stored energy (1/2) c (1 - d) s^2; the
 *    dissipated energy c Phi(s_max), Phi(s) = s0 s1 (s - s0) / (2 (s1 - s0)), (1/2) c s0 s1 =
 *    (1/2) c s_c^2 (the brittle bond's energy) when the bond fails at s1; nothing dissipated on
 *    unloading and reloading; no force past s1.
 *  - LPS (K, G; m = 1, theta = 3 w s, m^lost = d, w = 1 - d): the pair force 2 w s (9 K w + 15 G d^2)
 *    (derivation in the theory page); the force the gradient of the energy at fixed d (central
 *    difference of the energy below s_max); along a path of 4000 increments to failure the work
 *    done on the pair equals its stored energy plus the dissipation booked (trapezoidal work; the
 *    booking is taken at each increment's end, a first-order rule: within 2e-3 of the work). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "pd/pd_impl.h"
#include "sim/sim.h"

static const double SC = 0.01, R = 4, S0 = 0.005, S1 = 0.02, K = 1e9, G = 0.6e9, DELTA = 1.5;

static pf_sim *make(const char *model) {
  char deck[1024];
  const char *file = pf_test_write_file(0, "soft_points", "0 0 0 1\n1 0 0 1\n");
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 1000, bulk_modulus: %g, shear_modulus: %g}}\n"
           "bodies:\n  - {name: b, material: m, horizon: %g, geometry: {shape: points_file, file: %s},\n"
           "     damage: {law: softening, critical_stretch: %g, softening_ratio: %g}}\n"
           "time: {steps: 0, dt: 1}\n", model, K, G, DELTA, file, SC, R);
  pf_sim *sim = pf_test_sim("softening", deck);
  remove(file);
  return sim;
}

/* The pair at stretch s: the force on the point at x = 0 (along +x), the stored energy, and the
 * energy dissipated in this evaluation. */
static double at(pf_sim *sim, double s, double *energy, double *dissipated) {
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  for (pf_int i = 0; i < 3 * p->n_owned; i++) p->u[i] = i == 3 ? s : 0.0, p->y[i] = p->X[i] + p->u[i], p->f[i] = 0;
  PF_TEST_OK(pf_pd_body_force(b, p, 0.0));
  *energy = pf_pd_body_energy(b, p);
  *dissipated = pf_pd_body_take_damage_work(b);
  return p->X[0] < 0.5 ? p->f[0] : p->f[3];
}

static double envelope_w(double sm) { /* 1 - d */
  return sm <= S0 ? 1.0 : sm >= S1 ? 0.0 : S0 * (S1 - sm) / (sm * (S1 - S0));
}
static double phi(double sm) { return S0 * S1 * (fmin(fmax(sm, S0), S1) - S0) / (2 * (S1 - S0)); }

static void pmb_pair(void) {
  pf_sim *sim = make("pmb");
  const double c = 18 * K / (3.14159265358979323846 * pow(DELTA, 4));
  const double path[] = {0.004, 0.01, 0.005, 0.01, 0.015, 0.025}, smax[] = {0.004, 0.01, 0.01, 0.01, 0.015, 0.025};
  double booked = 0, worst_f = 0, worst_d = 0;
  for (int k = 0; k < 6; k++) {
    double e, d;
    const double f = at(sim, path[k], &e, &d), w = envelope_w(smax[k]);
    booked += d;
    PF_TEST_CLOSE(f, c * w * path[k], 1e-12, 1e-30);
    PF_TEST_CLOSE(e, 0.5 * c * w * path[k] * path[k], 1e-12, 1e-30);
    PF_TEST_CLOSE(booked, c * phi(smax[k]), 1e-12, 1e-30);
    worst_f = fmax(worst_f, fabs(f - c * w * path[k]) / (c * S0));
    worst_d = fmax(worst_d, fabs(booked - c * phi(smax[k])) / (c * phi(S1)));
  }
  PF_TEST_CLOSE(booked, 0.5 * c * SC * SC, 1e-12, 0); /* the brittle bond's energy at s_c */
  PF_TEST_TRUE(pf_sim_body(sim, 0)->fam.broken[0] != 0);
  pf_test_measure("pmb_pair_force_error", worst_f, "1");
  pf_test_measure("pmb_pair_dissipation_error", worst_d, "1");
  pf_sim_destroy(&sim);
}

static double lps_force(double s, double w) { return 2 * w * s * (9 * K * w + 15 * G * (1 - w) * (1 - w)); }

static void lps_pair(void) {
  pf_sim *sim = make("lps");
  double e, d, worst = 0;
  const double path[] = {0.004, 0.01, 0.005, 0.015};
  const double smax[] = {0.004, 0.01, 0.01, 0.015};
  for (int k = 0; k < 4; k++) {
    const double f = at(sim, path[k], &e, &d), want = lps_force(path[k], envelope_w(smax[k]));
    PF_TEST_CLOSE(f, want, 1e-12, 0);
    worst = fmax(worst, fabs(f / want - 1));
  }
  pf_test_measure("lps_pair_force_error", worst, "1");
  /* below s_max (d fixed at its value for s_max 0.015): the force is the energy's gradient */
  const double s = 0.012, h = 1e-6;
  double ep, em;
  const double f = at(sim, s, &e, &d);
  at(sim, s + h, &ep, &d);
  at(sim, s - h, &em, &d);
  PF_TEST_CLOSE(f, (ep - em) / (2 * h), 1e-7, 0);
  pf_test_measure("lps_gradient_error", fabs(f / ((ep - em) / (2 * h)) - 1), "1");
  pf_sim_destroy(&sim);

  sim = make("lps"); /* work = stored + dissipated along a path to failure */
  const int n = 4000;
  double work = 0, booked = 0, f0 = 0;
  for (int k = 1; k <= n; k++) {
    const double sk = 0.025 * k / n, fk = at(sim, sk, &e, &d);
    work += 0.5 * (f0 + fk) * (0.025 / n);
    booked += d;
    f0 = fk;
  }
  PF_TEST_TRUE(pf_sim_body(sim, 0)->fam.broken[0] != 0);
  PF_TEST_CLOSE(e, 0.0, 0, 1e-30);
  PF_TEST_CLOSE(booked, work, 2e-3, 0);
  pf_test_measure("lps_path_balance", fabs(booked / work - 1), "1");
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pmb_pair();
  lps_pair();
  return pf_test_finish();
}
