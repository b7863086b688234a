/* The run's and the bodies' accounts in the ledger (sim/ledger.h): the run's totals come first
 * in the history, then per body its motion and energies, then what each interaction opens, then
 * the probes. A body's state accounts are evaluated at each history row from its energies op
 * and its points; its running ones are booked during the steps (damage here, external work by
 * the conditions). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* One line per total: name, units, components. */
static int open_totals(pf_sim *sim) {
  pf_ledger *l = &sim->ledger;
  pf_sim_totals *T = &sim->acc.totals;
  const int S = PF_BOOK_STATE, N = PF_BOOK_NO_BALANCE;
  PF_CALL(pf_ledger_open(l, "kinetic_energy", "J", 1, 0, S, N, -1, &T->kinetic));
  PF_CALL(pf_ledger_open(l, "elastic_energy", "J", 1, 0, S, N, -1, &T->elastic));
  PF_CALL(pf_ledger_open(l, "contact_energy", "J", 1, 0, S, N, -1, &T->contact));
  PF_CALL(pf_ledger_open(l, "external_work", "J", 1, 0, S, N, -1, &T->work));
  PF_CALL(pf_ledger_open_error(l));
  T->error = l->error_id;
  PF_CALL(pf_ledger_open(l, "momentum", "kg m/s", 3, 0, S, N, -1, &T->momentum));
  PF_CALL(pf_ledger_open(l, "angular_momentum", "kg m^2/s", 3, 0, S, N, -1, &T->angular));
  PF_CALL(pf_ledger_open(l, "damage_fraction", "", 1, 0, S, N | PF_BOOK_SHARED, -1, &T->damage_fraction));
  PF_CALL(pf_ledger_open(l, "fe_internal_energy", "J", 1, 0, S, N, -1, &T->fe_internal));
  PF_CALL(pf_ledger_open(l, "hourglass_energy", "J", 1, 0, S, N, -1, &T->hourglass));
  PF_CALL(pf_ledger_open(l, "bulk_viscosity_work", "J", 1, 0, S, N, -1, &T->viscous));
  PF_CALL(pf_ledger_open(l, "wall_dissipation", "J", 1, 0, S, N, -1, &T->wall));
  PF_CALL(pf_ledger_open(l, "contact_dissipation", "J", 1, 0, S, N, -1, &T->contact_dissipation));
  PF_CALL(pf_ledger_open(l, "damage_dissipation", "J", 1, 0, S, N, -1, &T->damage));
  PF_CALL(pf_ledger_open(l, "damage_redistribution", "J", 1, 0, S, N, -1, &T->redistribution));
  T->relaxation = -1; /* quasi-static only: what the relaxation's damping takes at a fixed load */
  if (sim->solver.type == PF_SOLVER_QUASI_STATIC)
    PF_CALL(pf_ledger_open(l, "relaxation_dissipation", "J", 1, 1, PF_BOOK_RUNNING, 0, -1, &T->relaxation));
  T->conversion = -1; /* a column only where some body's particles come from converted elements */
  return pf_sim_converts(sim) ? pf_ledger_open(l, "conversion_loss", "J", 1, 0, S, N, -1, &T->conversion) : 0;
}

/* Body b's accounts: (column suffix, units, components, sign, kind, flags, total). */
static int open_body(pf_sim *sim, int b) {
  pf_ledger *l = &sim->ledger;
  const pf_sim_totals *T = &sim->acc.totals;
  pf_body_accounts *A = &sim->acc.body[b];
  const int S = PF_BOOK_STATE, R = PF_BOOK_RUNNING, H = PF_BOOK_HIDDEN;
  const struct {
    int *id;
    const char *suffix, *units;
    int ncomp, sign;
    pf_book_kind kind;
    int flags, total;
  } list[] = {
      {&A->position, "position", "m", 3, 0, S, PF_BOOK_SHARED, -1},
      {&A->velocity, "velocity", "m/s", 3, 0, S, PF_BOOK_SHARED, -1},
      {&A->kinetic, "kinetic_energy", "J", 1, 0, S, 0, T->kinetic},
      {&A->centred, "kinetic_energy_centred", "J", 1, 1, S, H, -1},
      {&A->internal, "internal_energy", "J", 1, 0, S, 0, -1},
      {&A->elastic, "elastic_energy", "J", 1, 1, S, H, T->elastic},
      {&A->fe_internal, "fe_internal_energy", "J", 1, 1, S, H, T->fe_internal},
      {&A->hourglass, "hourglass_energy", "J", 1, 1, S, 0, T->hourglass},
      {&A->viscous, "viscous_work", "J", 1, 1, S, 0, T->viscous},
      {&A->damage, "damage_dissipation", "J", 1, 1, R, 0, T->damage},
      {&A->redistribution, "damage_redistribution", "J", 1, 1, R, 0, T->redistribution},
      {&A->work, "external_work", "J", 1, -1, R, 0, T->work},
      {&A->momentum, "momentum", "kg m/s", 3, 0, S, 0, T->momentum},
      {&A->angular, "angular_momentum", "kg m^2/s", 3, 0, S, 0, T->angular},
      {&A->conversion, "conversion_loss", "J", 1, 1, S, H, T->conversion},
      {&A->bonds, "bonds", "", 1, 0, S, H, -1},
      {&A->broken, "broken_bonds", "", 1, 0, S, H, -1},
      {&A->moment, "mass_moment", "kg m", 3, 0, S, H, -1},
      {&A->mass, "mass", "kg", 1, 0, S, H, -1},
  };
  for (size_t k = 0; k < sizeof list / sizeof list[0]; k++) {
    char name[160];
    snprintf(name, sizeof name, "%s_%s", sim->body_name[b], list[k].suffix);
    PF_CALL(pf_ledger_open(l, name, list[k].units, list[k].ncomp, list[k].sign, list[k].kind, list[k].flags,
                           list[k].total, list[k].id));
  }
  sim->acc.body_work[b] = A->work;
  return 0;
}

