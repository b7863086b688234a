#!/usr/bin/env bash
# An output that is a symbolic link is written through it: the target is written (the log names
# it) and the link stays a link. restart.file ck.h5 -> results/run.restart.h5 (a target not yet
# there) and output.file out.e -> results/run.e (an existing file), on 1, 2 and 3 ranks: each run
# exits 0, both links remain, the targets are an HDF5 and a netCDF file, and the state digests
# are equal.
# usage: write_paths_symlink.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
mkdir results && touch results/run.e && ln -s results/run.restart.h5 ck.h5 && ln -s results/run.e out.e
pd_deck "output: {file: out.e, history_file: h.h5}
restart: {file: ck.h5, interval: 1}" > link.yaml
magic() { head -c 4 "$1" | od -An -c | tr -d ' '; }
digests=""
for np in 1 2 3; do
  out=$(run $np "$exe" --progress plain link.yaml 2>&1) || { echo "$out"; echo "FAIL: $np ranks: exit status $?"; fail=1; }
  digests="$digests $(digest_of "$out")"
  echo "$out" | grep -q "ck.h5 is a symbolic link: writing its target $scratch/results/run.restart.h5" ||
    { echo "$out"; echo "FAIL: $np ranks: the log does not name the checkpoint link's target"; fail=1; }
  [ -L ck.h5 ] && [ -L out.e ] || { echo "FAIL: $np ranks: a link was replaced: $(ls -l ck.h5 out.e)"; fail=1; }
  [ "$(magic results/run.restart.h5)" = "211HDF" ] && [ "$(magic results/run.e)" = "CDF002" ] ||
    { echo "FAIL: $np ranks: the targets are not the checkpoint and the Exodus file: $(ls -l results)"; fail=1; }
done
set -- $digests
[ $# = 3 ] && [ "$1" = "$2" ] && [ "$1" = "$3" ] || { echo "FAIL: state digests on 1, 2, 3 ranks:$digests"; fail=1; }
exit $fail
