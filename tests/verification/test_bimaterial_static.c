/* A statically loaded bar of two materials in one peridynamic body (material_regions,
 * docs/theory/interfaces.md §5), PMB (series interface micromodulus), LPS and elastic_plastic (in
 * its elastic range at h = 1 mm, and beyond the soft part's yield: run_plastic), solved by the
 * quasi-static solver: the patch test across the interface.
 *
 * A bar along x, lateral motion held (uniaxial strain), soft material for x < x_I, stiff beyond,
 * both of Poisson's ratio 1/4. Series springs: the stress is the same in both parts, so the
 * strains are eps1 in the soft part and eps2 = eps1 K1 / K2 in the stiff part (the operators
 * differ by K2 / K1 alone, so whatever the free lateral faces make of the uniaxial-strain modulus,
 * it is in that ratio), and
 *   u(x) = eps1 x (x < x_I),   u(x) = eps1 x_I + eps2 (x - x_I) (x >= x_I).
 * A horizon-thick layer at each end follows this field (as the single-material static bar,
 * inputs/static_bar.yaml); the points between relax to equilibrium. Asserted: every point's u
 * within 1 % of the end displacement of its closed form, and the strain of each part, measured
 * between points one horizon away from the interface and from the held layers, within 1 % of
 * eps1 and eps2 (no ghost force at the interface: a uniform stress crosses it). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"

static const double RHO1 = PF_TEST_RHO_SOFT, K1 = PF_TEST_K_SOFT, RHO2 = PF_TEST_RHO_STIFF, K2 = PF_TEST_K_STIFF, EPS1 = 1e-3;

static double closed_form(double x, double xI) {
  const double eps2 = EPS1 * K1 / K2;
  return x < xI ? EPS1 * x : EPS1 * xI + eps2 * (x - xI);
}

/* One run at spacing h; returns the larger relative strain error of the two parts. */
static double run(const char *model, double h, const char *name) {
  const double delta = 3.015 * h, L = 0.06, W = 2e-3;
  const int n = (int)lround(L / h) + 1;
  const double xI = (n / 2 - 0.5) * h, xend = (n - 1) * h, eps2 = EPS1 * K1 / K2;
  char deck[4096];
  snprintf(deck, sizeof deck,
           "%s"
           "%s",
           pf_test_bimaterial_bar(model, h, delta, xI, xend, W), pf_test_series_pull(delta, xI, xend, EPS1, eps2));
  pf_sim *sim = pf_test_sim("bimaterial_static", deck);
  if (!sim) return NAN;
  PF_TEST_OK(pf_sim_run_begin(sim));
  PF_TEST_OK(pf_sim_run_advance(sim, -1));
  const pf_points *p = pf_sim_points(sim);
  double worst = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    worst = fmax(worst, fabs(p->y[3 * i] - p->X[3 * i] - closed_form(p->X[3 * i], xI)));
  worst = pf_max_all(worst) / closed_form(xend, xI);
  /* the strains of the parts, between layers a horizon from the interface and the held layers */
  const double a1 = h * ceil(2 * delta / h), b1 = h * floor((xI - delta) / h); /* (lattice layers) */
  const double a2 = h * ceil((xI + delta) / h), b2 = h * floor((xend - 2 * delta) / h);
  const double e1 = (pf_test_layer_u(p, b1, h) - pf_test_layer_u(p, a1, h)) / (b1 - a1);
  const double e2 = (pf_test_layer_u(p, b2, h) - pf_test_layer_u(p, a2, h)) / (b2 - a2);
  PF_TEST_TRUE(worst < 0.01);
  PF_TEST_CLOSE(e1, EPS1, 0.01, 0);
  PF_TEST_CLOSE(e2, eps2, 0.01, 0);
  PF_TEST_CLOSE(e1 / e2, K2 / K1, 1e-3, 0); /* the same stress on both sides */
  char tag[64], key[96];
  snprintf(tag, sizeof tag, "%s_%s", model, name);
  snprintf(key, sizeof key, "u_error_%s", tag), pf_test_measure(key, worst, "1");
  snprintf(key, sizeof key, "strain_soft_%s", tag), pf_test_measure(key, e1 / EPS1, "1");
  snprintf(key, sizeof key, "strain_stiff_%s", tag), pf_test_measure(key, e2 / eps2, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("%s h %g mm: largest |u - closed form| %.2e of the end displacement; strains %.5f and %.5f of the "
           "closed form\n", model, h * 1e3, worst, e1 / EPS1, e2 / eps2);
  pf_test_print_digest(tag, sim);
  pf_sim_destroy(&sim);
  return fmax(fabs(e1 / EPS1 - 1), fabs(e2 / eps2 - 1));
}

/* Mitchell's (2011) plastic strain after one return, at a point of the bar (three points across, w = 1,
 * V = h^3) at lateral indices (jy, kz) under the uniaxial strain e, from the lattice sums of its own
 * family (docs/theory/materials.md §1): m = sum |xi|^2 V, theta = (3/m) sum |xi| ext V,
 * sigma_tr = 3 G sqrt(5 sum (ext - theta |xi| / 3)^2 V / m), eqps = (sigma_tr - Y) / 3G when positive (H = 0).
 * The bar's lateral faces truncate every family, so this is the model's own value there, not
 * von Mises' 2 G e. */
static double eqps_closed_form(double e, double h, double delta, int jy, int kz, double G, double Y) {
  const int r = (int)floor(delta / h);
  double m = 0, s = 0, n2 = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int dx = -r; dx <= r; dx++)
      for (int dy = -r; dy <= r; dy++)
        for (int dz = -r; dz <= r; dz++) {
          const double r0 = h * sqrt((double)(dx * dx + dy * dy + dz * dz));
          if ((!dx && !dy && !dz) || jy + dy < 0 || jy + dy > 2 || kz + dz < 0 || kz + dz > 2 || r0 > delta) continue;
          const double ext = h * sqrt(dx * dx * (1 + e) * (1 + e) + dy * dy + dz * dz) - r0, V = h * h * h;
          if (pass == 0) m += r0 * r0 * V, s += r0 * ext * V;
          else n2 += pow(ext - (3 * s / m) * r0 / 3, 2) * V;
        }
  const double st = 3 * G * sqrt(5 * n2 / m);
  return st > Y ? (st - Y) / (3 * G) : 0.0;
}

