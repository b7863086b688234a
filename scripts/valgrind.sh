#!/usr/bin/env bash
# A small mixed PD/FE run (tests/data/mixed_pd_fe.yaml) under valgrind memcheck: no invalid
# read or write, no use of uninitialised values, and no leak through perifem's own code (the
# MPI stack's allocations at start-up are its own). Needs a build without -march=native (valgrind does not decode
# AVX-512): it configures build-valgrind/ with PERIFEM_NATIVE=OFF.
#   bash scripts/valgrind.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cmake -S . -B build-valgrind -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPERIFEM_NATIVE=OFF >/dev/null
cmake --build build-valgrind -j"$(nproc)" --target perifem 2>&1 | grep -v "^\[" || true
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# the mixed PD/FE deck of the tests, cut to 20 steps, with output and checkpoints
sed -E 's/time: \{steps: 80\}/time: {steps: 20}/' tests/data/mixed_pd_fe.yaml > "$work/small.yaml"
printf 'restart: {interval: 10}\n' >> "$work/small.yaml"
(cd "$work" && valgrind --error-exitcode=9 --leak-check=full --show-leak-kinds=definite \
   --errors-for-leak-kinds=none --track-origins=yes \
   --suppressions=/usr/share/openmpi/openmpi-valgrind.supp \
   "$OLDPWD/build-valgrind/perifem" --quiet small.yaml) > "$work/log" 2>&1 || {
  echo "valgrind: memcheck errors:"; grep -E "Invalid|uninitialised|ERROR SUMMARY" "$work/log" | head -20; exit 1; }
# definite leaks whose stack passes through perifem (functions pf_*)
if awk '/definitely lost in loss record/ { rec = 1; next } /^==[0-9]+== $/ { rec = 0 } rec && / pf_/ { found = 1 } END { exit !found }' "$work/log"; then
  echo "valgrind: a leak through perifem's code:"; grep -A12 "definitely lost in loss record" "$work/log" | head -40; exit 1
fi
grep -E "ERROR SUMMARY|definitely lost:" "$work/log"
echo "valgrind: clean"
