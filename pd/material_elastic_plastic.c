/* Ordinary state-based elastic-plastic solid with linear isotropic hardening (Mitchell 2011,
 * "A nonlocal, ordinary, state-based plasticity model for peridynamics", SAND2011-3166; the
 * model of Peridigm's "Elastic Plastic Hardening" material), built on the LPS of
 * material_lps.c. Theory and calibration: docs/theory/materials.md section 1.
 *   m_i     = sum_j w |xi|^2 V_j,  theta_i = (3 / m_i) sum_j w |xi| e V_j     (as LPS)
 *   e^d     = e - theta_i |xi| / 3                              deviatoric extension
 *   t^d_tr  = alpha_i w (e^d - e^dp_n),  alpha_i = 15 G / m_i   trial deviatoric force state
 *   sigma_i = sqrt(m_i / 5) ||t^d||,  ||t||^2 = sum_j t^2 / w V_j
 *             (equivalent stress: von Mises under a homogeneous deformation of a full family;
 *             for w = 1 and m = 4 pi delta^5 / 5 the yield surface sigma = Y is Mitchell's
 *             ||t^d||^2 / 2 = psi0 = 25 Y^2 / (8 pi delta^5))
 *   yield   sigma_tr <= Y(eqps) = Y0 + H eqps, else the radial return (closed form, linear H):
 *             d eqps = (sigma_tr - Y_n) / (3 G + H),  beta = 1 - 3 G d eqps / sigma_tr,
 *             t^d = beta t^d_tr,  e^dp_{n+1} = e^d - beta (e^d - e^dp_n)
 *             (flow rule d e^dp = d lambda t^d / w, d eqps = d lambda ||t^d||^2 / sigma)
 *   t_ij    = w (3 K theta_i / m_i - alpha_i M_i / m_i) |xi| + t^d_ij,   f_i = V_i sum_j (t_ij + t_ji) M_ij V_j
 *   M_i     = beta_i (theta_i m^lost_i / 3 - sum_j w |xi| e^dp_n V_j), m^lost_i = the weighted
 *             volume of i's failed bonds: the term that keeps t the gradient of the energy once
 *             bonds have failed (0 while none has; docs/theory/materials.md §1, "Failed bonds")
 * Per-bond state: each directed bond (i, j) of i's family keeps e^dp of i's end ([0]) and a
 * mirror of j's end, e^dp of bond (j, i) ([1]). j's owner updates its own copy with the same
 * operands (|y_j - y_i|, |xi|, theta_j, beta_j: ghosted per-point values), so the two copies
 * stay bitwise equal and t_ji is computed at i without a per-bond exchange. Bonds fail in the
 * dilatation pass, as LPS. */
#include "pd/pd_impl.h"

#include <stdlib.h>

enum { NSTATE = 2 }; /* per directed bond: e^dp of the owner's end, of the neighbour's end */

typedef struct {
  double Y0, H;  /* yield stress, linear hardening modulus dY/d eqps (Pa) */
  double *m;     /* field "weighted_volume" */
  double *theta; /* field "dilatation" */
  double *beta;  /* field "plastic_return": t^d / t^d_tr of the step (1: elastic) */
  double *eqps;  /* field "eqps": equivalent plastic strain */
  double *mom;   /* field "dilatation_moment": M_i (header) */
} ep;

static int ep_create(const pf_deck *d, const pf_node *mat, pf_pd_body *b) {
  const char *need[] = {"bulk_modulus", "shear_modulus", "yield_stress"};
  for (int k = 0; k < 3; k++)
    if (!pf_node_get(mat, need[k]))
      return pf_deck_error(d, mat, need[k], "model 'elastic_plastic' needs '%s' (Pa)", need[k]);
  ep *p;
  PF_MALLOC(p, 1);
  b->mat = p;
  PF_CALL(pf_deck_real(d, mat, "yield_stress", &p->Y0));
  PF_CALL(pf_deck_real(d, mat, "hardening_modulus", &p->H));
  if (!(p->Y0 > 0))
    return pf_deck_error(d, pf_node_get(mat, "yield_stress"), "yield_stress", "must be positive (got %g)", p->Y0);
  if (!(p->H >= 0))
    return pf_deck_error(d, pf_node_get(mat, "hardening_modulus"), "hardening_modulus",
                         "must be >= 0 (got %g)", p->H);
  b->fam.nstate = NSTATE;
  return 0;
}

/* Fields (a re-partition or a restart brings eqps with the points and e^dp with the rows). */
static int ep_setup(pf_pd_body *b, pf_points *pts) {
  ep *p = b->mat;
  int im, it, ib, ie;
  PF_CALL(pf_points_field_register(pts, "weighted_volume", 1, PF_FIELD_GHOST | PF_FIELD_RESTART, &im));
  PF_CALL(pf_points_field_register(pts, "dilatation", 1, PF_FIELD_GHOST | PF_FIELD_OUTPUT, &it));
  PF_CALL(pf_points_field_register(pts, "plastic_return", 1, PF_FIELD_GHOST, &ib));
  PF_CALL(pf_points_field_register(pts, "eqps", 1, PF_FIELD_RESTART | PF_FIELD_OUTPUT, &ie));
  PF_CALL(pf_pd_lost_volume_fields(b, pts, &p->mom));
  p->m = pts->fields[im].data;
  p->theta = pts->fields[it].data;
  p->beta = pts->fields[ib].data;
  p->eqps = pts->fields[ie].data;
  return pf_pd_weighted_volumes(b, pts, p->m);
}

/* Pass 1 for point i: dilatation (failing bonds beyond the critical stretch, as LPS), then the
 * trial equivalent stress sigma_tr = 3 G sqrt(5 sum_j w (e^d - e^dp_n)^2 V_j / m_i) and the
 * return: beta and the new eqps. */
