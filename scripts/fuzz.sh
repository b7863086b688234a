#!/usr/bin/env bash
# Fuzz the deck loader with libFuzzer (clang 14, Debian's libclang-rt-14-dev) for SECONDS
# (default 600) from the committed seed corpus tests/fuzz/corpus (the shipped decks and the
# malformed ones); new inputs go to build-fuzz/corpus, crashes to build-fuzz/crash-*.
#   bash scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-600}
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPERIFEM_FUZZ=ON -DPERIFEM_NATIVE=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_deck 2>&1 | grep -v "^\[" || true
mkdir -p build-fuzz/corpus
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Leaks are left to scripts/sanitize.sh (bad_decks there checks every malformed deck for leaks
# through perifem's code): here the MPI stack's start-up allocations would need the slow
# unwinder to be told apart, which makes the deep-nesting seeds time out; and the leak check at
# exit would report MPI_Init's allocations as a crash of the last input.
export ASAN_OPTIONS="detect_leaks=0"
cd build-fuzz
./fuzz_deck -max_total_time="$secs" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 -detect_leaks=0 \
  -dict=../tests/fuzz/yaml.dict corpus ../tests/fuzz/corpus
