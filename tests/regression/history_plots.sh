#!/usr/bin/env bash
# What a user sees of a run besides the fields:
#  - the progress report: plain lines when the output is not a terminal, and on a terminal (a
#    pseudo-terminal from script(1)) one line rewritten in place (carriage return, erase to the
#    end of line) that ends before the summary; both give the step, the time, steps per second,
#    the time left, the energy error and the damage fraction; --progress plain forces plain lines
#    on a terminal and --progress line the rewritten line into a file;
#  - scripts/plot_history.py turns the run's history into PNG files (energies, energy error,
#    damage, each body's velocity, forces), and refuses a file that is not a history (exit 2).
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
"$exe" --progress line --output-dir "$scratch/plain" "$scratch/run.yaml" > "$scratch/line.log" 2>&1
grep -q $'\e\[K' "$scratch/line.log" || bad "--progress line into a file: no rewritten line"
# on a terminal (the run lasts a few seconds: several rewrites at 4 a second)
if command -v script > /dev/null; then
  script -qec "$exe --output-dir $scratch/tty $scratch/run.yaml" /dev/null > "$scratch/tty.log" 2>&1 \
    || bad "the run on a terminal exited $?"
  grep -q $'\r''step [0-9]*/300 .*energy error' "$scratch/tty.log" || bad "no status line rewritten in place"
  grep -q $'\e\[K' "$scratch/tty.log" || bad "the status line is not erased to its end"
  grep -q '^perifem: 300 steps' <(tr '\r' '\n' < "$scratch/tty.log") || bad "the summary does not start a line"
  ! grep -q '^step 15/300' "$scratch/tty.log" || bad "plain progress lines on a terminal"
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
"$PY" ../scripts/plot_history.py "$scratch/run.yaml" > /dev/null 2> "$scratch/notahistory.log"
[ $? -eq 2 ] || bad "a deck given as the history: exit status not 2"
grep -q "cannot read it as HDF5" "$scratch/notahistory.log" || bad "no clear message for a file that is not HDF5"
[ $fail -eq 0 ] && echo "progress and plots: $(wc -l < "$scratch/plots.log") PNG files"
exit $fail
