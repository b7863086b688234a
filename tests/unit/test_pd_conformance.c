/* Conformance suite over every registered peridynamic material: each name of
 * pf_pd_material_names() as a PD material, and a non-ordinary correspondence body
 * (pd/material_correspondence.c) for each continuum model of pf_material_names(). Both lists
 * are parsed at run time; a name without deck parameters in `cases` below fails the test (add
 * its parameters there). Each material is put on a lattice block (7^3 points, spacing h, horizon
 * 3.01 h, centred on the origin; 15^3 for the patch test, where 27 points are two horizons
 * deep) and checked with forces evaluated by
 * pf_pd_body_force, without time stepping:
 *  1. zero deformation -> zero force (round-off of K h^2);
 *  2. a rigid motion y = Q X + c (30 degrees about an oblique axis) -> zero force at every point
 *     (round-off of the 1 % strain force scale 0.01 K h^2); and objectivity: rotating a strained
 *     state, y2 = Q y1 + c, rotates every force, f2 = Q f1;
 *  3. correspondence: y = F X + c, F non-symmetric, det F > 0: the shape-tensor deformation
 *     gradient Fbar (field "correspondence", components 9..17, by columns) equals F to 1e-12 at
 *     every point, boundary included (Fbar = [sum w Y (x) xi] K^-1 = F K K^-1 for affine Y = F xi),
 *     and its rate Fdot (components 18..26) equals (F - I) / dt;
 *  4. linear and angular momentum: sum_i f_i = 0 and sum_i y_i x f_i = 0 to round-off of
 *     sum |f_i| and sum |y_i| |f_i| along a seeded random non-affine path (3 steps), with each
 *     damage law the material accepts (a law it rejects at set-up, naming the law's key, is
 *     skipped) and, for correspondence, the viscous hourglass control;
 *  5. energy consistent with force: (a) where the energy op is a stored energy of y alone (pmb,
 *     lps), -dW/dy_i by central differences equals f_i to 1e-6 of |f_i|; for correspondence with
 *     a hyperelastic model whose strain energy psi the test knows (neo_hookean), the force is
 *     -d/dy_i sum_k V_k psi(Fbar_k) (Silling et al. 2007, J. Elast. 88:151, sec. 15: with full
 *     families, d Fbar_k / d y_i gives f_i = V_i sum_j w V_j (P_i K_i^-1 + P_j K_j^-1) xi, P =
 *     dpsi/dF), checked the same way with the test's own Fbar, hourglass control off; (b) for
 *     every material, the energy op (stored energy, or stress work + plastic work + hourglass
 *     work) equals the work done on the body, -sum_n (f_n-1 + f_n)/2 . (y_n - y_n-1), along a
 *     path out and half-way back (plastic models flow and unload), for correspondence with each
 *     hourglass control: both sides are trapezoid-rule quadratures of one integral, so their
 *     difference must be small (1e-3) and fall as N^-2 with the number of steps N (see
 *     check_energy_path). The neo-Hookean model
 *     (material/material_neo_hookean.c: sigma = (G/J)(b - I) + (lambda ln J / J) I) derives from
 *       psi(F) = G/2 (tr F^T F - 3) - G ln J + lambda/2 (ln J)^2,  lambda = K - 2G/3
 *     (P = dpsi/dF = G (F - F^-T) + lambda ln J F^-T, and J^-1 P F^T is the stress above);
 *  6. linear patch test: y = (I + A) X + c with a small general A: zero force, to 1e-10 of
 *     K |A| h^2, at the points whose neighbours all have complete families (two horizons deep:
 *     state-based and correspondence forces use the neighbours' m, theta, K^-1);
 *  7. correspondence with a damage variable: a point that loses a bond while nothing moves keeps
 *     its stress (check_lost_bond).
 *
 * How a deformation is imposed. Correspondence bodies with a rate-form (hypoelastic, J2,
 * Johnson-Cook) model advance their stress only over a step dt > 0, from the relative
 * velocities: Fdot = [sum w (v_j - v_i) (x) xi] K^-1, L = Fdot Fm^-1 at the mid-step Fm = Fbar -
 * dt/2 Fdot, D = sym L, the previous stress rotated by the Hughes-Winget increment of W = skew L.
 * Setting y alone (dt = 0, or v = 0) leaves such a stress where it was, so checks 1, 2, 6 would
 * pass vacuously. Every check therefore moves the body as the integrator does: a step of dt > 0
 * with v = (y_new - y_old) / dt. Fbar is linear in y, so Fdot = (Fbar_new - Fbar_old) / dt and
 * Fm = (Fbar_old + Fbar_new) / 2 exactly. From the reference state to y = F X this gives
 * L = (2/dt) (F - I)(F + I)^-1; for a rotation F = Q that is the Cayley transform, skew, so
 * D = 0 and the Hughes-Winget increment (I - dt W/2)^-1 (I + dt W/2) is Q itself: a finite
 * rotation in one step is exact. Likewise from y1 = F1 X to y2 = Q y1: Fdot = (Q - I) F1 / dt,
 * Fm = (Q + I) F1 / 2, the same L, so a stressed state is rotated exactly (check 2). A general
 * y = F X from the reference state gives the rate-form stress C : sym[2 (F - I)(F + I)^-1], the
 * small-strain response to first order. Hyperelastic models (neo_hookean; modified_johnson_cook is Hencky-elastic below
 * yield) ignore the rate, so the same imposition serves them. Ordinary models ignore dt and v.
 * Each check builds a fresh body (stress, plastic strains, broken bonds start from zero).
 *
 * Serial: sums run over the owned points of one rank (no ghosts). */
