/* Internal forces of 8-node hexahedra, updated Lagrangian, explicit (docs/architecture.md §3).
 *
 * Kinematics at mid-step (Belytschko, Liu & Moran 2000, Box 6.1): the velocity gradient
 * L = sum_I v_I (x) dN_I/dx on the mid-step configuration x_{n+1/2} = x_{n+1} - dt/2 v_{n+1/2},
 * D = sym L, W = skew L. On that configuration a rigid rotation gives an exactly skew L (a Cayley
 * transform of the rotation), so D = 0 to round-off.
 * Objective rate: the previous stress is rotated by the Hughes & Winget (1980) increment
 * R = (I - dt W/2)^-1 (I + dt W/2), sigma* = R sigma R^T (the Jaumann rate, integrated so that a
 * rigid rotation leaves the stress invariants exact). The material then adds the constitutive
 * increment (hypoelastic models) or evaluates sigma(F) (hyperelastic models), batched over a
 * chunk of elements.
 * Integration: one point with the Flanagan & Belytschko (1981) mean gradient B and hourglass
 * control, f_iI = -V (sigma_ij - q delta_ij) B_jI - hourglass; or the selective-reduced B-bar
 * option (Hughes 1980): 2x2x2 Gauss with the dilatational part of each point's gradient
 * replaced by the element mean,
 *   f_iI = -sum_g V_g [sigma_ij dN_I/dx_j + tr(sigma)/3 (B_iI - dN_I/dx_i)].
 * Bulk viscosity (von Neumann & Richtmyer 1950; Wilkins 1980; LS-DYNA Theory Manual eq. 18.4):
 * q = rho l (C_q l tr D^2 - C_l c tr D) when tr D < 0, else 0.
 * Stable step (LS-DYNA Theory Manual eq. 20.2): dt_e = l / (Q + sqrt(Q^2 + c^2)),
 * Q = C_l c + C_q l |tr D| in compression, l = V / A_max. */
#include "fem/fem_impl.h"

#include <math.h>
#include <string.h>
#if defined(_OPENMP)
#include <omp.h>
#endif

enum { W = PF_HEX8_LANES }; /* (= PF_TENSOR_LANES) */
_Static_assert(PF_HEX8_LANES == PF_TENSOR_LANES, "the element lanes are the tensor helpers' lanes");

/* Per-element scratch of one chunk. */
typedef struct {
  double X[8][3], x[8][3], v[8][3]; /* the nodes: reference, current positions, velocities */
  double xm[8][3], Bm[8][3], Vm;    /* mid-step positions, their mean gradient and volume */
  double s_old[8][6]; /* rotated previous stress per quadrature point */
  double vmid[8];     /* quadrature-point volumes at mid-step */
  double trD;         /* tr D of the element mean velocity gradient */
  double V0;          /* reference volume */
  double Q_old[12];   /* rotated hourglass generalized forces */
  double B[8][3], V;  /* mean gradient and volume at the end of the step */
  double len;         /* characteristic length there (the stable step) */
  double gam[4][8];   /* hourglass vectors there (one-point elements with hourglass control) */
} scratch;

/* F, D, c, the scratch, and the states of a material with fewer than the body's (fem/materials.c). */
size_t pf_fem_chunk_doubles(int nqp, int nstate) {
  return (size_t)PF_FEM_CHUNK * ((16 + (size_t)nstate) * nqp + sizeof(scratch) / sizeof(double) + 1);
}

static void gather_nodes(const pf_fem_body *b, const pf_points *p, pf_int e, double dt, double X[8][3],
                         double x[8][3], double xm[8][3], double v[8][3]) {
  const pf_int *c = &b->conn[8 * (size_t)e];
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) {
      X[I][i] = p->X[3 * c[I] + i];
      x[I][i] = p->y[3 * c[I] + i];
      v[I][i] = p->v[3 * c[I] + i];
      xm[I][i] = x[I][i] - 0.5 * dt * v[I][i];
    }
}

static void grad_product(double a[8][3], double g[8][3], double M[3][3]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int I = 0; I < 8; I++) s += a[I][i] * g[I][j];
      M[i][j] = s;
    }
}