/* elastic_plastic beyond the soft part's yield (each point its own K, G and yield stress,
 * docs/theory/interfaces.md §3b): perfectly plastic, Y1 = 50 MPa soft, Y2 = 2 GPa stiff, the
 * bar of run() at h = 1 mm loaded by the soft part's strain 1e-3 (the stiff part's end layer at the
 * elastic strain that carries the soft part's stress in the continuum, (K1 e1 + 2 Y1 / 3) / M2).
 * Asserted: every soft point three horizons from the interface and the held layers has the plastic
 * strain of its own family under the part's strain, measured between layers two horizons from
 * them (eqps_closed_form with G1, Y1), within 1e-3 (measured 2e-4: the interface and end zones
 * reach a little further in the yielded part, whose tangent is K alone; at two horizons 4e-3), and
 * no stiff point yields (its own Y2; the soft Y1 would yield it). */
static void run_plastic(double h) {
  const double delta = 3.015 * h, L = 0.06, W = 2 * h, G1 = 0.6 * K1, G2 = 0.6 * K2, Y1 = 50e6;
  const int n = (int)lround(L / h) + 1;
  const double xI = (n / 2 - 0.5) * h, xend = (n - 1) * h, eps2 = (K1 * EPS1 + 2 * Y1 / 3) / (K2 + 4 * G2 / 3);
  char deck[4096];
  snprintf(deck, sizeof deck,
           "materials: {soft: {model: elastic_plastic, density: %g, bulk_modulus: %g, shear_modulus: %g, yield_stress: %g},\n"
           "            stiff: {model: elastic_plastic, density: %g, bulk_modulus: %g, shear_modulus: %g, yield_stress: 2.0e9}}\n"
           "bodies:\n  - {name: bar, material: soft, horizon: %.17g,\n"
           "     material_regions: [{material: stiff, region: {shape: box, lo: [%.17g, -1, -1], hi: [1, 1, 1]}}],\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
           "%s",
           RHO1, K1, G1, Y1, RHO2, K2, G2, delta, xI, xend, W, W, h, pf_test_series_pull(delta, xI, xend, EPS1, eps2));
  pf_sim *sim = pf_test_sim("bimaterial_static_plastic", deck);
  if (!sim) return;
  PF_TEST_OK(pf_sim_run_begin(sim));
  PF_TEST_OK(pf_sim_run_advance(sim, -1));
  const pf_points *p = pf_sim_points(sim);
  const double a1 = h * ceil(2 * delta / h), b1 = h * floor((xI - 2 * delta) / h);
  const double e1 = (pf_test_layer_u(p, b1, h) - pf_test_layer_u(p, a1, h)) / (b1 - a1);
  const double *eqps = pf_points_field_get(p, "eqps");
  double worst = 0, stiff = 0, least = INFINITY;
  for (pf_int i = 0; eqps && i < p->n_owned; i++) {
    const double x = p->X[3 * i];
    if (x > xI) stiff = fmax(stiff, eqps[i]);
    if (x < a1 + delta || x > b1 - delta) continue; /* (three horizons in: the zones of the yielded part) */
    const int jy = (int)lround(p->X[3 * i + 1] / h), kz = (int)lround(p->X[3 * i + 2] / h);
    const double want = eqps_closed_form(e1, h, delta, jy, kz, G1, Y1);
    worst = fmax(worst, fabs(eqps[i] / want - 1)), least = fmin(least, want);
  }
  worst = pf_max_all(worst), stiff = pf_max_all(stiff), least = -pf_max_all(-least);
  PF_TEST_TRUE(eqps != NULL);
  PF_TEST_TRUE(least > 0);       /* (every soft interior point has yielded) */
  PF_TEST_TRUE(worst < 1e-3);    /* the soft part's own G and Y */
  PF_TEST_TRUE(stiff == 0.0);    /* the stiff part's own Y: it stays elastic */
  pf_test_measure("eqps_error_plastic", worst, "1");
  if (getenv("PF_TEST_VERBOSE") && pf_comm_rank() == 0)
    printf("elastic_plastic, soft part yielded (strain %.5e): eqps within %.2e of its family's closed form (smallest "
           "%.4e); stiff eqps max %g\n", e1, worst, least, stiff);
  pf_test_print_digest("elastic_plastic_yielded", sim);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *models[] = {"pmb", "lps"};
  for (int m = 0; m < 2; m++) {
    const double coarse = run(models[m], 1e-3, "coarse"), fine = run(models[m], 0.5e-3, "fine");
    /* the interface zone (two horizons wide) stiffens LPS by a fixed amount: its share of the
     * bar's compliance, and so the strain error, halves with the horizon (docs/theory/interfaces.md §5) */
    if (m == 1) PF_TEST_TRUE(fine < 0.6 * coarse);
  }
  run("elastic_plastic", 1e-3, "coarse"); /* in its elastic range: LPS, each end its own K and G */
  run_plastic(1e-3);
  return pf_test_finish();
}
