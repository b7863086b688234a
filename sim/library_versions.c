/* The versions of the libraries perifem was built against that main.c cannot see (their
 * headers are private to the library): for `perifem --version`. */
#include "core/core.h"

#include <gmshc.h>
#include <metis.h>
#include <muParserDLL.h>
#include <netcdf_meta.h>
#include <petscversion.h>
#include <stdio.h>
#include <string.h>
#include <zoltan.h>

void pf_library_versions(char *out, size_t len) {
  muParserHandle_t h = mupCreate(muBASETYPE_FLOAT);
  const char *mu = h ? mupGetVersion(h) : "?"; /* "2.3.3 (Release) (...)": the number only */
  snprintf(out, len, "gmsh API %s, METIS %d.%d.%d, Zoltan %.2f, netCDF %s, muparser %.*s, PETSc %d.%d.%d",
           GMSH_API_VERSION, METIS_VER_MAJOR, METIS_VER_MINOR, METIS_VER_SUBMINOR, (double)ZOLTAN_VERSION_NUMBER,
           NC_VERSION, (int)strcspn(mu, " "), mu, PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR);
  if (h) mupRelease(h);
}