#include "test_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"
#include "fem/fem.h"

static const double h = 1e-3;        /* lattice spacing, m */
static const double DT = 1e-6;       /* the step of every imposed motion, s */
static const double HORIZON = 3.01;  /* in spacings */
enum { NSIDE = 7, NPATCH = 15 };     /* points per side: the checks; the patch test */

/* ---- the materials the test knows --------------------------------------------------------- */
typedef double (*psi_fn)(const double H[3][3], double K, double G); /* H = F - I */
static double psi_neo_hookean(const double H[3][3], double K, double G);

typedef struct {
  const char *model;  /* a name of pf_pd_material_names() or pf_material_names() */
  const char *params; /* the rest of the material mapping, flow style */
  int potential;      /* the energy op is a stored energy, a function of y alone (check 5a) */
  psi_fn psi;         /* correspondence: the model's strain energy per reference volume, or NULL */
  double K, G;        /* the moduli psi takes (as in params) */
} mat_case;

static const mat_case cases[] = {
    {"pmb", "density: 7800, bulk_modulus: 160e9", 1, NULL, 0, 0},
    {"lps", "density: 7800, bulk_modulus: 160e9, shear_modulus: 80e9", 1, NULL, 0, 0},
    /* history (plastic bond extensions): check 5b */
    {"elastic_plastic",
     "density: 7800, bulk_modulus: 160e9, shear_modulus: 80e9, yield_stress: 400e6, "
     "hardening_modulus: 2e9", 0, NULL, 0, 0},
    /* continuum models (decks of tests/unit/test_fem_materials.c) */
    {"elastic", "density: 7800, youngs_modulus: 200e9, poissons_ratio: 0.3", 0, NULL, 0, 0},
    {"neo_hookean", "density: 1100, bulk_modulus: 2.0e9, shear_modulus: 0.6e9", 0, psi_neo_hookean,
     2.0e9, 0.6e9},
    {"j2",
     "density: 8930, youngs_modulus: 117e9, poissons_ratio: 0.35, yield_stress: 400e6, "
     "hardening_modulus: 100e6", 0, NULL, 0, 0},
    {"johnson_cook",
     "density: 8960, youngs_modulus: 124e9, poissons_ratio: 0.34, specific_heat: 383, "
     "taylor_quinney: 0.9, johnson_cook: {A: 90e6, B: 292e6, C: 0.025, n: 0.31, m: 1.09, "
     "reference_strain_rate: 1.0, reference_temperature: 298, melt_temperature: 1356}", 0, NULL, 0, 0},
    {"modified_johnson_cook",
     "density: 2700, youngs_modulus: 72e9, poissons_ratio: 0.343, modified_johnson_cook: "
     "{sigma0: 250e6, B: 365e6, n: 0.04, C: 0.002, reference_strain_rate: 1}, damage: {d1: 0.875, "
     "d2: 0.13, d3: -1.5, d4: 0, reference_strain_rate: 1}", 0, NULL, 0, 0},
    /* isotropic constants (the elastic case's, E = 200 GPa, nu = 0.3). An anisotropic ply (T300/5208,
     * at [30, 20, 10] or on the axes) passes every check but the energy path's second-order
     * ratio: 0.48-0.51 (first order; the stress work's rotated old stress against the forces'
     * unrotated one differ by dt (W s - s W) : D, zero only when s and D commute:
     * docs/theory/fem_materials.md §8) */
    {"orthotropic",
     "density: 7800, E1: 200e9, E2: 200e9, E3: 200e9, G12: 76.923076923076923e9, G13: 76.923076923076923e9, G23: 76.923076923076923e9, "
     "nu12: 0.3, nu13: 0.3, nu23: 0.3", 0, NULL, 0, 0},
};
enum { NCASES = sizeof cases / sizeof cases[0] };

/* Body variants: extra keys of the body mapping. `key` is what a material that does not support
 * the variant names in its set-up error (then the variant is skipped for it); NULL: required. */
typedef struct {
  const char *label, *body, *key;
  int corr_only;   /* hourglass keys exist only for correspondence bodies */
  int must_damage; /* the momentum path must break bonds */
} variant;

static const variant HG_NONE = {"hourglass none", "    hourglass: {type: none}\n", NULL, 1, 0};
static const variant HG_VISCOUS = {"viscous hourglass", "    hourglass: {type: viscous, coefficient: 0.5}\n",
                                   NULL, 1, 0};
static const variant PLAIN = {"default keys", "", NULL, 0, 0};
/* Damage: the momentum path stretches nearest bonds by up to ~3 %. critical_energy: the PMB
 * bond energy (1/2) c s^2 |xi| exceeds w_c = 4 G0 / (pi delta^4) when 9 K s^2 |xi| > 4 G0, i.e.
 * s > 0.75 % at |xi| = h for G0 = 2e4 J/m^2, K = 160 GPa. critical_damage 1e-3: a correspondence
 * bond fails once an end's damage variable exceeds it; modified_johnson_cook's damage (plastic
 * strain over a failure strain ~1) reaches ~6e-3 on this path, at the most strained points. */
static const variant DAMAGE[] = {
    {"critical_stretch", "    damage: {law: critical_stretch, critical_stretch: 0.01}\n", NULL, 0, 1},
    {"critical_energy", "    damage: {law: critical_energy, energy_release_rate: 2e4}\n", "critical_energy", 0, 1},
    {"critical_damage", "    critical_damage: 1e-3\n", "critical_damage", 0, 1},
};
enum { NDAMAGE = sizeof DAMAGE / sizeof DAMAGE[0] };

