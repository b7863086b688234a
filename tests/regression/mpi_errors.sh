#!/usr/bin/env bash
# An error raised on one rank only stops every rank, non-zero, within 30 s, with a message that
# names the rank: (1) a NaN initial velocity at the points of one end of the bar (found during
# set-up, after partitioning, by the rank that owns them); (2) a prescribed velocity that turns
# NaN at step 3 on the points of one end (found by the time loop's guard); (3) the bar with a
# time step 3.7 times its stable step (the motion guard): on 1, 2 and 3 ranks the run stops
# with the point, body, motion and step, and the Exodus file's last step is the last good state
# (a time before the failing step), the same on every rank count.
# usage: mpi_errors.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
sed -E 's/initial_velocity: .*/initial_velocity: ["x > 0.0098 ? sqrt(-1) : 0", "0", "0"]/' \
  ../inputs/wave_in_bar.yaml > "$scratch/setup_nan.yaml"
# (2): the set-up samples a prescribed velocity at 101 times over the run and refuses a NaN it
# finds; with 200 steps of dt = 2.1675e-8 s its samples fall every 2 dt, and this velocity is
# NaN only in (5e-8, 8e-8) s = (2.3, 3.7) dt, between two samples, where the steps evaluate it
sed -E 's/^(\s*)final_time:.*/\1steps: 200/' ../inputs/wave_in_bar.yaml > "$scratch/run_nan.yaml"
cat >> "$scratch/run_nan.yaml" <<'DECK'
boundary_conditions:
  - region: {shape: box, lo: [0.0098, 0, 0], hi: [0.01, 0.001, 0.001]}
    velocity: ["t > 5e-8 && t < 8e-8 ? sqrt(-1) : 0", "free", "free"]
DECK
expect=( "initial_velocity" "non-finite force or velocity" )
k=0
for deck in setup_nan run_nan; do
  for np in 2 3; do
    start=$(date +%s)
    out=$(cd "$scratch" && timeout 60 mpirun --oversubscribe -np $np "$exe" "$deck.yaml" 2>&1)
    status=$? took=$(( $(date +%s) - start ))
    [ $status -ne 0 ] || { echo "$deck on $np ranks: exit 0"; fail=1; }
    [ $status -ne 124 ] || { echo "$deck on $np ranks: still running after 60 s"; fail=1; }
    [ $took -le 30 ] || { echo "$deck on $np ranks: took $took s to stop"; fail=1; }
    echo "$out" | grep -q "perifem error (rank [0-9]*): .*${expect[$k]}" ||
      { echo "$deck on $np ranks: no error naming the rank and '${expect[$k]}':"; echo "$out"; fail=1; }
  done
  k=$((k + 1))
done
# (3) the motion guard, with the last good state written
sed -E 's/^(\s*)final_time:.*/\1final_time: 2.0e-5\n\1dt: 1.0e-7/' ../inputs/wave_in_bar.yaml > "$scratch/unstable.yaml"
ref=""
for np in 1 2 3; do
  out=$(cd "$scratch" && rm -f unstable.e && run $np "$exe" unstable.yaml 2>&1)
  [ $? -ne 0 ] || { echo "unstable on $np ranks: exit 0"; fail=1; }
  msg=$(echo "$out" | grep -o "point [0-9]* (body 'bar') at .* moved .* in step [0-9]* at time [^ ]* s, more than time.max_motion" | head -1)
  [ -n "$msg" ] || { echo "unstable on $np ranks: no motion-guard message:"; echo "$out"; fail=1; continue; }
  step=$(echo "$msg" | sed -E 's/.* in step ([0-9]+) .*/\1/')
  last=$(ncdump -v time_whole "$scratch/unstable.e" | sed -n 's/.*time_whole = \(.*\) ;/\1/p' | tr -d ' ' | awk -F, '{print $NF}')
  awk -v t="$last" -v s="$step" 'BEGIN { exit !(t < s * 1.0e-7 - 1e-12) }' ||
    { echo "unstable on $np ranks: last Exodus time $last is not before step $step"; fail=1; }
  [ -n "$ref" ] || ref="$step $last"
  [ "$step $last" = "$ref" ] || { echo "unstable on $np ranks: step/time '$step $last', 1 rank '$ref'"; fail=1; }
done
exit $fail
