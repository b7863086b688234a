/* The `solver:` section (sim/solver.h): explicit dynamics by default, or quasi-static loading by
 * adaptive dynamic relaxation. Reads and checks the keys, and what a quasi-static run needs of the
 * rest of the deck; the load steps take the place of the time steps. */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <string.h>

const pf_key pf_sim_solver_keys[] = {
    {"type", PF_KEY_STRING, 0, "explicit", "",
     "explicit (velocity-Verlet dynamics) | quasi_static (load steps relaxed to equilibrium by adaptive "
     "dynamic relaxation; docs/theory/quasi_static.md)", NULL},
    {"method", PF_KEY_STRING, 0, "relaxation", "",
     "quasi_static: relaxation (adaptive dynamic relaxation) | newton_krylov (inexact Newton with a matrix-free "
     "preconditioned conjugate-gradient step, relaxation where it gives up; no walls; the same bits on any number "
     "of ranks) | snes (the same Newton step by PETSc's SNES and KSP; not the same bits on different numbers of "
     "ranks)", NULL},
    {"load_steps", PF_KEY_INT, 0, "10", "",
     "quasi_static: load steps N; load step k applies the boundary conditions at t = k / N time.final_time", NULL},
    {"tolerance", PF_KEY_REAL, 0, "1e-6", "",
     "quasi_static: a load step has converged when the out-of-balance force on the free components (2-norm) "
     "is below tolerance x the reference force (the reactions' and loads' 2-norm, else the internal forces')",
     NULL},
    {"max_iterations", PF_KEY_INT, 0, "100000", "",
     "quasi_static: relaxation iterations allowed per load step (one force evaluation each); a load step "
     "that has not converged then stops the run with an error", NULL},
    {"max_damage_passes", PF_KEY_INT, 0, "1000", "",
     "quasi_static: bodies fail no bond while a load step relaxes; at equilibrium one damage check fails the "
     "bonds whose limit is met and, if any failed, the load step relaxes again at the same load: at most this "
     "many times per load step, then the run stops with an error", NULL},
    {"failure", PF_KEY_STRING, 0, "at_equilibrium", "",
     "quasi_static: at_equilibrium (the bonds are checked at each equilibrium the load steps reach) | sequential "
     "(sequentially linear: before each check the state and the grips are scaled so that the most critical bond "
     "just meets its limit; bonds then fail at their limit, not past it; prescribed displacements linear in t, "
     "bodies without history, no walls, rigid surfaces, contact or body forces; docs/theory/quasi_static.md)",
     NULL},
    PF_KEY_END};

/* The rigid surfaces of the deck (`indenters:` and `contact: rigid_surfaces:`): list k of 2. */
static const pf_node *surfaces(const pf_node *root, int k) {
  return k == 0 ? pf_node_get(root, "indenters") : pf_node_get(pf_node_get(root, "contact"), "rigid_surfaces");
}

/* A rigid surface with a velocity is a load (friction, of a rigid surface or a contact pair, is a
 * tangential penalty under this solver: contact/rigid.c, contact/pairs.c). */
static int surfaces_move(const pf_node *root) {
  int moving = 0;
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < pf_node_count(surfaces(root, k)); j++)
      moving |= pf_node_get(pf_node_item(surfaces(root, k), j), "velocity") != NULL;
  return moving;
}

