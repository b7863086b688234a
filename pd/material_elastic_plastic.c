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
 * Several materials (docs/theory/interfaces.md §3b): K, G, Y0 and H are each point's own
 * material's (pf_pd_K, pf_pd_G, Y0q, Hq), so t_ij takes i's and t_ji j's, as LPS.
 * Per-bond state: each directed bond (i, j) of i's family keeps e^dp of i's end ([0]) and a
 * mirror of j's end, e^dp of bond (j, i) ([1]). j's owner updates its own copy with the same
 * operands (|y_j - y_i|, |xi|, theta_j, beta_j: ghosted per-point values), so the two copies
 * stay bitwise equal and t_ji is computed at i without a per-bond exchange. Bonds fail in the
 * dilatation pass, as LPS.
 * The bond loops go in batches of PF_BATCH bonds (pd/bond_batch.h): the neighbours' records
 * (X, V, y and s0, then theta) are transposed into lanes, and each batch's lengths, square
 * roots and divisions are one vector pass; the per-point sums then add the batch's terms one
 * bond after the other, in the row's order, so that every sum has the terms and the order of
 * the bond-by-bond loop (the same bits). The dilatation pass keeps each bond's |xi| and
 * extension in a scratch row for the trial-stress sums, so the lengths are formed twice a step,
 * not three times. */
#include "pd/bond_batch.h"
#include "pd/pd_impl.h"

#include <stdlib.h>

enum { NSTATE = 2 }; /* per directed bond: e^dp of the owner's end, of the neighbour's end */

typedef struct {
  double Y0, H;  /* yield stress, linear hardening modulus dY/d eqps (Pa) */
  double Y0q[PF_PD_MAX_PARTS], Hq[PF_PD_MAX_PARTS]; /* several materials: part q's (q = 0: Y0, H) */
  double *m;     /* field "weighted_volume" */
  double *theta; /* field "dilatation" */
  double *beta;  /* field "plastic_return": t^d / t^d_tr of the step (1: elastic) */
  double *eqps;  /* field "eqps": equivalent plastic strain */
  double *mom;   /* field "dilatation_moment": M_i (header) */
  pf_batch_records rec; /* pass 1: s0 in REC_AUX; pass 2: theta */
  double *a, *bc;       /* [store points] pass 2: the volumetric coefficient a_j and 15 G beta_j / m_j */
  pf_int ab_cap;
  double *row;          /* scratch of one row per thread: |xi|, the extension and w V_j of each bond,
                           [threads][3 row_cap] */
  int64_t row_cap;
  int row_threads;
  double *released;     /* [2 n] pass 1: each point's released energy and redistribution, booked
                           after the threads, in point order */
  pf_int released_cap;
} ep;

/* The plastic constants of the material mapping mat: Y0 > 0 (required, as K and G), H >= 0. */
static int read_plastic(const pf_deck *d, const pf_node *mat, double *Y0, double *H) {
  const char *need[] = {"bulk_modulus", "shear_modulus", "yield_stress"};
  for (int k = 0; k < 3; k++)
    if (!pf_node_get(mat, need[k]))
      return pf_deck_error(d, mat, need[k], "model 'elastic_plastic' needs '%s' (Pa)", need[k]);
  *Y0 = *H = 0;
  PF_CALL(pf_deck_real(d, mat, "yield_stress", Y0));
  PF_CALL(pf_deck_real(d, mat, "hardening_modulus", H));
  if (!(*Y0 > 0))
    return pf_deck_error(d, pf_node_get(mat, "yield_stress"), "yield_stress", "must be positive (got %g)", *Y0);
  if (!(*H >= 0))
    return pf_deck_error(d, pf_node_get(mat, "hardening_modulus"), "hardening_modulus", "must be >= 0 (got %g)", *H);
  return 0;
}

static int ep_create(const pf_deck *d, const pf_node *mat, pf_pd_body *b) {
  ep *p;
  PF_MALLOC(p, 1);
  b->mat = p;
  PF_CALL(read_plastic(d, mat, &p->Y0, &p->H));
  p->Y0q[0] = p->Y0, p->Hq[0] = p->H;
  b->fam.nstate = NSTATE;
  return 0;
}

/* Part q's material (several materials, docs/theory/interfaces.md §3b): of this model, its own
 * density, K, G, yield stress and hardening modulus (pf_pd_material_ops.read_part). */
static int ep_read_part(const pf_deck *d, const pf_node *mat, const char *name, pf_pd_body *b, int q,
                        pf_pd_part *part) {
  ep *p = b->mat;
  PF_CALL(pf_pd_part_read_constants(d, mat, name, b, part));
  return read_plastic(d, mat, &p->Y0q[q], &p->Hq[q]);
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
  PF_CALL(pf_pd_body_keep_history(b, ie)); /* (with e^dp, the bonds' state) */
  return pf_pd_weighted_volumes(b, pts, p->m);
}

