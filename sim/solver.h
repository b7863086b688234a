/* The solver the deck selects (`solver:`): explicit dynamics (velocity Verlet, sim/step.c; the
 * default) or quasi-static loading by adaptive dynamic relaxation (sim/solver_relaxation.c) or
 * Newton-Krylov (sim/solver_newton.c), over sim/solver_forces.c (docs/
 * theory/quasi_static.md). The quasi-static solver takes a "step" of the time loop as one load
 * step: the boundary conditions at pseudo-time t_k = k / N final_time, relaxed to equilibrium over
 * the same force evaluation as the explicit step. Private to sim/. */
#ifndef PF_SIM_SOLVER_H
#define PF_SIM_SOLVER_H

#include "core/core.h"
#include "sim/sim.h"

enum { PF_SOLVER_SUMS = 7 }; /* the sums of an iteration (sim/solver_relaxation.c) */
enum { S_RESIDUAL, S_REFERENCE, S_INTERNAL, S_UKU, S_UU, S_TRIPPED, S_SIGNAL }; /* their order */
enum { STOP_GUARD = 1, STOP_SIGNAL = 2 }; /* why a load step stopped before equilibrium */
typedef enum { PF_SOLVER_EXPLICIT, PF_SOLVER_QUASI_STATIC } pf_solver_type;
typedef enum { PF_SOLVER_RELAXATION, PF_SOLVER_NEWTON_KRYLOV, PF_SOLVER_SNES } pf_solver_method;

typedef struct {
  pf_solver_type type;
  pf_solver_method method;
  int (*load_step)(pf_sim *sim); /* the step the time loop takes (NULL: the explicit one, sim/step.c) */
  long load_steps;     /* N */
  double tolerance;    /* the residual relative to the reference force at convergence */
  long max_iterations; /* per load step */
  long max_damage_passes; /* re-equilibrations after bonds failed, per load step */
  int sequential;      /* failure: sequential (each bond's limit; docs/theory/quasi_static_failure.md §5.2) */
  long scalings;       /* sequential: the states scaled over every load step */
  double lam;          /* sequential: the grips' place as a fraction of the load step's target */
  /* what the run did: iterations, force evaluations and damage passes over every load step */
  long iterations, evaluations, damage_passes;
  long newton_steps, krylov_steps, fallbacks; /* newton_krylov: its iterations, and load steps relaxed after it */
  double wall; /* seconds in the load steps */
  /* the load step's scratch, [3 n] each over the owned points (n: as allocated) */
  pf_int n;
  double *lambda;  /* [n] fictitious mass per point (Kilic & Madenci 2010), kg s^-2 x (1 s)^2 */
  double *vel;     /* the relaxation's velocity u-dot^(n-1/2), m per iteration */
  double *f_old;   /* F^(n-1), the force of the previous iteration */
  double *u_last;  /* u at the last force evaluation (the bodies read v = u - u_last, dt = 1) */
  double *u_relax; /* u where the relaxation started (the damping's quotient reads u - u_relax) */
  double *f_body;  /* the bodies' part of the last evaluation (the rest is the interactions') */
  double *f_own;   /* the part of the interactions that book their own work (rigid surfaces, walls) */
  double *u0, *g0; /* u and the applied force (reaction or load) at the load step's start */
  double *u1, *g1; /* the same at its first equilibrium, before its damage checks failed a bond */
  double held1;    /* the energy the ledger holds there, J (sim/solver_relaxation.c, loaded) */
  double *um, *gm; /* sequential: u and the applied force at the path's last mark */
  double *beyond;  /* sequential: each component's work along the path past the first equilibrium, J */
  double *terms;   /* [PF_SOLVER_SUMS 3 n] each iteration's terms of its sums */
  double *kept;    /* [kept_n] the load step's start: point fields, the ledger's bookings */
  size_t kept_n;
  uint8_t *fixed;  /* [3 n] prescribed components */
  double *nk;      /* newton_krylov: [NK_ARRAYS 3 n] (sim/solver_newton.c) */
  pf_int nk_n;
} pf_sim_solver;

/* The point field of the last load step's displacement increment (the next load step's predictor;
 * carried by re-partitions and checkpoints). */
#define PF_SOLVER_INCREMENT "load_step_increment"

