/* Equilibrium of a load step by an inexact Newton method with a matrix-free Krylov step
 * (solver.method: newton_krylov; docs/theory/quasi_static_methods.md §9). With F(u) the force of the
 * explicit step on the free components (the bodies' history put back as committed at the load
 * step's start before each evaluation, so F is a function of u alone) and K = -dF/du:
 *   solve K du = F(u) by conjugate gradients, preconditioned by the fictitious masses lambda
 *   (the Gershgorin bounds of K's rows), to ||F - K du|| <= eta ||F|| (eta = NK_FORCING;
 *   Eisenstat & Walker 1996 for inexact Newton);
 *   K v is the finite difference -(F(u + e v) - F(u)) / e, e = NK_PERTURBATION L / max|v|, L
 *   the points' extent (Knoll & Keyes 2004 §2.2: the Jacobian-free product);
 *   u += s du, s = 1, 1/2, ... until the residual's 2-norm drops (Dennis & Schnabel 1996 §6.3).
 * Every dot product and norm is a pf_sim_solver_sums sum, so the iterates are the same bits on
 * any number of ranks. It gives up, leaving the relaxation to go on from its best state, when
 * K shows negative curvature (a limit point: necking past the peak, a snap-back), when the line
 * search finds no decrease, or after NK_MAX_NEWTON iterations. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NK_F0, NK_U0, NK_X, NK_R, NK_P, NK_Z, NK_KP, NK_ARRAYS };
enum { NK_MAX_NEWTON = 40, NK_MAX_HALVINGS = 8 };
static const double NK_FORCING = 0.05, NK_PERTURBATION = 1e-9;

typedef struct {
  pf_sim *sim;
  pf_int n3;
  double *a[NK_ARRAYS];
  double extent; /* L: the points' bounding-box diagonal over the ranks, m */
  long evaluations, krylov;
} newton;

static int arrays(newton *nk) {
  pf_sim_solver *s = &nk->sim->solver;
  const pf_int n = nk->sim->pts->n_owned;
  if (!s->nk || s->nk_n != n) {
    free(s->nk);
    s->nk = calloc((size_t)NK_ARRAYS * (3 * (size_t)n + 1), sizeof(double));
    PF_CHECK(s->nk, PF_ERR_MEMORY, "out of memory for the Newton-Krylov arrays (%" PF_INT_FMT " points)", n);
    s->nk_n = n;
  }
  nk->n3 = 3 * n;
  for (int k = 0; k < NK_ARRAYS; k++) nk->a[k] = s->nk + (size_t)k * (3 * (size_t)n + 1);
  return 0;
}

/* The bounding box diagonal of the points over every rank (max and min reduce exactly). */
static int extent(newton *nk) {
  const pf_points *p = nk->sim->pts;
  double b[6] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (pf_int i = 0; i < p->n_owned; i++)
    for (int c = 0; c < 3; c++) b[c] = fmax(b[c], p->X[3 * i + c]), b[3 + c] = fmax(b[3 + c], -p->X[3 * i + c]);
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, b, 6, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed in the Newton-Krylov solver");
  nk->extent = sqrt(pow(b[0] + b[3], 2) + pow(b[1] + b[4], 2) + pow(b[2] + b[5], 2));
  return 0;
}

/* Up to two dot products over the free components at once: out[k] = x_k . y_k. */
static int dots(newton *nk, int m, const double *x0, const double *y0, const double *x1, const double *y1,
                double *out) {
  pf_sim_solver *s = &nk->sim->solver;
  double *t = s->terms;
  const pf_int n3 = nk->n3;
  for (pf_int d = 0; d < n3; d++) {
    const int fr = pf_sim_solver_is_free(s, d);
    t[d] = fr ? x0[d] * y0[d] : 0;
    if (m > 1) t[n3 + d] = fr ? x1[d] * y1[d] : 0;
  }
  return pf_sim_solver_sums(t, n3, m, out);
}

/* The largest |v_d| over the free components and the ranks. */
static int max_abs(newton *nk, const double *v, double *out) {
  *out = 0;
  for (pf_int d = 0; d < nk->n3; d++)
    if (pf_sim_solver_is_free(&nk->sim->solver, d)) *out = fmax(*out, fabs(v[d]));
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed in the Newton-Krylov solver");
  return 0;
}

/* u = u0 + step v on the free components (y follows). */
static void place(newton *nk, const double *v, double step) {
  pf_points *p = nk->sim->pts;
  const double *u0 = nk->a[NK_U0];
  for (pf_int d = 0; d < nk->n3; d++)
    if (pf_sim_solver_is_free(&nk->sim->solver, d)) p->u[d] = u0[d] + step * v[d], p->y[d] = p->X[d] + p->u[d];
}

static int evaluate(newton *nk) {
  nk->evaluations++;
  return pf_sim_solver_evaluate(nk->sim);
}

