/* The run-health monitor: at every history row it looks at the run's energy balance, each
 * finite-element body's hourglass energy, each body's damage and each contact pair's deepest
 * interpenetration, and warns (rank 0, "perifem warning: …", with the time, the step and the
 * body responsible) the first time a figure passes its threshold below; each warning is given
 * once per class and body. With --strict the first warning is a run failure instead, on every
 * rank at once (exit status 1). The summary ends with the verdict, "health: ok" or
 * "health: N warnings (…)". The monitor only reads the state: the results do not change. */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* The thresholds (docs/user_guide.md, "Run health"). */
#define PF_HEALTH_ENERGY_LOW 0.01  /* energy balance error over the largest energy in play */
#define PF_HEALTH_ENERGY_HIGH 0.05
#define PF_HEALTH_HOURGLASS 0.10   /* a body's hourglass energy over its internal energy ... */
#define PF_HEALTH_HOURGLASS_FLOOR 1e-3 /* ... once it is this much of the largest energy in play */
#define PF_HEALTH_DAMAGE_JUMP 0.10 /* rise of a body's damaged fraction between two history rows */
#define PF_HEALTH_DEPTH 0.5        /* a point behind a contact surface by this much of r_c */
#define PF_HEALTH_CLOSE 0.5        /* two contact points closer than this much of r_c */

/* Per body, summed over the ranks: kinetic energy, PD stored energy, FE stress work, hourglass
 * energy, bulk-viscosity work, bonds and broken bonds. */
enum { H_KE, H_EL, H_INT, H_HG, H_BV, H_BONDS, H_BROKEN, H_N };

static double body_energy(const double *s) { return s[H_KE] + s[H_EL] + s[H_INT] + s[H_HG] + s[H_BV]; }

/* One warning, unless `what` (class and body) was given before; with --strict an error on
 * every rank (each rank holds the same reduced figures, so all of them stop here together). */
static int warn(pf_sim *sim, const char *what, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int warn(pf_sim *sim, const char *what, const char *fmt, ...) {
  pf_sim_health *h = &sim->health;
  for (int k = 0; k < h->n && k < PF_HEALTH_MAX_WARNINGS; k++)
    if (!strcmp(h->what[k], what)) return 0;
  if (h->n < PF_HEALTH_MAX_WARNINGS) snprintf(h->what[h->n], sizeof h->what[h->n], "%s", what);
  h->n++;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (sim->opt.strict)
    return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__, "%s; stopped by --strict at t = %.6e s, step %ld",
                          msg, sim->t, sim->step);
  pf_log("perifem warning: %s\n", msg);
  return 0;
}

/* The energy balance is the whole run's; the body whose own energy changed most since the first
 * check is named as where to look. */
static int energy(pf_sim *sim, const pf_sim_history_row *g, const double *s) {
  const double err = pf_sim_energy_error(g);
  int worst = 0;
  for (int b = 1; b < sim->nbodies; b++)
    if (fabs(body_energy(&s[H_N * b]) - sim->health.e0[b]) > fabs(body_energy(&s[H_N * worst]) - sim->health.e0[worst]))
      worst = b;
  const double change = body_energy(&s[H_N * worst]) - sim->health.e0[worst];
  char whose[160];
  if (sim->nbodies == 1) snprintf(whose, sizeof whose, "in body '%s', the only body", sim->body_name[0]);
  else
    snprintf(whose, sizeof whose, "over the whole run, not one body: body '%s' changed most since step %ld (%+.3g J)",
             sim->body_name[worst], sim->health.step0, change);
  const double level[2] = {PF_HEALTH_ENERGY_LOW, PF_HEALTH_ENERGY_HIGH};
  for (int k = 0; k < 2; k++) {
    if (!(err > level[k])) continue;
    char what[96];
    snprintf(what, sizeof what, "energy error %g %%", 100 * level[k]);
    PF_CALL(warn(sim, what,
                 "energy balance error passed %g %% at t = %.4e s (step %ld): %.3g J, %.3g %% of the largest energy "
                 "in play (%.3g J), %s",
                 100 * level[k], sim->t, sim->step, g->values[2 + G_EERR], 100 * err, pf_sim_energy_scale(g), whose));
  }
  return 0;
}

static int hourglass(pf_sim *sim, const pf_sim_history_row *g, const double *s) {
  const double floor = PF_HEALTH_HOURGLASS_FLOOR * pf_sim_energy_scale(g);
  for (int b = 0; b < sim->nbodies; b++) {
    const double hg = s[H_N * b + H_HG], in = s[H_N * b + H_INT];
    if (!(hg > PF_HEALTH_HOURGLASS * fmax(in, 0.0) && hg > floor)) continue;
    char what[96];
    snprintf(what, sizeof what, "hourglass '%.60s'", sim->body_name[b]);
    PF_CALL(warn(sim, what,
                 "body '%s': hourglass energy %.3g J is %.3g times its internal energy (%.3g J; more than %g) at "
                 "t = %.4e s (step %ld): the elements deform in zero-energy modes (finer mesh, stiffer hourglass "
                 "control or fully integrated elements)",
                 sim->body_name[b], hg, in > 0 ? hg / in : INFINITY, in, PF_HEALTH_HOURGLASS, sim->t, sim->step));
  }
  return 0;
}