/* grad_product lane by lane (the same bits). */
static void grad_product_lanes(double a[8][3][W], double g[8][3][W], double M[3][3][W]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
#pragma omp simd
      for (int l = 0; l < W; l++) M[i][j][l] = 0;
      for (int I = 0; I < 8; I++)
#pragma omp simd
        for (int l = 0; l < W; l++) M[i][j][l] += a[I][i][l] * g[I][j][l];
    }
}

static double sym_dot(const double a[6], const double d[6]) {
  return a[0] * d[0] + a[1] * d[1] + a[2] * d[2] + 2 * (a[3] * d[3] + a[4] * d[4] + a[5] * d[5]);
}

static int bad_element(const pf_fem_body *b, pf_int e, double x[8][3], const char *what, double value) {
  double c[3] = {0, 0, 0};
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++) c[i] += 0.125 * x[I][i];
  int code;
#if defined(_OPENMP)
#pragma omp critical(pf_error)
#endif
  code = pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
           "element %" PF_INT_FMT " of body '%s' (centroid (%g, %g, %g) m) at time %g s, step %ld: "
           "%s %g: the element is inverted or the run is unstable (reduce time.safety_factor, "
           "raise the hourglass or bulk viscosity coefficients, or refine the mesh)",
           b->eid[e] + 1, b->name, c[0], c[1], c[2], b->t, b->step, what, value);
  return code;
}

/* A deleted element (fem/erosion.c) gives the material F = I and D = 0 at each point. */
static void at_rest(int nq, double *F, double *D) {
  for (int g = 0; g < nq; g++) {
    for (int k = 0; k < 9; k++) F[9 * g + k] = k % 4 == 0;
    memset(&D[6 * g], 0, sizeof(double) * 6);
  }
}

/* PF_HEX8_LANES elements across the vector lanes, lane l of each array one element's. */
typedef struct {
  _Alignas(64) double x[8][3][W], xm[8][3][W], v[8][3][W], B[8][3][W], Bm[8][3][W], V[W], Vm[W], len[W], gam[4][8][W];
} lanes;

/* The nodes of elements [e, e + n), n <= PF_HEX8_LANES, into their scratch and into q, with what
 * depends on their positions alone: the mean gradients at mid-step and at the end of the step,
 * the characteristic length and the hourglass vectors there, the elements across the vector
 * lanes (each lane's bits those of one element at a time). Lanes past n repeat the first
 * element. */
static void gather_lanes(const pf_fem_body *b, const pf_points *p, pf_int e, int n, double dt, scratch *s, lanes *q) {
  const int hourglass = !b->bbar && b->hg != PF_HG_NONE;
  for (int l = 0; l < W; l++) {
    if (l < n) gather_nodes(b, p, e + l, dt, s[l].X, s[l].x, s[l].xm, s[l].v);
    const scratch *sl = &s[l < n ? l : 0];
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) q->x[I][i][l] = sl->x[I][i], q->xm[I][i][l] = sl->xm[I][i], q->v[I][i][l] = sl->v[I][i];
  }
  pf_hex8_mean_gradient_lanes(q->x, q->B, q->V);
  pf_hex8_mean_gradient_lanes(q->xm, q->Bm, q->Vm);
  pf_hex8_char_length_lanes(q->x, q->V, q->len);
  if (hourglass) pf_hex8_hourglass_vectors_lanes(q->x, q->B, q->gam);
  for (int l = 0; l < n; l++) {
    s[l].V = q->V[l], s[l].Vm = q->Vm[l], s[l].len = q->len[l];
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) s[l].B[I][i] = q->B[I][i][l], s[l].Bm[I][i] = q->Bm[I][i][l];
    for (int a = 0; a < 4 && hourglass; a++)
      for (int I = 0; I < 8; I++) s[l].gam[a][I] = q->gam[a][I][l];
  }
}

/* Pass 1 of one-point elements [e, e + n) across the lanes of q (gather_lanes), each lane with the
 * operations of its element alone (the same bits): the velocity gradient L = sum_I v_I (x) Bm_I at
 * mid-step, the Hughes-Winget rotation of the stress and of the hourglass forces, D = sym L, and
 * F = (J / det F0)^(1/3) F0 with F0 = sum_I x_I (x) B0_I (det F = the element's volume ratio J;
 * the cube root lane by lane). Eroded elements get F = I, D = 0 (at_rest) and keep their stress. */
