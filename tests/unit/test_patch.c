/* Patch tests: an affine displacement u = A X gives zero force at every point whose family
 * (and, for LPS, whose neighbours' families) is complete, to round-off, for PMB and LPS; an
 * isotropic expansion u = eps X gives theta = 3 eps at every point, surface points included,
 * because m and theta use the same quadrature (docs/theory/pd.md). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

enum { N = 16 };
static const double h = 1e-3, K = 14.9e9, G = 8.94e9;

static pf_sim *make(const char *model) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 2200, bulk_modulus: %g, shear_modulus: %g}}\n"
           "bodies:\n  - {name: b, material: m, horizon: %.17g,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           model, K, G, 3.0001 * h, (N - 1) * h, (N - 1) * h, (N - 1) * h, h);
  return pf_test_sim("patch", deck);
}

/* Largest |f| over points at least `depth` from every face. */
static double interior_force(const pf_points *p, double depth) {
  double worst = 0, L = (N - 1) * h;
  for (pf_int i = 0; i < p->n_owned; i++) {
    int inside = 1;
    for (int a = 0; a < 3; a++) inside &= p->X[3 * i + a] > depth - 1e-12 && p->X[3 * i + a] < L - depth + 1e-12;
    if (!inside) continue;
    worst = fmax(worst, sqrt(p->f[3 * i] * p->f[3 * i] + p->f[3 * i + 1] * p->f[3 * i + 1] + p->f[3 * i + 2] * p->f[3 * i + 2]));
  }
  return worst;
}

static void apply(pf_sim *sim, const double A[3][3]) {
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int a = 0; a < 3; a++) {
      p->u[3 * i + a] = 0;
      for (int b = 0; b < 3; b++) p->u[3 * i + a] += A[a][b] * p->X[3 * i + b];
      p->y[3 * i + a] = p->X[3 * i + a] + p->u[3 * i + a];
    }
  for (pf_int i = 0; i < 3 * p->n_owned; i++) p->f[i] = 0;
  PF_TEST_OK(pf_pd_body_force(pf_sim_body(sim, 0), p, 0.0));
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double eps = 1e-3, A[3][3] = {{1e-3, 2e-4, -3e-4}, {5e-4, -7e-4, 1e-4}, {-2e-4, 3e-4, 4e-4}};
  const double scale = K * eps * h * h; /* force on one point from a stress K eps */
  const char *models[2] = {"pmb", "lps"};
  for (int k = 0; k < 2; k++) {
    pf_sim *sim = make(models[k]);
    pf_points *p = pf_sim_points(sim);
    apply(sim, A);
    double depth = (k == 0 ? 3 : 6) * h; /* PMB: one horizon; LPS: two (neighbours' theta) */
    double fin = interior_force(p, depth), fsurf = interior_force(p, 0);
    PF_TEST_TRUE(p->n_owned == N * N * N);
    PF_TEST_TRUE(fin < 1e-10 * scale);
    PF_TEST_TRUE(fsurf > 1e-2 * scale); /* the surface is loaded: the test can fail */
    if (!(fin < 1e-10 * scale)) fprintf(stderr, "%s: interior |f| = %g N, scale %g N\n", models[k], fin, scale);
    char key[48];
    snprintf(key, sizeof key, "%s_interior_force", models[k]);
    pf_test_measure(key, fin / scale, "K eps h^2");
    snprintf(key, sizeof key, "%s_surface_force", models[k]);
    pf_test_measure(key, fsurf / scale, "K eps h^2");
    if (k == 1) {
      const double iso[3][3] = {{eps, 0, 0}, {0, eps, 0}, {0, 0, eps}};
      apply(sim, iso);
      const double *th = pf_points_field_get(p, "dilatation");
      double worst = 0;
      for (pf_int i = 0; i < p->n_owned; i++) {
        PF_TEST_CLOSE(th[i], 3 * eps, 1e-12, 0);
        worst = fmax(worst, fabs(th[i] / (3 * eps) - 1));
      }
      pf_test_measure("lps_theta_error", worst, "1");
    }
    pf_sim_destroy(&sim);
  }
  return pf_test_finish();
}