/* ---- reporting ---------------------------------------------------------------------------- */
static char where[160]; /* material and variant of the check under way */

static void within(double got, double limit, const char *what, int line) {
  if (!(got <= limit)) {
    fprintf(stderr, "%s:%d: %s: %s = %.3e, limit %.3e\n", __FILE__, line, where, what, got, limit);
    pf_test_failures++;
  }
}
#define WITHIN(got, limit, what) within((got), (limit), (what), __LINE__)

static void expect(int cond, const char *what, int line) {
  if (!cond) {
    fprintf(stderr, "%s:%d: %s: %s\n", __FILE__, line, where, what);
    pf_test_failures++;
  }
}
#define EXPECT(cond, what) expect((cond), (what), __LINE__)

/* ---- small algebra ------------------------------------------------------------------------ */
static double det3(const double A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Rotation by angle t about the unit axis a (Rodrigues): R = cos t I + sin t [a]x + (1 - cos t) a a^T. */
static void rotation(const double a[3], double t, double R[3][3]) {
  const double c = cos(t), s = sin(t), W[3][3] = {{0, -a[2], a[1]}, {a[2], 0, -a[0]}, {-a[1], a[0], 0}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[i][j] = (i == j ? c : 0.0) + s * W[i][j] + (1 - c) * a[i] * a[j];
}

/* psi = G/2 (tr C - 3) - G ln J + lambda/2 (ln J)^2 in terms of H = F - I, so that small strains
 * keep their digits: tr C - 3 = 2 tr H + H : H, J - 1 = j1 = tr H + i2 + i3 (i2, i3 the second
 * and third invariants of H), tr H - ln J = -(i2 + i3) + (j1 - log1p(j1)). */
static double psi_neo_hookean(const double H[3][3], double K, double G) {
  const double lam = K - 2.0 * G / 3.0, trH = H[0][0] + H[1][1] + H[2][2];
  double HH = 0, HtH = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) HH += H[i][j] * H[i][j], HtH += H[i][j] * H[j][i];
  const double i2 = 0.5 * (trH * trH - HtH), i3 = det3(H), j1 = trH + i2 + i3, lnJ = log1p(j1);
  return G * (-(i2 + i3) + (j1 - lnJ)) + 0.5 * G * HH + 0.5 * lam * lnJ * lnJ;
}

/* A uniform number in [-1, 1) from (seed, global id): splitmix64, so a point's perturbation does
 * not depend on the store order. */
static double hash_uniform(uint64_t seed, uint64_t id, int comp) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ULL + id * 0xBF58476D1CE4E5B9ULL + (uint64_t)comp * 0x94D049BB133111EBULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-52 - 1.0;
}

/* ---- bodies ------------------------------------------------------------------------------- */
typedef struct {
  pf_sim *sim;
  pf_points *p;
  pf_pd_body *b;
  double K, S; /* bulk modulus, force scale K h^2 */
  pf_int n;
  double *y, *f0; /* scratch [3n] */
} body_t;

/* Build a body of material mc (a correspondence body when mc->model is a continuum model) with
 * nside^3 points and the extra body keys. Returns 0, or the set-up error code (message in
 * pf_error_message()). */
static int body_make(const mat_case *mc, int nside, const char *extra, body_t *t) {
  memset(t, 0, sizeof *t);
  char deck[2048];
  const double L = 0.5 * (nside - 1) * h;
  snprintf(deck, sizeof deck,
           "materials:\n  m: {model: %s, %s}\n"
           "bodies:\n  - name: b\n    material: m\n    horizon: %.17g\n"
           "    geometry: {shape: box, lo: [%.17g, %.17g, %.17g], hi: [%.17g, %.17g, %.17g], spacing: %.17g}\n"
           "%s"
           "time: {steps: 0, dt: 1e-9}\n",
           mc->model, mc->params, HORIZON * h, -L, -L, -L, L, L, L, h, extra);
  const char *path = pf_test_write_file(0, "pd_conformance", deck);
  pf_sim_options opt = {.no_output = 1};
  pf_error_clear();
  int ierr = pf_sim_create(path, &opt, &t->sim);
  remove(path);
  if (ierr) return ierr;
  t->p = pf_sim_points(t->sim);
  t->b = pf_sim_body(t->sim, 0);
  t->n = t->p->n_owned;
  t->K = pf_pd_body_bulk_modulus(t->b);
  t->S = t->K * h * h;
  EXPECT(t->n == nside * nside * nside && t->p->n_total == t->n, "lattice size (serial test)");
  for (pf_int i = 0; i < 3 * t->n; i++) t->p->y[i] = t->p->X[i], t->p->u[i] = t->p->v[i] = t->p->f[i] = 0;
  t->y = calloc(3 * (size_t)t->n, sizeof(double));
  t->f0 = calloc(3 * (size_t)t->n, sizeof(double));
  return 0;
}

static int body_must(const mat_case *mc, int nside, const char *extra, body_t *t) {
  if (!body_make(mc, nside, extra, t)) return 1;
  fprintf(stderr, "%s: cannot build the body: %s\n", where, pf_error_message());
  pf_test_failures++;
  return 0;
}

static void body_free(body_t *t) {
  pf_sim_destroy(&t->sim);
  free(t->y), free(t->f0);
}

