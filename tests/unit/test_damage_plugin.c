/* A damage law defined here, in the test, and added at run time (pf_pd_damage_register): the
 * kernels fail the bonds its limits say, and only those, checked against hand calculations on
 * a 4 x 2 x 2 lattice of 1 mm spacing (points at x = 0, 1, 2, 3 mm and y, z = 0, 1 mm),
 * PMB with K = 1 GPa, horizon 1.5 mm (the axis bonds, |xi| = 1 mm, and the face diagonals,
 * |xi| = sqrt2 mm), stretched by u_x = 0.01 x:
 *   x bonds: s = 0.01;  xy and xz diagonals: s = sqrt((1.01^2 + 1) / 2) - 1 = 0.0050125;
 *   y, z and yz bonds: s = 0.
 *
 * 1. "graded_stretch", a stretch limit per point that the law fills at attach:
 *    s0_i = s0_at_origin + s0_gradient x_i; with 0.0035 and 5 /m, s0 = 0.0035, 0.0085, 0.0135,
 *    0.0185 in the four columns. A bond fails when s > min(s0_i, s0_j): the x bonds between
 *    columns 0-1 (4) and 1-2 (4), and the diagonals between columns 0-1 (8, two from each point of
 *    column 0); 16 bonds, 32 row entries.
 * 2. "stretch_or_energy", both limits at once (a bond fails on either): the PMB pair energy
 *    w = c s^2 |xi| / 2, c = 18 K / (pi delta^4) = 1.13177e21 J/m^6: x bonds 5.6588e13,
 *    diagonals 2.0107e13 J/m^6.
 *    (a) stretch_limit 0.02, energy_limit 3.5e13: the x bonds fail, on the energy alone (12
 *        bonds, 24 entries).
 *    (b) stretch_limit 0.004, energy_limit 1e30: the x bonds and the xy, xz diagonals fail, on
 *        the stretch alone (12 + 24 = 36 bonds, 72 entries: 2 diagonals of each kind between
 *        each of 3 column pairs in each of 2 layers).
 * Each bond is also checked against the same rule evaluated here from the positions. */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pd/pd_impl.h"

enum { LAW_GRADED, LAW_EITHER };

/* ---- law 1: graded_stretch ---------------------------------------------------------------- */
static const pf_key graded_keys[] = {
    {"s0_at_origin", PF_KEY_REAL, 0, NULL, "", "graded_stretch: s0 at x = 0", NULL},
    {"s0_gradient", PF_KEY_REAL, 0, NULL, "1/m", "graded_stretch: ds0/dx", NULL},
    PF_KEY_END};

typedef struct {
  double a, g;
} graded;

static int graded_read(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  graded *p;
  PF_MALLOC(p, 1);
  b->damage_data = p;
  PF_CALL(pf_pd_damage_read_required(d, map, "s0_at_origin", &p->a));
  PF_CALL(pf_pd_damage_read_required(d, map, "s0_gradient", &p->g));
  b->s0_init = p->a; /* a stretch limit; attach grades it */
  return 0;
}

static int graded_attach(pf_pd_body *b, pf_points *pts, int fresh) {
  const graded *p = b->damage_data;
  for (pf_int i = b->first; fresh && i < b->first + b->n; i++) b->s0[i] = p->a + p->g * pts->X[3 * i];
  return 0;
}

static const pf_pd_damage_ops graded_stretch = {
    .name = "graded_stretch", .keys = graded_keys, .read = graded_read, .attach = graded_attach};

/* ---- law 2: stretch_or_energy ------------------------------------------------------------- */
static const pf_key either_keys[] = {
    {"stretch_limit", PF_KEY_REAL, 0, NULL, "", "stretch_or_energy: s0", NULL},
    {"energy_limit", PF_KEY_REAL, 0, NULL, "J/m^6", "stretch_or_energy: w_c", NULL},
    PF_KEY_END};

static int either_read(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  PF_CALL(pf_pd_damage_read_required(d, map, "stretch_limit", &b->s0_init));
  return pf_pd_damage_read_required(d, map, "energy_limit", &b->critical_energy);
}

static const pf_pd_damage_ops stretch_or_energy = {
    .name = "stretch_or_energy", .keys = either_keys, .read = either_read};

/* ---- the lattice ----------------------------------------------------------------------- */
static const double K = 1e9, DELTA = 0.0015, EPS = 0.01;

