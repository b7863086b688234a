# Writes OUT (git_version.h: PERIFEM_GIT, the commit of the source tree SRC, "-dirty" when
# tracked files differ from it, "unknown" outside a git checkout), rewriting it only when it
# changes. Run at every build (the git_version target), so the outputs name the commit built.
execute_process(COMMAND git -C "${SRC}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE v OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE r)
if(NOT r EQUAL 0 OR v STREQUAL "")
  set(v "unknown")
endif()
file(WRITE "${OUT}.tmp" "#define PERIFEM_GIT \"${v}\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUT}.tmp" "${OUT}")
file(REMOVE "${OUT}.tmp")
