#!/usr/bin/env bash
# Corrupt checkpoints are refused, never used: a small bar (inputs/wave_in_bar.yaml cut to
# 30 x 10 x 10 points and 30 steps) writes a checkpoint at step 20 on 2 ranks; its clean restart
# gives the reference digest.
#  (a) Targeted corruptions, written with h5py (so HDF5's checksums hold and only the reader's
#      checks can find them): a negative and a too-large body index, a point id out of range and
#      a repeated one, a negative bond count, counts that do not add up, a bond id out of range,
#      a NaN position, a NaN time, a huge step (1e300, and 1e12: past the run's end), a negative dt, a field with a negative width, a
#      dataset rewritten without its checksum, and the file truncated. Each, on 1 and 2 ranks
#      (3 for a few), exits non-zero within 60 s, not by a signal, with a "perifem error" message
#      naming the file and the dataset or attribute.
#  (c) By meaning (valid numbers, checksums holding): a moved reference position, a changed
#      volume, a changed mass, a bond flag of 2, the point field critical_stretch deleted; each
#      refused on 1 and 2 ranks naming what differs.
#  (b) 30 copies with 1 to 4 random bytes flipped (seed 2024; in the first 4 KiB, the
#      superblock and the root group's header with the scalars, for the first 10): each either restarts to exactly
#      the reference digest, or is refused (non-zero exit, message naming the file); never a
#      signal, a hang or exit 0 with another digest. Copies alternate between 1 and 2 ranks
#      (every fifth on 3).
# usage: mpi_checkpoint_corrupt.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
$PY -c "import h5py" 2> /dev/null || { echo "skipped: $PY has no h5py"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
sed -E 's/^(\s*)final_time:.*/\1steps: 30/; s/hi: \[0.00995,/hi: [0.00295,/; s/interval: 50/interval: 1000/' \
  "$OLDPWD/../inputs/wave_in_bar.yaml" > bar.yaml
printf 'restart:\n  file: ck.h5\n  interval: 20\n' >> bar.yaml
run 2 "$exe" --quiet bar.yaml > /dev/null 2>&1 || { echo "the run with a checkpoint failed"; exit 1; }
mv ck.h5 clean.h5
ref=$(digest_of "$(run 1 "$exe" --quiet --restart clean.h5 bar.yaml 2>&1)")
[ -n "$ref" ] || { echo "the clean checkpoint does not restart"; exit 1; }

# Restarts run four at a time (each mostly waits on MPI's start-up: about 1 s, 2 s when it
# fails on 2 ranks), one rank without mpirun (whose exit after an error costs 2 s more).
# launch NP FILE: restart from FILE on NP ranks in the background, output in FILE.NP.out and
# the exit status (124: still running after 60 s) in FILE.NP.status
launch() {
  while [ "$(jobs -rp | wc -l)" -ge 4 ]; do sleep 0.05; done
  local cmd=("$exe")
  [ "$1" -gt 1 ] && cmd=(mpirun --oversubscribe -np "$1" "$exe")
  # a TMPDIR of its own: singletons side by side share Open MPI's session folder otherwise, and
  # the first to end removes it under the others (tests/CMakeLists.txt)
  mkdir -p "tmp.$2.$1"
  (export TMPDIR=$PWD/tmp.$2.$1
   timeout 60 "${cmd[@]}" --quiet --restart "$2" bar.yaml > "$2.$1.out" 2>&1; echo $? > "$2.$1.status") &
}
# result NP FILE: sets out and status of a finished launch
result() { out=$(cat "$2.$1.out"); status=$(cat "$2.$1.status"); }
# a crash: killed by a signal (status > 128 from timeout/mpirun, or mpirun's report of it)
crashed() { [ $status -gt 128 ] || crash_in "$out"; }
# refused NP FILE WHAT LABEL: non-zero, no crash, in time, a perifem error naming FILE and WHAT
refused() {
  result "$1" "$2"
  local err
  err=$(echo "$out" | grep "perifem error" | head -1)
  if [ $status -eq 0 ] || [ $status -eq 124 ] || crashed || ! echo "$err" | grep -qF "$2" ||
     ! echo "$err" | grep -qF -- "$3"; then
    echo "FAIL $4 on $1 ranks: exit $status, expected a refusal naming $2 and '$3':"
    echo "$out" | head -8
    fail=1
  fi
}
ranks_of() { case $1 in body_big|count_sum|truncated) echo 1 2 3 ;; *) echo 1 2 ;; esac; }

# (a) targeted corruptions: NAME  DATASET-OR-ATTRIBUTE-IN-THE-MESSAGE
$PY - << 'EOF' || { echo "could not write the corrupt copies"; exit 1; }
import shutil, h5py, numpy as np
def copy(name):
    shutil.copy("clean.h5", name + ".h5")
    return h5py.File(name + ".h5", "r+")
def edit(name, dset, index, value):
    with copy(name) as f:
        d = f[dset]
        a = d[...]
        a[index] = value if not callable(value) else value(a)
        d[...] = a