/* Move to y_new over a step dt, as the integrator does (v = (y_new - y) / dt), and evaluate the
 * forces into p->f. */
static void impose(body_t *t, const double *ynew, double dt) {
  pf_points *p = t->p;
  for (pf_int i = 0; i < 3 * t->n; i++) {
    p->v[i] = dt > 0 ? (ynew[i] - p->y[i]) / dt : 0.0;
    p->y[i] = ynew[i];
    p->u[i] = ynew[i] - p->X[i];
    p->f[i] = 0.0;
  }
  if (pf_pd_body_force(t->b, p, dt)) {
    fprintf(stderr, "%s: pf_pd_body_force failed: %s\n", where, pf_error_message());
    pf_test_failures++;
  }
}

/* y = F X + c + amp h r, r uniform in [-1, 1)^3 per point (seeded). */
static void target(const body_t *t, const double F[3][3], const double c[3], double amp, uint64_t seed,
                   double *y) {
  const pf_points *p = t->p;
  for (pf_int i = 0; i < t->n; i++)
    for (int a = 0; a < 3; a++) {
      const double *X = &p->X[3 * i];
      y[3 * i + a] = F[a][0] * X[0] + F[a][1] * X[1] + F[a][2] * X[2] + c[a] +
                     (amp > 0 ? amp * h * hash_uniform(seed, (uint64_t)p->gid[i], a) : 0.0);
    }
}

static double max_force(const body_t *t) {
  double m = 0;
  for (pf_int i = 0; i < t->n; i++) m = fmax(m, norm3(&t->p->f[3 * i]));
  return m;
}

static int64_t nbroken(const body_t *t) {
  const pf_family *fam = pf_pd_body_family(t->b);
  int64_t nb = 0;
  for (int64_t k = 0; k < pf_pd_family_nbonds(fam); k++) nb += fam->broken[k];
  return nb;
}

/* The shape-tensor displacement gradient of point i over its intact bonds (omega = 1, whole
 * cells): H = Fbar - I = [sum_j V_j (Y - xi) (x) xi] [sum_j V_j xi (x) xi]^-1. */
static void fbar_minus_I(const body_t *t, const double *y, pf_int i, double H[3][3]) {
  const pf_family *fam = pf_pd_body_family(t->b);
  const pf_points *p = t->p;
  double K[3][3] = {{0}}, A[3][3] = {{0}}, Ki[3][3];
  EXPECT(fam->vfrac == NULL, "whole cells (no partial volumes)");
  for (int64_t k = fam->offset[i - fam->first]; k < fam->offset[i - fam->first + 1]; k++) {
    if (fam->broken[k]) continue;
    const pf_int j = fam->neighbor[k];
    double xi[3], Y[3];
    for (int a = 0; a < 3; a++) xi[a] = p->X[3 * j + a] - p->X[3 * i + a], Y[a] = (y[3 * j + a] - y[3 * i + a]) - xi[a];
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) K[r][s] += p->vol[j] * xi[r] * xi[s], A[r][s] += p->vol[j] * Y[r] * xi[s];
  }
  pf_mat3_inverse(K, Ki);
  for (int r = 0; r < 3; r++)
    for (int s = 0; s < 3; s++) H[r][s] = A[r][0] * Ki[0][s] + A[r][1] * Ki[1][s] + A[r][2] * Ki[2][s];
}

/* The field "correspondence" of a correspondence body, with its component count. */
static const double *corr_field(const body_t *t, int *ncomp) {
  for (int k = 0; k < t->p->nfields; k++)
    if (!strcmp(t->p->fields[k].name, "correspondence")) {
      *ncomp = t->p->fields[k].ncomp;
      return t->p->fields[k].data;
    }
  return NULL;
}

static pf_int nearest_point(const body_t *t, const double x[3]) {
  pf_int best = 0;
  double d = INFINITY;
  for (pf_int i = 0; i < t->n; i++) {
    double e = 0;
    for (int a = 0; a < 3; a++) e += pow(t->p->X[3 * i + a] - x[a], 2);
    if (e < d) d = e, best = i;
  }
  return best;
}

static const double I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const double AXIS[3] = {1.0 / 3, -2.0 / 3, 2.0 / 3};
/* A small general (non-symmetric) displacement gradient, |A| ~ 1e-3. */
static const double A_SMALL[3][3] = {{1.0e-3, 2e-4, -3e-4}, {5e-4, -7e-4, 1e-4}, {-2e-4, 3e-4, 4e-4}};

/* ---- 1. zero deformation ------------------------------------------------------------------ */
static void check_zero(const mat_case *mc) {
  body_t t;
  if (!body_must(mc, NSIDE, "", &t)) return;
  impose(&t, t.p->X, 0.0);
  WITHIN(max_force(&t), 1e-13 * t.S, "zero deformation, dt = 0: max |f|");
  impose(&t, t.p->X, DT);
  WITHIN(max_force(&t), 1e-13 * t.S, "zero deformation, dt > 0: max |f|");
  body_free(&t);
}

