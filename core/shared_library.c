/* A shared library opened on first use (gmsh, PETSc: mesh/gmsh_library.h and
 * sim/petsc_library.h say why they are not linked), and its symbols. */
#include "core/core.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

void *pf_library_open(const char *path, char *why, size_t len) {
  void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char *reason = dlerror();
    snprintf(why, len, "%s", reason ? reason : path);
  }
  return library;
}

/* dlsym returns an object pointer; POSIX guarantees it converts to a function pointer, which ISO
 * C does not, so it is copied rather than cast. */
int pf_library_symbol(void *library, const char *path, const char *name, void *slot, char *why, size_t len) {
  void *symbol = dlsym(library, name);
  if (!symbol) {
    snprintf(why, len, "%s has no %s", path, name);
    return -1;
  }
  memcpy(slot, &symbol, sizeof symbol);
  return 0;
}