with h5py.File("clean.h5", "r") as f:
    n = f["/points/gid"].shape[0]
    g = f["/points/gid"][...]
edit("body_neg", "/points/body", 5, -1)
edit("body_big", "/points/body", 7, 3)
edit("gid_range", "/points/gid", 3, n + 5)
edit("gid_twice", "/points/gid", 3, g[4])
edit("count_neg", "/bonds/count", 2, -3)
edit("count_sum", "/bonds/count", 2, lambda a: a[2] + 1)
edit("bond_gid", "/bonds/gid", 10, -7)
edit("x_nan", "/points/X", (4, 1), np.nan)
for name, attr, value in [("time_nan", "time", np.nan), ("step_huge", "step", 1e300), ("step_past", "step", 1e12),
                          ("dt_neg", "dt", -1e-9)]:
    with copy(name) as f:
        f.attrs.modify(attr, value)
with copy("ncomp_neg") as f:
    f["/fields/damage"].attrs.modify("ncomp", np.int32(-1))
with copy("no_checksum") as f:  # /points/v rewritten contiguous, without Fletcher32
    v = f["/points/v"][...]
    del f["/points/v"]
    f.create_dataset("/points/v", data=v)
data = open("clean.h5", "rb").read()
open("truncated.h5", "wb").write(data[: len(data) // 2])
# (c) damage that only the meaning finds: each value a valid number
edit("moved", "/points/X", (4, 1), lambda a: a[4, 1] + 1e-4)
edit("vol_changed", "/points/vol", 4, lambda a: a[4] * 1.1)
edit("mass_changed", "/points/m", 3, lambda a: a[3] * 1.01)
edit("flag_two", "/bonds/broken", 10, 2)
with copy("field_gone") as f:
    del f["/fields/critical_stretch"]
EOF
cases="body_neg:/points/body body_big:/points/body gid_range:/points/gid gid_twice:/points/gid
       count_neg:/bonds/count count_sum:/bonds/count bond_gid:/bonds/gid x_nan:/points/X time_nan:time
       step_huge:step step_past:step dt_neg:dt ncomp_neg:/fields/damage no_checksum:/points/v truncated:truncated"
start=$(date +%s) nref=0
for c in $cases; do
  for np in $(ranks_of ${c%%:*}); do launch $np ${c%%:*}.h5; done
done
wait
for c in $cases; do
  name=${c%%:*} what=${c#*:}
  [ "$what" = truncated ] && what=""
  for np in $(ranks_of $name); do refused $np $name.h5 "$what" $name; nref=$((nref + 1)); done
done
echo "targeted: $nref refusals checked in $(( $(date +%s) - start )) s"

# (c) by meaning: a moved reference position, a changed volume or mass, a bond flag of 2, a point
# field the model keeps deleted; each refused naming what differs (before: a restart with exit 0
# and another result, or a message about the time step)
meaning="moved:reference_position vol_changed:its_volume mass_changed:carries_mass flag_two:not_a_flag
         field_gone:no_point_field"
for c in $meaning; do for np in 1 2; do launch $np ${c%%:*}.h5; done; done
wait
for c in $meaning; do
  name=${c%%:*} what=${c#*:}
  for np in 1 2; do
    result $np $name.h5
    if [ $status -eq 0 ] || [ $status -eq 124 ] || crashed || ! echo "$out" | grep "perifem error" | grep -qF "${what//_/ }"; then
      echo "FAIL $name on $np ranks: exit $status, expected a refusal saying '${what//_/ }':"
      echo "$out" | head -8
      fail=1
    fi
  done
done

# (b) random byte flips
$PY - << 'EOF' || { echo "could not write the flipped copies"; exit 1; }
import random
rng = random.Random(2024)
data = open("clean.h5", "rb").read()
for k in range(30):
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        at = rng.randrange(4096 if k < 10 else len(b))
        b[at] ^= rng.randint(1, 255)
    open("flip%02d.h5" % k, "wb").write(bytes(b))
EOF
start=$(date +%s) nequal=0 nrefused=0
np_of() { if [ $(( 10#$1 % 5 )) -eq 4 ]; then echo 3; else echo $(( 10#$1 % 2 + 1 )); fi; }
for k in $(seq -w 0 29); do launch $(np_of $k) flip$k.h5; done
wait
for k in $(seq -w 0 29); do
  np=$(np_of $k)
  result $np flip$k.h5
  d=$(digest_of "$out")
  if [ $status -eq 0 ] && [ "$d" = "$ref" ]; then
    nequal=$((nequal + 1))
  elif [ $status -ne 0 ] && [ $status -ne 124 ] && ! crashed && echo "$out" | grep "perifem error" | grep -qF flip$k.h5; then
    nrefused=$((nrefused + 1))
  else
    echo "FAIL flip$k.h5 on $np ranks: exit $status, digest '$d' (clean $ref):"
    echo "$out" | head -8
    fail=1
  fi
done
echo "random flips: $nrefused refused, $nequal restarted to the clean digest, in $(( $(date +%s) - start )) s"
exit $fail