/* ---- 2. rigid motion and objectivity ------------------------------------------------------ */
static void check_rotation(const mat_case *mc) {
  double Q[3][3], F1[3][3];
  const double c[3] = {0.3 * h, -0.2 * h, 0.1 * h}, zero[3] = {0, 0, 0};
  rotation(AXIS, PF_PI / 6, Q);
  body_t t;
  if (!body_must(mc, NSIDE, "", &t)) return;
  target(&t, Q, c, 0, 0, t.y);
  impose(&t, t.y, DT);
  WITHIN(max_force(&t), 1e-12 * t.S, "rigid motion: max |f| (1e-10 of the 1 % strain force scale)");
  body_free(&t);

  /* A strained state (strains ~3e-4, elastic for every case: the lowest yield strain here is
   * Johnson-Cook's A / E = 7e-4), then the same state rotated. A plastic state would relax in the
   * rotation step (a rate-dependent flow stress falls with the rate). */
  if (!body_must(mc, NSIDE, "", &t)) return;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F1[a][b] = I3[a][b] + 0.25 * A_SMALL[a][b];
  target(&t, F1, zero, 1e-4, 11, t.y);
  impose(&t, t.y, DT);
  memcpy(t.f0, t.p->f, 3 * sizeof(double) * (size_t)t.n);
  const double fmax1 = max_force(&t);
  const double *eqps = pf_points_field_get(t.p, "eqps");
  for (pf_int i = 0; eqps && i < t.n; i++) EXPECT(eqps[i] == 0, "the strained state is elastic (eqps = 0)");
  for (pf_int i = 0; i < t.n; i++)
    for (int a = 0; a < 3; a++) {
      const double *y1 = &t.p->y[3 * i];
      t.y[3 * i + a] = Q[a][0] * y1[0] + Q[a][1] * y1[1] + Q[a][2] * y1[2] + c[a];
    }
  impose(&t, t.y, DT);
  double err = 0;
  for (pf_int i = 0; i < t.n; i++) {
    double d[3];
    for (int a = 0; a < 3; a++)
      d[a] = t.p->f[3 * i + a] - (Q[a][0] * t.f0[3 * i] + Q[a][1] * t.f0[3 * i + 1] + Q[a][2] * t.f0[3 * i + 2]);
    err = fmax(err, norm3(d));
  }
  EXPECT(fmax1 > 1e-4 * t.S, "the strained state is loaded");
  WITHIN(err, 1e-10 * fmax1, "objectivity: max |f(Q y + c) - Q f(y)| (limit 1e-10 max |f(y)|)");
  body_free(&t);
}

/* ---- 3. Fbar of an affine motion (correspondence) ----------------------------------------- */
static void check_fbar(const mat_case *mc) {
  const double F[3][3] = {{1.1, 0.2, -0.15}, {0.05, 0.9, 0.3}, {-0.1, 0.25, 1.2}}, c[3] = {2e-4, -1e-4, 3e-4};
  EXPECT(det3(F) > 0, "det F > 0");
  body_t t;
  if (!body_must(mc, NSIDE, "", &t)) return;
  target(&t, F, c, 0, 0, t.y);
  impose(&t, t.y, DT);
  int nc = 0;
  const double *g = corr_field(&t, &nc);
  EXPECT(g && nc >= 27, "field 'correspondence' with Fbar at 9..17 and Fdot at 18..26, by columns");
  if (g && nc >= 27) {
    double eF = 0, eFd = 0;
    for (pf_int i = 0; i < t.n; i++)
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          eF = fmax(eF, fabs(g[nc * i + 9 + a + 3 * b] - F[a][b]));
          eFd = fmax(eFd, fabs(g[nc * i + 18 + a + 3 * b] - (F[a][b] - I3[a][b]) / DT));
        }
    WITHIN(eF, 1e-12, "affine motion: max |Fbar - F| over all points");
    WITHIN(eFd * DT, 1e-12, "affine motion: max |Fdot - (F - I)/dt| dt over all points");
  }
  body_free(&t);
}

/* ---- 7. a lost bond leaves the stress where it was -------------------------------------- */
/* Correspondence with critical_damage: the body is loaded past yield (y = (I + 20 A) X), unloaded
 * elastically part way with a non-affine scatter (y = (I + 18 A) X + 2e-3 h r), then, with no
 * motion (v = 0), a neighbour j of the centre point i is marked failed (damage 1 > D_c in the
 * exchanged record, component 28), so i loses its bond to j and its Fbar jumps to another
 * estimate of the same, unmoved material. The material did not move, so its stress must not
 * change: the Kirchhoff stress J sigma of a hyperelastic model (its elastic state is carried
 * over, docs/theory/materials.md §2.7), the Cauchy stress of a rate-form model (no rate, no
 * change), to 1e-10 of |sigma|. The jump of Fbar must be real (above 1e-6), or the check would be
 * vacuous. A model that rejects critical_damage (no damage variable: today all but
 * modified_johnson_cook) is skipped, and so is neo_hookean, which has no history to carry an
 * elastic state in (§2.7). */