static int kinematics_lanes(pf_fem_body *b, pf_int e, int n, double dt, lanes *q, double *F, double *D,
                            scratch *s) {
  _Alignas(64) double B0[8][3][W], ratio[W], det[W], cb[W], sig[6][W], hq[12][W], Lm[3][3][W], Fm[3][3][W], R[3][3][W];
  _Alignas(64) double Dl[6][W], trD[W];
  const int hg = b->hg != PF_HG_NONE;
  for (int l = 0; l < W; l++) {
    const pf_int el = e + (l < n ? l : 0);
    const double *ref = &b->ref[25 * (size_t)el], *sg = &b->sigma[6 * (size_t)el];
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) B0[I][i][l] = ref[3 * I + i];
    ratio[l] = q->V[l] / ref[24];
    for (int k = 0; k < 6; k++) sig[k][l] = sg[k];
    for (int k = 0; k < 12; k++) hq[k][l] = hg ? b->hgq[12 * (size_t)el + k] : 0.0;
  }
  for (int l = 0; l < n; l++) {
    if (pf_fem_element_eroded(b, e + l)) continue;
    if (!(q->V[l] > 0)) return bad_element(b, e + l, s[l].x, "volume", q->V[l]);
    if (!(q->Vm[l] > 0)) return bad_element(b, e + l, s[l].xm, "mid-step volume", q->Vm[l]);
  }
  grad_product_lanes(q->v, q->Bm, Lm);
  pf_mat3_hughes_winget_lanes(Lm, dt, R);
  grad_product_lanes(q->x, B0, Fm);
  pf_sym6_rotate_lanes(R, sig);
  pf_mat3_det_lanes(Fm, det);
#pragma omp simd
  for (int l = 0; l < W; l++) {
    trD[l] = Lm[0][0][l] + Lm[1][1][l] + Lm[2][2][l];
    ratio[l] = ratio[l] / det[l];
  }
  for (int k = 0; k < 6; k++)
#pragma omp simd
    for (int l = 0; l < W; l++)
      Dl[k][l] = 0.5 * (Lm[pf_voigt_i[k]][pf_voigt_j[k]][l] + Lm[pf_voigt_j[k]][pf_voigt_i[k]][l]);
  for (int l = 0; l < n; l++) cb[l] = cbrt(ratio[l]);
  for (int l = 0; l < n; l++) {
    const pf_int el = e + l;
    if (pf_fem_element_eroded(b, el)) {
      at_rest(1, &F[9 * l], &D[6 * l]);
      continue;
    }
    s[l].V0 = b->ref[25 * (size_t)el + 24], s[l].trD = trD[l], s[l].vmid[0] = q->Vm[l];
    for (int k = 0; k < 9; k++) F[9 * l + k] = cb[l] * Fm[k / 3][k % 3][l];
    for (int k = 0; k < 6; k++) D[6 * l + k] = Dl[k][l], s[l].s_old[0][k] = b->sigma[6 * (size_t)el + k] = sig[k][l];
    for (int c = 0; c < 4 && hg; c++) /* (the viscous form's: for its work) */
      for (int i = 0; i < 3; i++)
        s[l].Q_old[3 * c + i] = R[i][0][l] * hq[3 * c][l] + R[i][1][l] * hq[3 * c + 1][l] + R[i][2][l] * hq[3 * c + 2][l];
  }
  return 0;
}

/* Pass 1 of a B-bar element (the nodes and mean gradients in s from gather_lanes; one-point
 * elements take kinematics_lanes): its eight Gauss points at once, lane g point g (the same bits
 * as one point at a time): the velocity gradient with the element's mean dilatation, F-bar
 * (det F = the element's volume ratio), D, the rotated stress. */
