/* elastic_plastic (docs/theory/materials.md section 1) on small lattices.
 * 1. Below yield it is LPS: the same deck with model lps gives the same forces and energy, for
 *    omega = 1, 1/|xi| with partial volumes, and Gaussian, under a displacement with a random
 *    part. Not bitwise: lps takes the batched loops (pd/lps_batched.c: t = omega (Q |xi| +
 *    15 G e) / m, |y| from an inverse square root) and elastic_plastic the general ones, so the
 *    extensions e = |y| - |xi| differ by the round-off of |y| and |xi|, a few 1e-16 of |xi|,
 *    which at the strains here (up to 3e-4) is up to 1e-12 of e: 3e-12 of the largest force
 *    and of the energy (measured: 5e-13).
 * 2. Energy balance of the material: a 4^3 block (omega = 1 and 1/|xi|) is driven along
 *    u = lambda U (U affine, shear plus dilatation) past yield in 4000 steps and back until the
 *    conjugate force P = -sum f . U is zero. The work done on it, int P dlambda (trapezoid rule:
 *    exact between yield events, O(dlambda^2) at each point's onset), equals the energy op
 *    (stored elastic energy plus plastic work) to 1e-6. The plastic work, sum V (Y0 eqps +
 *    H eqps^2 / 2), is positive, and the rest is the elastic energy of the residual state
 *    evaluated here from theta and the residual e^dp:
 *    sum V [K theta^2 / 2 + (15 G / 2 m) sum w (e - theta |xi| / 3 - e^dp)^2 V_j]. The residual
 *    e^dp is non-zero, and each bond's copy of its neighbour's e^dp equals the neighbour's own,
 *    bit for bit. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"

static const double h = 1e-3, K = 162.0e9, G = 74.76923076923077e9;

static pf_sim *make(const char *tag, const char *material, int n, double horizon, const char *body_extra) {
  char deck[2048];
  snprintf(deck, sizeof deck,
           "materials: {m: {%s}}\n"
           "bodies:\n  - {name: b, material: m, horizon: %.17g, %s\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           material, horizon, body_extra, (n - 1) * h, (n - 1) * h, (n - 1) * h, h);
  return pf_test_sim(tag, deck);
}

/* Forces at u: y = X + u, f = 0, the body's force pass. */
static void forces(pf_sim *sim) {
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < 3 * p->n_owned; i++) p->y[i] = p->X[i] + p->u[i], p->f[i] = 0;
  PF_TEST_OK(pf_pd_body_force(pf_sim_body(sim, 0), p, 0.0));
}

/* A reproducible displacement: affine plus a hash of the position (the same for any point order). */
static void displace(pf_points *p, double scale) {
  const double A[3][3] = {{1.0, 0.3, -0.2}, {0.1, -0.6, 0.4}, {-0.5, 0.2, 0.7}};
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double *X = &p->X[3 * i];
    unsigned q = (unsigned)lround(X[0] / h) * 73856093u ^ (unsigned)lround(X[1] / h) * 19349663u ^
                 (unsigned)lround(X[2] / h) * 83492791u;
    for (int a = 0; a < 3; a++) {
      q = q * 1103515245u + 12345u;
      double r = ((q >> 8) & 0xffff) / 65536.0 - 0.5;
      p->u[3 * i + a] = scale * (A[a][0] * X[0] + A[a][1] * X[1] + A[a][2] * X[2] + 0.5 * h * r);
    }
  }
}

/* The largest over the cases: |f_ep - f_lps| / max |f_lps| below yield; |energy / work - 1|. */
static double worst_lps, worst_balance;

