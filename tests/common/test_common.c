#include "test_common.h"

#include <math.h>
#include <stdio.h>

int pf_test_failures = 0;

void pf_test_init(int *argc, char ***argv) {
  MPI_Init(argc, argv);
  pf_log_set_quiet(1);
}

int pf_test_finish(void) {
  int fails = pf_test_failures, total = 0;
  MPI_Allreduce(&fails, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Finalize();
  return total ? 1 : 0;
}

void pf_test_close(double got, double want, double tol_rel, double tol_abs, const char *what,
                   const char *file, int line) {
  double err = fabs(got - want);
  if (!(err <= tol_rel * fabs(want) + tol_abs)) {
    fprintf(stderr, "%s:%d: %s = %.15g, expected %.15g (error %.3g, tolerance rel %.3g abs %.3g)\n",
            file, line, what, got, want, err, tol_rel, tol_abs);
    pf_test_failures++;
  }
}

void pf_test_true(int cond, const char *what, const char *file, int line) {
  if (!cond) {
    fprintf(stderr, "%s:%d: check failed: %s\n", file, line, what);
    pf_test_failures++;
  }
}
