/* gmsh's library, opened on first use (mesh/gmsh_library.h says why). */
#define PF_GMSH_LIBRARY_SOURCE
#include "mesh/gmsh_library.h"

#include "core/core.h"

pf_gmsh_api pf_gmsh;

static int loaded;

int pf_gmsh_load(char *why, size_t len) {
  if (loaded) return 0;
  void *library = pf_library_open(PF_GMSH_LIBRARY, why, len);
  if (!library) return -1;
  pf_gmsh_api api;
#define PF_GMSH_FIND(name)                                                                    \
  if (pf_library_symbol(library, PF_GMSH_LIBRARY, #name, &api.name, why, len)) return -1;
  PF_GMSH_FUNCTIONS(PF_GMSH_FIND)
#undef PF_GMSH_FIND
  pf_gmsh = api;
  loaded = 1;
  return 0;
}
