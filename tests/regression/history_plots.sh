#!/usr/bin/env bash
# What a user sees of a run besides the fields:
#  - the progress report: plain lines when the output is not a terminal, and on a terminal (a
#    pseudo-terminal from script(1)) one line rewritten in place (carriage return, erase to the
#    end of line) that ends before the summary; both give the step, the time, steps per second,
#    the time left, the energy error and the damage fraction; --progress plain forces plain lines
#    on a terminal and --progress line the rewritten line into a file;
#  - scripts/plot_history.py turns the run's history into PNG files (energies, energy error,
#    damage, each body's velocity, forces; load against grip displacement for each boundary
#    condition, quasi-static and explicit), and refuses a file that is not a history (exit 2).
# The run: tests/data/sphere_on_block.yaml (FE sphere on a PD block: contact, damage), 300 steps.
# usage: history_plots.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch/plain" "$scratch/tty" "$scratch/png"
sed -E 's#\.\./\.\./meshes/#'"$PWD"'/../meshes/#; s/steps: 150/steps: 300/' data/sphere_on_block.yaml > "$scratch/run.yaml"
bad() { echo "FAIL: $*"; fail=1; }
"$exe" --output-dir "$scratch/plain" "$scratch/run.yaml" > "$scratch/plain.log" 2>&1 || bad "the run exited $?"
for want in "step 15/300" "steps/s" "s left" "energy error" "damage"; do
  grep -q "$want" "$scratch/plain.log" || bad "the plain progress lines lack '$want'"
done
[ "$(grep -c '^step ' "$scratch/plain.log")" -ge 10 ] || bad "fewer than 10 progress lines"
! grep -q $'\r' "$scratch/plain.log" || bad "carriage returns in output that is not a terminal"
# the rewritten line: the run 1,200 steps long (a time loop of about 1 s: several rewrites at 4 a
# second; the 300 steps' 0.23 s fell short of the first rewrite on a quiet machine)
long="--set time.steps=1200"
"$exe" --progress line $long --output-dir "$scratch/plain" "$scratch/run.yaml" > "$scratch/line.log" 2>&1
grep -q $'\e\[K' "$scratch/line.log" || bad "--progress line into a file: no rewritten line"
# on a terminal
if command -v script > /dev/null; then
  script -qec "$exe $long --output-dir $scratch/tty $scratch/run.yaml" /dev/null > "$scratch/tty.log" 2>&1 \
    || bad "the run on a terminal exited $?"
  grep -q $'\r''step [0-9]*/1200 .*energy error' "$scratch/tty.log" || bad "no status line rewritten in place"
  grep -q $'\e\[K' "$scratch/tty.log" || bad "the status line is not erased to its end"
  grep -q '^perifem: 1200 steps' <(tr '\r' '\n' < "$scratch/tty.log") || bad "the summary does not start a line"
  ! grep -q '^step 60/1200' "$scratch/tty.log" || bad "plain progress lines on a terminal"
  # --progress plain on a terminal (as under mpirun, whose ranks see a pseudo-terminal)
  script -qec "$exe --progress plain --output-dir $scratch/tty $scratch/run.yaml" /dev/null > "$scratch/plain_tty.log" 2>&1
  ! grep -q $'\e\[K' "$scratch/plain_tty.log" || bad "--progress plain rewrote a line"
  grep -q '^step 15/300' <(tr -d '\r' < "$scratch/plain_tty.log") || bad "--progress plain: no plain lines"
else
  echo "(script(1) not found: the terminal check is skipped)"
fi
# the plots
"$PY" ../scripts/plot_history.py "$scratch/plain/run.h5" --out "$scratch/png" > "$scratch/plots.log" \
  || bad "plot_history.py exited $?: $(cat "$scratch/plots.log")"
