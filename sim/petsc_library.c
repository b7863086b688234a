/* PETSc's library, opened on first use (sim/petsc_library.h says why). */
#define PF_PETSC_LIBRARY_SOURCE
#include "sim/petsc_library.h"

#include "core/core.h"

pf_petsc_api pf_petsc;

static int loaded;

int pf_petsc_load(char *why, size_t len) {
  if (loaded) return 0;
  void *library = pf_library_open(PF_PETSC_LIBRARY, why, len);
  if (!library) return -1;
  pf_petsc_api api;
#define PF_PETSC_FIND(name)                                                                        \
  if (pf_library_symbol(library, PF_PETSC_LIBRARY, #name, &api.name, why, len)) return -1;
  PF_PETSC_FUNCTIONS(PF_PETSC_FIND)
#undef PF_PETSC_FIND
  if (pf_library_symbol(library, PF_PETSC_LIBRARY, "PETSC_COMM_WORLD", &api.comm_world, why, len)) return -1;
  pf_petsc = api;
  loaded = 1;
  return 0;
}
