/* Global reductions and rank queries over MPI_COMM_WORLD, the threads per rank, and the wall clock. */
#include "core/core.h"

#include <stdlib.h>

#if defined(_OPENMP)
#include <omp.h>
#endif

void pf_mpi_defaults(void) {
  /* Open MPI (4.1) asks each of its shared-file-pointer components about every file MPI-IO opens
   * (HDF5's checkpoints and history); `lockedfile` formats the file's path into a fixed buffer and
   * aborts the process for a path of a few hundred characters ("buffer overflow detected", in
   * mca_sharedfp_lockedfile_component_file_query), and `sm` maps a segment in the session folder.
   * perifem never moves a shared file pointer: `individual` answers alone. A value the user set is
   * kept; other MPI libraries ignore the variable. */
  setenv("OMPI_MCA_sharedfp", "^lockedfile,sm", 0);
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
