#!/usr/bin/env bash
# "Nothing silently wrong", fuzzers cover the new paths: the API-lifetime fuzzer
# (tests/fuzz/fuzz_lifetimes.py) runs seeded sequences of Python calls - simulations created,
# stepped, closed, dropped and collected, views read after their simulation is gone, checkpoints
# to a fresh path, the deck or a folder, finalize() in the middle - each in a fresh interpreter;
# every call works or raises PerifemError, TypeError or ValueError, never a crash, and the deck is
# unchanged. Its default run: at most 10 s of cases (seed 1; FUZZ_SEED and FUZZ_BUDGET change them).
# The package from the source tree, the build's library.
#   bash tests/regression/fuzz_lifetimes.sh PERIFEM SCRATCH_DIR TESTS_BINARY_DIR
set -u
[ $# -ge 3 ] || { echo "usage: bash $0 PERIFEM SCRATCH_DIR TESTS_BINARY_DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
build=$(cd "$3/.." && pwd)
source "$here/common/mpi_env.sh"
rm -rf -- "$2" && mkdir -p -- "$2" || exit 1
PYTHONPATH="$here/../python" PERIFEM_LIBRARY="$build/libperifem.so.0" \
  $PY "$here/fuzz/fuzz_lifetimes.py" "$here/library/free_body.yaml" "$2" --seed "${FUZZ_SEED:-1}" \
  --budget "${FUZZ_BUDGET:-10}"
