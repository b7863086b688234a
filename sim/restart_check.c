/* What a restart checks of a checkpoint's content that only the simulation knows (the file's
 * own checks are core/checkpoint_check.c): the points' bodies among the deck's, each point's
 * global id in its body's range, and time, step and step size in range and consistent with
 * each other and with this run. Each failure is one message naming the checkpoint and the
 * dataset or attribute, on every rank (the points' checks are agreed; the scalars are the
 * same on every rank). Then by meaning: each point's reference position, volume and cell size
 * against the set-up's, and, after the set-up, every point field the models keep present. */
#include "sim/sim_impl.h"

#include <math.h>

/* Before the bodies' ids are numbered from the points' bodies: every body index one of the
 * deck's bodies. Collective. */
int pf_sim_check_restart_bodies(const pf_sim *sim) {
  const pf_points *p = sim->pts;
  char msg[512] = "";
  int ok = 1;
  for (pf_int i = 0; i < p->n_owned && ok; i++)
    if (p->body[i] < 0 || p->body[i] >= sim->nbodies) {
      ok = 0;
      snprintf(msg, sizeof msg, "checkpoint %s: dataset /points/body: point %" PF_GID_FMT " has body index %" PRId32
               ", the deck has %d bodies: the file is damaged", sim->opt.restart_from, p->gid[i], p->body[i], sim->nbodies);
    }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

/* After they are numbered: each point's global id in its body's range [gid0[b], gid0[b+1]).
 * Collective. */
int pf_sim_check_restart_gids(const pf_sim *sim) {
  const pf_points *p = sim->pts;
  char msg[512] = "";
  int ok = 1;
  for (pf_int i = 0; i < p->n_owned && ok; i++) {
    const int b = p->body[i];
    if (p->gid[i] >= sim->gid0[b] && p->gid[i] < sim->gid0[b + 1]) continue;
    ok = 0;
    snprintf(msg, sizeof msg, "checkpoint %s: datasets /points/gid and /points/body: point %" PF_GID_FMT
             " is in body %d, whose ids are [%" PF_GID_FMT ", %" PF_GID_FMT "): the file is damaged",
             sim->opt.restart_from, p->gid[i], b, sim->gid0[b], sim->gid0[b + 1]);
  }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

/* time (v[0]) not negative, step (v[1]) a whole number in [0, 2^53), dt (v[2]) positive, a step
 * before time 0 impossible, and each body's stable step (stable[nbodies]) not negative. */
int pf_sim_check_restart_scalars(const pf_sim *sim, const double *v, const double *stable) {
  const char *path = sim->opt.restart_from;
  PF_CHECK(v[0] >= 0, PF_ERR_INPUT, "checkpoint %s: attribute 'time' is %g s (negative): the file is damaged", path, v[0]);
  PF_CHECK(v[1] >= 0 && v[1] < 9007199254740992.0 && v[1] == floor(v[1]), PF_ERR_INPUT,
           "checkpoint %s: attribute 'step' is %g, not a step number: the file is damaged", path, v[1]);
  PF_CHECK(v[2] > 0, PF_ERR_INPUT, "checkpoint %s: attribute 'dt' is %g s (not positive): the file is damaged", path, v[2]);
  PF_CHECK((v[0] == 0) == (v[1] == 0), PF_ERR_INPUT,
           "checkpoint %s: attributes 'time' %g s and 'step' %g disagree: the file is damaged", path, v[0], v[1]);
  for (int b = 0; b < sim->nbodies; b++)
    PF_CHECK(stable[b] >= 0, PF_ERR_INPUT, "checkpoint %s: attribute 'body_%d_%s_stable_dt' is %g s (negative): the "
             "file is damaged", path, b, sim->body_name[b], stable[b]);
  return 0;
}

/* After the set-up, which gives the step size and the run's end: with a fixed step, time is
 * step x dt (to rounding); the checkpoint is not past the end of this run. */
int pf_sim_check_restart_time(const pf_sim *sim, const double *v) {
  const char *path = sim->opt.restart_from;
  const double t = v[0], step = v[1], dt = v[2];
  PF_CHECK(sim->adaptive || fabs(t - step * dt) <= 1e-6 * (t + dt), PF_ERR_INPUT,
           "checkpoint %s: attributes 'time' %.17g s, 'step' %.17g and 'dt' %.17g s disagree (time is not step x dt): "
           "the file is damaged", path, t, step, dt);
  const int by_time = sim->adaptive && isfinite(sim->final_time);
  PF_CHECK(by_time || step <= (double)sim->nsteps, PF_ERR_INPUT,
           "checkpoint %s: attribute 'step' is %.17g, past this run's %ld steps (nothing to do; a damaged file?)", path,
           step, sim->nsteps);
  PF_CHECK(!by_time || t <= sim->final_time + dt, PF_ERR_INPUT,
           "checkpoint %s: attribute 'time' is %.17g s, past this run's final_time %.17g s (nothing to do; a damaged "
           "file?)", path, t, sim->final_time);
  return 0;
}

int pf_sim_check_restart_reference(const pf_sim *sim, const pf_point_cloud *pc) {
  const pf_points *p = sim->pts;
  char msg[600] = "";
  int ok = 1;
  for (pf_int i = 0; i < p->n_owned && ok; i++) {
    const int b = p->body[i];
    const pf_int j = (pf_int)(p->gid[i] - sim->gid0[b]);
    const double *X = &pc[b].X[3 * (size_t)j], *Y = &p->X[3 * (size_t)i];
    const char *what = X[0] != Y[0] || X[1] != Y[1] || X[2] != Y[2] ? "reference position"
                       : pc[b].vol[j] != p->vol[i]                   ? "volume"
                       : pc[b].cell[j] != p->cell[i]                 ? "cell size"
                                                                     : NULL;
    if (!what) continue;
    ok = 0;
    snprintf(msg, sizeof msg, "checkpoint %s: point %" PF_GID_FMT " (body '%s', its point %" PF_GID_FMT "): its %s in "
             "/points/%s is not the set-up's (position %.17g %.17g %.17g m, volume %.17g m^3 in the file; %.17g %.17g "
             "%.17g m, %.17g m^3 made from the deck): the file is damaged or was written for other geometry",
             sim->opt.restart_from, p->gid[i], sim->body_name[b], (pf_gid)j, what,
             what[0] == 'r' ? "X" : what[0] == 'v' ? "vol" : "cell", Y[0], Y[1], Y[2], p->vol[i], X[0], X[1], X[2],
             pc[b].vol[j]);
  }
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

int pf_sim_check_restart_fields(const pf_sim *sim) {
  const pf_points *p = sim->pts;
  for (int k = sim->restart_nfields; k < p->nfields; k++)
    PF_CHECK(!(p->fields[k].flags & PF_FIELD_RESTART), PF_ERR_INPUT,
             "checkpoint %s has no point field '%s' (%d per point), which this run's models keep: it was written by "
             "another model or another version of perifem, or is damaged",
             sim->opt.restart_from, p->fields[k].name, p->fields[k].ncomp);
  return 0;
}
