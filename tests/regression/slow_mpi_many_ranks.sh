#!/usr/bin/env bash
# The decks of mpi_digests.sh on 4, 8 and 16 ranks (oversubscribed: the bits do not depend on the
# cores): each must end with the state digest of its 1-rank run. The decks and their 1-rank
# digests are the ones mpi_digests.sh leaves in TESTS_BINARY_DIR/work_mpi_digests (one_rank.txt;
# the test fixture in tests/CMakeLists.txt runs mpi_digests first). Every module takes part: PMB,
# LPS (METIS), elastic-plastic, correspondence with damage, several materials in one body, a
# variable horizon, FE, the coupled chain, FE <-> PD contact with friction, PD self-contact, the
# critical energy with re-partitioning, and a deck of 2 points (most ranks hold none).
# usage: slow_mpi_many_ranks.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") scratch=$2 bindir=${3:-} fail=0
source common/mpi_env.sh
decks=$bindir/work_mpi_digests
[ -n "$bindir" ] && [ -s "$decks/one_rank.txt" ] && [ "$decks/one_rank.txt" -nt "$exe" ] ||
  { echo "no 1-rank digests of this perifem in $decks/one_rank.txt: run regression/mpi_digests first"; exit 1; }
rm -rf "$scratch" && mkdir -p "$scratch"
count=0
while read -r name ref; do
  name=${name%:} ok=1
  for np in ${PF_MANY_RANKS:-4 8 16}; do
    mkdir -p "$scratch/np$np"
    out=$(cd "$decks" && run "$np" "$exe" --quiet --output-dir "$scratch/np$np" "$name.yaml" 2>&1 < /dev/null)
    st=$? d=$(digest_of "$out")
    if [ "$st" != 0 ] || [ "$d" != "$ref" ]; then
      echo "FAIL: $name on $np ranks: exit $st, digest '$d', 1 rank '$ref'"
      echo "$out" | tail -5
      fail=1 ok=0
    fi
  done
  [ $ok = 1 ] && echo "$name: $ref on 1, ${PF_MANY_RANKS:-4 8 16} ranks"
  count=$((count + 1))
done < "$decks/one_rank.txt"
[ "$count" -ge 20 ] || { echo "FAIL: only $count decks in one_rank.txt"; fail=1; }
exit $fail
