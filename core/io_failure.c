/* Failed writes: the ranks agree on a local failure before any further collective call, and a
 * file a library could not close is remembered. HDF5 keeps a file whose close failed half
 * destroyed and tries to close it again when MPI_Finalize ends the library (a segmentation
 * fault); after such a file the process ends through MPI_Abort instead (sim/main.c). */
#include "core/core.h"

#include <stdarg.h>

static int abandoned = 0;

int pf_agree(int ierr, const char *fmt, ...) {
  if (!(pf_max_all(ierr != 0) > 0) || ierr) return ierr; /* (no reduction before MPI_Init) */
  char what[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  return pf_error_raise(PF_ERR_RUN, __FILE__, __LINE__, __func__, "stopped: another rank failed %s", what);
}

void pf_io_abandon(void) { abandoned = 1; }

int pf_io_abandoned(void) { return abandoned; }
