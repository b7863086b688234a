/* The run-health monitor: at every history row it looks at the run's energy and momentum balances, each
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
#define PF_HEALTH_MOMENTUM 1e-6    /* momentum balance error over the momentum in play */

/* A body's figure from the ledger's last evaluation (the sums over the ranks). */
static double figure(const pf_sim *sim, int id) { return pf_ledger_value(&sim->ledger, id, 0); }

/* A body's kinetic, stored and element energies (internal: PD stored energy and stress work). */
static double body_energy(const pf_sim *sim, int b) {
  const pf_body_accounts *A = &sim->acc.body[b];
  return figure(sim, A->kinetic) + figure(sim, A->internal) + figure(sim, A->hourglass) + figure(sim, A->viscous);
}

static double body_damage(const pf_sim *sim, int b) {
  const double bonds = figure(sim, sim->acc.body[b].bonds);
  return bonds > 0 ? figure(sim, sim->acc.body[b].broken) / bonds : 0.0;
}

/* One warning, unless `what` (class and body) was given before; with --strict an error on
 * every rank (each rank holds the same reduced figures, so all of them stop here together). */
int pf_sim_health_warn(pf_sim *sim, const char *what, const char *fmt, ...) {
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
 * check is named as where to look. The error must pass a level at two history rows in a row: a
 * penalty contact's first steps, when the energy in play is still small, can pass 1 % of it at
 * one row by the step's integration error alone (tests/data/indentation.yaml at its first contact:
 * 2 % at step 15, 0.2 % at step 30 and 2e-5 at the end). */
static int energy(pf_sim *sim) {
  const double err = pf_sim_energy_error(sim);
  int worst = 0;
  for (int b = 1; b < sim->nbodies; b++)
    if (fabs(body_energy(sim, b) - sim->health.e0[b]) > fabs(body_energy(sim, worst) - sim->health.e0[worst])) worst = b;
  const double change = body_energy(sim, worst) - sim->health.e0[worst];
  char whose[160];
  if (sim->nbodies == 1) snprintf(whose, sizeof whose, "in body '%s', the only body", sim->body_name[0]);
  else
    snprintf(whose, sizeof whose, "over the whole run, not one body: body '%s' changed most since step %ld (%+.3g J)",
             sim->body_name[worst], sim->health.step0, change);
  const char *hint = sim->solver.type != PF_SOLVER_QUASI_STATIC ? ""
                     : "; quasi-static: the loads' work is the trapezoid over each load step, exact for a response "
                       "linear within it (yield, contact or a stiffening within a load step add to the error, "
                       "a quarter as much at twice the load steps)";
  const double level[2] = {PF_HEALTH_ENERGY_LOW, PF_HEALTH_ENERGY_HIGH}, before = sim->health.error;
  sim->health.error = err;
  for (int k = 0; k < 2; k++) {
    if (!(err > level[k] && before > level[k])) continue; /* two rows in a row: not a start-up transient */
    char what[96];
    snprintf(what, sizeof what, "energy error %g %%", 100 * level[k]);
    PF_CALL(pf_sim_health_warn(sim, what,
                               "energy balance error passed %g %% at t = %.4e s (step %ld): %.3g J, %.3g %% of the "
                               "largest energy in play (%.3g J), %s%s",
                               100 * level[k], sim->t, sim->step, pf_sim_total(sim, sim->acc.totals.error), 100 * err,
                               pf_sim_energy_scale(sim), whose, hint));
  }
  return 0;
}

/* The run's momentum p and the impulse I of every load from outside (the accounts in N s: the
 * conditions', rigid surfaces' and walls'), over the ranks. */
static void momentum_books(const pf_sim *sim, double p[3], double I[3]) {
  const pf_ledger *l = &sim->ledger;
  for (int a = 0; a < 3; a++) p[a] = pf_ledger_value(l, sim->acc.totals.momentum, a), I[a] = 0;
  for (int k = 0; k < l->n; k++)
    if (l->a[k].ncomp == 3 && l->a[k].units && !strcmp(l->a[k].units, "N s"))
      for (int a = 0; a < 3; a++) I[a] += pf_ledger_value(l, k, a);
}

/* The momentum in play: the bodies' sum of sqrt(2 M K), which bounds sum m |v| (Cauchy-Schwarz),
 * so that a body whose parts fly apart with no net momentum is not measured by its round-off. */
static double momentum_in_play(const pf_sim *sim) {
  double s = 0;
  for (int b = 0; b < sim->nbodies; b++) {
    const double M = figure(sim, sim->acc.body[b].mass), K = figure(sim, sim->acc.body[b].kinetic);
    s += sqrt(2 * fmax(M, 0.0) * fmax(K, 0.0));
  }
  return s;
}