/* Grow the row scratch to n bonds for each of the threads, and the released energies to the
 * body's points. */
static int ep_scratch_room(ep *p, int64_t n, int threads, pf_int points) {
  if (n > p->row_cap || threads > p->row_threads) {
    free(p->row);
    p->row_cap = n + PF_BATCH, p->row_threads = threads;
    PF_MALLOC(p->row, 3 * p->row_cap * threads);
  }
  if (points > p->released_cap) {
    free(p->released);
    p->released_cap = points;
    PF_MALLOC(p->released, 2 * (size_t)points);
  }
  return 0;
}

static int ep_thread(void) {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/* Pass 1 for point i (records with s0 in REC_AUX): dilatation (failing bonds beyond the
 * critical stretch, as LPS), then the trial equivalent stress
 * sigma_tr = 3 G sqrt(5 sum_j w (e^d - e^dp_n)^2 V_j / m_i) and the return: beta and the new eqps. */
static inline __attribute__((always_inline)) void ep_point(pf_pd_body *b, const pf_points *pts,
                                                            const double *restrict rec, pf_int i,
                                                            const int weighted, const int partial) {
  enum { L = PF_BATCH };
  ep *p = b->mat;
  const pf_family *fam = &b->fam;
  uint8_t *restrict broken = fam->broken;
  const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
  const double *ri = rec + (size_t)PF_REC * (size_t)i, s0i = ri[REC_AUX];
  double *restrict r0s = p->row + 3 * p->row_cap * ep_thread(), *restrict exts = r0s + p->row_cap,
                   *restrict wvs = r0s + 2 * p->row_cap;
  double sum = 0, smin = INFINITY;
  int fresh = 0;
  for (int64_t kb = k0; kb < k1; kb += L) {
    const int n = k1 - kb < L ? (int)(k1 - kb) : L;
    int32_t idx[L];
    double a[PF_REC][L], r0[L], r[L], e[3][L], s[L], om[L], vj[L];
    for (int l = 0; l < L; l++) idx[l] = fam->neighbor[kb + l];
    pf_batch_gather(rec, idx, a);
    pf_batch_sqrt_lengths(ri, a, r0, r, e);
#pragma omp simd
    for (int l = 0; l < L; l++) {
      s[l] = (r[l] - r0[l]) / r0[l];
      om[l] = weighted ? pf_pd_omega(&b->influence, r0[l]) : 1.0;
      vj[l] = partial && fam->vfrac ? a[REC_V][l] * fam->vfrac[kb + l] : a[REC_V][l];
      r0s[kb - k0 + l] = r0[l], exts[kb - k0 + l] = r[l] - r0[l], wvs[kb - k0 + l] = om[l] * vj[l];
    }
    for (int l = 0; l < n; l++) { /* (in the row's order) */
      const int64_t k = kb + l;
      if (broken[k]) continue;
      if (s[l] > (s0i < a[REC_AUX][l] ? s0i : a[REC_AUX][l])) { /* (?: for fmin: no NaN, no -0 here) */
        broken[k] = PF_BOND_FRESH;
        fresh++;
        continue;
      }
      smin = s[l] < smin ? s[l] : smin;
      sum += om[l] * r0[l] * (r[l] - r0[l]) * vj[l];
    }
  }
  b->smin[i - b->first] = smin;
  const double m = p->m[i], th = 3.0 * sum / m, G = pf_pd_G(b, i); /* (each point its own material's) */
  b->lost[i - b->first] = fresh > 0; /* (the release booked after the threads; plastic work stays) */
  if (fresh) p->released[2 * (i - b->first)] = pf_pd_lps_release_point(b, pts, i, m, fam->state, NSTATE,
                                                                         &p->released[2 * (i - b->first) + 1]);
  double n2 = 0, pm = 0; /* sum_j w (e^d - e^dp_n)^2 V_j, sum_j w |xi| e^dp_n V_j */
  for (int64_t k = k0; k < k1; k++) {
    if (broken[k]) continue;
    const double r0 = r0s[k - k0];
    const double tr = exts[k - k0] - th * r0 / 3 - fam->state[NSTATE * k];
    const double wv = wvs[k - k0];
    n2 += wv * tr * tr, pm += wv * r0 * fam->state[NSTATE * k];
  }
  const int q = b->part ? (int)b->part[i] : 0;
  const double Y0 = p->Y0q[q], H = p->Hq[q], st = 3 * G * sqrt(5 * n2 / m), Y = Y0 + H * p->eqps[i];
  p->theta[i] = th;
  p->beta[i] = 1.0;
  if (st > Y) {
    const double deq = (st - Y) / (3 * G + H);
    p->beta[i] = 1.0 - 3 * G * deq / st;
    p->eqps[i] += deq;
  }
  p->mom[i] = pf_pd_dilatation_moment(b, i, th, pm, p->beta[i]);
}

/* Pass 2 for point i (records with theta in REC_AUX): the force density sum into f[3], and
 * e^dp_{n+1} = e^d - beta (e^d - e^dp_n) at each end of each bond (untouched when elastic,
 * beta = 1). */
static inline __attribute__((always_inline)) void ep_point_force(const pf_pd_body *b, const double *restrict rec,
                                                                  pf_int i, const int weighted, const int partial,
                                                                  double f[3]) {
  enum { L = PF_BATCH };
  const ep *p = b->mat;
  const pf_family *fam = &b->fam;
  const uint8_t *restrict broken = fam->broken;
  double *restrict edp = fam->state;
  const int64_t k0 = fam->offset[i - b->first], k1 = fam->offset[i - b->first + 1];
  const double *ri = rec + (size_t)PF_REC * (size_t)i;
  const double thi = ri[REC_AUX], ai = p->a[i], bi = p->bc[i], betai = p->beta[i];
  f[0] = f[1] = f[2] = 0;
  for (int64_t kb = k0; kb < k1; kb += L) {
    const int n = k1 - kb < L ? (int)(k1 - kb) : L;
    int32_t idx[L];
    double a[PF_REC][L], r0[L], r[L], e[3][L], aj[L], bj[L], betaj[L], e0[L], e1[L];
    double fs[L], n0[L], n1[L];
    for (int l = 0; l < L; l++) idx[l] = fam->neighbor[kb + l];
    pf_batch_gather(rec, idx, a);
    pf_batch_gather1(p->a, idx, aj);
    pf_batch_gather1(p->bc, idx, bj);
    pf_batch_gather1(p->beta, idx, betaj);
    for (int l = 0; l < L; l++) /* (the state has no slack past the last row) */
      e0[l] = l < n ? edp[NSTATE * (kb + l)] : 0.0, e1[l] = l < n ? edp[NSTATE * (kb + l) + 1] : 0.0;
    pf_batch_sqrt_lengths(ri, a, r0, r, e);
#pragma omp simd
    for (int l = 0; l < L; l++) {
      const double ext = r[l] - r0[l], w = weighted ? pf_pd_omega(&b->influence, r0[l]) : 1.0;
      const double edi = ext - thi * r0[l] / 3, edj = ext - a[REC_AUX][l] * r0[l] / 3;
      const double tij = w * (ai * r0[l] + bi * (edi - e0[l]));
      const double tji = w * (aj[l] * r0[l] + bj[l] * (edj - e1[l]));
      const double vj = partial && fam->vfrac ? a[REC_V][l] * fam->vfrac[kb + l] : a[REC_V][l];
      fs[l] = (tij + tji) * vj / r[l];
      n0[l] = edi - betai * (edi - e0[l]);
      n1[l] = edj - betaj[l] * (edj - e1[l]);
    }
    for (int l = 0; l < n; l++) { /* (in the row's order) */
      const int64_t k = kb + l;
      if (broken[k]) continue;
      for (int c = 0; c < 3; c++) f[c] += fs[l] * e[c][l];
      if (betai != 1.0) edp[NSTATE * k] = n0[l];
      if (betaj[l] != 1.0) edp[NSTATE * k + 1] = n1[l];
    }
  }
}

static int ep_force(pf_pd_body *b, pf_points *pts) {
  ep *p = b->mat;
  const pf_family *fam = &b->fam;
  int64_t longest = 0;
  for (pf_int i = 0; i < b->n; i++) longest = fam->offset[i + 1] - fam->offset[i] > longest ? fam->offset[i + 1] - fam->offset[i] : longest;
#if defined(_OPENMP)
  const int threads = omp_get_max_threads();
#else
  const int threads = 1;
#endif
  PF_CALL(ep_scratch_room(p, longest, threads, b->n));
  PF_CALL(pf_batch_records_fill(&p->rec, pts, b->s0));
  const int weighted = b->influence.kind != PF_INFLUENCE_CONSTANT, partial = fam->vfrac != NULL;
  /* Owner computes, as the LPS loops (pd/lps_batched.c): a point writes only its own values and
   * row, so the threads (each a contiguous range of points) share nothing; the energy released
   * by failed bonds is added after, in point order, so the bits do not depend on the threads. */
#pragma omp parallel
  {
    pf_int lo, hi;
    pf_thread_range(b->first, b->n, &lo, &hi);
    if (!weighted && !partial) /* (omega = 1 folded away: x * 1.0 is x, the same bits) */
      for (pf_int i = lo; i < hi; i++) ep_point(b, pts, p->rec.rec, i, 0, 0);
    else
      for (pf_int i = lo; i < hi; i++) ep_point(b, pts, p->rec.rec, i, 1, 1);
  }
  for (pf_int i = 0; i < b->n; i++)
    if (b->lost[i]) b->damage_work += p->released[2 * i], b->damage_redistribution += p->released[2 * i + 1];
  PF_CALL(pf_points_exchange(pts, p->theta, 1)); /* the ghosts' theta and beta for the force pass */
  PF_CALL(pf_points_exchange(pts, p->beta, 1));
  PF_CALL(pf_points_exchange(pts, p->mom, 1));
  const pf_int nt = pts->n_total;
  if (nt > p->ab_cap) {
    free(p->a), free(p->bc);
    p->ab_cap = nt + nt / 8 + 16;
    PF_MALLOC(p->a, p->ab_cap);
    PF_MALLOC(p->bc, p->ab_cap);
  }
#pragma omp parallel for schedule(static)
  for (pf_int j = 0; j < nt; j++) { /* (each end's coefficients, as the bond-by-bond loop formed them) */
    p->rec.rec[(size_t)PF_REC * (size_t)j + REC_AUX] = p->theta[j];
    const double K = pf_pd_K(b, j), G = pf_pd_G(b, j); /* (each end its own material's) */
    p->a[j] = pf_pd_lps_volumetric(K, G, p->theta[j], p->mom[j], p->m[j]);
    p->bc[j] = 15 * G / p->m[j] * p->beta[j];
  }
#pragma omp parallel
  {
    pf_int lo, hi;
    pf_thread_range(b->first, b->n, &lo, &hi);
    for (pf_int i = lo; i < hi; i++) {
      double f[3];
      if (!weighted && !partial) ep_point_force(b, p->rec.rec, i, 0, 0, f);
      else ep_point_force(b, p->rec.rec, i, 1, 1, f);
      for (int a = 0; a < 3; a++) pts->f[3 * i + a] += pts->vol[i] * f[a];
    }
  }
  return 0;
}

/* Internal energy of the owned points: stored elastic energy plus plastic work,
 *   W_i = V_i [ (K/2) theta^2 + (alpha_i / 2) sum_j w (e^d - e^dp)^2 V_j + Y0 eqps + H eqps^2 / 2 ]
 * (the plastic work int Y d eqps = sum_j t^d de^dp V_j: the energy a run's balance needs, as the
 * stress work of FE and correspondence bodies). */
static double ep_point_energy(const pf_pd_body *b, const pf_points *pts, pf_int i) {
  const ep *p = b->mat;
  const double eq = p->eqps[i];
  const int q = b->part ? (int)b->part[i] : 0;
  return pts->vol[i] * (pf_pd_lps_energy_density(b, p->rec.rec, i, p->theta[i], p->m[i], b->fam.state, NSTATE) +
                        p->Y0q[q] * eq + 0.5 * p->Hq[q] * eq * eq);
}

static double ep_energy(const pf_pd_body *b, const pf_points *pts) {
  ep *p = b->mat; /* (the records are scratch: every force pass fills them again) */
  if (pf_batch_records_fill(&p->rec, pts, NULL)) return NAN; /* (out of memory: shows in the balance) */
  return pf_pd_body_point_sum(b, pts, ep_point_energy);
}

static void ep_destroy(pf_pd_body *b) {
  ep *p = b->mat;
  if (p) {
    pf_batch_records_free(&p->rec);
    free(p->a), free(p->bc), free(p->row), free(p->released);
  }
  PF_FREE(b->mat);
}

static const pf_key keys[] = {
    {"yield_stress", PF_KEY_REAL, 0, NULL, "Pa", "elastic_plastic: initial yield stress (> 0)", NULL},
    {"hardening_modulus", PF_KEY_REAL, 0, "0", "Pa", "elastic_plastic: linear hardening modulus (>= 0)", NULL},
    PF_KEY_END};

const pf_pd_material_ops pf_pd_material_elastic_plastic = {
    .name = "elastic_plastic",
    .keys = keys,
    .create = ep_create,
    .setup = ep_setup,
    .force = ep_force,
    .energy = ep_energy,
    .micromodulus = pf_pd_lps_micromodulus,     /* elastic LPS: plastic flow only softens */
    .critical_stretch = pf_pd_lps_critical_stretch, /* LPS closed forms: elastic fracture */
    .destroy = ep_destroy,
    .several_materials = 1,
    .family_stiffness = 1,
    .records_rest = 1,
    .read_part = ep_read_part,
};
