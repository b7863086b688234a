/* Uniaxial and hydrostatic compression of a block: correspondence PD and the FE module, with the
 * same J2 material (one constitutive library), give the same stress-strain response within 1 %
 * (the test Littlewood 2014 describes, "Examples of Simple Test Problems"), and both
 * follow the closed forms of rate-form J2 with linear hardening:
 *   uniaxial stress, compression at log strain e < 0: |sigma_zz| = E |e| below yield, above
 *     |sigma_zz| = sigma_y0 + H eqps with eqps = |e| - |sigma_zz| / E, i.e.
 *     |sigma_zz| = (sigma_y0 + H |e|) / (1 + H / E)   (Jaumann rate = log-strain rate here);
 *   hydrostatic, J = det F: sigma_m = K ln J (tr D = d ln J / dt; no yield).
 * The block is 10 x 10 x 20 mm; PD: 1 mm lattice, horizon 3.01 mm, grips of three layers at each
 * end driven with v_z = -rate z (affine, so the bonds into the grips see the homogeneous field);
 * FE: 5 x 5 x 10 hexahedra, end faces driven the same way. Loading is ramped over 20 us and runs
 * to 4 % strain at 200 /s (many wave transits: quasi-static). Stress: the mean over the points /
 * nodes of the middle 4 mm. */
#include "sim/sim.h"
#include "fem/fem.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double E = 200e9, NU = 0.3, SY = 400e6, H = 2e9, RATE = 200, TRAMP = 2e-5;

/* Driven velocity of body `body` (x0 its x origin) on the box [lo, hi]: all three components
 * (hydrostatic) or v_z only (uniaxial). */
static void bc(char *out, size_t cap, const char *body, double x0, const double lo[3], const double hi[3], int hydro) {
  char v[3][96];
  const char *axis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; a++) {
    if (a < 2 && !hydro) snprintf(v[a], sizeof v[a], "free");
    else snprintf(v[a], sizeof v[a], "\"-%g * (%s - %g) * min(t / %g, 1)\"", RATE, axis[a], a ? 0.0 : x0, TRAMP);
  }
  size_t n = strlen(out);
  snprintf(out + n, cap - n, "  - {body: %s, region: {shape: box, lo: [%g, %g, %g], hi: [%g, %g, %g]}, velocity: [%s, %s, %s]}\n",
           body, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], v[0], v[1], v[2]);
}

/* Uniaxial: the PD grips (z < 3.5 mm, z > 16.5 mm) and the FE end faces. Hydrostatic: every PD
 * point within 3.5 mm of a face and every FE boundary node (six slabs each). */
