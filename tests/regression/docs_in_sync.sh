#!/usr/bin/env bash
# The documentation cannot drift from the code:
#  - docs/deck_keys.md is exactly what `perifem --deck-keys` prints from the tables the deck
#    loader checks (a key in the loader but not in the docs, or the reverse, fails);
#  - every test under tests/verification/ and tests/regression/ is listed in docs/verification.md;
#  - every shipped deck in inputs/ is named in README.md or docs/.
# usage: docs_in_sync.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
rm -rf "$scratch" && mkdir -p "$scratch"
"$exe" --deck-keys > "$scratch/deck_keys.md" || { echo "FAIL: perifem --deck-keys exited $?"; exit 1; }
if ! diff -u ../docs/deck_keys.md "$scratch/deck_keys.md" > "$scratch/diff"; then
  head -40 "$scratch/diff"
  echo "FAIL: docs/deck_keys.md differs from the loader's tables; regenerate it with"
  echo "      build/perifem --deck-keys > docs/deck_keys.md"
  fail=1
fi
for f in verification/test_*.c regression/*.sh; do
  name=$(basename "${f%.*}")
  grep -q "$name" ../docs/verification.md || { echo "FAIL: $f is not listed in docs/verification.md"; fail=1; }
done
for f in ../inputs/*.yaml; do
  name=$(basename "$f")
  grep -rqF "$name" ../README.md ../docs || { echo "FAIL: inputs/$name is not named in README.md or docs/"; fail=1; }
done
[ $fail -eq 0 ] && echo "docs in sync: $(grep -c '^| `' ../docs/deck_keys.md) keys, $(ls verification/test_*.c regression/*.sh | wc -l) tests, $(ls ../inputs/*.yaml | wc -l) decks"
exit $fail
