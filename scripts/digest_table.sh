#!/usr/bin/env bash
# The state digest of every shipped deck and every digest-test deck on 1, 2 and 3 ranks, one
# line each: "DECK NP DIGEST". Run it with the binary before and after a change that must keep
# behaviour (a refactor) and diff the two tables:
#   bash scripts/digest_table.sh OLD/perifem > before.txt
#   bash scripts/digest_table.sh build/perifem > after.txt && diff before.txt after.txt
# The decks of tests/regression/mpi_digests.sh (reduced shipped decks and their variants) come
# from that test's own scratch folder; the shipped decks it does not reduce run here for a
# bounded number of steps (DIGEST_STEPS, default 40). Environment: DIGEST_RANKS (default "1 2 3").
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
steps=${DIGEST_STEPS:-40}
ranks=${DIGEST_RANKS:-1 2 3}
work=$(mktemp -d /tmp/perifem_digests.XXXXXX)
trap 'rm -rf "$work"' EXIT
source "$here/tests/common/mpi_env.sh"

# the mpi_digests decks: let the test write them (it also runs them; its digests.txt is one per deck)
(cd "$here/tests" && bash regression/mpi_digests.sh "$exe" "$work/mpi" >/dev/null 2>&1)
decks=()
for f in "$work"/mpi/*.yaml; do decks+=("$f"); done
# shipped decks and test decks, bounded in steps; mesh paths made absolute
for f in "$here"/inputs/*.yaml "$here"/tests/data/*.yaml; do
  name=$(basename "$f" .yaml)
  sed -E "s/^(\s*)final_time:.*/\1steps: $steps/; s/final_time: [0-9.eE+-]+/steps: $steps/; s/steps: [0-9]+/steps: $steps/; \
          s#\.\./\.\./meshes/#$here/meshes/#; s#\.\./meshes/#$here/meshes/#" "$f" > "$work/x_$name.yaml"
  decks+=("$work/x_$name.yaml")
done
for deck in "${decks[@]}"; do
  name=$(basename "$deck" .yaml)
  for np in $ranks; do
    mkdir -p "$work/out$np"
    out=$(cd "$work" && run "$np" "$exe" --quiet --output-dir "out$np" "$deck" 2>&1)
    rc=$?
    d=$(digest_of "$out")
    echo "$name $np ${d:-exit$rc}"
  done
done
