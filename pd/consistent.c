/* The consistent form's gradient weights (docs/theory/coupling.md §2.6): where the horizon
 * varies, correct each transition point's correspondence weights g_ik = w V_k K_i^-1 xi [k in H_i]
 * by the smallest h_ik (in sum |h_ik|^2 / (w V_k)) such that
 *   (B) sum_k h_ik (x) xi_ik = 0               at every transition point i (Fbar exact for a
 *                                               linear motion: sum_k xi (x) g_ik = I stays),
 *   (C) sum_j (V_j h_jn - V_n h_nj) = t_n      at every point n a correction reaches,
 * where t_n = V_n d_n, d_n the uniform-stress ghost vector of the standard form (§2.5) at a
 * transition point and 0 elsewhere. (C) makes the energy's force under a uniform stress P,
 * f_n = -P sum_j (V_j g_jn - V_n g_nj), the one a constant horizon gives: zero at an interior
 * point. Coupled to elements in the energy form (§3.4) each V of (C) and of h's owner is the
 * weight of the point's energy, beta V, and t_n also holds the blending's part of the
 * uniform-stress vector (PD one-sided sums and the elements' sum, pd/material_correspondence.c),
 * so that the overlap's kinks are free of ghost forces too. At a free-surface point (an incomplete family, first moment S) only the components of
 * (C) across S are kept, those a traction-free surface leaves to the model; the surface-normal
 * component balances the rest (the sum of (C) over all points vanishes for any weights).
 *
 * Lagrange's conditions give h_ik = w V_k (Lambda_i xi + beta_i V_i (mu_k - mu_i)) with mu already
 * projected at surface points; the multipliers solve the normal equations A W A^T lambda = r
 * (the surface rows made slightly soft, diagonal_blocks) by
 * conjugate gradients with a block-Jacobi preconditioner (Lambda_i: the 3x3 moment
 * sum_k w V_k xi xi^T; mu_n: the scalar sum of w V_k V_i^2 over its bonds). The problem is
 * gathered to every rank and solved there in global-id order, so that the weights, hence the
 * state digest, do not depend on the partition. Fixed geometry: solved once, at t = 0. */
#include "pd/pd_impl.h"

#include <stdlib.h>
#include <string.h>

/* A gathered constrained point: global id, position, volume, transition flag, target t,
 * surface direction S/|S| (0 at an interior point), its energy's weight beta V (V uncoupled). */
enum { R_GID = 0, R_X = 1, R_V = 4, R_ZONE = 5, R_T = 6, R_S = 9, R_BV = 12, RN = 13 };

typedef struct {
  pf_int np;           /* constrained points, ascending global id */
  double *rec;         /* [RN np] */
  int64_t *off;        /* [np + 1] bonds of transition point p: nb[off[p] .. off[p+1]) */
  pf_int *nb;          /* neighbour indices */
  double *P;           /* [9 np] projector of (C): I, or I - s s^T at a surface point */
  double *Minv, *sinv; /* block-Jacobi: [9 np] inverse moments, [np] 1 / sum w V_k V_i^2 */
  double *tau;         /* [np] the soft rows' weight: tau s_n mu added to (C) at surface points */
  double *bw;          /* [4 nbonds] each bond's xi and weight w V_q (bond_weights), read by
                        * every iteration of the solve */
  const pf_influence *infl;
} problem;

static int cmp_rec(const void *a, const void *b) {
  const double x = ((const double *)a)[R_GID], y = ((const double *)b)[R_GID];
  return (x > y) - (x < y);
}

static int cmp_pair(const void *a, const void *b) {
  const int64_t *x = a, *y = b;
  if (x[0] != y[0]) return (x[0] > y[0]) - (x[0] < y[0]);
  return (x[1] > y[1]) - (x[1] < y[1]);
}