static pf_sim *make(const char *damage) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: {model: pmb, density: 1000, bulk_modulus: %g}}\n"
           "bodies:\n"
           "  - name: b\n    material: m\n    horizon: %g\n"
           "    geometry: {shape: box, lo: [0, 0, 0], hi: [0.003, 0.001, 0.001], spacing: 0.001}\n"
           "    damage: %s\n"
           "time: {steps: 0, dt: 1e-9}\n", K, DELTA, damage);
  return pf_test_sim("damage_plugin", deck);
}

/* The bond's stretch and PMB pair energy (omega = 1) under u_x = EPS x, from the positions. */
static void bond_by_hand(const double *X, pf_int i, pf_int j, double *s, double *w) {
  double r02 = 0, r2 = 0;
  for (int a = 0; a < 3; a++) {
    const double d = X[3 * j + a] - X[3 * i + a], e = a == 0 ? (1 + EPS) * d : d;
    r02 += d * d, r2 += e * e;
  }
  *s = sqrt(r2 / r02) - 1;
  *w = 0.5 * (18 * K / (PF_PI * pow(DELTA, 4))) * *s * *s * sqrt(r02);
}

/* Does the law fail the bond i - j (the rule evaluated here)? */
static int fails_by_hand(int law, const double *X, pf_int i, pf_int j, double s0, double wc) {
  double s, w;
  bond_by_hand(X, i, j, &s, &w);
  if (law == LAW_GRADED) return s > fmin(0.0035 + 5 * X[3 * i], 0.0035 + 5 * X[3 * j]);
  return s > s0 || (s > 0 && w > wc);
}

/* One force evaluation under u_x = EPS x; every bond's flag against the hand rule; returns the
 * number of failed row entries. */
static long run(const char *damage, int law, double s0, double wc) {
  pf_sim *sim = make(damage);
  pf_points *p = pf_sim_points(sim);
  pf_pd_body *b = pf_sim_body(sim, 0);
  PF_TEST_TRUE(p->n_owned == 16);
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int a = 0; a < 3; a++) {
      p->u[3 * i + a] = a == 0 ? EPS * p->X[3 * i] : 0;
      p->y[3 * i + a] = p->X[3 * i + a] + p->u[3 * i + a], p->f[3 * i + a] = 0;
    }
  PF_TEST_OK(pf_pd_body_force(b, p, 0.0));
  long failed = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++)
    for (int64_t k = b->fam.offset[i - b->first]; k < b->fam.offset[i - b->first + 1]; k++) {
      const int want = fails_by_hand(law, p->X, i, b->fam.neighbor[k], s0, wc), got = b->fam.broken[k] != 0;
      if (want != got) {
        fprintf(stderr, "%s: bond %ld -> %ld %s, the hand rule says it %s\n", damage, (long)i,
                (long)b->fam.neighbor[k], got ? "failed" : "held", want ? "fails" : "holds");
        pf_test_failures++;
      }
      failed += got;
    }
  pf_sim_destroy(&sim);
  return failed;
}

/* The registry: the new names are found, a taken name is refused, the deck table has their keys,
 * and a key of another law is refused naming the keys this one takes. */
static void registry(void) {
  PF_TEST_TRUE(pf_pd_damage_find("graded_stretch") == &graded_stretch);
  pf_error_set_quiet(1);
  PF_TEST_TRUE(pf_pd_damage_register(&graded_stretch) != 0);
  pf_error_set_quiet(0);
  pf_error_clear();
  int found = 0;
  for (const pf_key *k = pf_pd_damage_keys; k->name; k++) found += !strcmp(k->name, "energy_limit");
  PF_TEST_TRUE(found == 1);
  PF_TEST_TRUE(strstr(pf_pd_damage_keys[0].doc, "| graded_stretch | stretch_or_energy") != NULL);
  PF_TEST_TRUE(strstr(pf_pd_damage_names(), ", graded_stretch, stretch_or_energy") != NULL);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  PF_TEST_OK(pf_pd_damage_register(&graded_stretch));
  PF_TEST_OK(pf_pd_damage_register(&stretch_or_energy));
  registry();
  /* the hand counts of the header */
  long n = run("{law: graded_stretch, s0_at_origin: 0.0035, s0_gradient: 5}", LAW_GRADED, 0, 0);
  PF_TEST_TRUE(n == 32);
  n = run("{law: stretch_or_energy, stretch_limit: 0.02, energy_limit: 3.5e13}", LAW_EITHER, 0.02, 3.5e13);
  PF_TEST_TRUE(n == 24);
  n = run("{law: stretch_or_energy, stretch_limit: 0.004, energy_limit: 1e30}", LAW_EITHER, 0.004, 1e30);
  PF_TEST_TRUE(n == 72);
  return pf_test_finish();
}
