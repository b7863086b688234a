/* Equilibrium of a load step by PETSc's SNES (solver.method: snes; docs/theory/quasi_static_methods.md
 * §9.1): the inexact Newton method of solver_newton.c, its parts taken from the library. With
 * F(u) the force on the free components (the bodies' history put back as committed at the load
 * step's start before each evaluation) the nonlinear function is -F, whose Jacobian K is the
 * stiffness:
 *   SNESNEWTONLS with the backtracking line search (SNESLINESEARCHBT; Dennis & Schnabel 1996 §6.3);
 *   the Jacobian-free product of MatCreateSNESMF (Knoll & Keyes 2004 §2.2; PETSc picks the
 *   differencing parameter);
 *   KSPCG to the relative residual SNES_FORCING (as solver_newton.c), preconditioned by a PCSHELL
 *   dividing by the fictitious masses lambda (the Gershgorin bounds of K's rows, §2);
 *   the convergence test the other methods use (pf_sim_solver_measure: the residual relative to
 *   the reference force, summed so that it is the same on any number of ranks).
 * PETSc's own dot products and norms are MPI sums that depend on how the components are spread
 * over the ranks, so the iterates are not the same bits on 1, 2 and 3 ranks (the hand-written
 * newton_krylov's are): the equilibria agree to the tolerance. It gives up, and the relaxation
 * goes on from its last iterate, when SNES does not converge (negative curvature in CG, a line
 * search that finds no decrease, SNES_MAX_NEWTON iterations). PETSc's library is opened and
 * initialised at the first load step (sim/petsc_library.h; without its signal handlers: the
 * run's own catch SIGTERM and SIGINT) and finalised when MPI is (an attribute of MPI_COMM_SELF,
 * deleted first by MPI_Finalize). */
#include "sim/petsc_library.h"
#include "sim/sim_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A PETSc call inside a PETSc callback or set-up: its error code returned as it is (PetscCall
 * would report it through PetscError, which the table of sim/petsc_library.h leaves out). */
#define PETSC_TRY(call)                                                                            \
  do {                                                                                             \
    PetscErrorCode e_ = (call);                                                                    \
    if (e_) return e_;                                                                             \
  } while (0)

enum { SNES_MAX_NEWTON = 40 };
static const double SNES_FORCING = 0.05;

typedef struct {
  pf_sim *sim;
  PetscInt nfree;
  pf_int *idx;   /* [nfree] the owned free components */
  double *u_at;  /* [nfree] u where the last measure was taken */
  double q[PF_SOLVER_SUMS], res;
  int measured, stop, failed; /* failed: a perifem error inside a callback (raised already) */
  long evaluations;
} snes_ctx;

static int finalize_petsc(MPI_Comm comm, int key, void *value, void *extra) {
  (void)comm, (void)key, (void)value, (void)extra;
  PetscBool fin = PETSC_FALSE;
  PetscFinalized(&fin);
  if (!fin) PetscFinalize();
  return MPI_SUCCESS;
}

/* PETSc once per process, finalised at the start of MPI_Finalize. */
static int start_petsc(void) {
  char why[512];
  PF_CHECK(pf_petsc_load(why, sizeof why) == 0, PF_ERR_LIB,
           "solver.method snes needs PETSc's library, which could not be opened: %s (Debian: petsc-dev)", why);
  PetscBool up = PETSC_FALSE;
  PetscInitialized(&up);
  if (up) return 0;
  static char name[] = "perifem", nosig[] = "-no_signal_handler";
  static char *args[] = {name, nosig, NULL};
  int argc = 2;
  char **argv = args;
  PF_CHECK(PetscInitialize(&argc, &argv, NULL, NULL) == 0, PF_ERR_LIB, "PETSc did not initialise (solver.method snes)");
  int key;
  PF_CHECK(MPI_Comm_create_keyval(MPI_COMM_NULL_COPY_FN, finalize_petsc, &key, NULL) == MPI_SUCCESS &&
               MPI_Comm_set_attr(MPI_COMM_SELF, key, NULL) == MPI_SUCCESS,
           PF_ERR_LIB, "MPI could not keep PETSc's finaliser");
  return 0;
}

/* u on the free components from x (y follows). */
static void put(snes_ctx *c, const PetscScalar *x) {
  pf_points *p = c->sim->pts;
  for (PetscInt k = 0; k < c->nfree; k++) {
    const pf_int d = c->idx[k];
    p->u[d] = x[k], p->y[d] = p->X[d] + x[k];
  }
}

