#!/usr/bin/env bash
# The ledger's time-centred rule keeps the energy balance second order in the step where the
# work is done by a moving surface, a wall or a prescribed velocity (theory/pd.md §6 and §8):
#   indentation  tests/data/indentation.yaml: a rigid sphere pressed at 100 m/s into a PMB
#                cylinder (the indenter's work -(R^n + R^(n+1))/2 . dx), 15 us;
#   wall         tests/data/wall_bar.yaml: an LPS bar flying onto a wall, 3 us;
#   grip         tests/data/pulled_bar.yaml without failure: a PMB bar pulled by two
#                prescribed-velocity grips, 6 us.
# Each runs at dt, dt/2 and dt/4 over the same time. The largest |energy_error| over the largest
# energy in play (the run summary's measure) must be below 1e-4 at dt and fall at least 3 times
# with each halving (4 for second order), unless it is already at round-off (below 1e-10). No
# run may give a run-health warning. The same runs on 2 ranks give the same errors to 1e-9.
# usage: ledger_order.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
data=$PWD/data
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"

# err NP DECK DT STEPS [--set ...]: the largest relative energy error of the run (stdout); the
# run's warnings go to warnings.txt
err() {
  local np=$1 deck=$2 dt=$3 steps=$4 out
  shift 4
  rm -rf out
  out=$(run "$np" "$exe" --output-dir out --set "time.dt=$dt" --set "time.steps=$steps" \
        --set "output.history_interval=$((steps / 10))" "$@" "$deck" 2>&1) || { echo "$deck failed: $out" >&2; echo nan; return; }
  echo "$out" | grep "perifem warning" >> warnings.txt
  "$PY" - out/*.h5 <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    c = {k: np.asarray(f[k][:], dtype=float) for k in f.keys()}
z = np.zeros_like(c["time"])
play = c["kinetic_energy"] + c["elastic_energy"] + c["contact_energy"] + np.abs(c.get("fe_internal_energy", z))
scale = max(np.max(np.abs(c["external_work"])), np.max(play))
print(f"{np.max(np.abs(c['energy_error'])) / scale:.6e}")
PY
}

# check NAME DECK DT STEPS [--set ...]
check() {
  local name=$1 deck=$2 dt=$3 steps=$4
  shift 4
  : > warnings.txt
  local e1 e2 e4 e1p
  e1=$(err 1 "$deck" "$dt" "$steps" "$@")
  e2=$(err 1 "$deck" "$("$PY" -c "print($dt / 2)")" $((2 * steps)) "$@")
  e4=$(err 1 "$deck" "$("$PY" -c "print($dt / 4)")" $((4 * steps)) "$@")
  e1p=$(err 2 "$deck" "$dt" "$steps" "$@")
  echo "$name: energy error / energy in play at dt, dt/2, dt/4: $e1 $e2 $e4 (2 ranks at dt: $e1p)"
  "$PY" - "$e1" "$e2" "$e4" "$e1p" <<'PY' || fail=1
import sys
e1, e2, e4, e1p = map(float, sys.argv[1:])
ok = e1 < 1e-4 and abs(e1p - e1) <= 1e-9 + 1e-6 * e1
for a, b in ((e1, e2), (e2, e4)):
    ok = ok and (a < 1e-10 or a / max(b, 1e-300) > 3.0)
if not ok:
    print("  expected below 1e-4, falling at least 3 times per halving, the same on 2 ranks")
sys.exit(0 if ok else 1)
PY
  if [ -s warnings.txt ]; then echo "$name: run-health warnings:"; cat warnings.txt; fail=1; fi
}

check indentation "$data/indentation.yaml" 1.0e-7 150
check wall "$data/wall_bar.yaml" 5.0e-8 60
check grip "$data/pulled_bar.yaml" 2.0e-8 300 --set bodies.bar.damage.critical_stretch=1
exit $fail
