#!/usr/bin/env bash
# An error raised on one rank only stops every rank, non-zero, within 30 s, with a message that
# names the rank: (1) a NaN initial velocity at the points of one end of the bar (found during
# set-up, after partitioning, by the rank that owns them); (2) a prescribed velocity that turns
# NaN at step 5 on the points of one end (found by the time loop's guard).
# usage: mpi_errors.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
sed -E 's/initial_velocity: .*/initial_velocity: ["x > 0.0098 ? sqrt(-1) : 0", "0", "0"]/' \
  ../inputs/wave_in_bar.yaml > "$scratch/setup_nan.yaml"
sed -E 's/^(\s*)final_time:.*/\1steps: 60/' ../inputs/wave_in_bar.yaml > "$scratch/run_nan.yaml"
cat >> "$scratch/run_nan.yaml" <<'DECK'
boundary_conditions:
  - region: {shape: box, lo: [0.0098, 0, 0], hi: [0.01, 0.001, 0.001]}
    velocity: ["t > 4.5e-8 ? sqrt(-1) : 0", "free", "free"]
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
exit $fail
