/* Create_Pamgen_Mesh with its C++ exceptions caught. Pamgen is C++ behind a C interface: an
 * input it does not check (a negative block count, for one) throws std::bad_array_new_length or
 * std::bad_alloc, which would end the process through std::terminate (SIGABRT) on its way out
 * through C frames. Here it becomes a status and a message (mesh/pamgen.c reports it). */
#include <climits>
#include <cstdio>
#include <exception>

#include <create_inline_mesh.h>

#include "mesh/pamgen_guard.h"

extern "C" long long pf_pamgen_create(const char *text, char *what, size_t len) {
  try {
    return Create_Pamgen_Mesh(text, 3, 0, 1, INT_MAX);
  } catch (const std::exception &e) {
    std::snprintf(what, len, "%s", e.what());
  } catch (...) {
    std::snprintf(what, len, "an exception of unknown type");
  }
  return PF_PAMGEN_THREW;
}
