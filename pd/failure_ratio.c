/* How near a body's bonds are to failing: the largest failure ratio over the owned points'
 * intact bonds that may fail, at the state of the last force evaluation, against the limits the
 * law leaves (pd/pd_impl.h; its own while the damage is frozen):
 *   stretch: s / s_lim, s_lim = min(s0_i, s0_j) or the interface's (pf_pd_stretch_fails);
 *   energy:  sqrt(w / w_c) for a bond in tension, w its energy per V_i V_j as the material's
 *            kernel evaluates it (pf_pd_material_ops.bond_energy_at), w_c its limit.
 * Both grow in proportion when a linear state is scaled, so a state scaled by 1 / r puts the
 * most critical bond exactly at its limit: the quasi-static solver's sequentially linear failure
 * (docs/theory/quasi_static_failure.md §5.2; Rots & Invernizzi 2004, Ni et al. 2018). */
#include "pd/pd_impl.h"

#include <math.h>

typedef struct {
  const double *s0, *wc_bond;
  double interface_s0, critical_energy;
} limits;

static limits limits_of(const pf_pd_body *b) {
  if (b->frozen.on)
    return (limits){b->frozen.s0, b->frozen.wc_bond, b->frozen.interface_s0, b->frozen.critical_energy};
  return (limits){b->s0, b->wc_bond, b->interface_s0, b->critical_energy};
}

static double stretch_limit(const pf_pd_body *b, const limits *l, pf_int i, pf_int j) {
  if (b->interface_law && b->part[i] != b->part[j]) return l->interface_s0;
  return fmin(l->s0[i], l->s0[j]);
}

/* The largest ratio over point i's intact bonds in tension. */
static double point_ratio(const pf_pd_body *b, const pf_points *pts, const limits *l, int energy, pf_int i) {
  const pf_family *fam = &b->fam;
  double rmax = 0, e[3], r0, r;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    const pf_int j = fam->neighbor[k];
    if (fam->broken[k] || !pf_pd_may_fail(b, i, j)) continue;
    pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
    const double ext = r - r0, slim = stretch_limit(b, l, i, j);
    if (ext <= 0) continue;
    if (slim > 0 && isfinite(slim)) rmax = fmax(rmax, ext / r0 / slim);
    const double wc = l->wc_bond ? l->wc_bond[k] : l->critical_energy;
    if (energy && isfinite(wc)) rmax = fmax(rmax, sqrt(b->ops->bond_energy_at(b, i, k, r0, ext) / wc));
  }
  return rmax;
}

double pf_pd_body_failure_ratio(const pf_pd_body *b, const pf_points *pts) {
  const limits l = limits_of(b);
  const int energy = (isfinite(l.critical_energy) || l.wc_bond) && b->ops->bond_energy_at;
  double rmax = 0;
#pragma omp parallel for schedule(static) reduction(max : rmax)
  for (pf_int i = b->first; i < b->first + b->n; i++) rmax = fmax(rmax, point_ratio(b, pts, &l, energy, i));
  return rmax;
}
