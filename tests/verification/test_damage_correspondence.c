/* Damage correspondence (Tupek, Rimoli & Radovitzky 2013, eqs. 6-7) has an effect: a bar of the
 * modified Johnson-Cook aluminium (Tupek et al. Table 3, with d1 lowered to 0.1 so that it fails
 * early) pulled at both ends at 40 m/s
 *  - without a damage model (no `damage:` mapping) keeps every bond and keeps carrying load;
 *  - with Johnson-Cook damage it breaks into two pieces: some cross-section is crossed by no
 *    intact bond (the grip force then only rings with the elastic waves of the two halves);
 *  - the failure localises: every point whose bond damage exceeds 1/2 lies within one horizon
 *    of a single cross-section (damage does not diffuse, the point of the paper);
 *  - it fails when the plastic strain reaches the Johnson-Cook failure strain: the largest
 *    equivalent plastic strain at separation is within [0.85, 1.05] of
 *    eps_f(1/3) = d1 + d2 exp(d3 / 3) (uniaxial tension, triaxiality 1/3; necking raises the
 *    triaxiality and lowers eps_f, hence the wider lower band), times D_c = 0.99.
 * Bar 4 x 4 x 20 mm, 0.5 mm lattice, horizon 3.01 spacings, Gaussian influence (Tupek eq. 7).
 * w_D removes the bonds of failed points only, so bonds that reach over a failed layer (up to a
 * horizon long) survive it; a critical stretch of 0.5 (a bond at 1.5 times its length no longer
 * spans continuous material) removes them once the halves have parted. It cannot break a bond
 * before the damage model does: the strains before failure are below 0.2. */
#include "sim/sim.h"
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static pf_sim *make(int damage) {
  char deck[2048];
  snprintf(deck, sizeof deck,
           "materials:\n  al: {model: modified_johnson_cook, density: 2700, youngs_modulus: 72.0e9, poissons_ratio: 0.343,\n"
           "       modified_johnson_cook: {sigma0: 250.0e6, B: 365.0e6, n: 0.04, C: 0.002, reference_strain_rate: 1}%s}\n"
           "bodies:\n  - {name: bar, material: al, horizon: 1.505e-3, influence: gaussian,\n"
           "     damage: {law: critical_stretch, critical_stretch: 0.5},\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.004, 0.004, 0.02], spacing: 0.5e-3, origin: [0.25e-3, 0.25e-3, 0.25e-3]}}\n"
           "boundary_conditions:\n"
           "  - {region: {shape: box, lo: [-1, -1, -1], hi: [1, 1, 0.00175]}, velocity: [free, free, \"-40 * min(t / 2e-6, 1)\"]}\n"
           "  - {region: {shape: box, lo: [-1, -1, 0.01825], hi: [1, 1, 1]}, velocity: [free, free, \"40 * min(t / 2e-6, 1)\"]}\n"
           "time: {final_time: 4.5e-5}\n",
           damage ? ",\n       damage: {d1: 0.1, d2: 0.13, d3: -1.5, d4: 0, reference_strain_rate: 1}" : "");
  return pf_test_sim(damage ? "damage_corr" : "damage_corr_off", deck);
}

/* The fewest intact bonds crossing any plane z = const between two lattice layers of the bar's
 * middle (8-12 mm): 0 once the bar is in two pieces. */
static double fewest_crossing(pf_sim *sim) {
  const pf_points *p = pf_sim_points(sim);
  const pf_family *fam = pf_pd_body_family(pf_sim_body(sim, 0));
  double fewest = INFINITY;
  for (double zc = 0.008; zc <= 0.012; zc += 0.5e-3) {
    double n = 0;
    for (pf_int i = 0; i < fam->n; i++)
      for (int64_t k = fam->offset[i]; k < fam->offset[i + 1]; k++) {
        pf_int a = fam->first + i, b = fam->neighbor[k];
        n += !fam->broken[k] && (p->X[3 * a + 2] - zc) * (p->X[3 * b + 2] - zc) < 0;
      }
    fewest = fmin(fewest, pf_sum_all(n));
  }
  return fewest;
}

/* Axial force the top grip's points receive from the rest of the bar (pair forces between grip
 * points cancel in the sum). */
static double grip_force(const pf_points *p) {
  double f = 0;
  for (pf_int i = 0; i < p->n_owned; i++)
    if (p->X[3 * i + 2] > 0.01825) f += p->f[3 * i + 2];
  return pf_sum_all(f);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const double eps_f = 0.1 + 0.13 * exp(-1.5 / 3.0), dc = 0.99;
  for (int damage = 0; damage <= 1; damage++) {
    pf_sim *sim = make(damage);
    const pf_points *p = pf_sim_points(sim);
    double fpeak = 0, eqps_sep = -1;
    while (!pf_sim_finished(sim)) {
      PF_TEST_OK(pf_sim_step(sim, 10));
      double f = grip_force(p);
      fpeak = fmax(fpeak, fabs(f));
      pf_sim_globals g;
      PF_TEST_OK(pf_sim_globals_get(sim, &g));
      if (eqps_sep < 0 && g.damage_fraction > 0) { /* the first broken bonds */
        const double *e = pf_points_field_get(p, "eqps");
        double m = 0;
        for (pf_int i = 0; i < p->n_owned; i++) m = fmax(m, e[i]);
        eqps_sep = pf_max_all(m);
      }
    }
    const double f_end = fabs(grip_force(p)), crossing = fewest_crossing(sim);
    const double *phi = pf_points_field_get(p, "damage");
    double zlo = INFINITY, zhi = -INFINITY;
    for (pf_int i = 0; i < p->n_owned; i++)
      if (phi[i] > 0.5) zlo = fmin(zlo, p->X[3 * i + 2]), zhi = fmax(zhi, p->X[3 * i + 2]);
    zlo = pf_min_all(zlo), zhi = pf_max_all(zhi);
    if (damage) {
      pf_test_measure("eqps_at_failure", eqps_sep, "1");
      pf_test_measure("band_lo", zlo * 1e3, "mm");
      pf_test_measure("band_hi", zhi * 1e3, "mm");
    }
    if (pf_comm_rank() == 0 && getenv("PF_TEST_VERBOSE"))
      printf("damage %d: max grip force %.4g N, final %.4g N, eqps at first failure %.4f (eps_f Dc %.4f), damaged band z %.3g..%.3g mm, fewest crossing bonds %g\n",
             damage, fpeak, f_end, eqps_sep, eps_f * dc, zlo * 1e3, zhi * 1e3, crossing);
    if (!damage) {
      PF_TEST_TRUE(crossing > 0);
      PF_TEST_TRUE(eqps_sep < 0);            /* no bond broke */
      PF_TEST_TRUE(f_end > 0.5 * fpeak);      /* still carrying load */
      PF_TEST_TRUE(fpeak > 0);
    } else {
      PF_TEST_TRUE(crossing == 0);            /* separated */
      PF_TEST_TRUE(eqps_sep >= 0.85 * eps_f * dc && eqps_sep <= 1.05 * eps_f * dc);
      PF_TEST_TRUE(zhi - zlo <= 2 * 1.505e-3); /* one band, at most a horizon either side */
    }
    pf_test_print_digest(damage ? "damage_corr" : "damage_corr_off", sim);
    pf_sim_destroy(&sim);
  }
  return pf_test_finish();
}
