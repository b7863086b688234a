/* The start-up variables of a process no launcher started (core/comm.c, docs/parallel.md
 * "Start-up"): before MPI_Init, pf_mpi_defaults sets Open MPI's isolated singleton and the ob1
 * point-to-point layer, unless the user set them; after it, pf_mpi_defaults_release takes back
 * exactly those it set (a process the run starts, a Python campaign's mpirun, must not inherit
 * ob1); under a launcher's environment (mpirun, srun, PMI, PMIx) neither is set. The shared-file
 * pointer exclusion is set in every case. The functions only touch the environment, so the cases
 * run in this process before MPI starts. Started by a launcher itself (its variables must reach
 * MPI_Init), the test checks only that nothing is set. */
#include "test_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const launchers[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                                        "SLURM_STEP_ID", "MPI_LOCALNRANKS", "HYDI_CONTROL_FD"};
enum { NLAUNCHERS = sizeof launchers / sizeof *launchers };

static int is(const char *name, const char *value) {
  const char *v = getenv(name);
  return value ? v && !strcmp(v, value) : v == NULL;
}

static void clean(void) {
  for (int k = 0; k < NLAUNCHERS; k++) unsetenv(launchers[k]);
  unsetenv("OMPI_MCA_pml");
  unsetenv("OMPI_MCA_ess_singleton_isolated");
}

/* A launcher started this process: pf_mpi_defaults leaves both variables as they were. */
static int launched_alone(void) {
  char pml[64] = "", iso[64] = "";
  const char *p = getenv("OMPI_MCA_pml"), *i = getenv("OMPI_MCA_ess_singleton_isolated");
  if (p) snprintf(pml, sizeof pml, "%s", p);
  if (i) snprintf(iso, sizeof iso, "%s", i);
  pf_mpi_defaults();
  int ok = is("OMPI_MCA_pml", p ? pml : NULL) && is("OMPI_MCA_ess_singleton_isolated", i ? iso : NULL);
  pf_mpi_defaults_release();
  return ok && is("OMPI_MCA_pml", p ? pml : NULL);
}

int main(int argc, char **argv) {
  int launched = 0;
  for (int k = 0; k < NLAUNCHERS; k++) launched |= getenv(launchers[k]) != NULL;
  if (launched) {
    const int ok = launched_alone();
    pf_test_init(&argc, &argv);
    PF_TEST_TRUE(ok);
    return pf_test_finish();
  }

  /* no launcher, nothing set: both set, then both taken back */
  clean();
  pf_mpi_defaults();
  int ok = is("OMPI_MCA_pml", "ob1") && is("OMPI_MCA_ess_singleton_isolated", "1") &&
           is("OMPI_MCA_sharedfp", "^lockedfile,sm");
  pf_mpi_defaults_release();
  ok &= is("OMPI_MCA_pml", NULL) && is("OMPI_MCA_ess_singleton_isolated", NULL) &&
        is("OMPI_MCA_sharedfp", "^lockedfile,sm");
  const int singleton_ok = ok;

  /* the user's transport kept through both; only the variable set here is taken back */
  clean();
  setenv("OMPI_MCA_pml", "ucx", 1);
  pf_mpi_defaults();
  ok = is("OMPI_MCA_pml", "ucx") && is("OMPI_MCA_ess_singleton_isolated", "1");
  pf_mpi_defaults_release();
  ok &= is("OMPI_MCA_pml", "ucx") && is("OMPI_MCA_ess_singleton_isolated", NULL);
  const int user_ok = ok;

  /* each launcher's variable alone: nothing set, nothing taken back */
  int launcher_ok = 1;
  for (int k = 0; k < NLAUNCHERS; k++) {
    clean();
    setenv(launchers[k], "0", 1);
    launcher_ok &= launched_alone();
  }
  clean();

  pf_test_init(&argc, &argv);
  PF_TEST_TRUE(singleton_ok);
  PF_TEST_TRUE(user_ok);
  PF_TEST_TRUE(launcher_ok);
  return pf_test_finish();
}