static int open_probes(pf_sim *sim) {
  sim->acc.nprobe = pf_sim_probe_columns(sim);
  sim->acc.probe0 = sim->ledger.n;
  for (int k = 0; k < sim->acc.nprobe; k++) {
    char name[160];
    const char *units;
    int id;
    pf_sim_probe_column(sim, k, name, sizeof name, &units);
    PF_CALL(pf_ledger_open(&sim->ledger, name, units, 1, 0, PF_BOOK_STATE, PF_BOOK_SHARED, -1, &id));
  }
  return 0;
}

int pf_sim_accounts_open(pf_sim *sim) {
  PF_CALL(open_totals(sim));
  for (int b = 0; b < sim->nbodies; b++) PF_CALL(open_body(sim, b));
  PF_CALL(pf_sim_interactions_open_accounts(sim));
  return open_probes(sim);
}

/* Body b's kinetic energy, momentum, angular momentum about the origin (sum m y x v at the current
 * positions: velocity Verlet, a symplectic partitioned Runge-Kutta method, keeps this quadratic
 * invariant exactly under forces of no total moment, Hairer, Lubich & Wanner 2006, sec. IV.2) and
 * the centred kinetic energy: a prescribed component's
 * force (marked in fixed) is a reaction, not an acceleration, so it does not enter the centred
 * kinetic energy sum m (|v|^2 - (dt/2)^2 |a|^2) / 2 = sum m v(t - dt/2) . v(t + dt/2) / 2, the
 * kinetic part of the energy velocity Verlet conserves exactly for linear forces. Quasi-static,
 * the force left at a load step's end is the relaxation's residual, not an acceleration over a
 * step: the centred kinetic energy is the kinetic energy (0, the points at rest). */
static void body_motion(pf_sim *sim, int b, const uint8_t *fixed) {
  const pf_points *p = sim->pts;
  const pf_body_accounts *A = &sim->acc.body[b];
  const double h = sim->solver.type == PF_SOLVER_QUASI_STATIC ? 0.0 : 0.5 * sim->dt;
  double ke = 0, kc = 0, mom[3] = {0, 0, 0}, ang[3] = {0, 0, 0};
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) {
    const double *y = &p->y[3 * i], *v = &p->v[3 * i];
    for (int a = 0; a < 3; a++) {
      double acc = fixed[3 * i + a] || !(p->m[i] > 0) ? 0 : p->f[3 * i + a] / p->m[i];
      ke += 0.5 * p->m[i] * v[a] * v[a];
      kc += 0.5 * p->m[i] * (v[a] * v[a] - h * h * acc * acc);
      mom[a] += p->m[i] * v[a];
      ang[a] += p->m[i] * (y[(a + 1) % 3] * v[(a + 2) % 3] - y[(a + 2) % 3] * v[(a + 1) % 3]);
    }
  }
  pf_ledger_set(&sim->ledger, A->kinetic, &ke);
  pf_ledger_set(&sim->ledger, A->centred, &kc);
  pf_ledger_set(&sim->ledger, A->momentum, mom);
  pf_ledger_set(&sim->ledger, A->angular, ang);
}

/* Each body's first moment of mass (current positions) and mass, summed with the other accounts:
 * after the reduction, its centre of mass and mass-averaged velocity (momentum / mass), a
 * projectile's path and its residual velocity. */
static void body_moment(pf_sim *sim, int b) {
  const pf_points *p = sim->pts;
  double s[4] = {0, 0, 0, 0}; /* m y (3), m */
  for (pf_int i = sim->body_start[b]; i < sim->body_start[b + 1]; i++) {
    for (int a = 0; a < 3; a++) s[a] += p->m[i] * p->y[3 * i + a];
    s[3] += p->m[i];
  }
  pf_ledger_set(&sim->ledger, sim->acc.body[b].moment, s);
  pf_ledger_set(&sim->ledger, sim->acc.body[b].mass, s + 3);
}

