/* Critical time step (Silling & Askari 2005; Peridigm's form dt = min_i sqrt(2 rho / sum_j V_j
 * c / |xi_ij|)) for K = 14.9 GPa, rho = 2200, h = 0.5 mm at an interior point, against
 * values computed independently of the code (recomputed in docs/theory/pd.md §6): delta/h = 2,
 * 3, 4, 5 -> 9.66e-8, 1.355e-7, 1.863e-7, 2.298e-7 s. Bonds with |xi| = delta count (delta is
 * taken 1e-9 above ratio*h so that round-off in the lattice does not decide).
 *
 * Correspondence (docs/theory/materials.md §2.6): at an interior point of a 13^3 lattice (w = 1,
 * delta = 3.01 h, elastic, at rest) the field "stable_step" must be 2 lambda_min(K) / (c_L gamma
 * sum_j V |xi|), with K and the sum enumerated here over the lattice offsets and gamma from the
 * closed form int_0^a x^3 j1(x) dx = 3 sin a - 3 a cos a - a^2 sin a: gamma = max_a 4 (3 sin a
 * - 3 a cos a - a^2 sin a) / a^4 (0.4161). And pf_sym3_min_eigenvalue against matrices of known
 * spectrum, pf_sym3_min_relative_eigenvalue (the correspondence span test) against pencils of
 * known spectrum and lattice families cut by a plane. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>

#include "sim/sim.h"

/* Q diag(l) Q^T with Q a rotation about (1, 2, 2)/3 by 0.7 rad: its smallest eigenvalue. */
static void check_min_eigenvalue(double l0, double l1, double l2) {
  const double n[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, c = cos(0.7), s = sin(0.7), l[3] = {l0, l1, l2};
  double Q[3][3], A[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) /* Rodrigues */
      Q[i][j] = c * (i == j) + (1 - c) * n[i] * n[j] +
                s * (i == j ? 0 : (((j - i + 3) % 3 == 1) ? -n[3 - i - j] : n[3 - i - j]));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) A[i][j] = Q[i][0] * l[0] * Q[j][0] + Q[i][1] * l[1] * Q[j][1] + Q[i][2] * l[2] * Q[j][2];
  PF_TEST_CLOSE(pf_sym3_min_eigenvalue(A), fmin(l0, fmin(l1, l2)), 1e-12, 1e-12);
}

/* pf_sym3_min_relative_eigenvalue: with B = S S^T and A = S diag(m) S^T for an invertible S,
 * A v = lambda B v reduces to diag(m) w = lambda w (w = S^T v), so the answer is min(m); and on
 * a lattice family (delta = 3.01 h) the bonds on one side of a plane through the point, those in
 * the plane included (a crack through it), keep exactly half of the family's second moment
 * normal to the plane, more along it: 1/2; the bonds in the plane alone: 0. */
static void check_relative_eigenvalue(void) {
  const double m[4][3] = {{1, 1, 1}, {0.5, 0.5, 0.5}, {1, 0.05, 0.7}, {1, 1, 0}};
  const double d[3] = {1, 2, 0.5}, c = cos(0.4), s = sin(0.4);
  const double P[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}}, R[3][3] = {{1, 0, 0}, {0, c, -s}, {0, s, c}};
  double S[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) S[i][j] = P[i][0] * d[0] * R[0][j] + P[i][1] * d[1] * R[1][j] + P[i][2] * d[2] * R[2][j];
  for (int t = 0; t < 4; t++) {
    double A[3][3], B[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        A[i][j] = B[i][j] = 0;
        for (int k = 0; k < 3; k++) A[i][j] += S[i][k] * m[t][k] * S[j][k], B[i][j] += S[i][k] * S[j][k];
      }
    PF_TEST_CLOSE(pf_sym3_min_relative_eigenvalue(A, B), fmin(m[t][0], fmin(m[t][1], m[t][2])), 1e-12, 1e-12);
  }
  double K0[3][3] = {{0}}, Kh[3][3] = {{0}}, Kp[3][3] = {{0}};
  for (int i = -3; i <= 3; i++)
    for (int j = -3; j <= 3; j++)
      for (int k = -3; k <= 3; k++) {
        const double x[3] = {i, j, k};
        if (i * i + j * j + k * k == 0 || i * i + j * j + k * k > 3.01 * 3.01) continue;
        for (int a = 0; a < 3; a++)
          for (int b = 0; b < 3; b++) {
            K0[a][b] += x[a] * x[b];
            if (k >= 0) Kh[a][b] += x[a] * x[b];
            if (k == 0) Kp[a][b] += x[a] * x[b];
          }
      }
  PF_TEST_CLOSE(pf_sym3_min_relative_eigenvalue(K0, K0), 1.0, 1e-12, 0);
  PF_TEST_CLOSE(pf_sym3_min_relative_eigenvalue(Kh, K0), 0.5, 1e-12, 0);
  PF_TEST_CLOSE(pf_sym3_min_relative_eigenvalue(Kp, K0), 0.0, 0, 1e-12);
  double Z[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0}}; /* B not positive definite */
  PF_TEST_CLOSE(pf_sym3_min_relative_eigenvalue(K0, Z), 0.0, 0, 0);
}

/* The correspondence tests' material (steel, elastic, no hourglass control), h = 1 mm, delta =
 * 3.01 h, on a box of lattice points 12 h x 12 h x height, at rest. */
static const double CH = 1e-3, CDELTA = 3.01e-3, CE = 200e9, CNU = 0.3, CRHO = 7800;