static pf_sim *make(int hydro) {
  char deck[8192], bcs[4096] = "";
  const double L[3] = {0.01, 0.01, 0.02};
  for (int f = 0; f < 2; f++) {
    const char *body = f ? "hex" : "pd";
    const double x0 = f ? 0.02 : 0.0, w = f ? 1e-6 : 3.5e-3;
    for (int a = hydro ? 0 : 2; a < 3; a++)
      for (int side = 0; side < 2; side++) {
        double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
        if (side) lo[a] = (a ? 0.0 : x0) + L[a] - w;
        else hi[a] = (a ? 0.0 : x0) + w;
        bc(bcs, sizeof bcs, body, x0, lo, hi, hydro);
      }
  }
  snprintf(deck, sizeof deck,
           "materials:\n  steel: {model: j2, density: 7800, youngs_modulus: %g, poissons_ratio: %g, "
           "yield_stress: %g, hardening_modulus: %g}\n"
           "bodies:\n"
           "  - {name: pd, material: steel, horizon: 3.01e-3,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.01, 0.01, 0.02], spacing: 1.0e-3, origin: [0.5e-3, 0.5e-3, 0.5e-3]}}\n"
           "  - name: hex\n    type: finite_element\n    material: steel\n%s"
           "boundary_conditions:\n%s"
           "time: {final_time: 2.0e-4}\n",
           E, NU, SY, H, pf_test_pamgen_box(5, 5, 10, (const double[3]){0.02, 0, 0}, (const double[3]){0.03, 0.01, 0.02}),
           bcs);
  return pf_test_sim(hydro ? "compression_hydro" : "compression_uniaxial", deck);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  for (int hydro = 0; hydro <= 1; hydro++) {
    pf_sim *sim = make(hydro);
    const pf_points *p = pf_sim_points(sim);
    double worst = 0, worst_ref = 0;
    for (int k = 1; k <= 8; k++) {
      const double t_k = k * 2.5e-5;
      pf_sim_globals g;
      do {
        PF_TEST_OK(pf_sim_step(sim, 1));
        PF_TEST_OK(pf_sim_globals_get(sim, &g));
      } while (g.time < t_k && !pf_sim_finished(sim));
      PF_TEST_OK(pf_fem_body_output_fields(pf_sim_fem_body(sim, 1), pf_sim_points(sim)));
      const double *s = pf_points_field_get(p, "stress");
      double sum[2] = {0, 0}, cnt[2] = {0, 0};
      for (pf_int i = 0; i < p->n_owned; i++) {
        const double *X = &p->X[3 * i];
        if (fabs(X[2] - 0.01) > 2.001e-3 || (hydro && (fabs(X[0] - (X[0] > 0.015 ? 0.025 : 0.005)) > 2.001e-3 || fabs(X[1] - 0.005) > 2.001e-3))) continue;
        const int fe = X[0] > 0.015;
        sum[fe] += hydro ? (s[6 * i] + s[6 * i + 1] + s[6 * i + 2]) / 3.0 : s[6 * i + 2];
        cnt[fe] += 1;
      }
      for (int b = 0; b < 2; b++) sum[b] = pf_sum_all(sum[b]) / pf_sum_all(cnt[b]);
      /* the driven log strain: the ramp integrates to rate (t - tramp/2) once past the ramp */
      const double t = g.time, e = log(1 - RATE * (t < TRAMP ? t * t / (2 * TRAMP) : t - TRAMP / 2));
      const double ref = hydro ? (E / (3 * (1 - 2 * NU))) * 3 * e
                               : (fabs(e) * E < SY ? E * e : -(SY + H * fabs(e)) / (1 + H / E));
      /* the rate form integrates D, not ln(F): the same to O(e^2) for the closed forms */
      PF_TEST_CLOSE(sum[0], sum[1], 0.01, 0);
      PF_TEST_CLOSE(sum[0], ref, 0.01, 0);
      PF_TEST_CLOSE(sum[1], ref, 0.01, 0);
      worst = fmax(worst, fabs(sum[0] / sum[1] - 1)), worst_ref = fmax(worst_ref, fabs(sum[0] / ref - 1));
    }
    if (getenv("PF_TEST_DEBUG")) {
      const double *s = pf_points_field_get(p, "stress");
      for (pf_int i = 0; i < p->n_owned; i += 97)
        printf("X %g %g %g  s %g %g %g %g %g %g\n", p->X[3*i], p->X[3*i+1], p->X[3*i+2], s[6*i], s[6*i+1], s[6*i+2], s[6*i+3], s[6*i+4], s[6*i+5]);
    }
    pf_test_measure(hydro ? "hydrostatic_vs_fe" : "uniaxial_vs_fe", worst, "1");
    pf_test_measure(hydro ? "hydrostatic_vs_closed_form" : "uniaxial_vs_closed_form", worst_ref, "1");
    if (pf_comm_rank() == 0 && getenv("PF_TEST_VERBOSE"))
      printf("%s: |PD/FE - 1| <= %.4f, |PD/closed form - 1| <= %.4f\n", hydro ? "hydrostatic" : "uniaxial", worst, worst_ref);
    pf_test_print_digest(hydro ? "compression_hydro" : "compression_uniaxial", sim);
    pf_sim_destroy(&sim);
  }
  return pf_test_finish();
}
