/* gmsh's library, opened on first use (mesh/gmsh_library.h says why). */
#define PF_GMSH_LIBRARY_SOURCE
#include "mesh/gmsh_library.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

pf_gmsh_api pf_gmsh;

static int loaded;

/* one symbol: dlsym returns an object pointer; POSIX guarantees it converts to a function
 * pointer, which ISO C does not, so it is copied rather than cast */
static int find(void *library, const char *name, void *slot, char *why, size_t len) {
  void *symbol = dlsym(library, name);
  if (!symbol) {
    snprintf(why, len, "%s has no %s", PF_GMSH_LIBRARY, name);
    return -1;
  }
  memcpy(slot, &symbol, sizeof symbol);
  return 0;
}

int pf_gmsh_load(char *why, size_t len) {
  if (loaded) return 0;
  void *library = dlopen(PF_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char *reason = dlerror();
    snprintf(why, len, "%s", reason ? reason : PF_GMSH_LIBRARY);
    return -1;
  }
  pf_gmsh_api api;
#define PF_GMSH_FIND(name)                                                                    \
  if (find(library, #name, &api.name, why, len)) return -1;
  PF_GMSH_FUNCTIONS(PF_GMSH_FIND)
#undef PF_GMSH_FIND
  pf_gmsh = api;
  loaded = 1;
  return 0;
}