static pf_sim *correspondence_box(const char *name, double height) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {s: {model: elastic, density: %g, youngs_modulus: %g, poissons_ratio: %g}}\n"
           "bodies:\n  - {name: b, material: s, horizon: %.17g, hourglass: {type: none},\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
           "time: {steps: 0}\n", CRHO, CE, CNU, CDELTA, 12 * CH, 12 * CH, height, CH);
  return pf_test_sim(name, deck);
}

static void correspondence_step(void) {
  const double h = CH, delta = CDELTA, E = CE, nu = CNU, rho = CRHO;
  pf_sim *sim = correspondence_box("stable_dt_corr", 12 * h);
  const pf_points *p = pf_sim_points(sim);
  const double *step = pf_points_field_get(p, "stable_step");
  PF_TEST_TRUE(step != NULL);
  double lam = 0, sum = 0, gamma = 0; /* lattice sums: K = lam I by cubic symmetry */
  for (int i = -3; i <= 3; i++)
    for (int j = -3; j <= 3; j++)
      for (int k = -3; k <= 3; k++) {
        const double r = h * sqrt(i * i + j * j + k * k);
        if (r == 0 || r > delta) continue;
        lam += h * h * h * r * r / 3, sum += h * h * h * r;
      }
  for (double a = 0.001; a < 30; a += 0.001)
    gamma = fmax(gamma, 4 * (3 * sin(a) - 3 * a * cos(a) - a * a * sin(a)) / pow(a, 4));
  PF_TEST_CLOSE(gamma, 0.4161, 0, 1e-4);
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu)), cl = sqrt((K + 4 * G / 3) / rho);
  int found = 0;
  for (pf_int i = 0; step && i < p->n_owned; i++)
    if (fabs(p->X[3 * i] - 6 * h) + fabs(p->X[3 * i + 1] - 6 * h) + fabs(p->X[3 * i + 2] - 6 * h) < 1e-9) {
      PF_TEST_CLOSE(step[i], 2 * lam / (cl * gamma * sum), 2e-4, 0);
      found++;
    }
  PF_TEST_TRUE(pf_sum_all(found) == 1);
  pf_sim_destroy(&sim);
}

/* A nearly flat family (docs/theory/materials.md §2.6, the second bound): a point of the lower
 * layer of a plate two points thick (w = 1, delta = 3.01 h, elastic, at rest) has its in-plane
 * disc and the bonds to the layer above, so K = diag(a, a, c) with c << a (square-lattice
 * symmetry). Its step must be 2 / (c_L min(gamma sum_j V |xi| / c, sum_j V |K^-1 xi|)), both sums
 * enumerated here over the lattice offsets; the second is the smaller here, so the gamma bound
 * alone fails the check. */
static void flat_family_step(void) {
  const double h = CH, delta = CDELTA, E = CE, nu = CNU, rho = CRHO;
  pf_sim *sim = correspondence_box("stable_dt_flat", h);
  const pf_points *p = pf_sim_points(sim);
  const double *step = pf_points_field_get(p, "stable_step");
  PF_TEST_TRUE(step != NULL);
  double a = 0, c = 0, len = 0, spread = 0, gamma = 0, V = h * h * h;
  for (int pass = 0; pass < 2; pass++) /* K first, then sum |K^-1 xi| */
    for (int i = -3; i <= 3; i++)
      for (int j = -3; j <= 3; j++)
        for (int k = 0; k <= 1; k++) {
          const double x = i * h, y = j * h, z = k * h, r = sqrt(x * x + y * y + z * z);
          if (r == 0 || r > delta) continue;
          if (pass == 0) a += V * x * x, c += V * z * z, len += V * r;
          else spread += V * sqrt(x * x / (a * a) + y * y / (a * a) + z * z / (c * c));
        }
  for (double q = 0.001; q < 30; q += 0.001)
    gamma = fmax(gamma, 4 * (3 * sin(q) - 3 * q * cos(q) - q * q * sin(q)) / pow(q, 4));
  PF_TEST_TRUE(c < a && spread < gamma * len / c); /* the second bound is the sharper one here */
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu)), cl = sqrt((K + 4 * G / 3) / rho);
  int found = 0;
  for (pf_int i = 0; step && i < p->n_owned; i++)
    if (fabs(p->X[3 * i] - 6 * h) + fabs(p->X[3 * i + 1] - 6 * h) + fabs(p->X[3 * i + 2]) < 1e-9) {
      PF_TEST_CLOSE(step[i], 2 / (cl * spread), 1e-9, 0);
      found++;
    }
  PF_TEST_TRUE(pf_sum_all(found) == 1);
  pf_test_measure("flat_family_bound_ratio", spread / (gamma * len / c), "1");
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double h = 5e-4, want[4] = {9.66e-8, 1.355e-7, 1.863e-7, 2.298e-7};
  for (int r = 2; r <= 5; r++) {
    char deck[1024];
    snprintf(deck, sizeof deck,

             "materials: {g: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
             "bodies:\n  - {name: b, material: g, horizon: %.17g,\n"
             "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n"
             "time: {steps: 0, safety_factor: 1.0}\n",
             r * h * (1 + 1e-9), 12 * h, 12 * h, 12 * h, h);
    pf_sim *sim = pf_test_sim("stable_dt", deck);
    PF_TEST_CLOSE(pf_sim_dt(sim), want[r - 2], 5e-4, 0);
    char key[32];
    snprintf(key, sizeof key, "dt_delta_%dh", r);
    pf_test_measure(key, pf_sim_dt(sim), "s");
    pf_sim_destroy(&sim);
  }
  check_min_eigenvalue(3, 1, 2);
  check_min_eigenvalue(-1, 5, 0.5);
  check_min_eigenvalue(2, 2, 2);
  check_min_eigenvalue(4, 1e-3, 1e-3);
  check_relative_eigenvalue();
  correspondence_step();
  flat_family_step();
  return pf_test_finish();
}
