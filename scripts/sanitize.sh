#!/usr/bin/env bash
# The tests under AddressSanitizer + UndefinedBehaviorSanitizer (any UB report is fatal) in
# their own build folder, build-sanitize/. Leaks the MPI stack, gmsh and Pamgen keep are
# suppressed (scripts/lsan.supp).
#   bash scripts/sanitize.sh        # the default suite (ctest -LE slow): about 20 minutes on 2 cores
#   bash scripts/sanitize.sh --ci   # the tests labelled sanitize (tests/CMakeLists.txt: one or more
#                                   # per module; about 10 minutes with the build): .ci/run
# Every ASan and LSan report goes to a file in build-sanitize/reports/ as well as failing its
# process; the script fails when a test fails or when any report was written, so a report from
# a run a test expected to fail (exit 1 or 2, as an ASan report exits) is not lost. gcc's UBSan
# runtime ignores log_path: a UB report aborts the process instead (SIGABRT, status 134), which
# the tests count as a crash.
# After scripts/setup.sh has installed the packages.
set -euo pipefail
cd "$(dirname "$0")/.."
select=(-LE slow) omp=ON
[ "${1:-}" = --ci ] && select=(-L sanitize) omp=OFF # (no threads test there: no perifem_omp to build)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPERIFEM_SANITIZE=ON -DPERIFEM_WERROR=ON \
  -DPERIFEM_OPENMP_CHECK=$omp >/dev/null
cmake --build build-sanitize -j"$(nproc)" 2>&1 | grep -v "^\[" ||
  [ "${PIPESTATUS[0]}" -eq 0 ] || { echo "sanitize.sh: the build failed" >&2; exit 1; }
reports=$PWD/build-sanitize/reports
rm -rf "$reports" && mkdir -p "$reports"
export ASAN_OPTIONS="detect_stack_use_after_return=0:abort_on_error=0:log_path=$reports/asan"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1"
status=0
ctest --test-dir build-sanitize --output-on-failure "${select[@]}" -j"$(nproc)" || status=1
if [ -n "$(ls -A "$reports")" ]; then
  echo "sanitize.sh: sanitizer reports in $reports:"
  for f in "$reports"/*; do echo "== $f"; head -60 "$f"; done
  status=1
fi
exit $status
