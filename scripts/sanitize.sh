#!/usr/bin/env bash
# The default test suite under AddressSanitizer + UndefinedBehaviorSanitizer (any UB report is
# fatal) in its own build folder, build-sanitize/. Leaks the MPI stack, gmsh and Pamgen keep
# are suppressed (scripts/lsan.supp). About 20 minutes on 2 cores.
#   bash scripts/sanitize.sh            # after scripts/setup.sh has installed the packages
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPERIFEM_SANITIZE=ON -DPERIFEM_WERROR=ON >/dev/null
cmake --build build-sanitize -j"$(nproc)" 2>&1 | grep -v "^\[" || true
export ASAN_OPTIONS="detect_stack_use_after_return=0:abort_on_error=0"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-sanitize --output-on-failure -LE slow -j"$(nproc)"
