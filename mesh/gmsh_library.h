/* gmsh's C API, loaded when a deck first reads a gmsh file instead of at start-up. gmsh's library
 * brings about 30 others (OpenCASCADE, FLTK, MED, CGNS): loading and relocating them cost every
 * run about 0.15 s of CPU per process, and every deck, valid or not, paid it on every rank. The
 * calls in mesh/gmsh.c keep gmsh's own names: after this header, gmshFree(p) calls through the
 * table pf_gmsh, which pf_gmsh_load() fills from the library the build linked against
 * (PF_GMSH_LIBRARY). Private to mesh/. */
#ifndef PF_MESH_GMSH_LIBRARY_H
#define PF_MESH_GMSH_LIBRARY_H

#include <gmshc.h>
#include <stddef.h>

/* X(name): every gmsh function perifem calls */
#define PF_GMSH_FUNCTIONS(X)                                                                  \
  X(gmshFree) X(gmshInitialize) X(gmshFinalize) X(gmshOpen) X(gmshOptionSetNumber)            \
  X(gmshLoggerStart) X(gmshLoggerGet) X(gmshLoggerStop) X(gmshModelGetBoundingBox)            \
  X(gmshModelGetEntitiesForPhysicalGroup) X(gmshModelGetPhysicalGroups)                       \
  X(gmshModelGetPhysicalName) X(gmshModelMeshClear) X(gmshModelMeshGenerate)                  \
  X(gmshModelMeshGetElementProperties) X(gmshModelMeshGetElementTypes)                        \
  X(gmshModelMeshGetElementsByType) X(gmshModelMeshGetNodes)                                  \
  X(gmshModelMeshGetNodesForPhysicalGroup)

typedef struct {
#define PF_GMSH_POINTER(name) __typeof__(name) *name;
  PF_GMSH_FUNCTIONS(PF_GMSH_POINTER)
#undef PF_GMSH_POINTER
} pf_gmsh_api;

extern pf_gmsh_api pf_gmsh;

/* Load the library and fill pf_gmsh (once per process; later calls return at once). 0, or -1
 * with the reason (dlopen's or dlsym's message) in why[len]. */
int pf_gmsh_load(char *why, size_t len);

/* gmsh's names from here on call through the table (a macro is not expanded inside its own
 * expansion, so pf_gmsh.gmshFree names the member); not in the file that fills it */
#ifndef PF_GMSH_LIBRARY_SOURCE
#define gmshFree (*pf_gmsh.gmshFree)
#define gmshInitialize (*pf_gmsh.gmshInitialize)
#define gmshFinalize (*pf_gmsh.gmshFinalize)
#define gmshOpen (*pf_gmsh.gmshOpen)
#define gmshOptionSetNumber (*pf_gmsh.gmshOptionSetNumber)
#define gmshLoggerStart (*pf_gmsh.gmshLoggerStart)
#define gmshLoggerGet (*pf_gmsh.gmshLoggerGet)
#define gmshLoggerStop (*pf_gmsh.gmshLoggerStop)
#define gmshModelGetBoundingBox (*pf_gmsh.gmshModelGetBoundingBox)
#define gmshModelGetEntitiesForPhysicalGroup (*pf_gmsh.gmshModelGetEntitiesForPhysicalGroup)
#define gmshModelGetPhysicalGroups (*pf_gmsh.gmshModelGetPhysicalGroups)
#define gmshModelGetPhysicalName (*pf_gmsh.gmshModelGetPhysicalName)
#define gmshModelMeshClear (*pf_gmsh.gmshModelMeshClear)
#define gmshModelMeshGenerate (*pf_gmsh.gmshModelMeshGenerate)
#define gmshModelMeshGetElementProperties (*pf_gmsh.gmshModelMeshGetElementProperties)
#define gmshModelMeshGetElementTypes (*pf_gmsh.gmshModelMeshGetElementTypes)
#define gmshModelMeshGetElementsByType (*pf_gmsh.gmshModelMeshGetElementsByType)
#define gmshModelMeshGetNodes (*pf_gmsh.gmshModelMeshGetNodes)
#define gmshModelMeshGetNodesForPhysicalGroup (*pf_gmsh.gmshModelMeshGetNodesForPhysicalGroup)
#endif

#endif