/* The forces at x, and the iteration's sums there (the residual the convergence test reads). */
static int evaluate_at(snes_ctx *c, const PetscScalar *x) {
  put(c, x);
  c->evaluations++;
  PF_CALL(pf_sim_solver_evaluate(c->sim));
  PF_CALL(pf_sim_solver_measure(c->sim, c->q));
  c->res = pf_sim_solver_residual(c->q);
  memcpy(c->u_at, x, sizeof(double) * (size_t)c->nfree);
  c->measured = 1;
  return 0;
}

static PetscErrorCode function(SNES snes, Vec x, Vec f, void *ctx) {
  (void)snes;
  snes_ctx *c = ctx;
  const PetscScalar *xa;
  PetscScalar *fa;
  PETSC_TRY(VecGetArrayRead(x, &xa));
  int ierr = evaluate_at(c, xa);
  PETSC_TRY(VecRestoreArrayRead(x, &xa));
  if (ierr) {
    c->failed = 1;
    return PETSC_ERR_USER;
  }
  PETSC_TRY(VecGetArray(f, &fa));
  for (PetscInt k = 0; k < c->nfree; k++) fa[k] = -c->sim->pts->f[c->idx[k]];
  PETSC_TRY(VecRestoreArray(f, &fa));
  return 0;
}

/* The relative residual at the current iterate (measured again unless the last evaluation was
 * there: MFFD's products evaluate at probes), against solver.tolerance. */
static PetscErrorCode converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal gnorm, PetscReal fnorm,
                                SNESConvergedReason *reason, void *ctx) {
  (void)xnorm, (void)gnorm, (void)fnorm;
  snes_ctx *c = ctx;
  Vec x;
  const PetscScalar *xa;
  PETSC_TRY(SNESGetSolution(snes, &x));
  PETSC_TRY(VecGetArrayRead(x, &xa));
  int here = c->measured && !memcmp(xa, c->u_at, sizeof(double) * (size_t)c->nfree), ierr = here ? 0 : evaluate_at(c, xa);
  PETSC_TRY(VecRestoreArrayRead(x, &xa));
  if (ierr) {
    c->failed = 1;
    return PETSC_ERR_USER;
  }
  c->stop = c->q[S_TRIPPED] > 0 || !isfinite(c->res) ? STOP_GUARD : c->q[S_SIGNAL] > 0 ? STOP_SIGNAL : 0;
  *reason = c->stop ? SNES_DIVERGED_FUNCTION_DOMAIN /* (a guard, a signal: c->stop says which) */
            : c->res <= c->sim->solver.tolerance                   ? SNES_CONVERGED_FNORM_ABS
            : it >= SNES_MAX_NEWTON                                ? SNES_DIVERGED_MAX_IT
            : c->evaluations >= c->sim->solver.max_iterations      ? SNES_DIVERGED_FUNCTION_COUNT
                                                                   : SNES_CONVERGED_ITERATING;
  return 0;
}

static PetscErrorCode precondition(PC pc, Vec r, Vec z) {
  snes_ctx *c;
  const PetscScalar *ra;
  PetscScalar *za;
  PETSC_TRY(PCShellGetContext(pc, &c));
  PETSC_TRY(VecGetArrayRead(r, &ra));
  PETSC_TRY(VecGetArray(z, &za));
  for (PetscInt k = 0; k < c->nfree; k++) za[k] = ra[k] / c->sim->solver.lambda[c->idx[k] / 3];
  PETSC_TRY(VecRestoreArray(z, &za));
  PETSC_TRY(VecRestoreArrayRead(r, &ra));
  return 0;
}