static int damage(pf_sim *sim, const double *s) {
  for (int b = 0; b < sim->nbodies; b++) {
    const double bonds = s[H_N * b + H_BONDS], d = bonds > 0 ? s[H_N * b + H_BROKEN] / bonds : 0.0;
    const double before = sim->health.damage[b];
    sim->health.damage[b] = d;
    if (!(d - before > PF_HEALTH_DAMAGE_JUMP)) continue;
    char what[96];
    snprintf(what, sizeof what, "damage jump '%.60s'", sim->body_name[b]);
    PF_CALL(warn(sim, what,
                 "body '%s': damaged fraction jumped from %.4g to %.4g (more than %g) between two history rows, "
                 "at t = %.4e s (step %ld; rows every %ld steps)",
                 sim->body_name[b], before, d, PF_HEALTH_DAMAGE_JUMP, sim->t, sim->step, sim->history_interval));
  }
  return 0;
}

/* Each contact pair's smallest gap over the ranks (one reduction). */
static int interpenetration(pf_sim *sim) {
  const int np = pf_contact_npairs(sim->contact);
  if (np == 0) return 0;
  double *gap;
  PF_MALLOC(gap, np);
  pf_contact_gap *info;
  PF_MALLOC(info, np);
  for (int k = 0; k < np; k++) gap[k] = pf_contact_pair_gap(sim->contact, k, &info[k]);
  int ierr = MPI_Allreduce(MPI_IN_PLACE, gap, np, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD) != MPI_SUCCESS;
  for (int k = 0; k < np && !ierr; k++) {
    const pf_contact_gap *c = &info[k];
    const char *a = sim->body_name[c->a], *b = sim->body_name[c->b];
    char what[96], pair[200];
    snprintf(what, sizeof what, "interpenetration '%.34s'/'%.34s'", a, b);
    if (c->a == c->b) snprintf(pair, sizeof pair, "body '%s' (with itself)", a);
    else snprintf(pair, sizeof pair, "bodies '%s' and '%s'", a, b);
    const char *start = sim->step == sim->health.step0 ? " (they start inside each other)" : "";
    if (c->surface && gap[k] < -PF_HEALTH_DEPTH)
      ierr = warn(sim, what,
                  "%s interpenetrate at t = %.4e s (step %ld)%s: a point is %.3g m behind the surface of '%s', "
                  "%.3g contact radii (r_c = %.3g m; more than %g)",
                  pair, sim->t, sim->step, start, -gap[k] * c->length, a, -gap[k], c->length, PF_HEALTH_DEPTH);
    else if (!c->surface && gap[k] < PF_HEALTH_CLOSE)
      ierr = warn(sim, what,
                  "%s interpenetrate at t = %.4e s (step %ld)%s: two points are %.3g of their contact radius "
                  "apart (less than %g; r_c = %.3g m)",
                  pair, sim->t, sim->step, start, gap[k], PF_HEALTH_CLOSE, c->length);
  }
  free(gap), free(info);
  return ierr;
}

/* Per-body figures summed over the ranks into s[H_N * nbodies] (one reduction). */
static int body_sums(const pf_sim *sim, double *s) {
  const pf_points *p = sim->pts;
  for (int b = 0; b < sim->nbodies; b++) {
    double *x = &s[H_N * b], ke = 0;
    for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++)
      for (int a = 0; a < 3; a++) ke += 0.5 * p->m[i] * p->v[3 * i + a] * p->v[3 * i + a];
    const pf_body_energies *e = &sim->health.local[b];
    x[H_KE] = ke, x[H_EL] = e->elastic, x[H_INT] = e->fe[0], x[H_HG] = e->fe[1], x[H_BV] = e->fe[2];
    x[H_BONDS] = e->bonds, x[H_BROKEN] = e->broken;
  }
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, s, H_N * sim->nbodies, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS,
           PF_ERR_LIB, "MPI_Allreduce failed in the run-health check");
  return 0;
}

int pf_sim_health_check(pf_sim *sim, const pf_sim_history_row *g) {
  double s[H_N * PF_MAX_BODIES];
  PF_CALL(body_sums(sim, s));
  pf_sim_health *h = &sim->health;
  if (!h->started) { /* the first row: the reference of the bodies' energies and damage */
    h->started = 1, h->step0 = sim->step;
    for (int b = 0; b < sim->nbodies; b++) {
      h->e0[b] = body_energy(&s[H_N * b]);
      h->damage[b] = s[H_N * b + H_BONDS] > 0 ? s[H_N * b + H_BROKEN] / s[H_N * b + H_BONDS] : 0.0;
    }
  }
  PF_CALL(interpenetration(sim));
  PF_CALL(energy(sim, g, s));
  PF_CALL(hourglass(sim, g, s));
  return damage(sim, s);
}

void pf_sim_health_summary(const pf_sim *sim) {
  const pf_sim_health *h = &sim->health;
  if (h->n == 0) {
    pf_log("health: ok\n");
    return;
  }
  char list[PF_HEALTH_MAX_WARNINGS * 100] = "";
  size_t len = 0;
  for (int k = 0; k < h->n && k < PF_HEALTH_MAX_WARNINGS; k++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? "; " : "", h->what[k]);
  pf_log("health: %d warning%s (%s%s)\n", h->n, h->n > 1 ? "s" : "", list, h->n > PF_HEALTH_MAX_WARNINGS ? "; …" : "");
}