for p in energies energy_error damage velocity forces; do
  f="$scratch/png/run_$p.png"
  [ -s "$f" ] || { bad "no $f"; continue; }
  [ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || bad "$f is not a PNG"
  [ "$(stat -c %s "$f")" -gt 10000 ] || bad "$f is nearly empty ($(stat -c %s "$f") bytes)"
done
# load against displacement, one plot per boundary condition: a quasi-static run (inputs/
# static_bar.yaml, its LPS bar at twice the spacing: 4 load steps) and an explicit one
# (tests/data/pulled_bar.yaml: two grips pulled apart); the curves are the history's columns
sed -E 's/spacing: 0.002/spacing: 0.004/; s/origin: \[0.001, 0.031, 0.001\]/origin: [0.002, 0.032, 0.002]/;
        s/horizon: 0.00603/horizon: 0.01206/; s/hi: \[0.006, 1, 1\]/hi: [0.012, 1, 1]/;
        s/lo: \[0.094, -1, -1\]/lo: [0.088, -1, -1]/' ../inputs/static_bar.yaml > "$scratch/bar.yaml"
"$exe" --quiet --output-dir "$scratch/qs" "$scratch/bar.yaml" > "$scratch/qs.log" 2>&1 || bad "the quasi-static run exited $?"
"$exe" --quiet --output-dir "$scratch/ex" data/pulled_bar.yaml > "$scratch/ex.log" 2>&1 || bad "the explicit run exited $?"
for run in qs/bar ex/pulled_bar; do
  "$PY" ../scripts/plot_history.py "$scratch/$run.h5" --out "$scratch/png" >> "$scratch/plots.log" || bad "plot_history.py on $run.h5"
done
for p in bar_load_displacement_fe_held bar_load_displacement_fe_pulled bar_load_displacement_pd_held \
         bar_load_displacement_pd_pulled pulled_bar_load_displacement_left pulled_bar_load_displacement_right; do
  f="$scratch/png/$p.png"
  [ -s "$f" ] && [ "$(stat -c %s "$f")" -gt 10000 ] || bad "no $f, or nearly empty"
done
"$PY" - "$scratch/qs/bar.h5" "$scratch/ex/pulled_bar.h5" <<'PYEOF' || fail=1
import sys
import h5py
import numpy as np
sys.path.insert(0, "../scripts")
from plot_history import load_displacement
ok = True
for path, names in ((sys.argv[1], ["fe_held", "fe_pulled", "pd_held", "pd_pulled"]), (sys.argv[2], ["left", "right"])):
    h = h5py.File(path, "r")
    c = {k: np.asarray(h[k][:], dtype=float) for k in h.keys()}
    got = load_displacement(c)
    if sorted(got) != names: print("FAIL: %s: load-displacement curves for %s, want %s" % (path, sorted(got), names)); ok = False; continue
    for n in names:
        x = [cv for cv in got[n] if cv[0] == "x"]
        if len(x) != 1 or not np.array_equal(x[0][1], c[n + "_displacement_x"]) or not np.array_equal(x[0][2], c[n + "_reaction_x"]):
            print("FAIL: %s: %s's x curve is not its displacement and reaction columns" % (path, n)); ok = False
# the quasi-static pulled grip: 5 points (t = 0 and 4 load steps), displacement d t / T, reaction rising
u, r = [cv for cv in load_displacement({k: np.asarray(v[:], dtype=float) for k, v in h5py.File(sys.argv[1], "r").items()})["fe_pulled"] if cv[0] == "x"][0][1:]
if len(u) != 5 or not np.allclose(u, 1e-4 * np.arange(5) / 4, rtol=1e-12) or not (np.diff(r) > 0).all():
    print("FAIL: the quasi-static fe_pulled curve: u %s, reaction %s" % (u, r)); ok = False
sys.exit(0 if ok else 1)
PYEOF
"$PY" ../scripts/plot_history.py "$scratch/run.yaml" > /dev/null 2> "$scratch/notahistory.log"
[ $? -eq 2 ] || bad "a deck given as the history: exit status not 2"
grep -q "cannot read it as HDF5" "$scratch/notahistory.log" || bad "no clear message for a file that is not HDF5"
[ $fail -eq 0 ] && echo "progress and plots: $(wc -l < "$scratch/plots.log") PNG files"
exit $fail