static void below_yield_is_lps(void) {
  const char *bodies[3] = {"", "influence: inverse_distance, partial_volumes: true,", "influence: gaussian,"};
  char ep[256], lps[256];
  snprintf(ep, sizeof ep, "model: elastic_plastic, density: 7870, bulk_modulus: %.17g, shear_modulus: %.17g, "
           "yield_stress: 1.0e15", K, G);
  snprintf(lps, sizeof lps, "model: lps, density: 7870, bulk_modulus: %.17g, shear_modulus: %.17g", K, G);
  for (int c = 0; c < 3; c++) {
    pf_sim *s1 = make("ep_lps_a", ep, 7, 3.0001 * h, bodies[c]);
    pf_sim *s2 = make("ep_lps_b", lps, 7, 3.0001 * h, bodies[c]);
    pf_points *p1 = pf_sim_points(s1), *p2 = pf_sim_points(s2);
    PF_TEST_TRUE(p1->n_owned == p2->n_owned);
    double fbig = 0, diff = 0;
    for (int step = 1; step <= 3; step++) { /* three load steps: the state stays zero */
      displace(p1, 1e-4 * step), displace(p2, 1e-4 * step);
      forces(s1), forces(s2);
      for (pf_int i = 0; i < 3 * p1->n_owned; i++) {
        fbig = fmax(fbig, fabs(p2->f[i]));
        diff = fmax(diff, fabs(p1->f[i] - p2->f[i]));
      }
    }
    PF_TEST_TRUE(fbig > 0);
    PF_TEST_TRUE(diff <= 3e-12 * fbig);
    worst_lps = fmax(worst_lps, diff / fbig);
    if (!(diff <= 3e-12 * fbig) || getenv("PF_TEST_VERBOSE"))
      fprintf(stderr, "case %d: max |f_ep - f_lps| = %g of %g N\n", c, diff, fbig);
    double e1 = pf_pd_body_energy(pf_sim_body(s1, 0), p1), e2 = pf_pd_body_energy(pf_sim_body(s2, 0), p2);
    PF_TEST_CLOSE(e1, e2, 3e-12, 0);
    const double *eqps = pf_points_field_get(p1, "eqps");
    for (pf_int i = 0; i < p1->n_owned; i++) PF_TEST_TRUE(eqps[i] == 0);
    pf_sim_destroy(&s1);
    pf_sim_destroy(&s2);
  }
}

/* P = -sum f . U over the owned points (U = A X). */
static double conjugate_force(pf_sim *sim, const double A[3][3], double lambda) {
  pf_points *p = pf_sim_points(sim);
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int a = 0; a < 3; a++)
      p->u[3 * i + a] = lambda * (A[a][0] * p->X[3 * i] + A[a][1] * p->X[3 * i + 1] + A[a][2] * p->X[3 * i + 2]);
  forces(sim);
  double P = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int a = 0; a < 3; a++)
      P -= p->f[3 * i + a] * (A[a][0] * p->X[3 * i] + A[a][1] * p->X[3 * i + 1] + A[a][2] * p->X[3 * i + 2]);
  return pf_sum_all(P);
}