/* Newton's third law: the momentum changes by the loads' impulse and nothing else (every force
 * between points, bonds, elements, contact and coupling, acts on both sides). Dynamic runs only
 * (quasi-static, the points are at rest and the impulse is over pseudo-time). Two rows in a row. */
static int momentum(pf_sim *sim) {
  pf_sim_health *h = &sim->health;
  if (sim->solver.type == PF_SOLVER_QUASI_STATIC) return 0;
  double p[3], I[3], e[3];
  momentum_books(sim, p, I);
  for (int a = 0; a < 3; a++) e[a] = p[a] - h->p0[a] - (I[a] - h->i0[a]);
  const double dI = hypot(hypot(I[0] - h->i0[0], I[1] - h->i0[1]), I[2] - h->i0[2]);
  h->p_scale = fmax(h->p_scale, momentum_in_play(sim) + dI);
  const double err = h->p_scale > 0 ? hypot(hypot(e[0], e[1]), e[2]) / h->p_scale : 0, before = h->p_error;
  h->p_error = err;
  if (!(err > PF_HEALTH_MOMENTUM && before > PF_HEALTH_MOMENTUM)) return 0;
  return pf_sim_health_warn(sim, "momentum balance",
                            "momentum balance error passed %g of the momentum in play at t = %.4e s (step %ld): "
                            "p - p0 - I = (%.3g, %.3g, %.3g) kg m/s against %.3g kg m/s in play (I the loads' "
                            "impulse): forces between points that do not balance (a one-sided bond, contact "
                            "or coupling force) or momentum lost without a load",
                            PF_HEALTH_MOMENTUM, sim->t, sim->step, e[0], e[1], e[2], h->p_scale);
}

static int hourglass(pf_sim *sim) {
  const double floor = PF_HEALTH_HOURGLASS_FLOOR * pf_sim_energy_scale(sim);
  for (int b = 0; b < sim->nbodies; b++) {
    const double hg = figure(sim, sim->acc.body[b].hourglass), in = figure(sim, sim->acc.body[b].fe_internal);
    if (!(hg > PF_HEALTH_HOURGLASS * fmax(in, 0.0) && hg > floor)) continue;
    char what[96];
    snprintf(what, sizeof what, "hourglass '%.60s'", sim->body_name[b]);
    PF_CALL(pf_sim_health_warn(sim, what,
                               "body '%s': hourglass energy %.3g J is %.3g times its internal energy (%.3g J; more "
                               "than %g) at t = %.4e s (step %ld): the elements deform in zero-energy modes (finer "
                               "mesh, stiffer hourglass control or fully integrated elements)",
                               sim->body_name[b], hg, in > 0 ? hg / in : INFINITY, in, PF_HEALTH_HOURGLASS, sim->t,
                               sim->step));
  }
  return 0;
}

static int damage(pf_sim *sim) {
  for (int b = 0; b < sim->nbodies; b++) {
    const double d = body_damage(sim, b), before = sim->health.damage[b];
    sim->health.damage[b] = d;
    if (!(d - before > PF_HEALTH_DAMAGE_JUMP)) continue;
    char what[96], every[48];
    snprintf(what, sizeof what, "damage jump '%.60s'", sim->body_name[b]);
    if (sim->history_period > 0) snprintf(every, sizeof every, "%.4g s", sim->history_period);
    else snprintf(every, sizeof every, "%ld steps", sim->history_interval);
    PF_CALL(pf_sim_health_warn(sim, what,
                               "body '%s': damaged fraction jumped from %.4g to %.4g (more than %g) between two "
                               "history rows, at t = %.4e s (step %ld; rows every %s)",
                               sim->body_name[b], before, d, PF_HEALTH_DAMAGE_JUMP, sim->t, sim->step, every));
  }
  return 0;
}

/* At each history row, after the ledger's evaluation. */
int pf_sim_health_check(pf_sim *sim) {
  pf_sim_health *h = &sim->health;
  if (!h->started) { /* the first row: the reference of the bodies' energies and damage */
    h->started = 1, h->step0 = sim->step;
    for (int b = 0; b < sim->nbodies; b++) h->e0[b] = body_energy(sim, b), h->damage[b] = body_damage(sim, b);
    momentum_books(sim, h->p0, h->i0);
  }
  PF_CALL(pf_sim_interactions_health(sim));
  PF_CALL(energy(sim));
  PF_CALL(momentum(sim));
  PF_CALL(hourglass(sim));
  return damage(sim);
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