/* What a quasi-static run needs of the rest of the deck. */
static int check_deck(const pf_deck *d, const pf_node *sv) {
  const pf_node *root = pf_deck_root(d), *n;
  if (pf_node_count(pf_node_get(root, "boundary_conditions")) == 0 && !surfaces_move(root))
    return pf_deck_error(d, pf_node_get(sv, "type"), "type",
                         "a quasi_static solver needs a load: give boundary_conditions (displacement, velocity or "
                         "body_force) or a rigid surface that moves (indenters or contact.rigid_surfaces with a "
                         "velocity)");
  const pf_node *bodies = pf_node_get(root, "bodies");
  for (int b = 0; b < pf_node_count(bodies); b++)
    if ((n = pf_node_get(pf_node_item(bodies, b), "initial_velocity"))) {
      const char *name = "";
      PF_CALL(pf_deck_string(d, pf_node_item(bodies, b), "name", &name));
      return pf_deck_error(d, n, "initial_velocity",
                           "a quasi_static solver starts at rest: remove the initial velocity of body '%s'", name);
    }
  if (!pf_node_get(pf_node_get(root, "time"), "final_time"))
    return pf_deck_error(d, pf_node_get(root, "time"), "final_time",
                         "a quasi_static solver needs time.final_time: the pseudo-time of the last load step");
  return 0;
}

static int read_numbers(const pf_deck *d, const pf_node *sv, pf_sim_solver *s) {
  PF_CALL(pf_deck_int(d, sv, "load_steps", &s->load_steps));
  PF_CALL(pf_deck_real(d, sv, "tolerance", &s->tolerance));
  PF_CALL(pf_deck_int(d, sv, "max_iterations", &s->max_iterations));
  PF_CALL(pf_deck_int(d, sv, "max_damage_passes", &s->max_damage_passes));
  const char *method = "relaxation";
  PF_CALL(pf_deck_string(d, sv, "method", &method));
  if (strcmp(method, "relaxation") && strcmp(method, "newton_krylov") && strcmp(method, "snes"))
    return pf_deck_error(d, pf_node_get(sv, "method"), "method", "relaxation, newton_krylov or snes (got '%s')",
                         method);
  s->method = !strcmp(method, "relaxation") ? PF_SOLVER_RELAXATION
              : !strcmp(method, "snes")     ? PF_SOLVER_SNES
                                            : PF_SOLVER_NEWTON_KRYLOV;
  const char *failure = "at_equilibrium";
  PF_CALL(pf_deck_string(d, sv, "failure", &failure));
  if (strcmp(failure, "at_equilibrium") && strcmp(failure, "sequential"))
    return pf_deck_error(d, pf_node_get(sv, "failure"), "failure", "at_equilibrium or sequential (got '%s')", failure);
  s->sequential = !strcmp(failure, "sequential");
  if (s->method != PF_SOLVER_RELAXATION && pf_node_count(pf_node_get(pf_deck_root(d), "walls")) > 0)
    return pf_deck_error(d, pf_node_get(sv, "method"), "method",
                         "%s does not take walls (their points are projected back between relaxation iterations): "
                         "use method: relaxation, or a rigid plane (contact.rigid_surfaces)", method);
  if (s->load_steps < 1)
    return pf_deck_error(d, pf_node_get(sv, "load_steps"), "load_steps", "must be at least 1 (got %ld)", s->load_steps);
  if (!(s->tolerance > 0 && s->tolerance < 1))
    return pf_deck_error(d, pf_node_get(sv, "tolerance"), "tolerance", "must be in (0, 1) (got %g)", s->tolerance);
  if (s->max_iterations < 1)
    return pf_deck_error(d, pf_node_get(sv, "max_iterations"), "max_iterations", "must be at least 1 (got %ld)",
                         s->max_iterations);
  if (s->max_damage_passes < 0)
    return pf_deck_error(d, pf_node_get(sv, "max_damage_passes"), "max_damage_passes", "must be at least 0 (got %ld)",
                         s->max_damage_passes);
  return 0;
}

/* The solver section into *s (its type, and a quasi-static solver's numbers) and what a
 * quasi-static solver needs of the rest of the deck: all that needs no model. */
