/* Instability guards: a step that produces a NaN/Inf force or velocity, moves a point more than
 * a set fraction of its horizon (PD) or of its cell (FE node), or inverts an element stops the
 * run with the point or element, its body, position, time and step. Every rank learns of it at
 * the step's end (one reduction), so all of them go back to the state at the start of the step
 * — the last good state — which the run then writes to the Exodus file before failing. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_sim_guard_save(pf_sim *sim) {
  const pf_points *p = sim->pts;
  if (sim->good_n != p->n_owned || !sim->good_u) { /* first step, or after a re-partition */
    free(sim->good_u), free(sim->good_v);
    sim->good_u = malloc(sizeof(double) * (3 * (size_t)p->n_owned + 1));
    sim->good_v = malloc(sizeof(double) * (3 * (size_t)p->n_owned + 1));
    PF_CHECK(sim->good_u && sim->good_v, PF_ERR_MEMORY, "out of memory for the last good state");
    sim->good_n = p->n_owned;
  }
  memcpy(sim->good_u, p->u, sizeof(double) * 3 * (size_t)p->n_owned);
  memcpy(sim->good_v, p->v, sizeof(double) * 3 * (size_t)p->n_owned);
  sim->good_t = sim->t, sim->good_step = sim->step;
  return 0;
}

void pf_sim_guard_free(pf_sim *sim) {
  PF_FREE(sim->good_u);
  PF_FREE(sim->good_v);
}

/* The length a point's step motion is measured against, and its name: the body's (a PD point's
 * horizon), or by default the point's cell (an FE node's: the cube root of its lumped volume). */
static double reach(const pf_sim *sim, pf_int i) {
  const pf_body *body = &sim->body[sim->pts->body[i]];
  return pf_body_reach(body, sim->pts, i);
}

static const char *reach_name(const pf_sim *sim, pf_int i) {
  const pf_body *body = &sim->body[sim->pts->body[i]];
  return pf_body_reach_name(body);
}

void pf_sim_guard_motion(pf_sim *sim, double dt) {
  const pf_points *p = sim->pts;
  for (pf_int i = 0; i < p->n_owned && !sim->guard_tripped; i++) {
    const double *v = &p->v[3 * i];
    double d = dt * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), lim = sim->max_motion * reach(sim, i);
    if (!(d > lim)) continue; /* NaN too: the finite check at the step's end names it */
    sim->guard_tripped = 1;
    pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                   "point %" PF_GID_FMT " (body '%s') at (%g, %g, %g) m moved %g m in step %ld at time %g s, "
                   "more than time.max_motion = %g of its %s (%g m): the run is unstable (reduce time.dt or "
                   "time.safety_factor)",
                   p->gid[i], sim->body_name[p->body[i]], p->y[3 * i], p->y[3 * i + 1], p->y[3 * i + 2], d,
                   sim->step + 1, sim->t + dt, sim->max_motion, reach_name(sim, i), reach(sim, i));
  }
}

static void check_finite(pf_sim *sim) {
  const pf_points *p = sim->pts;
  for (pf_int i = 0; i < p->n_owned && !sim->guard_tripped; i++) {
    double s = p->f[3 * i] + p->f[3 * i + 1] + p->f[3 * i + 2] + p->v[3 * i] + p->v[3 * i + 1] + p->v[3 * i + 2];
    if (isfinite(s)) continue;
    sim->guard_tripped = 1;
    pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                   "non-finite force or velocity at point %" PF_GID_FMT " (body '%s') at (%g, %g, %g) m, "
                   "time %g s, step %ld: the run is unstable (reduce time.dt or time.safety_factor) or a "
                   "prescribed motion is not finite",
                   p->gid[i], sim->body_name[p->body[i]], p->X[3 * i], p->X[3 * i + 1], p->X[3 * i + 2], sim->t, sim->step);
  }
}

/* One reduction a step for both: has any rank tripped a guard, and the largest signal received. */
int pf_sim_guard_check(pf_sim *sim) {
  check_finite(sim);
  int flags[2] = {sim->guard_tripped, pf_sim_signal_here()};
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed in the step's guard");
  sim->signal = flags[1];
  if (!flags[0]) return 0;
  pf_points *p = sim->pts;
  memcpy(p->u, sim->good_u, sizeof(double) * 3 * (size_t)p->n_owned);
  memcpy(p->v, sim->good_v, sizeof(double) * 3 * (size_t)p->n_owned);
  for (pf_int i = 0; i < 3 * p->n_owned; i++) p->y[i] = p->X[i] + p->u[i];
  sim->t = sim->good_t, sim->step = sim->good_step;
  sim->last_good = 1;
  if (sim->guard_tripped) return PF_ERR_RUN; /* this rank's message is out */
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__,
                        "stopped at step %ld: another rank found the run unstable", sim->step + 1);
}