static int kinematics_bbar(pf_fem_body *b, pf_int e, double dt, double *F, double *D, scratch *s) {
  _Alignas(64) double g0[8][3][W], gm[8][3][W], vm[W], det0[W], vb[8][3][W], xb[8][3][W], L[3][3][W], Fm[3][3][W];
  _Alignas(64) double R[3][3][W], sig[6][W], det[W], ratio[W], Lm[3][3];
  double *sg = &b->sigma[6 * (size_t)b->nqp * e];
  s->V0 = b->ref[25 * (size_t)e + 24];
  if (!(s->V > 0)) return bad_element(b, e, s->x, "volume", s->V);
  if (!(s->Vm > 0)) return bad_element(b, e, s->xm, "mid-step volume", s->Vm);
  grad_product(s->v, s->Bm, Lm);
  s->trD = Lm[0][0] + Lm[1][1] + Lm[2][2];
  pf_hex8_gauss_gradients_lanes(s->X, g0, det0);
  pf_hex8_gauss_gradients_lanes(s->xm, gm, vm);
  for (int g = 0; g < 8; g++) {
    s->vmid[g] = vm[g];
    if (!(vm[g] > 0)) return bad_element(b, e, s->xm, "mid-step Jacobian", vm[g]);
  }
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
      for (int l = 0; l < W; l++) vb[I][i][l] = s->v[I][i], xb[I][i][l] = s->x[I][i];
  grad_product_lanes(vb, gm, L);
#pragma omp simd
  for (int l = 0; l < W; l++) {
    double corr = (s->trD - (L[0][0][l] + L[1][1][l] + L[2][2][l])) / 3.0; /* B-bar: mean dilatation */
    for (int i = 0; i < 3; i++) L[i][i][l] += corr;
  }
  grad_product_lanes(xb, g0, Fm);
  const double J = s->V / s->V0;
  pf_mat3_det_lanes(Fm, det);
#pragma omp simd
  for (int l = 0; l < W; l++) ratio[l] = J / det[l];
  pf_mat3_hughes_winget_lanes(L, dt, R);
  for (int g = 0; g < 8; g++)
    for (int k = 0; k < 6; k++) sig[k][g] = sg[6 * g + k];
  pf_sym6_rotate_lanes(R, sig);
  for (int g = 0; g < 8; g++) {
    const double cb = cbrt(ratio[g]); /* F-bar: det F = the element's volume ratio */
    for (int k = 0; k < 9; k++) F[9 * g + k] = cb * Fm[k / 3][k % 3][g];
    for (int k = 0; k < 6; k++) {
      D[6 * g + k] = 0.5 * (L[pf_voigt_i[k]][pf_voigt_j[k]][g] + L[pf_voigt_j[k]][pf_voigt_i[k]][g]);
      s->s_old[g][k] = sg[6 * g + k] = sig[k][g];
    }
  }
  return 0;
}

/* The B-bar stress divergence, f_iI -= sum_g V_g [sigma_ij dN_I/dx_j + tr(sigma)/3 (B_iI -
 * dN_I/dx_i)] with sigma - q I, the eight Gauss points' gradients and terms in the lanes, summed
 * into f in point order (the same bits as one point at a time). */
static int bbar_forces(pf_fem_body *b, pf_int e, const scratch *s, double q, double f[8][3]) {
  _Alignas(64) double gr[8][3][W], Vg[W], S[3][3][W], mean[W], t[8][3][W];
  const double *sig = &b->sigma[6 * (size_t)b->nqp * e];
  pf_hex8_gauss_gradients_lanes((double(*)[3])s->x, gr, Vg);
  for (int g = 0; g < 8; g++)
    if (!(Vg[g] > 0)) return bad_element(b, e, (double(*)[3])s->x, "Jacobian", Vg[g]);
  for (int k = 0; k < 6; k++)
    for (int g = 0; g < W; g++) S[pf_voigt_i[k]][pf_voigt_j[k]][g] = S[pf_voigt_j[k]][pf_voigt_i[k]][g] = sig[6 * g + k];
#pragma omp simd
  for (int l = 0; l < W; l++) {
    mean[l] = (S[0][0][l] + S[1][1][l] + S[2][2][l]) / 3.0;
    for (int i = 0; i < 3; i++) S[i][i][l] -= q;
  }
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
#pragma omp simd
      for (int l = 0; l < W; l++) {
        double ti = S[i][0][l] * gr[I][0][l] + S[i][1][l] * gr[I][1][l] + S[i][2][l] * gr[I][2][l];
        ti += mean[l] * (s->B[I][i] - gr[I][i][l]);
        t[I][i][l] = ti;
      }
  for (int g = 0; g < 8; g++)
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) f[I][i] -= Vg[g] * t[I][i][g];
  return 0;
}

