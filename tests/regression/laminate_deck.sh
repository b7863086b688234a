#!/usr/bin/env bash
# The shipped [0/90]s laminate (inputs/laminate.yaml: FE plies in tension, docs/examples/
# laminate.md) runs as shipped, and its in-plane stiffness A11 (and A21) from the faces'
# reactions is within 2 % of classical laminate theory (scripts/laminate.py check; CLT from the
# lamina's E1, E2, G12, nu12 alone). The plot of docs/examples/laminate.png is drawn from the same
# run (scripts/laminate.py plot): it must be a PNG.
# usage: laminate_deck.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch"
out=$(cd "$scratch" && "$exe" "$OLDPWD/../inputs/laminate.yaml" 2>&1) || { echo "FAIL: the deck: $out"; exit 1; }
echo "$out" | grep -q '^health: ok' || { echo "FAIL: no 'health: ok': $out"; fail=1; }
"$PY" ../scripts/laminate.py check "$scratch/laminate.h5" || fail=1
"$PY" ../scripts/laminate.py plot "$scratch/laminate.h5" "$scratch/laminate.e" "$scratch/laminate.png" > /dev/null || fail=1
[ "$(head -c 8 "$scratch/laminate.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || { echo "FAIL: no PNG"; fail=1; }
exit $fail
