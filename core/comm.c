/* Global reductions and rank queries over MPI_COMM_WORLD, the threads per rank, and the wall clock. */
#include "core/core.h"

#include <stdlib.h>

#if defined(_OPENMP)
#include <omp.h>
#endif

/* The start-up variables pf_mpi_defaults set (the user had not), for pf_mpi_defaults_release. */
static const char *const singleton_vars[][2] = {{"OMPI_MCA_ess_singleton_isolated", "1"}, {"OMPI_MCA_pml", "ob1"}};
enum { SINGLETON_VARS = sizeof singleton_vars / sizeof *singleton_vars };
static int singleton_set[SINGLETON_VARS];

void pf_mpi_defaults(void) {
  /* Open MPI (4.1) asks each of its shared-file-pointer components about every file MPI-IO opens
   * (HDF5's checkpoints and history); `lockedfile` formats the file's path into a fixed buffer and
   * aborts the process for a path of a few hundred characters ("buffer overflow detected", in
   * mca_sharedfp_lockedfile_component_file_query), and `sm` maps a segment in the session folder.
   * perifem never moves a shared file pointer: `individual` answers alone. A value the user set is
   * kept; other MPI libraries ignore the variable. */
  setenv("OMPI_MCA_sharedfp", "^lockedfile,sm", 0);
  /* A process that no launcher started (no mpirun, srun or PMI/PMIx environment) is a singleton:
   * it has no peer to talk to and never spawns one. Open MPI would still start a helper daemon
   * and probe its network libraries for a point-to-point layer, which took 0.36 of the 0.43 s
   * that `perifem --version` took here; isolated and with ob1 it starts in 0.07 s
   * (docs/parallel.md, "Start-up"). */
  static const char *const launcher[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                                         "SLURM_STEP_ID", "MPI_LOCALNRANKS", "HYDI_CONTROL_FD"};
  for (size_t k = 0; k < sizeof launcher / sizeof *launcher; k++)
    if (getenv(launcher[k])) return;
  for (int k = 0; k < SINGLETON_VARS; k++)
    if (!getenv(singleton_vars[k][0])) singleton_set[k] = setenv(singleton_vars[k][0], singleton_vars[k][1], 1) == 0;
}

void pf_mpi_defaults_release(void) {
  for (int k = 0; k < SINGLETON_VARS; k++)
    if (singleton_set[k]) unsetenv(singleton_vars[k][0]), singleton_set[k] = 0;
}

static int mpi_ready(void) {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  return init && !fin;
}

int pf_comm_rank(void) {
  int r = 0;
  if (mpi_ready()) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int pf_comm_size(void) {
  int s = 1;
  if (mpi_ready()) MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

int pf_threads_per_rank(void) {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

static double reduce(double local, MPI_Op op) {
  double g = local;
  if (mpi_ready()) MPI_Allreduce(&local, &g, 1, MPI_DOUBLE, op, MPI_COMM_WORLD);
  return g;
}

double pf_sum_all(double local) { return reduce(local, MPI_SUM); }
double pf_min_all(double local) { return reduce(local, MPI_MIN); }
double pf_max_all(double local) { return reduce(local, MPI_MAX); }

double pf_wtime(void) { return MPI_Wtime(); }
