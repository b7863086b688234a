#!/usr/bin/env bash
# The contact search's skin and rebuild rule change no bit of a run. The contact forces depend
# only on the pairs within the contact radius r_c; a search redone from scratch at every step
# (a skin of 0.1 um: every pair's list is rebuilt at every step) finds exactly those, so it is the
# reference: the deck's own skin (each pair rebuilt when two entities of its own bodies may have
# moved a skin relative to each other since its last build, the other pair's list kept,
# contact/search.c), a skin twice as large, and
# the deck's skin on 2 ranks (the kept lists' ghost partners renumbered at a rebuild of the other
# pair) must give its state digest. A rule that let a list go stale would miss an interaction
# and change the digest.
#   bash contact_skin.sh PERIFEM WORKDIR
# Deck: tests/data/sphere_on_block.yaml (an FE sphere at 200 m/s on a PD block with friction,
# and the block's self-contact), 150 steps; a few seconds. Then a spinning ring, and the expanding
# tube with element conversion (below; about a minute).
set -euo pipefail
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
source "$here/tests/common/mpi_env.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sed "s#\.\./\.\./meshes/#$here/meshes/#" "$here/tests/data/sphere_on_block.yaml" > deck.yaml

rebuilds_of() { echo "$1" | sed -n 's/^ *contact: \([0-9]*\) search rebuilds.*/\1/p'; }
fail=0
# case name, ranks, extra arguments
declare -a cases=("every_step 1 --set contact.skin=1e-7" "deck_skin 1" "double_skin 1 --set contact.skin=2.2e-3"
                  "deck_skin_2_ranks 2")
ref=""
for c in "${cases[@]}"; do
  read -r name np extra <<< "$c"
  mkdir -p "$name"
  # shellcheck disable=SC2086
  out=$(cd "$name" && run "$np" "$exe" --output-dir . $extra ../deck.yaml 2>&1) || { echo "$out"; echo "FAIL: $name did not run"; exit 1; }
  d=$(digest_of "$out")
  n=$(rebuilds_of "$out")
  echo "$name: $np rank(s), $n search rebuilds, digest $d"
  [[ -n $d && -n $n ]] || { echo "$out"; echo "FAIL: $name printed no digest or rebuild count"; exit 1; }
  if [[ $name == every_step ]]; then
    ref=$d
    ((n >= 150)) || { echo "FAIL: a skin of 0.1 um rebuilt $n times in 150 steps (expected every step)"; fail=1; }
  elif [[ $d != "$ref" ]]; then
    echo "FAIL: $name: digest $d differs from the every-step search's $ref"
    fail=1
  fi
  if [[ $name == deck_skin ]] && ((n >= 150)); then
    echo "FAIL: the deck's skin rebuilt at every step ($n): the test would not exercise the kept lists"
    fail=1
  fi
done

# A body whose grains move together with one affine map (expanding, or imploding, and spinning):
# a pair keeps its lists while the grains move little relative to the map fitted to their moves
# (contact/search.c, affine_keeps). Imploding, the grains touch; a bound looser than the rule
# (the rest below s, without the factor 2 and the stretch term) misses interactions there and
# changes the digest. Expanding, every grain travels at least 300 m/s x 300 steps x dt, and a
# rule on each grain's own move (rebuilt at s/2) needs at least that path over s/2 rebuilds;
# the affine rule must need fewer than half as many.
ring=$here/tests/data/spinning_ring.yaml
implode='bodies.ring.initial_velocity=["-300 * x / sqrt(x^2 + y^2) - 2.0e4 * y", "-300 * y / sqrt(x^2 + y^2) + 2.0e4 * x", "0"]'
for motion in expanding imploding; do
  extra=()
  [[ $motion == imploding ]] && extra=(--set "$implode")
  ref=""
  for c in "every_step 1 1e-7" "deck_skin 1 5e-4" "deck_skin_2_ranks 2 5e-4"; do
    read -r name np skin <<< "$c"
    dir=ring_${motion}_$name
    mkdir -p "$dir"
    out=$(cd "$dir" && run "$np" "$exe" --output-dir . --set contact.skin="$skin" "${extra[@]}" "$ring" 2>&1) \
      || { echo "$out"; echo "FAIL: $dir did not run"; exit 1; }
    d=$(digest_of "$out")
    n=$(rebuilds_of "$out")
    dt=$(echo "$out" | sed -n 's/^perifem: [0-9]* steps of \([0-9.e+-]*\) s.*/\1/p')
    echo "ring $motion, $name: $np rank(s), $n search rebuilds, digest $d"
    [[ -n $d && -n $n && -n $dt ]] || { echo "$out"; echo "FAIL: $dir printed no digest, step or rebuild count"; exit 1; }
    if [[ $name == every_step ]]; then
      ref=$d
    elif [[ $d != "$ref" ]]; then
      echo "FAIL: ring $motion, $name: digest $d differs from the every-step search's $ref"
      fail=1
    fi
    if [[ $motion == expanding && $name == deck_skin ]]; then
      least=$(awk -v dt="$dt" -v s="$skin" 'BEGIN { printf "%d", 300 * 300 * dt / (s / 2) }')
      echo "  a rule on each grain's own move: at least $least rebuilds"
      if ((2 * n >= least)); then
        echo "FAIL: ring expanding: $n rebuilds, not fewer than half of $least"
        fail=1
      fi
    fi
  done
done

# Faces a particle is far behind (docs/theory/contact.md sec. 2, "Reach"): the closest face is
# sought among the faces within the pair's r_c, which every skin finds; a skin also lists some
# faces beyond it, and when the closest face was taken among all the candidates, a Lexan particle
# made from a deleted element 1.1 mm behind two faces met one with the deck's default skin and
# another with 0.2 mm, and the digests parted at 27.05 us. The expanding tube with element conversion to 27.2 us
# (the first conversions at about 15 us), the default skin (the largest r_c, 0.675 mm) and 0.2 mm,
# on 2 ranks: one digest.
conv=$here/tests/data/expanding_tube_conversion.yaml
ref=""
for skin in default 2.0e-4; do
  extra=()
  [[ $skin != default ]] && extra=(--set contact.skin="$skin")
  dir=conversion_$skin
  mkdir -p "$dir"
  out=$(cd "$dir" && run 2 "$exe" --output-dir . --set time.final_time=27.2e-6 --set output.interval=0 \
        --set output.history_interval=1000 "${extra[@]}" "$conv" 2>&1) || { echo "$out"; echo "FAIL: $dir did not run"; exit 1; }
  d=$(digest_of "$out")
  echo "conversion, skin $skin: 2 ranks, $(rebuilds_of "$out") search rebuilds, digest $d"
  [[ -n $d ]] || { echo "$out"; echo "FAIL: $dir printed no digest"; exit 1; }
  if [[ -z $ref ]]; then
    ref=$d
  elif [[ $d != "$ref" ]]; then
    echo "FAIL: conversion: the skin $skin gives $d, the default skin $ref"
    fail=1
  fi
done
exit $fail