/* Pass 2 of a B-bar element: forces from the new stress and bulk viscosity; energies; stable
 * step; *tangled when the body converts elements and a corner's Jacobian is negative
 * (docs/theory/fem.md sec. 9b). One-point elements take forces_lanes. */
static int element_forces(pf_fem_body *b, pf_int e, double dt, const double *c, const double *D,
                          const scratch *s, double *stable_dt, int *tangled) {
  double f[8][3] = {{0}};
  double(*x)[3] = (double(*)[3])s->x;
  double V = s->V, l = s->len, cmax = 0;
  double rho = pf_fem_element_material(b, e)->rho * s->V0 / V, Vmid = 0;
  for (int g = 0; g < b->nqp; g++) cmax = fmax(cmax, c[g]);
  double q = 0;
  if (s->trD < 0) q = rho * l * (b->bv_quadratic * l * s->trD * s->trD - b->bv_linear * cmax * s->trD);
  const double *sig = &b->sigma[6 * (size_t)b->nqp * e];
  double *en = &b->energy[3 * (size_t)e];
  PF_CALL(bbar_forces(b, e, s, q, f));
  /* stress work: trapezoid in time on the mid-step volumes, sum_g V_g (s_old + s_new)/2 : D */
  for (int g = 0; g < b->nqp; g++) {
    double avg[6];
    for (int k = 0; k < 6; k++) avg[k] = 0.5 * (s->s_old[g][k] + sig[6 * g + k]);
    en[0] += dt * s->vmid[g] * sym_dot(avg, &D[6 * g]);
    Vmid += s->vmid[g];
  }
  /* bulk-viscosity work: the mean of the last and this evaluation's q, as velocity Verlet
   * applies the forces (docs/theory/fem.md §6) */
  en[2] += dt * 0.5 * (b->bvq[e] + q) * (-s->trD) * Vmid;
  b->bvq[e] = q;
  memcpy(&b->fe[24 * (size_t)e], f, sizeof f);
  double Qb = s->trD < 0 ? b->bv_linear * cmax + b->bv_quadratic * l * fabs(s->trD) : 0;
  *stable_dt = fmin(*stable_dt, l / (Qb + sqrt(Qb * Qb + cmax * cmax)));
  *tangled = b->convert && pf_hex8_min_corner_jacobian(x) < 0;
  return 0;
}

/* Pass 2 of one-point elements across the lanes (forces_lanes): their data, lane l element l. */
typedef struct {
  _Alignas(64) double B[8][3][W], v[8][3][W], gam[4][8][W], f[8][3][W], sg[6][W], so[6][W], Dl[6][W], Qo[12][W], Q[12][W];
  _Alignas(64) double V[W], len[W], cmax[W], rho[W], q[W], trD[W], vm[W], bvq[W], en[3][W], k4[W];
} pass2;

/* Elements [e, e + n) into the lanes (lanes past n repeat the first). */
static void pass2_load(const pf_fem_body *b, pf_int e, int n, const double *c, const double *Dv, const scratch *s,
                       pass2 *r) {
  const int hg = b->hg != PF_HG_NONE;
  for (int l = 0; l < W; l++) {
    const int k = l < n ? l : 0;
    const pf_int el = e + k;
    const scratch *sl = &s[k];
    const pf_fem_material *fm = pf_fem_element_material(b, el);
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) r->B[I][i][l] = sl->B[I][i], r->v[I][i][l] = sl->v[I][i];
    for (int a = 0; a < 4 && hg; a++)
      for (int I = 0; I < 8; I++) r->gam[a][I][l] = sl->gam[a][I];
    for (int m = 0; m < 12; m++) r->Qo[m][l] = hg ? sl->Q_old[m] : 0.0;
    for (int m = 0; m < 6; m++)
      r->sg[m][l] = b->sigma[6 * (size_t)el + m], r->so[m][l] = sl->s_old[0][m], r->Dl[m][l] = Dv[6 * k + m];
    for (int m = 0; m < 3; m++) r->en[m][l] = b->energy[3 * (size_t)el + m];
    r->V[l] = sl->V, r->len[l] = sl->len, r->trD[l] = sl->trD, r->vm[l] = sl->vmid[0], r->bvq[l] = b->bvq[el];
    r->cmax[l] = fmax(0, c[k]), r->rho[l] = fm->rho * sl->V0 / r->V[l], r->k4[l] = fm->K + 4.0 * fm->G / 3.0;
  }
}

