/* The interaction interface of the driver, the bodies' twin (docs/architecture.md §4b): whatever
 * acts on bodies without being one (rigid surfaces and indenters, contact between bodies, walls,
 * prescribed motions and loads) is an interaction kind, an ops table listed once in
 * sim/interaction_kinds.h. sim/ calls interactions only through the dispatchers below, which
 * give an optional op its default: no call site tests an op for NULL. Private to sim/.
 *
 * One step (sim/step.c) calls, in list order:
 *   half kick;  midstep (prescribed velocities);  drift;  after_drift (walls put points back,
 *   rigid surfaces move);  the ghosts' positions;  prepare (contact's search);  body forces;
 *   force (each rank's part of the sums) -> one reduction
 *   for every interaction -> take_sums (reactions, penalty energies into the ledger);  half kick;
 *   endstep (prescribed velocities, the step's work and impulse booked by the ledger's rule). */
#ifndef PF_SIM_INTERACTION_H
#define PF_SIM_INTERACTION_H

#include "core/core.h"
#include "sim/ledger.h"
#include "sim/sim.h"

/* What an interaction sees of the step. */
typedef struct {
  pf_points *pts;
  pf_ledger *ledger;
  double t;             /* the step's start (midstep, after_drift) or end (prepare, force, endstep), s */
  double dt;            /* the step, s (0: forces that advance nothing: the initial ones) */
  int nbodies;
  const int *body_work; /* [nbodies] each body's external-work account (sim/ledger.h) */
} pf_interaction_step;

typedef struct {
  const char *kind; /* in messages */
  /* Required: create every instance of the kind the deck asks for, each added with
   * pf_sim_interaction_add (after the bodies are named; before the points exist). */
  int (*build)(pf_sim *sim);
  int (*destroy)(void **data);
  /* Optional (default in brackets). Open the instance's ledger accounts [none]; after every
   * (re)partition, take the bodies' current points [nothing]; mark the velocity components it
   * prescribes (fixed[3 i + c] = 1) [none]. */
  int (*open_accounts)(void *data, pf_sim *sim);
  int (*attach)(void *data, pf_sim *sim);
  void (*mark_prescribed)(const void *data, uint8_t *fixed);
  /* The step's hooks [nothing]. */
  void (*midstep)(void *data, const pf_interaction_step *s);
  void (*after_drift)(void *data, const pf_interaction_step *s);
  /* Before the bodies' forces of an explicit step (and of the initial forces), the ghosts'
   * positions exchanged, at the positions and velocities force will see (no body's or
   * interaction's force moves a point or changes a velocity): work that needs nothing of the
   * bodies' forces (contact's search), whose exchanges then meet the ranks together [nothing;
   * force does it all]. */
  int (*prepare)(void *data, const pf_interaction_step *s);
  /* Forces at the current positions: add to pts->f, write this rank's part of nsums values into
   * sums; take_sums gets them summed over the ranks [no sums]. */
  int (*nsums)(const void *data);
  int (*force)(void *data, const pf_interaction_step *s, double *sums);
  void (*take_sums)(void *data, const pf_interaction_step *s, const double *sums);
  void (*endstep)(void *data, const pf_interaction_step *s);
  /* Quasi-static loading (sim/solver_relaxation.c): put the components it prescribes (a rigid
   * surface: itself) at their values at s->t, s->dt the load step; s->dt < 0: the load step is
   * abandoned, go back to its start (the solver then puts the points back) [nothing]. */
  void (*place)(void *data, const pf_interaction_step *s);
  /* Quasi-static loading: the load step from s->t - s->dt to s->t has reached its first
   * equilibrium, before its damage check; past it the load stays while bonds fail and the state
   * relaxes again: keep what the load step's work needs (a rigid surface: its force) [nothing]. */
  void (*loaded)(void *data, const pf_interaction_step *s);
  /* Quasi-static loading: the load step from s->t - s->dt to s->t has reached equilibrium; g0,
   * u0: [3 n_owned] the force from outside on each owned component (on a prescribed one its
   * reaction, minus the point's force; on a free one the loads, without the forces of the
   * interactions that book their own work) and the displacement at the load step's start; g1,
   * u1 the same at its first equilibrium (loaded), NULL when that is this one (no bond failed);
   * beyond: with sequential failure, each component's work along the scaled path past the first
   * equilibrium (else NULL: that part is the trapezoid from g1, u1 to the state now): book its
   * reactions and work. Collective [nothing]. */
  int (*settled)(void *data, const pf_interaction_step *s, const double *g0, const double *u0, const double *g1,
                 const double *u1, const double *beyond);
  /* Quasi-static loading: add to k[i] (N/m, over the owned points) a bound of the row sums of the
   * stiffness its forces add to point i, over the states the load step placed at s->t can reach
   * (the fictitious masses bound the interactions' stiffness with the bodies') [nothing]. */
  void (*stiffness_bounds)(const void *data, const pf_points *pts, double *k);
  /* Quasi-static loading: after each relaxation iteration moved the points, put back on its
   * constraint a point that went through it, with no inward velocity left in pts->v (the
   * relaxation's) [nothing]. */
  void (*project)(const void *data, pf_points *pts);
  /* 1: the work of its forces on the points is booked by the interaction itself (a moving rigid
   * surface's work, a fixed wall's none; its penalty energy is a potential), so the quasi-static
   * solver leaves its forces out of the trapezoid of the loads' work [0]. */
  int books_own_work;
  /* Add to w[i] (over the owned points) the work its force evaluation spends on point i, in bond
   * evaluations (the unit of the partition's weights, pf_partition_weight), for re-partitioning
   * [nothing]. */
  void (*work)(const void *data, const pf_points *pts, int *w);
  /* The stable step its penalties allow; collective [INFINITY]. */
  double (*stable_dt)(const void *data, const pf_points *pts);
  /* At set-up (a restart's too), before the time step is chosen: set what follows the bodies'
   * stable steps (a soft contact pair's stiffness); collective [nothing]. */
  int (*fit_step)(void *data, pf_sim *sim);
  /* Checkpoint state besides the ledger's accounts (a surface's position): count, names
   * (96 characters each), values and their restoring [none]; after a restart restored
   * everything [nothing]. */
  int (*nstate)(const void *data);
  void (*state_names)(const void *data, char (*names)[96]);
  void (*state_get)(const void *data, double *v);
  void (*state_set)(void *data, const double *v);
  int (*restored)(void *data);
  /* Before the first step: refuse an expression it evaluates (a prescribed motion, a load) that is
   * not finite at some time of [0, t_end] (nt + 1 times); collective [nothing]. */
  int (*check_finite)(void *data, pf_sim *sim, double t_end, int nt);
  /* At each history row: run-health checks, warning through pf_sim_health_warn; collective
   * [nothing]. */
  int (*health)(void *data, pf_sim *sim);
  /* The end-of-run summary line(s) [none]. */
  void (*summary)(const void *data, pf_sim *sim);
  /* Points took or lost mass (elements converted into particles) [nothing]. */
  void (*masses_changed)(void *data);
  /* The instance's name, for --check [the kind]. */
  const char *(*name)(const void *data);
} pf_interaction_ops;