static void ep_point(pf_pd_body *b, const pf_points *pts, pf_int i) {
  ep *p = b->mat;
  const pf_family *fam = &b->fam;
  const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
  double sum = 0, smin = INFINITY, e[3], r0, r;
  int fresh = 0;
  for (int64_t k = k0; k < k1; k++) {
    if (fam->broken[k]) continue;
    pf_int j = fam->neighbor[k];
    pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
    double s = (r - r0) / r0;
    if (s > fmin(b->s0[i], b->s0[j])) {
      fam->broken[k] = PF_BOND_FRESH;
      fresh++;
      continue;
    }
    smin = fmin(smin, s);
    sum += pf_pd_omega(&b->influence, r0) * r0 * (r - r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
  }
  b->smin[i - b->first] = smin;
  const double m = p->m[i], th = 3.0 * sum / m, G = b->shear_modulus;
  if (fresh) b->damage_work += pf_pd_lps_release(b, pts, i, m, fam->state, NSTATE); /* (plastic work stays) */
  double n2 = 0, pm = 0; /* sum_j w (e^d - e^dp_n)^2 V_j, sum_j w |xi| e^dp_n V_j */
  for (int64_t k = k0; k < k1; k++) {
    if (fam->broken[k]) continue;
    pf_int j = fam->neighbor[k];
    pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
    const double tr = (r - r0) - th * r0 / 3 - fam->state[NSTATE * k];
    const double wv = pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
    n2 += wv * tr * tr, pm += wv * r0 * fam->state[NSTATE * k];
  }
  const double st = 3 * G * sqrt(5 * n2 / m), Y = p->Y0 + p->H * p->eqps[i];
  p->theta[i] = th;
  p->beta[i] = 1.0;
  if (st > Y) {
    const double deq = (st - Y) / (3 * G + p->H);
    p->beta[i] = 1.0 - 3 * G * deq / st;
    p->eqps[i] += deq;
  }
  p->mom[i] = pf_pd_dilatation_moment(b, i, th, pm, p->beta[i]);
}

static int ep_force(pf_pd_body *b, pf_points *pts) {
  ep *p = b->mat;
  const double K = b->bulk_modulus, G = b->shear_modulus;
  const pf_family *fam = &b->fam;
  double *edp = fam->state;
  for (pf_int i = b->first; i < b->first + b->n; i++) ep_point(b, pts, i);
  PF_CALL(pf_points_exchange(pts, p->theta, 1)); /* the ghosts' theta and beta for the force pass */
  PF_CALL(pf_points_exchange(pts, p->beta, 1));
  PF_CALL(pf_points_exchange(pts, p->mom, 1));
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double f[3] = {0, 0, 0}, e[3], r0, r;
    const double ai = pf_pd_lps_volumetric(K, G, p->theta[i], p->mom[i], p->m[i]), bi = 15 * G / p->m[i] * p->beta[i];
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (fam->broken[k]) continue;
      pf_int j = fam->neighbor[k];
      pf_pd_bond_lengths(pts->X, pts->y, i, j, &r0, &r, e);
      const double ext = r - r0, w = pf_pd_omega(&b->influence, r0);
      const double aj = pf_pd_lps_volumetric(K, G, p->theta[j], p->mom[j], p->m[j]), bj = 15 * G / p->m[j] * p->beta[j];
      const double edi = ext - p->theta[i] * r0 / 3, edj = ext - p->theta[j] * r0 / 3;
      const double tij = w * (ai * r0 + bi * (edi - edp[NSTATE * k]));
      const double tji = w * (aj * r0 + bj * (edj - edp[NSTATE * k + 1]));
      const double fs = (tij + tji) * pf_pd_bond_volume(fam, pts->vol, k, j) / r;
      for (int a = 0; a < 3; a++) f[a] += fs * e[a];
      /* e^dp_{n+1} = e^d - beta (e^d - e^dp_n) at each end; untouched when elastic (beta = 1) */
      if (p->beta[i] != 1.0) edp[NSTATE * k] = edi - p->beta[i] * (edi - edp[NSTATE * k]);
      if (p->beta[j] != 1.0) edp[NSTATE * k + 1] = edj - p->beta[j] * (edj - edp[NSTATE * k + 1]);
    }
    for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * f[a];
  }
  return 0;
}

/* Internal energy of the owned points: stored elastic energy plus plastic work,
 *   W_i = V_i [ (K/2) theta^2 + (alpha_i / 2) sum_j w (e^d - e^dp)^2 V_j + Y0 eqps + H eqps^2 / 2 ]
 * (the plastic work int Y d eqps = sum_j t^d de^dp V_j: the energy a run's balance needs, as the
 * stress work of FE and correspondence bodies). */
static double ep_energy(const pf_pd_body *b, const pf_points *pts) {
  const ep *p = b->mat;
  double w = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const double eq = p->eqps[i];
    w += pts->vol[i] * (pf_pd_lps_energy_density(b, pts, i, p->theta[i], p->m[i], b->fam.state, NSTATE) +
                        p->Y0 * eq + 0.5 * p->H * eq * eq);
  }
  return w;
}

static void ep_destroy(pf_pd_body *b) {
  PF_FREE(b->mat);
}

const pf_pd_material_ops pf_pd_material_elastic_plastic = {
    .name = "elastic_plastic",
    .create = ep_create,
    .setup = ep_setup,
    .force = ep_force,
    .energy = ep_energy,
    .micromodulus = pf_pd_lps_micromodulus,     /* elastic LPS: plastic flow only softens */
    .critical_stretch = pf_pd_lps_critical_stretch, /* LPS closed forms: elastic fracture */
    .destroy = ep_destroy,
};
