#!/usr/bin/env bash
# "Nothing silently wrong", fuzzers cover the new paths: the file-kind fuzzer
# (tests/fuzz/fuzz_paths.py) points the paths a run writes (output.file, output.history_file,
# restart.file, --output-dir) at FIFOs, devices, folders, the deck, another output, the
# checkpoint's temporary file, dangling links and very long paths; every wrong kind must be
# refused with nothing written, and nothing may crash or change what it was given. Its default
# run: at most 10 s of cases (seed 1; FUZZ_SEED and FUZZ_BUDGET change them).
#   bash tests/regression/fuzz_paths.sh PERIFEM SCRATCH_DIR [TESTS_BINARY_DIR (unused)]
set -u
[ $# -ge 2 ] || { echo "usage: bash $0 PERIFEM SCRATCH_DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
source "$here/common/mpi_env.sh"
rm -rf -- "$2" && mkdir -p -- "$2" || exit 1
$PY "$here/fuzz/fuzz_paths.py" "$1" "$2" --seed "${FUZZ_SEED:-1}" --budget "${FUZZ_BUDGET:-10}"
