#!/usr/bin/env bash
# Fuzz with libFuzzer (clang 14, Debian's libclang-rt-14-dev) for SECONDS (default 600) one of:
#   deck        the deck loader (tests/fuzz/fuzz_deck.c), from the committed seed corpus
#               tests/fuzz/corpus (the shipped decks and the malformed ones);
#   checkpoint  the checkpoint reader and the restore of a --restart run
#               (tests/fuzz/fuzz_checkpoint.c), from seeds written here: the checkpoint of each
#               deck in tests/fuzz/decks at step 2 (by build/perifem, or $PERIFEM), behind the
#               byte that picks the deck, plus copies with damaged content (h5py, when installed).
# New inputs go to build-fuzz/corpus_TARGET, crashes to build-fuzz/crash-*. An input running longer
# than FUZZ_TIMEOUT seconds (default 10, wall time) is a hang: on a machine shared with other
# jobs, raise it (28_alias_bomb.yaml takes 1.4 s of CPU but 18 s of wall time at a load of 17).
#   bash scripts/fuzz.sh [deck|checkpoint] [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
target=deck
case ${1:-} in deck | checkpoint) target=$1 && shift ;; esac
secs=${1:-600}
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPERIFEM_FUZZ=ON -DPERIFEM_NATIVE=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_"$target" 2>&1 | grep -v "^\[" || true
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# checkpoint_seeds DIR: the seeds of the checkpoint target in DIR
checkpoint_seeds() {
  local dir=$1 exe=${PERIFEM:-$PWD/build/perifem} k=0 work
  [ -x "$exe" ] || { echo "fuzz.sh: no $exe to write the seed checkpoints (run scripts/setup.sh)"; exit 1; }
  work=$(mktemp -d)
  for deck in pd fe coupled contact; do # (the order of decks[] in fuzz_checkpoint.c)
    sed 's/steps: 4/steps: 2/' "tests/fuzz/decks/$deck.yaml" > "$work/$deck.yaml"
    (cd "$work" && "$exe" --quiet "$deck.yaml" > /dev/null)
    { printf "\\$(printf %03o $k)"; cat "$work/$deck.restart.h5"; } > "$dir/$deck"
    k=$((k + 1))
  done
  local py=python3
  [ -x /usr/bin/python3 ] && py=/usr/bin/python3 # (the system python has h5py)
  $py -c "import h5py" 2> /dev/null || { rm -rf "$work"; return 0; }
  $py - "$work/pd.restart.h5" "$dir" << 'EOF'
import shutil, sys, h5py, numpy as np
clean, out = sys.argv[1], sys.argv[2]
def edit(name, dset, index, value=None):
    shutil.copy(clean, out + "/x.h5")
    with h5py.File(out + "/x.h5", "r+") as f:
        if value is not None:
            a = f[dset][...]
            a[index] = value
            f[dset][...] = a
        else:  # a scalar attribute of the root group
            f.attrs.modify(dset, index)
    open(out + "/pd_" + name, "wb").write(b"\0" + open(out + "/x.h5", "rb").read())
edit("body_neg", "/points/body", 5, -1)
edit("gid_twice", "/points/gid", 3, 4)
edit("count_neg", "/bonds/count", 2, -3)
edit("x_nan", "/points/X", (4, 1), np.nan)
edit("step_huge", "step", 1e300)
edit("dt_neg", "dt", -1e-9)
import os; os.remove(out + "/x.h5")
EOF
  rm -rf "$work"
}

seeds=tests/fuzz/corpus extra=(-dict=../tests/fuzz/yaml.dict)
if [ "$target" = checkpoint ]; then
  seeds=build-fuzz/seeds_checkpoint extra=()
  rm -rf "$seeds" && mkdir -p "$seeds" && checkpoint_seeds "$seeds"
fi
mkdir -p build-fuzz/corpus_"$target"
# Leaks are left to scripts/sanitize.sh (bad_decks there checks every malformed deck for leaks
# through perifem's code): here the MPI stack's start-up allocations would need the slow
# unwinder to be told apart, which makes the deep-nesting seeds time out; and the leak check at
# exit would report MPI_Init's allocations as a crash of the last input.
export ASAN_OPTIONS="detect_leaks=0" UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" # (any UB is a crash)
cd build-fuzz
./fuzz_"$target" -max_total_time="$secs" -print_final_stats=1 -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb=2048 -detect_leaks=0 \
  "${extra[@]}" corpus_"$target" ../"$seeds"