/* Bulk viscosity q, the stress divergence f = -V (sigma - q I) B, the stress and bulk-viscosity
 * work (element_forces' formulas). */
static void pass2_divergence(const pf_fem_body *b, double dt, pass2 *r) {
  _Alignas(64) double S[3][3][W];
  const double bq = b->bv_quadratic, bl = b->bv_linear;
#pragma omp simd
  for (int l = 0; l < W; l++) {
    const double qv = r->rho[l] * r->len[l] * (bq * r->len[l] * r->trD[l] * r->trD[l] - bl * r->cmax[l] * r->trD[l]);
    r->q[l] = r->trD[l] < 0 ? qv : 0;
  }
  for (int m = 0; m < 6; m++)
#pragma omp simd
    for (int l = 0; l < W; l++) S[pf_voigt_i[m]][pf_voigt_j[m]][l] = S[pf_voigt_j[m]][pf_voigt_i[m]][l] = r->sg[m][l];
  for (int i = 0; i < 3; i++)
#pragma omp simd
    for (int l = 0; l < W; l++) S[i][i][l] -= r->q[l];
  for (int I = 0; I < 8; I++)
    for (int i = 0; i < 3; i++)
#pragma omp simd
      for (int l = 0; l < W; l++) {
        double t = S[i][0][l] * r->B[I][0][l] + S[i][1][l] * r->B[I][1][l] + S[i][2][l] * r->B[I][2][l];
        r->f[I][i][l] = 0;
        r->f[I][i][l] -= r->V[l] * t;
      }
#pragma omp simd
  for (int l = 0; l < W; l++) {
    double avg[6];
    for (int m = 0; m < 6; m++) avg[m] = 0.5 * (r->so[m][l] + r->sg[m][l]);
    const double d = avg[0] * r->Dl[0][l] + avg[1] * r->Dl[1][l] + avg[2] * r->Dl[2][l] +
                     2 * (avg[3] * r->Dl[3][l] + avg[4] * r->Dl[4][l] + avg[5] * r->Dl[5][l]); /* (sym_dot) */
    double Vmid = 0;
    r->en[0][l] += dt * r->vm[l] * d;
    Vmid += r->vm[l];
    r->en[2][l] += dt * 0.5 * (r->bvq[l] + r->q[l]) * (-r->trD[l]) * Vmid;
  }
}

/* Hourglass forces and their work. Viscous form (FB eq. 88): Q = q_hv rho c V^(2/3) / 4 qdot.
 * Stiffness form (FB eq. 90): Qdot = k qdot, k = q_hs (K + 4G/3) V B_iI B_iI / 48, scaled so that
 * q_hs = 1 gives an hourglass mode of a cube about the stiffness it has in a fully integrated
 * element (docs/theory/fem.md §4). The work over the step as velocity Verlet does it: the mean of
 * the last and this evaluation's forces on the mid-step velocity (docs/theory/fem.md §6). */
static void pass2_hourglass(const pf_fem_body *b, double dt, pass2 *r) {
  _Alignas(64) double qd[4][3][W], cv[W];
  const double hc = b->hg_coef;
  const int viscous = b->hg == PF_HG_VISCOUS;
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 3; i++) {
#pragma omp simd
      for (int l = 0; l < W; l++) qd[a][i][l] = 0;
      for (int I = 0; I < 8; I++)
#pragma omp simd
        for (int l = 0; l < W; l++) qd[a][i][l] += r->v[I][i][l] * r->gam[a][I][l];
    }
  if (viscous)
    for (int l = 0; l < W; l++) cv[l] = hc * r->rho[l] * r->cmax[l] * cbrt(r->V[l] * r->V[l]) / 4.0;
  else