/* An interaction of the simulation. */
typedef struct {
  const pf_interaction_ops *ops;
  void *data;
} pf_interaction;

#define PF_INTERACTION_KIND(id) extern const pf_interaction_ops pf_interaction_kind_##id;
#include "sim/interaction_kinds.h"
#undef PF_INTERACTION_KIND

/* The registered kinds in list order (sim/interaction_kinds.h). */
int pf_interaction_kind_count(void);
const pf_interaction_ops *pf_interaction_kind_at(int k);
/* Add a kind at run time (a program or a test with its own kind; before pf_sim_create). */
int pf_interaction_kind_register(const pf_interaction_ops *ops);
/* Add an instance (a kind's build); a kind missing a required op is refused naming it. */
int pf_sim_interaction_add(pf_sim *sim, const pf_interaction_ops *ops, void *data);

/* The dispatchers, over every interaction in list order. */
int pf_sim_interactions_build(pf_sim *sim);
void pf_sim_interactions_destroy(pf_sim *sim);
int pf_sim_interactions_open_accounts(pf_sim *sim);
int pf_sim_interactions_attach(pf_sim *sim);
/* Each owned point's work in the interactions' force evaluations, added to w[n_owned]. */
void pf_sim_interactions_work(const pf_sim *sim, int *w);
void pf_sim_interactions_mark(const pf_sim *sim, uint8_t *fixed);
void pf_sim_interactions_midstep(pf_sim *sim, double dt);
void pf_sim_interactions_after_drift(pf_sim *sim, double dt);
/* Each interaction's prepare ahead of the bodies' forces (explicit steps). Collective. */
int pf_sim_interactions_prepare(pf_sim *sim, double dt);
/* Forces of every interaction at the current positions with one reduction of their sums;
 * dt: the step just taken; own: NULL, or [3 n_owned] set to the part of the forces from the
 * interactions that book their own work (books_own_work). Collective. */
int pf_sim_interactions_force(pf_sim *sim, double dt, double *own);
void pf_sim_interactions_endstep(pf_sim *sim, double dt);
void pf_sim_interactions_place(pf_sim *sim, double dt);
void pf_sim_interactions_loaded(pf_sim *sim, double dt);
int pf_sim_interactions_settled(pf_sim *sim, double dt, const double *g0, const double *u0, const double *g1,
                                const double *u1, const double *beyond);
void pf_sim_interactions_stiffness_bounds(const pf_sim *sim, double *k);
void pf_sim_interactions_project(const pf_sim *sim);
double pf_sim_interactions_stable_dt(const pf_sim *sim);
int pf_sim_interactions_fit_step(pf_sim *sim);
/* Interaction k's stable step (--check); collective. */
double pf_sim_interaction_stable_dt(const pf_sim *sim, int k);
int pf_sim_interactions_nstate(const pf_sim *sim);
void pf_sim_interactions_state_names(const pf_sim *sim, char (*names)[96]);
void pf_sim_interactions_state_get(const pf_sim *sim, double *v);
void pf_sim_interactions_state_set(pf_sim *sim, const double *v);
int pf_sim_interactions_restored(pf_sim *sim);
int pf_sim_interactions_health(pf_sim *sim);
int pf_sim_interactions_check_finite(pf_sim *sim, double t_end, int nt);
void pf_sim_interactions_summary(pf_sim *sim);
void pf_sim_interactions_masses_changed(pf_sim *sim);
/* Interaction k's name and kind (--check). */
const char *pf_sim_interaction_name(const pf_sim *sim, int k);

#endif
