#!/usr/bin/env bash
# A SIGTERM or SIGINT during the set-up (gmsh meshing a .geo, a PD body's lattice and neighbour
# search) ends perifem promptly: within a few seconds, with exit status 128 + signal, a message,
# and nothing written in the output folder (the signal after 1 s and 3 s). (Before: the signal was held until the first step,
# so a set-up of minutes could not be stopped.) Each set-up here takes 8 s or more alone on the
# fastest machine this ran on (the PD block's 400 000 points of before took 3.5 s there, so the
# signal came after the set-up: a signal after it checkpoints at the end of the step instead).
#
#   bash tests/regression/setup_signal.sh PERIFEM SCRATCH_DIR [TESTS_BINARY_DIR (unused)]
set -u
[ $# -ge 2 ] || { echo "usage: bash $0 PERIFEM SCRATCH_DIR" >&2; exit 2; }
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
rm -rf -- "$scratch" && mkdir -p -- "$scratch" && scratch=$(cd "$scratch" && pwd) || exit 1
cd "$scratch" || exit 1
fail=0

cat > fe.yaml <<DECK
title: FE bar meshed by gmsh (1.25 million hexahedra, about 17 s of meshing)
units: SI
materials:
  steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}
bodies:
  - name: bar
    type: finite_element
    material: steel
    mesh: {file: $here/../meshes/bar.geo, element_size: 2.0e-5}
time:
  steps: 10
DECK
cat > pd.yaml <<'DECK'
title: PD block (950 000 points, about 8 s of lattice and neighbour search on an AMD EPYC of 2026)
units: SI
materials:
  steel: {model: pmb, density: 7800, bulk_modulus: 160.0e9}
bodies:
  - name: block
    material: steel
    geometry: {shape: box, lo: [0, 0, 0], hi: [0.08, 0.08, 0.06], spacing: 0.75e-3}
    horizon: 3.015e-3
time:
  steps: 10
DECK

# catching PID SIGNAL: whether the process has a handler for the signal (SigCgt in /proc), i.e.
# perifem is past MPI_Init and into its set-up (a signal before that kills it without a word).
catching() {
  local mask
  mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$1/status" 2> /dev/null) || return 1
  [ -n "$mask" ] && (( (0x$mask >> ($(kill -l "$2") - 1)) & 1 ))
}

# case NAME DECK SIGNAL DELAY: start perifem, send the signal DELAY s after it began its set-up,
# expect it gone within 5 s.
case_() {
  local name=$1 deck=$2 sig=$3 delay=$4 want
  want=$((128 + $(kill -l "$sig")))
  mkdir -p "out_$name"
  local t0 t1 status
  t0=$(date +%s%N)
  "$exe" --output-dir "out_$name" "$deck" > "$name.out" 2> "$name.err" &
  local pid=$!
  for _ in $(seq 1 100); do catching "$pid" "$sig" && break; sleep 0.1; done
  sleep "$delay"
  kill -s "$sig" "$pid"
  for _ in $(seq 1 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2> /dev/null; then
    echo "FAIL $name: still running 5 s after $sig"
    kill -9 "$pid"
    fail=1
  fi
  wait "$pid"
  status=$?
  t1=$(date +%s%N)
  [ "$status" -eq "$want" ] || { echo "FAIL $name: exit status $status, expected $want"; fail=1; }
  grep -q "$sig (signal .*) during the set-up: stopped" "$name.err" ||
    { echo "FAIL $name: no message on stderr: $(head -c 300 "$name.err")"; fail=1; }
  [ -z "$(ls -A "out_$name")" ] || { echo "FAIL $name: files left: $(ls -A "out_$name")"; fail=1; }
  echo "$name: $sig after $delay s, exit $status after $(( (t1 - t0) / 1000000 )) ms"
}

case_ gmsh fe.yaml TERM 1
case_ neighbours pd.yaml INT 3
exit $fail