/* SNES, its Krylov solver and preconditioner, and the Jacobian-free operator. */
static PetscErrorCode build(snes_ctx *c, Vec x, Vec r, SNES *snes, Mat *J) {
  KSP ksp;
  PC pc;
  SNESLineSearch ls;
  PETSC_TRY(SNESCreate(PETSC_COMM_WORLD, snes));
  PETSC_TRY(SNESSetType(*snes, SNESNEWTONLS));
  PETSC_TRY(SNESSetFunction(*snes, r, function, c)); /* (r: its sizes make the operator's) */
  PETSC_TRY(MatCreateSNESMF(*snes, J));
  PETSC_TRY(SNESSetJacobian(*snes, *J, *J, MatMFFDComputeJacobian, NULL));
  PETSC_TRY(SNESSetConvergenceTest(*snes, converged, c, NULL));
  PETSC_TRY(SNESSetTolerances(*snes, 0, 0, 0, SNES_MAX_NEWTON, (PetscInt)c->sim->solver.max_iterations));
  PETSC_TRY(SNESGetLineSearch(*snes, &ls));
  PETSC_TRY(SNESLineSearchSetType(ls, SNESLINESEARCHBT));
  PETSC_TRY(SNESGetKSP(*snes, &ksp));
  PETSC_TRY(KSPSetType(ksp, KSPCG));
  PETSC_TRY(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED)); /* (||F - K du|| <= eta ||F||, as newton_krylov) */
  PETSC_TRY(KSPSetTolerances(ksp, SNES_FORCING, 0, PETSC_DEFAULT, (PetscInt)c->sim->solver.max_iterations));
  PETSC_TRY(KSPGetPC(ksp, &pc));
  PETSC_TRY(PCSetType(pc, PCSHELL));
  PETSC_TRY(PCShellSetContext(pc, c));
  PETSC_TRY(PCShellSetApply(pc, precondition));
  PETSC_TRY(SNESSetFromOptions(*snes)); /* (PETSC_OPTIONS may tune it) */
  PETSC_TRY(SNESSetSolution(*snes, x));
  return 0;
}

/* The owned free components and x = u there. */
static int setup(snes_ctx *c, Vec *x) {
  const pf_points *p = c->sim->pts;
  const pf_int n3 = 3 * p->n_owned;
  c->nfree = 0;
  for (pf_int d = 0; d < n3; d++) c->nfree += pf_sim_solver_is_free(&c->sim->solver, d);
  c->idx = malloc(sizeof(pf_int) * ((size_t)c->nfree + 1));
  c->u_at = malloc(sizeof(double) * ((size_t)c->nfree + 1));
  PF_CHECK(c->idx && c->u_at, PF_ERR_MEMORY, "out of memory for the SNES solver");
  PetscInt k = 0;
  for (pf_int d = 0; d < n3; d++)
    if (pf_sim_solver_is_free(&c->sim->solver, d)) c->idx[k++] = d;
  PetscScalar *xa;
  PF_CHECK(VecCreateMPI(PETSC_COMM_WORLD, c->nfree, PETSC_DETERMINE, x) == 0 && VecGetArray(*x, &xa) == 0, PF_ERR_LIB,
           "PETSc could not make the solution vector");
  for (k = 0; k < c->nfree; k++) xa[k] = p->u[c->idx[k]];
  VecRestoreArray(*x, &xa);
  return 0;
}

int pf_sim_solver_snes(pf_sim *sim, long *it, double *res, int *stop, int *is_converged) {
  pf_sim_solver *s = &sim->solver;
  snes_ctx c = {.sim = sim};
  SNES snes = NULL;
  Mat J = NULL;
  Vec x = NULL, r = NULL;
  *is_converged = 0, *stop = 0;
  PF_CALL(start_petsc());
  memset(s->vel, 0, sizeof(double) * 3 * (size_t)sim->pts->n_owned); /* (the damping sums of measure: none) */
  int ierr = setup(&c, &x);
  if (!ierr && (VecDuplicate(x, &r) || build(&c, x, r, &snes, &J))) ierr = pf_error_raise(PF_ERR_LIB, __FILE__, __LINE__, __func__, "PETSc could not set up SNES");
  if (!ierr && SNESSolve(snes, NULL, x) && !c.failed)
    ierr = pf_error_raise(PF_ERR_LIB, __FILE__, __LINE__, __func__, "PETSc's SNESSolve failed");
  if (!ierr && c.failed) ierr = PF_ERR_RUN; /* (raised in the callback) */
  if (!ierr) {
    SNESConvergedReason reason;
    PetscInt newton = 0, krylov = 0;
    SNESGetConvergedReason(snes, &reason);
    SNESGetIterationNumber(snes, &newton);
    SNESGetLinearSolveIterations(snes, &krylov);
    s->newton_steps += newton, s->krylov_steps += krylov;
    *is_converged = reason > 0, *stop = c.stop, *res = c.res;
    const PetscScalar *xa;
    VecGetArrayRead(x, &xa);
    if (!c.measured || memcmp(xa, c.u_at, sizeof(double) * (size_t)c.nfree)) put(&c, xa); /* (relaxation evaluates) */
    VecRestoreArrayRead(x, &xa);
  }
  SNESDestroy(&snes), MatDestroy(&J), VecDestroy(&r), VecDestroy(&x);
  free(c.idx), free(c.u_at);
  *it = c.evaluations;
  return ierr;
}