/* sim/solver.c: the `solver:` keys; read the section (after the time and output set-up: the
 * load steps replace time.dt and the step count, history rows come at every load step unless
 * a history key of the output says otherwise); refuse decks the quasi-static solver cannot run (no
 * load: neither a boundary condition nor a moving rigid surface; an initial velocity; no
 * time.final_time) as input errors naming file:line and key; the summary line; free the scratch.
 * pf_sim_check_solver_keys does the checks that need no model before the bodies are built, so
 * that a slip there is reported at once rather than after the set-up. */
extern const pf_key pf_sim_solver_keys[];
int pf_sim_check_solver_keys(const pf_deck *d);
int pf_sim_setup_solver(pf_sim *sim);
void pf_sim_solver_summary(const pf_sim *sim);
void pf_sim_solver_free(pf_sim *sim);
/* sim/solver_relaxation.c: one load step (the time loop's step when the solver is quasi-static):
 * t and step advance by one load step, the state relaxed to equilibrium; a load step that does
 * not converge in max_iterations is a run error naming it, the residual and the iterations.
 * Collective. */
int pf_sim_solver_load_step(pf_sim *sim);
/* The force from outside whose work the solver books on component d: the reaction on a prescribed
 * one; on a free one the interactions' force less that of the interactions that book their own
 * work (a rigid surface's, a wall's). */
static inline double pf_sim_solver_applied(const pf_sim_solver *s, const pf_points *p, pf_int d) {
  return s->fixed[d] ? -p->f[d] : p->f[d] - s->f_body[d] - s->f_own[d];
}
/* sim/solver_sequential.c, failure: sequential (docs/theory/quasi_static_failure.md §5.2): the deck's
 * refusals (set-up; input errors naming file:line and key); a load step's prescribed components
 * in proportion to t (its start; a run error otherwise); the largest failure ratio over the
 * bodies and ranks; the path's mark at the current state (beyond zeroed: the first equilibrium)
 * and the segment from the mark to the current state booked into beyond; the state scaled by a
 * (lam with it; back at the target the load step places its components exactly), evaluated
 * and booked as a segment. Collective (but the mark and the segment). */
int pf_sim_solver_sequential_check(const pf_sim *sim, const pf_node *sv);
int pf_sim_solver_proportional(pf_sim *sim);
double pf_sim_solver_failure_ratio(pf_sim *sim);
void pf_sim_solver_path_mark(pf_sim *sim);
void pf_sim_solver_path_segment(pf_sim *sim);
int pf_sim_solver_scale(pf_sim *sim, double a);
/* sim/solver_forces.c, what both methods use: whether component d is free; the forces at the current
 * u (p->f: everything; s->f_body: the bodies'); the iteration's sums (q[PF_SOLVER_SUMS]); the
 * residual relative to the reference force. */
int pf_sim_solver_is_free(const pf_sim_solver *s, pf_int d);
int pf_sim_solver_evaluate(pf_sim *sim);
int pf_sim_solver_measure(pf_sim *sim, double *q);
/* Component d's terms of the damping's Rayleigh quotient (docs/theory/quasi_static.md §2):
 * u_d 1K_dd u_d into *uku and u_d^2 into *uu, both 0 on a component that is not free. */
void pf_sim_solver_quotient_terms(const pf_sim_solver *s, const pf_points *p, pf_int d, double *uku, double *uu);
double pf_sim_solver_residual(const double *q);
/* sim/solver_newton.c: equilibrium by inexact Newton with a matrix-free, Jacobi-preconditioned
 * conjugate-gradient step and a backtracking line search, from the current state; *converged 0
 * when it gave up (negative curvature, a line search that found no decrease, or its iteration
 * limit), the state left at its best point for the relaxation to go on from. *it force
 * evaluations. Collective. */
int pf_sim_solver_newton(pf_sim *sim, long *it, double *res, int *stop, int *converged);
/* sim/solver_snes.c: the same by PETSc's SNES (Newton with a backtracking line search, its
 * Jacobian-free operator, CG preconditioned by the fictitious masses): not the same bits on any
 * number of ranks (PETSc's sums depend on the partition). Collective. */
int pf_sim_solver_snes(pf_sim *sim, long *it, double *res, int *stop, int *converged);
/* A sum over every rank's terms x[0 .. n-1] that does not depend on how the terms are spread
 * over the ranks (each term rounded to a grid fixed by the largest |x| over the ranks, the
 * integers summed): the same bits on any number of ranks. m sums at once: x[j n .. j n + n-1]
 * into out[j]. Collective. */
int pf_sim_solver_sums(const double *x, pf_int n, int m, double *out);

#endif
