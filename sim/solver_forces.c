/* What both quasi-static methods use (sim/solver.h): the forces at the current displacements,
 * the iteration's sums, taken so that they are the same bits on any number of ranks, and the
 * residual relative to the reference force (docs/theory/quasi_static.md §2-3, §9). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_sim_solver_sums(const double *x, pf_int n, int m, double *out) {
  double mx[PF_SOLVER_SUMS + 1] = {0};
  for (int j = 0; j < m; j++)
    for (pf_int d = 0; d < n; d++) mx[j] = fmax(mx[j], fabs(x[(size_t)j * n + d])); /* (NaN: dropped) */
  for (int j = 0; j < m; j++)
    for (pf_int d = 0; d < n; d++)
      if (!isfinite(x[(size_t)j * n + d])) mx[j] = INFINITY;
  double count = (double)n; /* the terms over the ranks: room for all of them, the same on any partition */
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, mx, m, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS &&
               MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS,
           PF_ERR_LIB, "MPI_Allreduce failed in the quasi-static solver");
  const int bits = 61 - (int)ceil(log2(count + 2));
  int64_t q[PF_SOLVER_SUMS] = {0};
  int e[PF_SOLVER_SUMS] = {0};
  for (int j = 0; j < m; j++) {
    if (!(mx[j] > 0) || !isfinite(mx[j])) continue;
    frexp(mx[j], &e[j]); /* mx < 2^e */
    const double scale = ldexp(1.0, bits - e[j]); /* (a power of 2: x scale is exact) */
    for (pf_int d = 0; d < n; d++) q[j] += (int64_t)llrint(x[(size_t)j * n + d] * scale);
  }
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, q, m, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed in the quasi-static solver");
  for (int j = 0; j < m; j++) out[j] = isfinite(mx[j]) ? ldexp((double)q[j], e[j] - bits) : NAN;
  return 0;
}

int pf_sim_solver_is_free(const pf_sim_solver *s, pf_int d) { return !s->fixed[d] && s->lambda[d / 3] > 0; }

/* Each body's velocity for its force op over a step of 1: a body that keeps history (sim/body.h)
 * gets it back as committed at the load step's start and reads the load step's increment u - u0,
 * so each evaluation is one increment from the last converged state; the others read the
 * increment since the last evaluation. */
static int velocities(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  for (int b = 0; b < sim->nbodies; b++) {
    const int hist = pf_body_keeps_history(&sim->body[b], p);
    const double *from = hist ? s->u0 : s->u_last;
    if (hist) PF_CALL(pf_body_history(&sim->body[b], p, PF_HISTORY_RESTORE));
    for (pf_int d = 3 * sim->body_start[b]; d < 3 * sim->body_start[b + 1]; d++) p->v[d] = p->u[d] - from[d];
  }
  return 0;
}

/* Forces at the current positions: the bodies' (with the velocities above, over a step of 1),
 * then the loads' (dt 0: no work booked here). */
int pf_sim_solver_evaluate(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  pf_points *p = sim->pts;
  const pf_int n3 = 3 * p->n_owned;
  PF_CALL(velocities(sim));
  PF_CALL(pf_sim_body_forces(sim, 1.0, 0));
  memcpy(s->f_body, p->f, sizeof(double) * (size_t)n3);
  PF_CALL(pf_sim_interactions_force(sim, 0.0, s->f_own));
  memcpy(s->u_last, p->u, sizeof(double) * (size_t)n3);
  s->evaluations++;
  return 0;
}

/* The force from outside on component d: the reaction on a prescribed one, the interactions' force
 * on a free one. */
static double applied(const pf_sim_solver *s, const pf_points *p, pf_int d) {
  return s->fixed[d] ? -p->f[d] : p->f[d] - s->f_body[d];
}

void pf_sim_solver_quotient_terms(const pf_sim_solver *s, const pf_points *p, pf_int d, double *uku, double *uu) {
  const int fr = pf_sim_solver_is_free(s, d);
  const double w = p->u[d] - s->u_relax[d], dv = s->vel[d] * s->lambda[d / 3];
  *uku = fr && dv != 0 ? -w * w * (p->f[d] - s->f_old[d]) / dv : 0;
  *uu = fr ? w * w : 0;
}

/* The iteration's sums: the residual, the reference force and the internal forces (squared
 * 2-norms), u^T 1K u and u^T u of the damping coefficient, and whether a body tripped. */
int pf_sim_solver_measure(pf_sim *sim, double *q) {
  pf_sim_solver *s = &sim->solver;
  const pf_points *p = sim->pts;
  const pf_int n3 = 3 * p->n_owned;
  double *t = s->terms;
  for (pf_int d = 0; d < n3; d++) {
    const int fr = pf_sim_solver_is_free(s, d);
    const double g = applied(s, p, d);
    t[S_RESIDUAL * n3 + d] = fr ? p->f[d] * p->f[d] : 0;
    t[S_REFERENCE * n3 + d] = g * g;
    t[S_INTERNAL * n3 + d] = s->f_body[d] * s->f_body[d];
    pf_sim_solver_quotient_terms(s, p, d, &t[S_UKU * n3 + d], &t[S_UU * n3 + d]);
    t[S_TRIPPED * n3 + d] = d == 0 ? sim->guard_tripped : 0;
    t[S_SIGNAL * n3 + d] = d == 0 ? pf_sim_signal_here() : 0;
  }
  return pf_sim_solver_sums(t, n3, PF_SOLVER_SUMS, q);
}

/* The residual relative to the reference force (the loads' and reactions', else the internal). */
double pf_sim_solver_residual(const double *q) {
  const double ref = q[S_REFERENCE] > 0 ? q[S_REFERENCE] : q[S_INTERNAL];
  return q[S_RESIDUAL] == 0 ? 0 : sqrt(q[S_RESIDUAL] / ref); /* (NaN or inf, the guard's stop, when the forces are not finite) */
}