#pragma omp simd
    for (int l = 0; l < W; l++) {
      double bb = 0;
      for (int I = 0; I < 8; I++)
        bb += r->B[I][0][l] * r->B[I][0][l] + r->B[I][1][l] * r->B[I][1][l] + r->B[I][2][l] * r->B[I][2][l];
      cv[l] = hc * r->k4[l] * r->V[l] * bb / 48.0;
    }
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 3; i++) {
      const int m = 3 * a + i;
#pragma omp simd
      for (int l = 0; l < W; l++) {
        r->Q[m][l] = viscous ? cv[l] * qd[a][i][l] : r->Qo[m][l] + dt * cv[l] * qd[a][i][l];
        r->en[1][l] += dt * 0.5 * (r->Qo[m][l] + r->Q[m][l]) * qd[a][i][l];
      }
      for (int I = 0; I < 8; I++)
#pragma omp simd
        for (int l = 0; l < W; l++) r->f[I][i][l] -= r->Q[m][l] * r->gam[a][I][l];
    }
}

/* The stable step, and elements [e, e + n) out of the lanes: forces, energies, q, Q; erosion flags
 * (the corner test of a converting body lane by lane). */
static void pass2_store(pf_fem_body *b, pf_int e, int n, const scratch *s, const pass2 *r, double *stable_dt) {
  _Alignas(64) double dte[W];
  const double bq = b->bv_quadratic, bl = b->bv_linear;
#pragma omp simd
  for (int l = 0; l < W; l++) {
    const double Qb = r->trD[l] < 0 ? bl * r->cmax[l] + bq * r->len[l] * fabs(r->trD[l]) : 0;
    dte[l] = r->len[l] / (Qb + sqrt(Qb * Qb + r->cmax[l] * r->cmax[l]));
  }
  for (int l = 0; l < n; l++) {
    const pf_int el = e + l;
    if (b->erosion) b->due[el] = -1;
    if (pf_fem_element_eroded(b, el)) {
      memset(&b->fe[24 * (size_t)el], 0, sizeof(double) * 24);
      continue;
    }
    for (int m = 0; m < 3; m++) b->energy[3 * (size_t)el + m] = r->en[m][l];
    b->bvq[el] = r->q[l];
    for (int m = 0; m < 12 && b->hg != PF_HG_NONE; m++) b->hgq[12 * (size_t)el + m] = r->Q[m][l];
    for (int I = 0; I < 8; I++)
      for (int i = 0; i < 3; i++) b->fe[24 * (size_t)el + 3 * I + i] = r->f[I][i][l];
    *stable_dt = fmin(*stable_dt, dte[l]);
    const int tangled = b->convert && pf_hex8_min_corner_jacobian((double(*)[3])s[l].x) < 0;
    if (b->erosion && (tangled || pf_fem_erosion_due(b, el, s[l].V / s[l].V0))) b->due[el] = b->eid[el];
  }
}

/* Pass 2 of one-point elements [e, e + n) across the lanes, each lane with the operations of its
 * element alone (the same bits): forces from the new stress, bulk viscosity and hourglass
 * control, their work, the stable step, erosion flags. */
static void forces_lanes(pf_fem_body *b, pf_int e, int n, double dt, const double *c, const double *Dv,
                         const scratch *s, double *stable_dt) {
  pass2 r;
  pass2_load(b, e, n, c, Dv, s, &r);
  pass2_divergence(b, dt, &r);
  if (b->hg != PF_HG_NONE) pass2_hourglass(b, dt, &r);
  pass2_store(b, e, n, s, &r, stable_dt);
}

/* One chunk of elements [e0, e0 + ne) with its own scratch buf: kinematics, the batched material
 * call, forces into the element's own slots of fe (the nodes gather them in a fixed order,
 * pf_fem_body_node_force), erosion flags into due[e] (compacted in element order after). */