/* Kv = -(F(u0 + e v) - F(u0)) / e. */
static int product(newton *nk, const double *v, double *kv) {
  double vmax;
  PF_CALL(max_abs(nk, v, &vmax));
  const double e = vmax > 0 ? NK_PERTURBATION * nk->extent / vmax : 0;
  if (e == 0) {
    memset(kv, 0, sizeof(double) * (size_t)nk->n3);
    return 0;
  }
  place(nk, v, e);
  PF_CALL(evaluate(nk));
  const double *f = nk->sim->pts->f, *f0 = nk->a[NK_F0];
  for (pf_int d = 0; d < nk->n3; d++) kv[d] = pf_sim_solver_is_free(&nk->sim->solver, d) ? -(f[d] - f0[d]) / e : 0;
  return 0;
}

/* Preconditioned CG for K x = F0 (x from 0) to ||r|| <= NK_FORCING ||F0||, at most budget products;
 * *ok 0 on negative curvature before any step. */
static int krylov(newton *nk, long budget, int *ok) {
  const pf_sim_solver *s = &nk->sim->solver;
  double *x = nk->a[NK_X], *r = nk->a[NK_R], *pv = nk->a[NK_P], *z = nk->a[NK_Z], *kp = nk->a[NK_KP];
  const pf_int n3 = nk->n3;
  for (pf_int d = 0; d < n3; d++) {
    const int fr = pf_sim_solver_is_free(s, d);
    x[d] = 0, r[d] = fr ? nk->a[NK_F0][d] : 0;
    z[d] = fr ? r[d] / s->lambda[d / 3] : 0, pv[d] = z[d];
  }
  double q[2];
  PF_CALL(dots(nk, 2, r, z, r, r, q));
  double rz = q[0];
  const double goal = NK_FORCING * NK_FORCING * q[1];
  *ok = 1;
  for (long j = 0; j < budget && q[1] > goal; j++) {
    PF_CALL(product(nk, pv, kp));
    nk->krylov++;
    double pkp;
    PF_CALL(dots(nk, 1, pv, kp, NULL, NULL, &pkp));
    if (!(pkp > 0)) {
      *ok = j > 0;
      return 0;
    }
    const double alpha = rz / pkp;
    for (pf_int d = 0; d < n3; d++) x[d] += alpha * pv[d], r[d] -= alpha * kp[d];
    for (pf_int d = 0; d < n3; d++) z[d] = pf_sim_solver_is_free(s, d) ? r[d] / s->lambda[d / 3] : 0;
    PF_CALL(dots(nk, 2, r, z, r, r, q));
    const double beta = q[0] / rz;
    rz = q[0];
    for (pf_int d = 0; d < n3; d++) pv[d] = z[d] + beta * pv[d];
  }
  return 0;
}

/* The state at u0 + step x, its sums into q and the relative residual. */
static int trial(newton *nk, double step, double *q, double *res) {
  place(nk, nk->a[NK_X], step);
  PF_CALL(evaluate(nk));
  PF_CALL(pf_sim_solver_measure(nk->sim, q));
  *res = pf_sim_solver_residual(q);
  return 0;
}

/* The state at u0, its force kept as F0 (the base of the products and the next right-hand side). */
static void keep_base(newton *nk) {
  const pf_points *p = nk->sim->pts;
  memcpy(nk->a[NK_U0], p->u, sizeof(double) * (size_t)nk->n3);
  memcpy(nk->a[NK_F0], p->f, sizeof(double) * (size_t)nk->n3);
}

static int stopped(const double *q, double res) {
  return q[S_TRIPPED] > 0 || !isfinite(res) ? STOP_GUARD : q[S_SIGNAL] > 0 ? STOP_SIGNAL : 0;
}

int pf_sim_solver_newton(pf_sim *sim, long *it, double *res, int *stop, int *converged) {
  pf_sim_solver *s = &sim->solver;
  newton nk = {.sim = sim};
  double q[PF_SOLVER_SUMS];
  *converged = 0;
  PF_CALL(arrays(&nk));
  PF_CALL(extent(&nk));
  memset(s->vel, 0, sizeof(double) * (size_t)nk.n3); /* (the damping sums of measure: none here) */
  PF_CALL(evaluate(&nk));
  PF_CALL(pf_sim_solver_measure(sim, q));
  *res = pf_sim_solver_residual(q);
  int failed = 0;
  for (int k = 0; k <= NK_MAX_NEWTON && !failed; k++) {
    *stop = stopped(q, *res);
    if (*stop || (*converged = *res <= s->tolerance) || k == NK_MAX_NEWTON) break;
    keep_base(&nk);
    int ok;
    PF_CALL(krylov(&nk, s->max_iterations - nk.evaluations, &ok));
    failed = !ok; /* (u is u0 + a probe: back to u0 below) */
    s->newton_steps++;
    const double before = *res;
    double step = 1;
    for (int h = 0; h <= NK_MAX_HALVINGS && !failed; h++, step *= 0.5) {
      PF_CALL(trial(&nk, step, q, res));
      if (*res < before || stopped(q, *res)) break;
      failed = h == NK_MAX_HALVINGS;
    }
  }
  if (failed && !*stop) { /* the relaxation goes on from the last accepted state */
    memcpy(sim->pts->u, nk.a[NK_U0], sizeof(double) * (size_t)nk.n3);
    for (pf_int d = 0; d < nk.n3; d++) sim->pts->y[d] = sim->pts->X[d] + sim->pts->u[d];
  }
  s->krylov_steps += nk.krylov;
  *it = nk.evaluations;
  return 0;
}
