#!/usr/bin/env bash
# "Nothing silently wrong", fuzzers cover the new paths: the derived-number fuzzer
# (tests/fuzz/fuzz_numbers.py) runs the small fuzz decks with one number or expression made
# huge, negative, zero or not finite; each run must exit 0, or 2 naming a deck key, or 1 with a
# message: never a signal, a hang or a silent exit 1. Its default run: at most 50 s of cases
# (seed 1; FUZZ_SEED and FUZZ_BUDGET change them).
#   bash tests/regression/fuzz_numbers.sh PERIFEM SCRATCH_DIR [TESTS_BINARY_DIR (unused)]
set -u
[ $# -ge 2 ] || { echo "usage: bash $0 PERIFEM SCRATCH_DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
source "$here/common/mpi_env.sh"
rm -rf -- "$2" && mkdir -p -- "$2" || exit 1
$PY "$here/fuzz/fuzz_numbers.py" "$1" "$2" --seed "${FUZZ_SEED:-1}" --budget "${FUZZ_BUDGET:-50}"