static void check_lost_bond(const mat_case *mc) {
  if (!strcmp(mc->model, "neo_hookean")) return;
  body_t t;
  pf_error_set_quiet(1);
  int ierr = body_make(mc, NSIDE, "    hourglass: {type: none}\n    critical_damage: 0.5\n", &t);
  pf_error_set_quiet(0);
  if (ierr) {
    if (!strstr(pf_error_message(), "critical_damage")) {
      fprintf(stderr, "%s: cannot build the body: %s\n", where, pf_error_message());
      pf_test_failures++;
    }
    pf_error_clear();
    return;
  }
  double F[3][3];
  const double c[3] = {0, 0, 0}, x0[3] = {0, 0, 0}, x1[3] = {h, 0, 0};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + 20 * A_SMALL[a][b];
  target(&t, F, c, 0, 0, t.y);
  impose(&t, t.y, DT);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + 18 * A_SMALL[a][b];
  target(&t, F, c, 2e-3, 11, t.y);
  impose(&t, t.y, DT);
  const pf_int i = nearest_point(&t, x0), j = nearest_point(&t, x1);
  int nc = 0;
  double *g = (double *)corr_field(&t, &nc);
  const double *sig = pf_points_field_get(t.p, "stress");
  EXPECT(g && nc >= 29 && sig, "fields 'correspondence' (Fbar at 9..17, damage at 28) and 'stress'");
  if (!(g && nc >= 29 && sig)) {
    body_free(&t);
    return;
  }
  double Fa[3][3], sa[6], Ja, jump = 0, err = 0, scale = 0;
  for (int k = 0; k < 9; k++) Fa[k / 3][k % 3] = g[nc * i + 9 + k];
  for (int k = 0; k < 6; k++) sa[k] = sig[6 * i + k];
  Ja = det3(Fa);
  const int64_t broken0 = nbroken(&t);
  g[nc * j + 28] = 1.0;
  impose(&t, t.y, DT); /* no motion */
  const int hyper = !strcmp(mc->model, "modified_johnson_cook");
  double Fb[3][3];
  for (int k = 0; k < 9; k++) Fb[k / 3][k % 3] = g[nc * i + 9 + k], jump = fmax(jump, fabs(Fb[k / 3][k % 3] - Fa[k / 3][k % 3]));
  const double Jb = det3(Fb);
  for (int k = 0; k < 6; k++) {
    const double before = hyper ? Ja * sa[k] : sa[k], after = hyper ? Jb * sig[6 * i + k] : sig[6 * i + k];
    err = fmax(err, fabs(after - before)), scale = fmax(scale, fabs(before));
  }
  EXPECT(nbroken(&t) > broken0, "the failed neighbour's bonds broke");
  EXPECT(jump > 1e-6, "losing the bond moved Fbar (the check is not vacuous)");
  EXPECT(scale > 1e6, "the point is stressed");
  WITHIN(err, 1e-10 * scale, hyper ? "max |J sigma after - J sigma before| of the point that lost a bond"
                                   : "max |sigma after - sigma before| of the point that lost a bond");
  body_free(&t);
}

/* ---- 4. linear and angular momentum ------------------------------------------------------- */
static void check_momentum(const mat_case *mc, int corr, const variant *var) {
  if (var->corr_only && !corr) return;
  body_t t;
  pf_error_set_quiet(var->key != NULL);
  int ierr = body_make(mc, NSIDE, var->body, &t);
  pf_error_set_quiet(0);
  if (ierr) {
    if (!var->key || !strstr(pf_error_message(), var->key)) {
      fprintf(stderr, "%s: cannot build the body: %s\n", where, pf_error_message());
      pf_test_failures++;
    }
    pf_error_clear();
    return; /* the material does not take this law: nothing to check */
  }
  double F[3][3];
  const double c[3] = {1e-4, 2e-4, -1e-4};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + 5 * A_SMALL[a][b];
  target(&t, F, c, 0.01, 7, t.f0); /* the end of the path */
  for (int s = 1; s <= 3; s++) {
    for (pf_int i = 0; i < 3 * t.n; i++) t.y[i] = t.p->X[i] + s / 3.0 * (t.f0[i] - t.p->X[i]);
    impose(&t, t.y, DT);
    double P[3] = {0, 0, 0}, Lm[3] = {0, 0, 0}, fs = 0, yfs = 0;
    for (pf_int i = 0; i < t.n; i++) {
      const double *f = &t.p->f[3 * i], *y = &t.p->y[3 * i];
      for (int a = 0; a < 3; a++) P[a] += f[a];
      Lm[0] += y[1] * f[2] - y[2] * f[1], Lm[1] += y[2] * f[0] - y[0] * f[2], Lm[2] += y[0] * f[1] - y[1] * f[0];
      fs += norm3(f), yfs += norm3(y) * norm3(f);
    }
    char what[2][96];
    snprintf(what[0], sizeof what[0], "random path, step %d/3: |sum f_i| (limit 1e-13 sum |f_i|)", s);
    snprintf(what[1], sizeof what[1], "random path, step %d/3: |sum y_i x f_i| (limit 1e-13 sum |y_i||f_i|)", s);
    EXPECT(fs > 1e-3 * t.S, "the path loads the body");
    WITHIN(norm3(P), 1e-13 * fs, what[0]);
    WITHIN(norm3(Lm), 1e-13 * yfs, what[1]);
  }
  if (var->must_damage) EXPECT(nbroken(&t) > 0, "the damage law broke bonds on the path");
  body_free(&t);
}

/* ---- 5a. force = -dW/dy by central differences -------------------------------------------- */
/* Stored energy at y: the energy op after a force evaluation (which updates the materials'
 * per-point quantities, e.g. the dilatation), or the test's sum_k V_k psi(Fbar_k). The psi form
 * returns the difference from the energy at yref point by point (only the points near the
 * perturbed one change, so the large sum does not swamp the difference). */
static double energy_at(body_t *t, const mat_case *mc, const double *y, const double *yref) {
  if (mc->psi) {
    double d = 0, H[3][3], Hr[3][3];
    for (pf_int i = 0; i < t->n; i++) {
      fbar_minus_I(t, y, i, H), fbar_minus_I(t, yref, i, Hr);
      d += t->p->vol[i] * (mc->psi(H, mc->K, mc->G) - mc->psi(Hr, mc->K, mc->G));
    }
    return d;
  }
  impose(t, y, 0.0);
  return pf_pd_body_energy(t->b, t->p);
}

