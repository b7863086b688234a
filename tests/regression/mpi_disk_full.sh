#!/usr/bin/env bash
# A full disk, for real: the output of runs on 2 ranks goes to a small tmpfs, where writes fail
# with ENOSPC (mpi_io_failure makes EFBIG with `ulimit -f`; this is the file system running out).
# A bar (inputs/wave_in_bar.yaml cut to 30 x 10 x 10 points, 40 steps):
#  (1) checkpoints at steps 20 and 40 into a tmpfs that holds the first (with its reserve) but
#      not the second beside it: the run exits with status 1 within 60 s, no signal, with a
#      message naming the checkpoint, the step and "No space left on device"; no .tmp is left,
#      and the step-20 checkpoint restarts (on 1 rank, into another folder) to the digest of the
#      uninterrupted 40-step run;
#  (2) Exodus frames every 5 steps into a tmpfs that holds a few of them: the same exit and a
#      message naming the Exodus file, and the file is still readable (netCDF4) with its frames
#      up to a time before the failing step.
# Needs root and a kernel that lets it mount a tmpfs: otherwise SKIPPED (exit 77, the reason
# printed). The mounts are removed on exit.
# usage: mpi_disk_full.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "not root: cannot mount a tmpfs"
$PY -c "import netCDF4" 2> /dev/null || skip "$PY has no netCDF4"
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
mounted=()
cleanup() { for m in "${mounted[@]}"; do umount "$m" 2> /dev/null || umount -l "$m"; done; }
trap cleanup EXIT
# tmpfs DIR KB: a tmpfs of KB kilobytes at DIR (skipped when mount is not permitted)
tmpfs() {
  mkdir -p "$1"
  mount -t tmpfs -o size="$2"k pf_disk_full "$1" 2> mount.err ||
    skip "mount -t tmpfs not permitted here: $(cat mount.err)"
  mounted+=("$PWD/$1")
}
sed -E 's/^(\s*)final_time:.*/\1steps: 40/; s/hi: \[0.00995,/hi: [0.00295,/; s/interval: 50/interval: 1000/;
        s/history_interval: 5/history_interval: 1000/' "$OLDPWD/../inputs/wave_in_bar.yaml" > ck.yaml
printf 'restart:\n  file: cp.h5\n  interval: 20\n' >> ck.yaml
sed -E 's/^(\s*)interval: 1000$/\1interval: 5/; s/interval: 20$/interval: 0/' ck.yaml > ex.yaml

# expect_full LABEL OUT STATUS FILE: exit 1 in time, no signal, the message naming FILE and ENOSPC
expect_full() {
  local label=$1 out=$2 status=$3 file=$4
  [ "$status" -ne 124 ] || { echo "$label: still running after 60 s"; fail=1; return; }
  [ "$status" -eq 1 ] || { echo "$label: exit status $status, expected 1"; fail=1; }
  crash_in "$out" && { echo "$label: crashed:"; echo "$out"; fail=1; }
  echo "$out" | grep "perifem error" | grep -F "$file" | grep -q "No space left on device" ||
    { echo "$label: no message naming $file and 'No space left on device':"; echo "$out"; fail=1; }
}

# (1) the checkpoint
out=$(timeout 60 "$exe" --quiet --output-dir . ex.yaml 2>&1)
ref=$(digest_of "$out")
[ -n "$ref" ] || { echo "the uninterrupted run failed:"; echo "$out"; exit 1; }
tmpfs ck 8192
start=$(date +%s)
out=$(timeout 60 mpirun --oversubscribe -np 2 "$exe" --quiet --output-dir ck ck.yaml 2>&1)
expect_full checkpoint "$out" $? ck/cp.h5
echo "$out" | grep "perifem error" | grep -q "step 40," || { echo "checkpoint: the message names no step 40:"; echo "$out"; fail=1; }
[ ! -e ck/cp.h5.tmp ] || { echo "checkpoint: ck/cp.h5.tmp left behind"; fail=1; }
mkdir -p again
out=$(timeout 60 "$exe" --quiet --output-dir again --restart ck/cp.h5 ex.yaml 2>&1)
[ "$(digest_of "$out")" = "$ref" ] ||
  { echo "checkpoint: the step-20 checkpoint left in the full tmpfs does not restart to $ref:"; echo "$out"; fail=1; }

# (2) the Exodus file
tmpfs ex 1024
out=$(timeout 60 mpirun --oversubscribe -np 2 "$exe" --quiet --output-dir ex ex.yaml 2>&1)
expect_full Exodus "$out" $? ex/ex.e
frames=$($PY -c "
import netCDF4, sys
with netCDF4.Dataset('ex/ex.e') as f:
    t = f['time_whole'][:]
    print(len(t), t[-1] if len(t) else -1)
" 2>&1)
read -r n last <<< "$frames"
if ! [[ "$n" =~ ^[0-9]+$ ]] || [ "$n" -lt 1 ]; then
  echo "Exodus: ex/ex.e unreadable or without frames after the failure: $frames"; fail=1
fi
tfail=$(echo "$out" | grep "perifem error" | sed -nE 's/.*step [0-9]+, t = ([-0-9.e+]+).*/\1/p' | head -1)
[ -n "$tfail" ] && $PY -c "import sys; sys.exit(not (float('$last') < float('$tfail')))" 2> /dev/null ||
  { echo "Exodus: last frame t = $last s is not before the failing step's t = $tfail s"; fail=1; }
echo "disk full: $(( $(date +%s) - start )) s, the Exodus file kept $n frames (last t = $last s)"
exit $fail