static pf_int find(const problem *q, int64_t gid) {
  pf_int lo = 0, hi = q->np - 1;
  while (lo <= hi) {
    const pf_int mid = lo + (hi - lo) / 2;
    const int64_t g = (int64_t)q->rec[RN * mid + R_GID];
    if (g == gid) return mid;
    if (g < gid) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

/* Gather to every rank (MPI_Allgatherv) n items of size `width` of MPI type t; *out is allocated. */
static int allgather(const void *mine, int n, int width, MPI_Datatype t, size_t esize, void **out, int *total) {
  const int size = pf_comm_size();
  int *cnt, *dsp;
  PF_MALLOC(cnt, size);
  PF_MALLOC(dsp, size + 1);
  const int mycount = n * width;
  MPI_Allgather(&mycount, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
  dsp[0] = 0;
  for (int r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  *total = dsp[size] / width;
  char *buf = malloc(esize * (size_t)dsp[size] + 1);
  PF_CHECK(buf, PF_ERR_RUN, "out of memory gathering the consistent form's transition (%d items)", *total);
  MPI_Allgatherv(mine, mycount, t, buf, cnt, dsp, t, MPI_COMM_WORLD);
  free(cnt), free(dsp);
  *out = buf;
  return 0;
}

/* This rank's records (its owned constrained points) and the bonds of its transition points. */
static int local_parts(const pf_pd_body *b, const pf_points *pts, const double *t, double **rec, int *nrec,
                       int64_t **pairs, int *npairs) {
  const pf_family *fam = &b->fam;
  int64_t nbond = 0;
  *nrec = 0;
  PF_MALLOC(*rec, (size_t)RN * b->n + 1);
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const int zone = pf_pd_consistent_at(b, i) != 0;
    int reached = zone;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
      if (!fam->broken[k]) reached |= pf_pd_consistent_at(b, fam->neighbor[k]) != 0, nbond += zone;
    if (!reached) continue;
    double *r = &(*rec)[RN * (*nrec)++], S[3];
    const int complete = pf_pd_family_complete(b, pts, i, S);
    const double s = complete ? 0.0 : sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
    r[R_GID] = (double)pts->gid[i], r[R_V] = pts->vol[i], r[R_ZONE] = zone;
    r[R_BV] = pf_pd_energy_weight(b, i) * pts->vol[i];
    for (int a = 0; a < 3; a++) {
      r[R_X + a] = pts->X[3 * i + a];
      r[R_T + a] = t[3 * (i - b->first) + a];
      r[R_S + a] = s > 0 ? S[a] / s : 0.0;
    }
  }
  PF_MALLOC(*pairs, 2 * (size_t)nbond + 1);
  *npairs = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    if (!pf_pd_consistent_at(b, i)) continue;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
      if (fam->broken[k]) continue;
      (*pairs)[2 * *npairs] = pts->gid[i], (*pairs)[2 * *npairs + 1] = pts->gid[fam->neighbor[k]];
      (*npairs)++;
    }
  }
  return 0;
}

/* The bond from transition point p to q: xi, and its weight w V_q. */
static double bond(const problem *q, pf_int p, pf_int n, double xi[3]) {
  double r2 = 0;
  for (int a = 0; a < 3; a++) {
    xi[a] = q->rec[RN * n + R_X + a] - q->rec[RN * p + R_X + a];
    r2 += xi[a] * xi[a];
  }
  return pf_pd_omega(q->infl, sqrt(r2)) * q->rec[RN * n + R_V];
}

/* The bonds' xi and w V_q, once: the solve applies the operator hundreds of times. */
static void bond_weights(problem *q) {
  for (pf_int p = 0; p < q->np; p++)
    for (int64_t k = q->off[p]; k < q->off[p + 1]; k++) q->bw[4 * k + 3] = bond(q, p, q->nb[k], &q->bw[4 * k]);
}

/* out = (A W A^T + T) lambda: lambda = (Lambda [9 np], mu [3 np]), out the (B) and (C) residuals
 * alike; T the soft surface rows' diagonal (diagonal_blocks). */
static void apply(const problem *q, const double *lam, double *out) {
  const pf_int np = q->np;
  const double *L = lam, *mu = lam + 9 * (size_t)np;
  double *oB = out, *oC = out + 9 * (size_t)np, *mt = oC + 3 * (size_t)np; /* (scratch past out) */
  memset(out, 0, sizeof(double) * 12 * (size_t)np);
  for (pf_int p = 0; p < np; p++) /* projected mu */
    for (int a = 0; a < 3; a++) {
      const double *P = &q->P[9 * p + 3 * a];
      mt[3 * p + a] = P[0] * mu[3 * p] + P[1] * mu[3 * p + 1] + P[2] * mu[3 * p + 2];
    }
  for (pf_int p = 0; p < np; p++) {
    const double Vp = q->rec[RN * p + R_BV];
    for (int64_t k = q->off[p]; k < q->off[p + 1]; k++) {
      const pf_int n = q->nb[k];
      const double *xi = &q->bw[4 * k], c = xi[3];
      double h[3];
      for (int a = 0; a < 3; a++) {
        h[a] = c * (L[9 * p + 3 * a] * xi[0] + L[9 * p + 3 * a + 1] * xi[1] + L[9 * p + 3 * a + 2] * xi[2] +
                    Vp * (mt[3 * n + a] - mt[3 * p + a]));
        for (int e = 0; e < 3; e++) oB[9 * p + 3 * a + e] += h[a] * xi[e];
        oC[3 * n + a] += Vp * h[a], oC[3 * p + a] -= Vp * h[a];
      }
    }
  }
  for (pf_int p = 0; p < np; p++) {
    double t[3];
    for (int a = 0; a < 3; a++) t[a] = oC[3 * p + a] + q->tau[p] * mt[3 * p + a];
    for (int a = 0; a < 3; a++) oC[3 * p + a] = q->P[9 * p + 3 * a] * t[0] + q->P[9 * p + 3 * a + 1] * t[1] + q->P[9 * p + 3 * a + 2] * t[2];
  }
}

/* Block-Jacobi preconditioner z = M^-1 r. */
static void precondition(const problem *q, const double *r, double *z) {
  const pf_int np = q->np;
  for (pf_int p = 0; p < np; p++) {
    const double *M = &q->Minv[9 * p];
    for (int a = 0; a < 3; a++)
      for (int e = 0; e < 3; e++) {
        const double *ra = &r[9 * p + 3 * a];
        z[9 * p + 3 * a + e] = ra[0] * M[e] + ra[1] * M[3 + e] + ra[2] * M[6 + e];
      }
    for (int a = 0; a < 3; a++) {
      const double *P = &q->P[9 * p + 3 * a], *rc = &r[9 * (size_t)np + 3 * p];
      z[9 * (size_t)np + 3 * p + a] = q->sinv[p] * (P[0] * rc[0] + P[1] * rc[1] + P[2] * rc[2]);
    }
  }
}

/* The surface rows are soft: tau s_n mu_n is added to them (s_n their diagonal), so that the
 * normal equations stay regular where the kept components of (C) at free surfaces and the
 * balance of all of them cannot all hold (a steep taper close to an end face); the solution
 * then misses those rows by about tau times their multiplier, and the interior rows not at all. */
static const double PF_CONSISTENT_SOFT = 1e-6;

static void diagonal_blocks(problem *q) {
  const pf_int np = q->np;
  double *s = calloc((size_t)np + 1, sizeof(double));
  for (pf_int p = 0; p < np; p++) {
    const double Vp = q->rec[RN * p + R_BV];
    double M[3][3] = {{0}}, Mi[3][3];
    for (int64_t k = q->off[p]; k < q->off[p + 1]; k++) {
      const double *xi = &q->bw[4 * k], c = xi[3];
      for (int a = 0; a < 3; a++)
        for (int e = 0; e < 3; e++) M[a][e] += c * xi[a] * xi[e];
      s[q->nb[k]] += c * Vp * Vp, s[p] += c * Vp * Vp;
    }
    if (q->off[p + 1] > q->off[p] && pf_mat3_inverse(M, Mi) > 0) memcpy(&q->Minv[9 * p], Mi, sizeof Mi);
    else memset(&q->Minv[9 * p], 0, 9 * sizeof(double));
  }
  for (pf_int p = 0; p < np; p++) {
    const int surface = q->rec[RN * p + R_S] != 0 || q->rec[RN * p + R_S + 1] != 0 || q->rec[RN * p + R_S + 2] != 0;
    q->tau[p] = surface ? PF_CONSISTENT_SOFT * s[p] : 0.0;
    q->sinv[p] = s[p] > 0 ? 1.0 / (s[p] + q->tau[p]) : 0.0;
  }
  free(s);
}

static double dot(const double *x, const double *y, size_t n) {
  double s = 0;
  for (size_t k = 0; k < n; k++) s += x[k] * y[k];
  return s;
}

/* Preconditioned conjugate gradients from lambda = 0, to a relative preconditioned residual of
 * 1e-13 or PF_CONSISTENT_MAXIT iterations; the iterations into *its, the final relative
 * residual into *rel. */
enum { PF_CONSISTENT_MAXIT = 20000 };
static int solve(const problem *q, const double *rhs, double *lam, int *its, double *rel) {
  const size_t n = 12 * (size_t)q->np;
  double *r, *z, *p, *Ap;
  PF_MALLOC(r, n + 1);
  PF_MALLOC(z, n + 1);
  PF_MALLOC(p, n + 1);
  PF_MALLOC(Ap, n + 3 * (size_t)q->np + 1);
  memset(lam, 0, n * sizeof(double));
  memcpy(r, rhs, n * sizeof(double));
  precondition(q, r, z);
  memcpy(p, z, n * sizeof(double));
  double rz = dot(r, z, n);
  const double rz0 = rz;
  int it = 0;
  while (it < PF_CONSISTENT_MAXIT && rz > 1e-26 * rz0) {
    apply(q, p, Ap);
    const double pAp = dot(p, Ap, n);
    if (!(pAp > 0)) break;
    const double alpha = rz / pAp;
    for (size_t k = 0; k < n; k++) lam[k] += alpha * p[k], r[k] -= alpha * Ap[k];
    precondition(q, r, z);
    const double rz1 = dot(r, z, n);
    for (size_t k = 0; k < n; k++) p[k] = z[k] + rz1 / rz * p[k];
    rz = rz1;
    it++;
  }
  *rel = rz0 > 0 ? sqrt(rz / rz0) : 0.0, *its = it;
  free(r), free(z), free(p), free(Ap);
  return 0;
}

/* Sort the gathered records and bonds into the problem's arrays. */
static int assemble(problem *q, double *rec, int nrec, int64_t *pairs, int npairs) {
  qsort(rec, (size_t)nrec, RN * sizeof(double), cmp_rec);
  qsort(pairs, (size_t)npairs, 2 * sizeof(int64_t), cmp_pair);
  q->np = nrec, q->rec = rec;
  PF_MALLOC(q->off, (size_t)nrec + 1);
  PF_MALLOC(q->nb, (size_t)npairs + 1);
  PF_MALLOC(q->P, 9 * (size_t)nrec + 1);
  PF_MALLOC(q->Minv, 9 * (size_t)nrec + 1);
  PF_MALLOC(q->sinv, (size_t)nrec + 1);
  PF_MALLOC(q->tau, (size_t)nrec + 1);
  PF_MALLOC(q->bw, 4 * (size_t)npairs + 1);
  int64_t k = 0;
  for (pf_int p = 0; p < nrec; p++) {
    const int64_t g = (int64_t)rec[RN * p + R_GID];
    q->off[p] = k;
    while (k < npairs && pairs[2 * k] == g) {
      q->nb[k] = find(q, pairs[2 * k + 1]);
      PF_CHECK(q->nb[k] >= 0, PF_ERR_RUN, "consistent form: neighbour %lld of point %lld was not gathered",
               (long long)pairs[2 * k + 1], (long long)g);
      k++;
    }
    const double *s = &rec[RN * p + R_S];
    for (int a = 0; a < 3; a++)
      for (int e = 0; e < 3; e++) q->P[9 * p + 3 * a + e] = (a == e) - s[a] * s[e];
  }
  q->off[nrec] = k;
  PF_CHECK(k == npairs, PF_ERR_RUN, "consistent form: %lld bonds of points outside the transition",
           (long long)(npairs - k));
  bond_weights(q);
  diagonal_blocks(q);
  return 0;
}

int pf_pd_consistent_solve(const pf_pd_body *b, const pf_points *pts, const double *t, double *lm) {
  double *mine, *rec;
  int64_t *mypairs, *pairs;
  int nmine = 0, nmypairs = 0, nrec = 0, npairs = 0, it = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) memset(&lm[PF_CONSISTENT_NLM * i], 0, sizeof(double) * PF_CONSISTENT_NLM);
  PF_CALL(local_parts(b, pts, t, &mine, &nmine, &mypairs, &nmypairs));
  PF_CALL(allgather(mine, nmine, RN, MPI_DOUBLE, sizeof(double), (void **)&rec, &nrec));
  PF_CALL(allgather(mypairs, nmypairs, 2, MPI_INT64_T, sizeof(int64_t), (void **)&pairs, &npairs));
  free(mine), free(mypairs);
  problem q = {.infl = &b->influence};
  PF_CALL(assemble(&q, rec, nrec, pairs, npairs));
  const size_t n = 12 * (size_t)q.np;
  double *rhs, *lam, rel = 0;
  PF_MALLOC(rhs, n + 1);
  PF_MALLOC(lam, n + 1);
  memset(rhs, 0, 9 * (size_t)q.np * sizeof(double));
  for (pf_int p = 0; p < q.np; p++)
    for (int a = 0; a < 3; a++) {
      const double *P = &q.P[9 * p + 3 * a], *tp = &rec[RN * p + R_T];
      rhs[9 * (size_t)q.np + 3 * p + a] = P[0] * tp[0] + P[1] * tp[1] + P[2] * tp[2];
    }
  PF_CALL(solve(&q, rhs, lam, &it, &rel));
  pf_log("body '%s': consistent form, %lld transition bonds of %lld points solved in %d iterations "
         "(residual %.1e)%s\n", b->name, (long long)npairs, (long long)q.np, it, rel,
         rel > 1e-8 ? "; NOT converged: the transition keeps ghost forces of about that relative size" : "");
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const pf_int p = find(&q, pts->gid[i]);
    if (p < 0) continue;
    double *o = &lm[PF_CONSISTENT_NLM * i];
    memcpy(o, &lam[9 * p], 9 * sizeof(double));
    const double *mu = &lam[9 * (size_t)q.np + 3 * p];
    for (int a = 0; a < 3; a++) /* mu as h uses it: projected */
      o[9 + a] = q.P[9 * p + 3 * a] * mu[0] + q.P[9 * p + 3 * a + 1] * mu[1] + q.P[9 * p + 3 * a + 2] * mu[2];
  }
  free(rhs), free(lam), free(rec), free(pairs);
  free(q.off), free(q.nb), free(q.P), free(q.Minv), free(q.sinv), free(q.tau), free(q.bw);
  return 0;
}
