/* PETSc's library, opened on first use (sim/petsc_library.h says why). */
#define PF_PETSC_LIBRARY_SOURCE
#include "sim/petsc_library.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

pf_petsc_api pf_petsc;

static int loaded;

/* one symbol: dlsym returns an object pointer; POSIX guarantees it converts to a function
 * pointer, which ISO C does not, so it is copied rather than cast */
static int find(void *library, const char *name, void *slot, char *why, size_t len) {
  void *symbol = dlsym(library, name);
  if (!symbol) {
    snprintf(why, len, "%s has no %s", PF_PETSC_LIBRARY, name);
    return -1;
  }
  memcpy(slot, &symbol, sizeof symbol);
  return 0;
}

int pf_petsc_load(char *why, size_t len) {
  if (loaded) return 0;
  void *library = dlopen(PF_PETSC_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char *reason = dlerror();
    snprintf(why, len, "%s", reason ? reason : PF_PETSC_LIBRARY);
    return -1;
  }
  pf_petsc_api api;
#define PF_PETSC_FIND(name)                                                                        \
  if (find(library, #name, &api.name, why, len)) return -1;
  PF_PETSC_FUNCTIONS(PF_PETSC_FIND)
#undef PF_PETSC_FIND
  if (find(library, "PETSC_COMM_WORLD", &api.comm_world, why, len)) return -1;
  pf_petsc = api;
  loaded = 1;
  return 0;
}