static void body_centre(pf_sim *sim, int b) {
  pf_ledger *l = &sim->ledger;
  const pf_body_accounts *A = &sim->acc.body[b];
  const double m = pf_ledger_value(l, A->mass, 0);
  for (int a = 0; a < 3; a++) {
    l->a[A->position].value[a] = l->a[A->position].local[a] = m > 0 ? pf_ledger_value(l, A->moment, a) / m : 0.0;
    l->a[A->velocity].value[a] = l->a[A->velocity].local[a] = m > 0 ? pf_ledger_value(l, A->momentum, a) / m : 0.0;
  }
}

/* Each body's energies op into its state accounts. */
static void body_energies(pf_sim *sim, int b) {
  pf_ledger *l = &sim->ledger;
  const pf_body_accounts *A = &sim->acc.body[b];
  pf_body_energies e;
  sim->body[b].ops->energies(sim->body[b].data, sim->pts, &e);
  const double internal = e.elastic + e.fe[0];
  pf_ledger_set(l, A->internal, &internal);
  pf_ledger_set(l, A->elastic, &e.elastic);
  pf_ledger_set(l, A->fe_internal, &e.fe[0]);
  pf_ledger_set(l, A->hourglass, &e.fe[1]);
  pf_ledger_set(l, A->viscous, &e.fe[2]);
  pf_ledger_set(l, A->conversion, &e.converted);
  pf_ledger_set(l, A->bonds, &e.bonds);
  pf_ledger_set(l, A->broken, &e.broken);
}

int pf_sim_accounts_evaluate(pf_sim *sim, int first) {
  const pf_points *p = sim->pts;
  uint8_t *fixed = calloc(3 * (size_t)p->n_owned + 1, 1);
  PF_CHECK(fixed, PF_ERR_MEMORY, "out of memory");
  pf_sim_interactions_mark(sim, fixed);
  for (int b = 0; b < sim->nbodies; b++) {
    body_energies(sim, b);
    body_motion(sim, b, fixed);
    body_moment(sim, b);
  }
  free(fixed);
  double *probe;
  PF_MALLOC(probe, sim->acc.nprobe + 1);
  int ierr = sim->acc.nprobe ? pf_sim_probes_eval(sim, probe) : 0; /* (its reduction only with probes) */
  for (int k = 0; k < sim->acc.nprobe && !ierr; k++) pf_ledger_set(&sim->ledger, sim->acc.probe0 + k, &probe[k]);
  free(probe);
  if (!ierr) ierr = pf_ledger_evaluate(&sim->ledger, first);
  for (int b = 0; b < sim->nbodies && !ierr; b++) body_centre(sim, b);
  double bonds = 0, broken = 0;
  for (int b = 0; b < sim->nbodies; b++)
    bonds += pf_ledger_value(&sim->ledger, sim->acc.body[b].bonds, 0),
        broken += pf_ledger_value(&sim->ledger, sim->acc.body[b].broken, 0);
  sim->ledger.a[sim->acc.totals.damage_fraction].value[0] = bonds > 0 ? broken / bonds : 0;
  return ierr;
}

/* w[0]: the stored energy the failed bonds took, w[1] the part of it moved, not released (<= 0;
 * docs/theory/pd.md §5.1): the dissipation is the rest. */
void pf_sim_accounts_book_damage(pf_sim *sim) {
  for (int b = 0; b < sim->nbodies; b++) {
    double w[2] = {0, 0};
    pf_body_take_damage_work(&sim->body[b], w);
    pf_ledger_add(&sim->ledger, sim->acc.body[b].damage, w[0] - w[1]);
    pf_ledger_add(&sim->ledger, sim->acc.body[b].redistribution, w[1]);
  }
}

double pf_sim_total(const pf_sim *sim, int id) { return id >= 0 ? pf_ledger_value(&sim->ledger, id, 0) : 0.0; }

double pf_sim_energy_scale(const pf_sim *sim) {
  const pf_sim_totals *T = &sim->acc.totals;
  const double in_play = pf_sim_total(sim, T->kinetic) + pf_sim_total(sim, T->elastic) +
                         pf_sim_total(sim, T->contact) + fabs(pf_sim_total(sim, T->fe_internal));
  return fmax(fabs(sim->ledger.e0), fmax(fabs(pf_sim_total(sim, T->work)), in_play));
}

double pf_sim_energy_error(const pf_sim *sim) {
  const double scale = pf_sim_energy_scale(sim);
  return scale > 0 ? fabs(pf_sim_total(sim, sim->acc.totals.error)) / scale : 0.0;
}