static void check_energy_fd(const mat_case *mc, int corr) {
  if (!mc->potential && !mc->psi) return; /* history or rate models: check 5b only */
  body_t t;
  if (!body_must(mc, NSIDE, corr ? HG_NONE.body : "", &t)) return;
  double F[3][3];
  const double c[3] = {1e-4, 0, -2e-4};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + A_SMALL[a][b];
  target(&t, F, c, 1e-3, 5, t.y);
  double *ybase = malloc(3 * sizeof(double) * (size_t)t.n), *yp = malloc(3 * sizeof(double) * (size_t)t.n);
  memcpy(ybase, t.y, 3 * sizeof(double) * (size_t)t.n);
  impose(&t, ybase, DT);
  memcpy(t.f0, t.p->f, 3 * sizeof(double) * (size_t)t.n);
  if (mc->psi) { /* the test's Fbar is the library's (field "correspondence", 9..17) */
    int nc = 0;
    const double *g = corr_field(&t, &nc);
    double e = 0, Fb[3][3];
    for (pf_int i = 0; g && i < t.n; i++) {
      fbar_minus_I(&t, ybase, i, Fb);
      for (int k = 0; k < 9; k++) e = fmax(e, fabs(g[nc * i + 9 + k] - (k % 4 == 0) - Fb[k % 3][k / 3]));
    }
    EXPECT(g != NULL, "field 'correspondence'");
    WITHIN(e, 1e-13, "the test's Fbar against the library's");
    WITHIN(fabs(pf_pd_body_bulk_modulus(t.b) - mc->K), 1e-15 * mc->K, "|K of the body - K of psi|");
  }
  /* A corner, a face centre, the centre. delta = 1e-5 h: truncation ~(delta / h)^2 (the forces
   * vary on the scale of a bond length), round-off ~1e-16 W / (delta |f|) ~ 1e-12. */
  const double L = 0.5 * (NSIDE - 1) * h, where_[3][3] = {{-L, -L, -L}, {L, 0, 0}, {0, 0, 0}}, del = 1e-5 * h;
  for (int q = 0; q < 3; q++) {
    const pf_int k = nearest_point(&t, where_[q]);
    const double fk = norm3(&t.f0[3 * k]);
    EXPECT(fk > 1e-5 * t.S, "the probed point is loaded");
    for (int a = 0; a < 3; a++) {
      memcpy(yp, ybase, 3 * sizeof(double) * (size_t)t.n);
      yp[3 * k + a] = ybase[3 * k + a] + del;
      const double ep = energy_at(&t, mc, yp, ybase);
      yp[3 * k + a] = ybase[3 * k + a] - del;
      const double em = energy_at(&t, mc, yp, ybase);
      WITHIN(fabs(-(ep - em) / (2 * del) - t.f0[3 * k + a]), 1e-6 * fk, "|-dW/dy - f| at a probed point");
    }
  }
  free(ybase), free(yp);
  body_free(&t);
}

/* ---- 5b. energy op = work done on the body along a path ----------------------------------- */
/* y(s) = X + s U, U = 5 A X + c + r (strains ~5e-3, random part 3e-3 h): out s = 0 -> 1 in N
 * steps, back to s = 1/2 in N/2 steps, over a fixed time (dt = 20 DT / N, so rate-dependent
 * models and viscous hourglass forces see the same motion for every N). Returns the energy op
 * at the end in *E and the work done on the body, W = -sum_n (f_n-1 + f_n)/2 . (y_n - y_n-1),
 * in *W, the largest eqps in *eqps_max (-1: the material has no field "eqps"). Returns 0 when
 * the body cannot be built. */
static int path_energy(const mat_case *mc, const variant *var, int N, double *E, double *W,
                       double *eqps_max) {
  body_t t;
  if (!body_must(mc, NSIDE, var->body, &t)) return 0;
  double F[3][3];
  const double c[3] = {1e-4, -1e-4, 2e-4}, dt = 20 * DT / N;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + 5 * A_SMALL[a][b];
  double *yend = malloc(3 * sizeof(double) * (size_t)t.n), *dy = malloc(3 * sizeof(double) * (size_t)t.n);
  target(&t, F, c, 3e-3, 3, yend);
  for (pf_int i = 0; i < 3 * t.n; i++) t.f0[i] = 0; /* the force at the reference state */
  *W = 0;
  for (int n = 1; n <= N + N / 2; n++) {
    const double s = n <= N ? (double)n / N : 1.0 - (double)(n - N) / N;
    for (pf_int i = 0; i < 3 * t.n; i++) {
      t.y[i] = t.p->X[i] + s * (yend[i] - t.p->X[i]);
      dy[i] = t.y[i] - t.p->y[i];
    }
    impose(&t, t.y, dt);
    for (pf_int i = 0; i < 3 * t.n; i++) *W -= 0.5 * (t.f0[i] + t.p->f[i]) * dy[i], t.f0[i] = t.p->f[i];
  }
  *E = pf_pd_body_energy(t.b, t.p);
  const double *eqps = pf_points_field_get(t.p, "eqps");
  *eqps_max = eqps ? 0.0 : -1.0;
  for (pf_int i = 0; eqps && i < t.n; i++) *eqps_max = fmax(*eqps_max, eqps[i]);
  free(yend), free(dy);
  body_free(&t);
  return 1;
}