static void energy_balance(void) {
  const double Y0 = 1.72e6, H = 19.4e9, A[3][3] = {{1.0, 0.4, 0}, {0.4, -0.3, 0.2}, {0, 0.2, -0.2}};
  const char *bodies[2] = {"", "influence: inverse_distance,"};
  char mat[256];
  snprintf(mat, sizeof mat, "model: elastic_plastic, density: 7870, bulk_modulus: %.17g, shear_modulus: %.17g, "
           "yield_stress: %.17g, hardening_modulus: %.17g", K, G, Y0, H);
  for (int c = 0; c < 2; c++) {
    pf_sim *sim = make("ep_energy", mat, 4, 1.7 * h, bodies[c]);
    pf_points *p = pf_sim_points(sim);
    pf_pd_body *b = pf_sim_body(sim, 0);
    enum { NSTEP = 4000 };
    const double lmax = 5e-5, dl = lmax / NSTEP;
    double W = 0, P0 = 0, l = 0, Pmax = 0;
    for (int s = 1; s <= NSTEP; s++) { /* loading */
      double P1 = conjugate_force(sim, A, l + dl);
      W += 0.5 * (P0 + P1) * dl;
      P0 = P1, l += dl, Pmax = fmax(Pmax, fabs(P1));
    }
    int guard = 0;
    while (P0 > 0 && guard++ < 2 * NSTEP) { /* elastic unloading until P changes sign */
      double P1 = conjugate_force(sim, A, l - dl);
      if (P1 <= 0) { /* the last step ends where P = 0 (P is linear in lambda while unloading) */
        double lz = l - dl * P0 / (P0 - P1);
        P1 = conjugate_force(sim, A, lz);
        W += 0.5 * (P0 + P1) * (lz - l);
        P0 = P1, l = lz;
        break;
      }
      W += 0.5 * (P0 + P1) * -dl;
      P0 = P1, l -= dl;
    }
    PF_TEST_TRUE(fabs(P0) < 1e-9 * Pmax);
    const double E = pf_sum_all(pf_pd_body_energy(b, p));
    PF_TEST_CLOSE(E, W, 1e-6, 0);
    /* plastic work from eqps; elastic energy of the residual state, here */
    const double *eqps = pf_points_field_get(p, "eqps"), *theta = pf_points_field_get(p, "dilatation");
    const pf_family *fam = pf_pd_body_family(b);
    double D = 0, Wel = 0, edpmax = 0, eqmax = 0;
    int mirrors = 1;
    for (pf_int i = 0; i < p->n_owned; i++) {
      D += p->vol[i] * (Y0 * eqps[i] + 0.5 * H * eqps[i] * eqps[i]);
      eqmax = fmax(eqmax, eqps[i]);
      double m = 0, dev = 0;
      for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
        pf_int j = fam->neighbor[k];
        double r0 = 0, r = 0;
        for (int a = 0; a < 3; a++) {
          r0 += pow(p->X[3 * j + a] - p->X[3 * i + a], 2);
          r += pow(p->X[3 * j + a] + p->u[3 * j + a] - p->X[3 * i + a] - p->u[3 * i + a], 2);
        }
        r0 = sqrt(r0), r = sqrt(r);
        const double w = c == 0 ? 1.0 : 1.0 / r0, V = p->vol[j];
        const double ed = r - r0 - theta[i] * r0 / 3 - fam->state[2 * k];
        m += w * r0 * r0 * V;
        dev += w * ed * ed * V;
        edpmax = fmax(edpmax, fabs(fam->state[2 * k]));
        for (int64_t q = fam->offset[j]; q < fam->offset[j + 1]; q++) /* bond (j, i) */
          if (fam->neighbor[q] == i) mirrors &= fam->state[2 * q] == fam->state[2 * k + 1];
      }
      Wel += p->vol[i] * (0.5 * K * theta[i] * theta[i] + 7.5 * G / m * dev);
    }
    PF_TEST_TRUE(D > 0.05 * E);
    PF_TEST_CLOSE(E - D, Wel, 1e-9, 0);
    PF_TEST_TRUE(edpmax > 0);
    PF_TEST_TRUE(mirrors);
    worst_balance = fmax(worst_balance, fabs(E / W - 1));
    if (!(fabs(E / W - 1) <= 1e-6) || getenv("PF_TEST_VERBOSE"))
      fprintf(stderr, "case %d: work %.10g J, energy op %.10g J (rel %.2e), plastic work %.6g J, residual elastic "
              "%.6g J, max eqps %.3g, max |e^dp| %.3g m\n", c, W, E, E / W - 1, D, Wel, eqmax, edpmax);
    pf_sim_destroy(&sim);
  }
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  below_yield_is_lps();
  energy_balance();
  pf_test_measure("below_yield_lps_difference", worst_lps, "1");
  pf_test_measure("work_energy_balance", worst_balance, "1");
  return pf_test_finish();
}
