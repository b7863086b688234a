/* PETSc's library, loaded when a deck first selects `solver.method: snes` instead of at start-up.
 * PETSc brings about 50 other libraries (hypre, MUMPS, ScaLAPACK, SuperLU, OpenCL): linked into
 * perifem, they cost every run about 35 ms of CPU per process to load and raised the set-up's
 * resident peak of a 6-million-bond box from 191 to 260 MB (tests/regression/setup_memory.sh),
 * whether or not the deck used PETSc. The calls in sim/solver_snes.c keep PETSc's own names:
 * after this header, SNESCreate(...) calls through the table pf_petsc, which pf_petsc_load()
 * fills from the library the build found (PF_PETSC_LIBRARY). Private to sim/. */
#ifndef PF_SIM_PETSC_LIBRARY_H
#define PF_SIM_PETSC_LIBRARY_H

#include <petscsnes.h>
#include <stddef.h>

/* X(name): every PETSc function perifem calls */
#define PF_PETSC_FUNCTIONS(X)                                                                      \
  X(PetscInitialized) X(PetscFinalized) X(PetscInitialize) X(PetscFinalize) X(VecCreateMPI)       \
  X(VecDuplicate) X(VecDestroy) X(VecGetArray) X(VecRestoreArray) X(VecGetArrayRead)              \
  X(VecRestoreArrayRead) X(MatDestroy) X(MatCreateSNESMF) X(MatMFFDComputeJacobian) X(SNESCreate) \
  X(SNESDestroy) X(SNESSetType) X(SNESSetFunction) X(SNESSetJacobian) X(SNESSetConvergenceTest)   \
  X(SNESSetTolerances) X(SNESGetLineSearch) X(SNESLineSearchSetType) X(SNESGetKSP)               \
  X(SNESSetFromOptions) X(SNESSetSolution) X(SNESGetSolution) X(SNESSolve)                       \
  X(SNESGetConvergedReason) X(SNESGetIterationNumber) X(SNESGetLinearSolveIterations)            \
  X(KSPSetType) X(KSPSetNormType) X(KSPSetTolerances) X(KSPGetPC) X(PCSetType)                   \
  X(PCShellSetContext) X(PCShellGetContext) X(PCShellSetApply)

typedef struct {
#define PF_PETSC_POINTER(name) __typeof__(name) *name;
  PF_PETSC_FUNCTIONS(PF_PETSC_POINTER)
#undef PF_PETSC_POINTER
  MPI_Comm *comm_world; /* PETSc's PETSC_COMM_WORLD */
} pf_petsc_api;

extern pf_petsc_api pf_petsc;

/* Load the library and fill pf_petsc (once per process; later calls return at once). 0, or -1
 * with the reason (dlopen's or dlsym's message) in why[len]. */
int pf_petsc_load(char *why, size_t len);

/* PETSc's names from here on call through the table (a macro is not expanded inside its own
 * expansion, so pf_petsc.SNESCreate names the member); not in the file that fills it */
#ifndef PF_PETSC_LIBRARY_SOURCE
#define PetscInitialized (*pf_petsc.PetscInitialized)
#define PetscFinalized (*pf_petsc.PetscFinalized)
#define PetscInitialize (*pf_petsc.PetscInitialize)
#define PetscFinalize (*pf_petsc.PetscFinalize)
#define VecCreateMPI (*pf_petsc.VecCreateMPI)
#define VecDuplicate (*pf_petsc.VecDuplicate)
#define VecDestroy (*pf_petsc.VecDestroy)
#define VecGetArray (*pf_petsc.VecGetArray)
#define VecRestoreArray (*pf_petsc.VecRestoreArray)
#define VecGetArrayRead (*pf_petsc.VecGetArrayRead)
#define VecRestoreArrayRead (*pf_petsc.VecRestoreArrayRead)
#define MatDestroy (*pf_petsc.MatDestroy)
#define MatCreateSNESMF (*pf_petsc.MatCreateSNESMF)
#define MatMFFDComputeJacobian (*pf_petsc.MatMFFDComputeJacobian)
#define SNESCreate (*pf_petsc.SNESCreate)
#define SNESDestroy (*pf_petsc.SNESDestroy)
#define SNESSetType (*pf_petsc.SNESSetType)
#define SNESSetFunction (*pf_petsc.SNESSetFunction)
#define SNESSetJacobian (*pf_petsc.SNESSetJacobian)
#define SNESSetConvergenceTest (*pf_petsc.SNESSetConvergenceTest)
#define SNESSetTolerances (*pf_petsc.SNESSetTolerances)
#define SNESGetLineSearch (*pf_petsc.SNESGetLineSearch)
#define SNESLineSearchSetType (*pf_petsc.SNESLineSearchSetType)
#define SNESGetKSP (*pf_petsc.SNESGetKSP)
#define SNESSetFromOptions (*pf_petsc.SNESSetFromOptions)
#define SNESSetSolution (*pf_petsc.SNESSetSolution)
#define SNESGetSolution (*pf_petsc.SNESGetSolution)
#define SNESSolve (*pf_petsc.SNESSolve)
#define SNESGetConvergedReason (*pf_petsc.SNESGetConvergedReason)
#define SNESGetIterationNumber (*pf_petsc.SNESGetIterationNumber)
#define SNESGetLinearSolveIterations (*pf_petsc.SNESGetLinearSolveIterations)
#define KSPSetType (*pf_petsc.KSPSetType)
#define KSPSetNormType (*pf_petsc.KSPSetNormType)
#define KSPSetTolerances (*pf_petsc.KSPSetTolerances)
#define KSPGetPC (*pf_petsc.KSPGetPC)
#define PCSetType (*pf_petsc.PCSetType)
#define PCShellSetContext (*pf_petsc.PCShellSetContext)
#define PCShellGetContext (*pf_petsc.PCShellGetContext)
#define PCShellSetApply (*pf_petsc.PCShellSetApply)
#undef PETSC_COMM_WORLD
#define PETSC_COMM_WORLD (*pf_petsc.comm_world)
#endif

#endif