static int evaluate_chunk(pf_fem_body *b, const pf_points *pts, double dt, pf_int e0, pf_int ne, double *buf,
                          double *stable_dt) {
  const int nq = b->nqp;
  double *F = buf, *D = F + 9 * (size_t)nq * PF_FEM_CHUNK, *c = D + 6 * (size_t)nq * PF_FEM_CHUNK;
  scratch *s = (scratch *)(c + (size_t)nq * PF_FEM_CHUNK);
  for (pf_int k0 = 0; k0 < ne; k0 += PF_HEX8_LANES) {
    const int nl = ne - k0 < PF_HEX8_LANES ? (int)(ne - k0) : PF_HEX8_LANES;
    lanes q;
    gather_lanes(b, pts, e0 + k0, nl, dt, &s[k0], &q);
    if (!b->bbar) {
      PF_CALL(kinematics_lanes(b, e0 + k0, nl, dt, &q, &F[9 * (size_t)k0], &D[6 * (size_t)k0], &s[k0]));
      continue;
    }
    for (pf_int k = k0; k < k0 + nl; k++)
      if (pf_fem_element_eroded(b, e0 + k)) at_rest(nq, &F[9 * (size_t)nq * k], &D[6 * (size_t)nq * k]);
      else PF_CALL(kinematics_bbar(b, e0 + k, dt, &F[9 * (size_t)nq * k], &D[6 * (size_t)nq * k], &s[k]));
  }
  pf_fem_materials_update(b, e0, ne, dt, F, D, c, (double *)(s + PF_FEM_CHUNK));
  for (pf_int k0 = 0; k0 < ne && !b->bbar; k0 += PF_HEX8_LANES)
    forces_lanes(b, e0 + k0, ne - k0 < PF_HEX8_LANES ? (int)(ne - k0) : PF_HEX8_LANES, dt, &c[k0], &D[6 * (size_t)k0], &s[k0],
                 stable_dt);
  for (pf_int k = 0; k < ne && b->bbar; k++) {
    const pf_int e = e0 + k;
    if (b->erosion) b->due[e] = -1;
    if (pf_fem_element_eroded(b, e)) {
      memset(&b->fe[24 * (size_t)e], 0, sizeof(double) * 24);
      continue;
    }
    int tangled = 0;
    PF_CALL(element_forces(b, e, dt, &c[(size_t)nq * k], &D[6 * (size_t)nq * k], &s[k], stable_dt, &tangled));
    if (b->erosion && (tangled || pf_fem_erosion_due(b, e, s[k].V / s[k].V0))) b->due[e] = b->eid[e];
  }
  return 0;
}

/* The chunk scratch of every thread (pf_fem_chunk_doubles each), grown when more threads run. */
static int thread_buffers(pf_fem_body *b, int nthreads) {
  if (nthreads <= b->nbuf) return 0;
  free(b->buf);
  b->buf = NULL, b->nbuf = 0;
  PF_MALLOC(b->buf, (size_t)nthreads * pf_fem_chunk_doubles(b->nqp, b->nstate));
  b->nbuf = nthreads;
  return 0;
}

/* The chunks are independent (each element writes only its own stress, state, forces and
 * energies), so threads share them out; the stable step is their minimum, exact in any order. */
int pf_fem_elements_evaluate(pf_fem_body *b, const pf_points *pts, double dt) {
  int nthreads = 1;
#if defined(_OPENMP)
  nthreads = omp_get_max_threads();
#endif
  PF_CALL(thread_buffers(b, nthreads));
  const size_t per_thread = pf_fem_chunk_doubles(b->nqp, b->nstate);
  const pf_int nchunks = (b->nel + PF_FEM_CHUNK - 1) / PF_FEM_CHUNK;
  double stable_dt = INFINITY;
  int ierr = 0;
#pragma omp parallel reduction(min : stable_dt) reduction(max : ierr)
  { /* (the reduction copies start at the identities DBL_MAX and INT_MIN: each thread's own) */
    int t = 0, err = 0;
#if defined(_OPENMP)
    t = omp_get_thread_num();
#endif
    double *buf = b->buf + (size_t)t * per_thread, dtmin = INFINITY;
#pragma omp for schedule(static)
    for (pf_int ch = 0; ch < nchunks; ch++) {
      const pf_int e0 = ch * PF_FEM_CHUNK, ne = b->nel - e0 < PF_FEM_CHUNK ? b->nel - e0 : PF_FEM_CHUNK;
      if (!err) err = evaluate_chunk(b, pts, dt, e0, ne, buf, &dtmin);
    }
    stable_dt = dtmin, ierr = err;
  }
  b->stable_dt = stable_dt;
  if (ierr) return ierr;
  b->n_due = 0;
  for (pf_int e = 0; e < b->nel && b->erosion; e++) /* the due elements in element order */
    if (b->due[e] >= 0) b->due[b->n_due++] = b->due[e];
  return 0;
}
