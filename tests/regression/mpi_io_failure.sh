#!/usr/bin/env bash
# A write that fails (here: past the file-size limit of `ulimit -f`, which perifem meets as EFBIG
# the way a full disk gives ENOSPC) stops every rank: on 1 and 2 ranks, for (1) a checkpoint, (2)
# the Exodus file and (3) the HDF5 history, the run exits with status 1 within 60 s (no signal,
# no hang: before, a checkpoint crashed in MPI_Finalize on 1 rank and hung in H5Fclose on 2),
# printing the message that names the file and the step; the checkpoint fails when rank 0
# reserves room for the whole file before the collective dataset creation (a limit below the
# data's size, and one just below the file's size). Before that reservation, a limit reached
# inside HDF5's collective chunk allocation failed one rank and left the other in a barrier. The failed checkpoint leaves no
# <file>.tmp and the previous checkpoint byte for byte as it was, and a restart from it runs.
# The bar (inputs/wave_in_bar.yaml, 10,000 points) writes a 14 MB checkpoint (limit 8000 KB),
# Exodus frames of 1 MB (limit 1500 KB); its 120-point cut writes a 240 KB history at the first
# row (limit 220 KB) beside a 40 KB Exodus file.
# usage: mpi_io_failure.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
# limited NP KB ARGS...: run on NP ranks with files limited to KB kilobytes. The limit is set in
# each rank, not in mpirun (whose session files it would stop), and the ranks talk over TCP
# (Open MPI's shared-memory segments are files larger than the limits).
limited() {
  local np=$1 kb=$2
  shift 2
  timeout 60 mpirun --oversubscribe --mca btl self,tcp -np "$np" bash -c "ulimit -f $kb; exec \"\$@\"" limited "$@"
}
bar=$OLDPWD/../inputs/wave_in_bar.yaml
sed -E 's/^(\s*)final_time:.*/\1steps: 60/; s/interval: 50/interval: 1000/' "$bar" > ck.yaml
printf 'restart:\n  file: cp.h5\n  interval: 40\n' >> ck.yaml
sed -E 's/interval: 40/interval: 0/' ck.yaml > ck_out.yaml
sed -E 's/^(\s*)final_time:.*/\1steps: 120/; s/interval: 50/interval: 20/' "$bar" > ex.yaml
sed -E 's/^(\s*)final_time:.*/\1steps: 20/; s/hi: \[0.00995, 0.00095, 0.00095\]/hi: [0.00295, 0.00025, 0.00025]/' "$bar" > hi.yaml
# the previous checkpoint: step 40 of the bar
sed -E 's/steps: 60/steps: 40/' ck.yaml > ck40.yaml
run 1 "$exe" --quiet ck40.yaml > /dev/null 2>&1 && cp cp.h5 good.h5 || { echo "no checkpoint to start from"; exit 1; }

# expect_failure LABEL NP KB DECK PATTERN: exit 1, in time, no signal, the message
expect_failure() {
  local label=$1 np=$2 kb=$3 deck=$4 pattern=$5 out status
  out=$(limited "$np" "$kb" "$exe" --quiet "$deck" 2>&1)
  status=$?
  [ $status -ne 124 ] || { echo "$label on $np ranks: still running after 60 s"; fail=1; return; }
  [ $status -eq 1 ] || { echo "$label on $np ranks: exit status $status, expected 1"; fail=1; }
  crash_in "$out" && { echo "$label on $np ranks: crashed:"; echo "$out"; fail=1; }
  echo "$out" | grep -qE "perifem error.*$pattern" ||
    { echo "$label on $np ranks: no message matching '$pattern':"; echo "$out"; fail=1; }
}
for np in 1 2; do
  cp good.h5 cp.h5
  expect_failure checkpoint $np 8000 ck.yaml \
    "cannot write the checkpoint cp.h5: no room for its .* of cp.h5.tmp .*step 40, t = "
  [ ! -e cp.h5.tmp ] || { echo "checkpoint on $np ranks: cp.h5.tmp left behind"; fail=1; }
  cmp -s cp.h5 good.h5 || { echo "checkpoint on $np ranks: the previous checkpoint changed"; fail=1; }
  # the data fits but not the metadata HDF5 writes when it closes the file (before, the ranks
  # hung in H5Fclose: one failed a metadata write and went on, the other waited for it)
  expect_failure "checkpoint close" $np $(( $(stat -c %s good.h5) / 1024 )) ck.yaml \
    "cannot write the checkpoint cp.h5: no room for (its|the last) .* of cp.h5.tmp .*step 40, t = "
  [ ! -e cp.h5.tmp ] && cmp -s cp.h5 good.h5 || { echo "checkpoint close on $np ranks: .tmp left or previous changed"; fail=1; }
  out=$(timeout 60 mpirun --oversubscribe -np $np "$exe" --quiet --restart cp.h5 ck_out.yaml 2>&1)
  [ -n "$(digest_of "$out")" ] || { echo "restart on $np ranks from the kept checkpoint failed:"; echo "$out"; fail=1; }
  rm -f ex.e
  expect_failure Exodus $np 1500 ex.yaml "Exodus: .* failed \(file ex.e\).*File too large.*step 20, t = "
  rm -f hi.h5
  expect_failure history $np 220 hi.yaml "cannot write the history hi.h5: .*File too large.*step 0, t = "
done
exit $fail