/* The energy ops are the stored energy (pmb, lps), or integrate the power by the trapezoid rule
 * over the same stress sequence the forces come from (stress work, hourglass work, the plastic
 * work of elastic_plastic, exact for its linear hardening), so E - W is the difference of two
 * second-order quadratures of one integral: it must fall as N^-2. Checked on N = 20 and 40:
 * |E - W| (N = 40) <= 0.35 |E - W| (N = 20) (0.25 for second order, 0.5 for first), unless it is
 * at the noise floor 1e-8 W; and |E - W| <= 1e-3 W at N = 40. A plastic model must flow on the
 * path (its field "eqps" > 0). */
static void check_energy_path(const mat_case *mc, const variant *var) {
  double E1, W1, E2, W2, q1, q2;
  if (!path_energy(mc, var, 20, &E1, &W1, &q1) || !path_energy(mc, var, 40, &E2, &W2, &q2)) return;
  const double e1 = fabs(E1 - W1), e2 = fabs(E2 - W2);
  EXPECT(W2 > 0, "work done on the body along the path");
  WITHIN(e2 / W2, 1e-3, "path: |energy op - work of the forces| / work (N = 40)");
  if (e2 > 1e-8 * W2) WITHIN(e2 / e1, 0.35, "path: second-order convergence, error(N = 40) / error(N = 20)");
  if (q1 >= 0) EXPECT(q1 > 0 && q2 > 0, "the path reaches plastic flow (eqps > 0)");
}

/* ---- 6. linear patch test ----------------------------------------------------------------- */
static void check_patch(const mat_case *mc) {
  body_t t;
  if (!body_must(mc, NPATCH, "", &t)) return;
  double F[3][3];
  const double c[3] = {3e-5, -2e-5, 1e-5}, eps = 1e-3, depth = 0.5 * (NPATCH - 1) * h - 6 * h;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) F[a][b] = I3[a][b] + A_SMALL[a][b];
  target(&t, F, c, 0, 0, t.y);
  impose(&t, t.y, DT);
  double fin = 0, fall = 0;
  int nin = 0;
  for (pf_int i = 0; i < t.n; i++) {
    const double *X = &t.p->X[3 * i], fi = norm3(&t.p->f[3 * i]);
    fall = fmax(fall, fi);
    if (fabs(X[0]) <= depth + 1e-9 * h && fabs(X[1]) <= depth + 1e-9 * h && fabs(X[2]) <= depth + 1e-9 * h)
      fin = fmax(fin, fi), nin++;
  }
  EXPECT(nin == 27, "27 points two horizons deep");
  EXPECT(fall > 1e-2 * t.K * eps * h * h, "the surface is loaded");
  WITHIN(fin, 1e-10 * t.K * eps * h * h, "uniform strain: max interior |f| (limit 1e-10 K eps h^2)");
  body_free(&t);
}

/* ---- the loop over every registered material ---------------------------------------------- */
static void run_material(const mat_case *mc, int corr) {
  char base[96];
  snprintf(base, sizeof base, "%s%s", corr ? "correspondence " : "", mc->model);
#define AT(label) snprintf(where, sizeof where, "%s [%s]", base, (label))
  AT("zero deformation");
  check_zero(mc);
  AT("rigid motion");
  check_rotation(mc);
  if (corr) {
    AT("affine Fbar");
    check_fbar(mc);
  }
  char label[96];
  const variant *mom[2 + NDAMAGE] = {&PLAIN, &HG_VISCOUS};
  for (int k = 0; k < NDAMAGE; k++) mom[2 + k] = &DAMAGE[k];
  for (int k = 0; k < 2 + NDAMAGE; k++) {
    snprintf(label, sizeof label, "momentum, %s", mom[k]->label);
    AT(label);
    check_momentum(mc, corr, mom[k]);
  }
  AT("energy by finite differences");
  check_energy_fd(mc, corr);
  const variant *path[3] = {&PLAIN, &HG_NONE, &HG_VISCOUS};
  for (int k = 0; k < (corr ? 3 : 1); k++) {
    snprintf(label, sizeof label, "energy along a path, %s", path[k]->label);
    AT(label);
    check_energy_path(mc, path[k]);
  }
  AT("patch test");
  check_patch(mc);
  if (corr) {
    AT("a lost bond");
    check_lost_bond(mc);
  }
#undef AT
}

/* Every name of a comma-separated list must have a case; returns how many names. The list is
 * split first (strtok keeps state; the checks build decks in between). */
static int run_list(const char *names, int corr) {
  char list[512], *name[64];
  snprintf(list, sizeof list, "%s", names);
  int n = 0;
  for (char *tok = strtok(list, ", "); tok && n < 64; tok = strtok(NULL, ", ")) name[n++] = tok;
  for (int k = 0; k < n; k++) {
    const mat_case *mc = NULL;
    for (int c = 0; c < NCASES && !mc; c++)
      if (!strcmp(cases[c].model, name[k])) mc = &cases[c];
    if (!mc) {
      fprintf(stderr, "%s material '%s' has no deck parameters in tests/unit/test_pd_conformance.c: "
                      "add its parameters to cases[]\n", corr ? "continuum (correspondence)" : "peridynamic", name[k]);
      pf_test_failures++;
      continue;
    }
    run_material(mc, corr);
  }
  return n;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  PF_TEST_TRUE(run_list(pf_pd_material_names(), 0) >= 3);
  PF_TEST_TRUE(run_list(pf_material_names(), 1) >= 5);
  return pf_test_finish();
}
