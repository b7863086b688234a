/* The contact-method registry (contact/methods.h), every method through one conformance loop.
 *
 * The list: each method has an id of its own and its required ops; a method is picked by its
 * case (PD <-> PD, FE <-> PD, FE <-> FE) and its `method:` name, which no other method of the
 * case shares (a method without a name is its case's first, the default); every case has a
 * method; the flags fit the case (faces and FE-node entities need FE bodies, bonds two PD
 * bodies).
 *
 * Each method on a tiny two-body set-up of its case (two 4 x 4 x 4 mm boxes along x, spacing
 * 1 mm, PD boxes of PMB glass, FE boxes of 4^3 steel hexahedra), the pair picked by its `method:`
 * name and a contact radius of 1.2 mm, the contact forces evaluated at the reference positions:
 *  - the boxes overlapping by 0.5 mm: the pair's force (on its body a) is not zero, body a's
 *    points carry it and body b's points its opposite (equal and opposite forces: the linear
 *    momentum is conserved, the forces of all points sum to zero, to round-off), the gap is
 *    finite and the stable step positive;
 *  - the boxes 10 mm apart: no point has a contact force, the pair's force is zero and no
 *    interaction is within reach (gap INFINITY). */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact_impl.h"

static const char *const case_name[PF_CONTACT_NCASES] = {"PD <-> PD", "FE <-> PD", "FE <-> FE"};

static void fail(const char *what, const pf_contact_method *m) {
  fprintf(stderr, "contact method '%s': %s\n", m && m->id ? m->id : "?", what);
  pf_test_failures++;
}

static void registry(void) {
  int per_case[PF_CONTACT_NCASES] = {0};
  for (int q = 0; q < pf_contact_nmethods; q++) {
    const pf_contact_method *m = pf_contact_methods[q];
    if (!m->id || !m->id[0]) fail("no id", m);
    if (!m->read || !m->evaluate || !m->stable_w2) fail("a required op (read, evaluate, stable_w2) is missing", m);
    if (!((int)m->claims >= 0 && m->claims < PF_CONTACT_NCASES)) {
      fail("claims no case", m);
      continue;
    }
    per_case[m->claims]++;
    /* its case and name pick it; without a name it is its case's default */
    if (pf_contact_method_find(m->claims, m->name) != m) fail("its case and `method:` name do not pick it", m);
    for (int r = 0; r < q; r++) {
      const pf_contact_method *o = pf_contact_methods[r];
      if (o->id && m->id && !strcmp(o->id, m->id)) fail("its id is another method's", m);
      if (o->claims == m->claims && (!o->name || !m->name || !strcmp(o->name, m->name)))
        fail("its case and `method:` name do not tell it from another method", m);
    }
    if (m->partners == PF_CONTACT_PARTNER_FACES && m->claims == PF_CONTACT_PD_PD) fail("faces without an FE body", m);
    if (m->fe_entities && m->claims != PF_CONTACT_FE_FE) fail("FE-node entities without two FE bodies", m);
    if (m->bonds && m->claims != PF_CONTACT_PD_PD) fail("bonds without two PD bodies", m);
  }
  for (int cs = 0; cs < PF_CONTACT_NCASES; cs++)
    if (!per_case[cs]) {
      fprintf(stderr, "no contact method claims %s pairs\n", case_name[cs]);
      pf_test_failures++;
    }
  PF_TEST_TRUE(pf_contact_method_find(PF_CONTACT_FE_PD, "no_such_method") == NULL);
}

enum { NB = 4 };           /* cells (elements) of a box along each axis */
static const double H = 1e-3, RC = 1.2e-3;

/* One body of the deck: a box [x0, x0 + NB H] x [0, NB H]^2. */
static void body_text(char *out, size_t n, const char *name, int fe, double x0) {
  const double lo[3] = {x0, 0, 0}, hi[3] = {x0 + NB * H, NB * H, NB * H};
  if (fe)
    snprintf(out, n, "  - name: %s\n    type: finite_element\n    material: steel\n%s", name,
             pf_test_pamgen_box(NB, NB, NB, lo, hi));
  else
    snprintf(out, n,
             "  - name: %s\n    material: glass\n    horizon: 3.0001e-3\n"
             "    geometry: {shape: box, lo: [%.17g, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %g}\n",
             name, lo[0], hi[0], hi[1], hi[2], H);
}

/* The sum of the contact forces of the points of body b (b < 0: of every point) into f, and of
 * their magnitudes into *mag. */
static void force_sum(const pf_points *p, const double *fc, int b, double f[3], double *mag) {
  f[0] = f[1] = f[2] = 0;
  *mag = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    if (b >= 0 && p->body[i] != b) continue;
    for (int a = 0; a < 3; a++) f[a] += fc[3 * i + a];
    *mag += sqrt(fc[3 * i] * fc[3 * i] + fc[3 * i + 1] * fc[3 * i + 1] + fc[3 * i + 2] * fc[3 * i + 2]);
  }
}