static int read_section(const pf_deck *d, pf_sim_solver *s) {
  const pf_node *sv = pf_node_get(pf_deck_root(d), "solver");
  *s = (pf_sim_solver){.type = PF_SOLVER_EXPLICIT, .load_steps = 10, .tolerance = 1e-6, .max_iterations = 100000,
                        .max_damage_passes = 1000};
  const char *chosen = "explicit";
  PF_CALL(pf_deck_string(d, sv, "type", &chosen));
  if (!strcmp(chosen, "explicit")) return 0;
  if (strcmp(chosen, "quasi_static"))
    return pf_deck_error(d, pf_node_get(sv, "type"), "type", "explicit or quasi_static (got '%s')", chosen);
  s->type = PF_SOLVER_QUASI_STATIC;
  PF_CALL(read_numbers(d, sv, s));
  return check_deck(d, sv);
}

int pf_sim_check_solver_keys(const pf_deck *d) {
  pf_sim_solver s;
  return read_section(d, &s);
}

int pf_sim_setup_solver(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *root = pf_deck_root(d), *sv = pf_node_get(root, "solver");
  pf_sim_solver *s = &sim->solver;
  PF_CALL(read_section(d, s));
  if (s->type == PF_SOLVER_EXPLICIT) return pf_body_kinds_check_dynamic_forms(d, sim->nsteps, sim->body_name);
  s->load_step = pf_sim_solver_load_step;
  if (s->sequential) PF_CALL(pf_sim_solver_sequential_check(sim, sv));
  int idx;
  PF_CALL(pf_points_field_register(sim->pts, PF_SOLVER_INCREMENT, 3, PF_FIELD_RESTART, &idx));
  sim->nsteps = s->load_steps; /* one step of the time loop per load step */
  sim->dt = sim->final_time / (double)s->load_steps;
  sim->adaptive = 0;
  const pf_node *out = pf_node_get(root, "output");
  if (!pf_node_get(out, "history_interval") && !pf_node_get(out, "history_time_interval") &&
      !pf_node_get(out, "history_frames"))
    sim->history_interval = 1;
  pf_log("solver: quasi-static, %ld load steps of %g s (pseudo-time), tolerance %g, at most %ld iterations each%s\n",
         s->load_steps, sim->dt, s->tolerance, s->max_iterations, s->sequential ? ", sequential failure" : "");
  return 0;
}

void pf_sim_solver_summary(const pf_sim *sim) {
  const pf_sim_solver *s = &sim->solver;
  if (s->type != PF_SOLVER_QUASI_STATIC) return;
  /* (this run's: after a restart, the load steps since the checkpoint; the counters are not in it) */
  pf_log("  quasi-static: load steps %ld to %ld of %ld, %ld iterations, %ld force evaluations, %ld damage "
         "passes in %.2f s\n",
         sim->step - sim->loop_steps + (sim->loop_steps > 0), sim->step, s->load_steps, s->iterations, s->evaluations,
         s->damage_passes, s->wall);
  if (s->sequential) pf_log("  sequential failure: %ld scaled states\n", s->scalings);
  if (s->method != PF_SOLVER_RELAXATION)
    pf_log("  %s: %ld Newton steps, %ld conjugate-gradient steps; %ld equilibria finished by relaxation\n",
           s->method == PF_SOLVER_SNES ? "snes (PETSc)" : "newton_krylov", s->newton_steps, s->krylov_steps,
           s->fallbacks);
}

void pf_sim_solver_free(pf_sim *sim) {
  pf_sim_solver *s = &sim->solver;
  free(s->lambda), free(s->vel), free(s->f_old), free(s->u_last), free(s->f_body), free(s->u0), free(s->g0);
  free(s->u1), free(s->g1), free(s->fixed), free(s->terms), free(s->f_own), free(s->nk), free(s->um);
  free(s->u_relax), free(s->kept);
  s->terms = NULL, s->nk = NULL, s->um = s->gm = s->beyond = s->u_relax = s->kept = NULL;
  s->kept_n = 0;
  s->lambda = s->vel = s->f_old = s->u_last = s->f_body = s->f_own = s->u0 = s->g0 = s->u1 = s->g1 = NULL;
  s->fixed = NULL;
  s->n = 0;
}