static double norm(const double f[3]) { return sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

/* Method m on its case's two boxes, body b's box from x = shift: the checks of the file head. */
static void two_bodies(const pf_contact_method *m, double shift, int touching) {
  const int fe_a = m->claims != PF_CONTACT_PD_PD, fe_b = m->claims == PF_CONTACT_FE_FE;
  char a[1024], b[1024], method[64] = "", deck[4096];
  body_text(a, sizeof a, "one", fe_a, 0);
  body_text(b, sizeof b, "two", fe_b, shift);
  if (m->name) snprintf(method, sizeof method, ", method: %s", m->name);
  snprintf(deck, sizeof deck,
           "materials:\n"
           "  glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}\n"
           "  steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}\n"
           "bodies:\n%s%s"
           "contact:\n  pairs:\n    - {bodies: [one, two], radius: %g%s}\n"
           "time: {steps: 1}\n",
           a, b, RC, method);
  char tag[96];
  snprintf(tag, sizeof tag, "contact_methods_%s_%s", m->id, touching ? "touching" : "apart");
  pf_sim *sim = pf_test_sim(tag, deck);
  pf_contact *c = pf_sim_contact(sim);
  pf_points *p = pf_sim_points(sim);
  if (!c || pf_contact_npairs(c) != 1 || c->pair[0].method != m) {
    fail("the deck of its case and name does not make a pair of it", m);
    pf_sim_destroy(&sim);
    return;
  }
  const int ia = c->pair[0].a, ib = c->pair[0].b;
  PF_TEST_TRUE(c->body[ia].is_fe == fe_a && c->body[ib].is_fe == fe_b);
  const int ns = pf_contact_nsums(c);
  double sums[16] = {0}, diss = 0, energy = 0, pair[3];
  PF_TEST_TRUE(ns <= 16);
  PF_TEST_OK(pf_contact_force(c, p, 0.0, sums, &diss));
  pf_contact_sums_take(c, sums, &energy);
  pf_contact_pair_force(c, 0, pair);
  const double *fc = pf_points_field_get(p, "contact_force");
  PF_TEST_TRUE(fc != NULL);
  if (!fc) {
    pf_sim_destroy(&sim);
    return;
  }
  double fa[3], fb[3], fall[3], ma, mb, mall;
  force_sum(p, fc, ia, fa, &ma);
  force_sum(p, fc, ib, fb, &mb);
  force_sum(p, fc, -1, fall, &mall);
  pf_contact_gap info;
  const double gap = pf_contact_pair_gap(c, 0, &info);
  char what[256];
  if (touching) {
    const double F = norm(pair);
    if (!(F > 0)) fail("no force between the overlapping boxes", m);
    if (!(energy > 0)) fail("no penalty energy between the overlapping boxes", m);
    for (int k = 0; k < 3; k++) {
      if (!(fabs(fa[k] - pair[k]) <= 1e-10 * F)) {
        snprintf(what, sizeof what, "body a's points carry %.17g N along %d, the pair's force %.17g N", fa[k], k,
                 pair[k]);
        fail(what, m);
      }
      if (!(fabs(fb[k] + pair[k]) <= 1e-10 * F)) {
        snprintf(what, sizeof what, "body b's points carry %.17g N along %d, not the opposite of %.17g N", fb[k], k,
                 pair[k]);
        fail(what, m);
      }
    }
    if (!(norm(fall) <= 1e-12 * mall)) {
      snprintf(what, sizeof what, "the contact forces sum to %.3g N (sum of magnitudes %.3g N): momentum not conserved",
               norm(fall), mall);
      fail(what, m);
    }
    if (!(fabs(pair[0]) > fabs(pair[1]) && fabs(pair[0]) > fabs(pair[2]) && pair[0] < 0))
      fail("the force on body a does not push it back along -x", m);
    if (!isfinite(gap)) fail("no gap while touching", m);
    PF_TEST_TRUE(info.surface == m->signed_gap && info.a == ia && info.b == ib);
    const double dt = pf_contact_stable_dt(c, p);
    if (!(dt > 0 && isfinite(dt))) fail("no finite positive stable step", m);
  } else {
    if (!(ma == 0 && mb == 0 && norm(pair) == 0)) fail("a force between boxes 10 mm apart", m);
    if (gap != INFINITY) fail("an interaction within reach between boxes 10 mm apart", m);
  }
  printf("%-12s %-9s %-9s pair force [%+.4e %+.4e %+.4e] N, sum over the points %.2e N (of %.4e N), gap %.4g\n", m->id,
         case_name[m->claims], touching ? "touching" : "apart", pair[0], pair[1], pair[2], norm(fall), mall, gap);
  pf_sim_destroy(&sim);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  registry();
  for (int q = 0; q < pf_contact_nmethods; q++) {
    two_bodies(pf_contact_methods[q], NB * H - 0.5 * H, 1);
    two_bodies(pf_contact_methods[q], NB * H + 10 * H, 0);
  }
  return pf_test_finish();
}
