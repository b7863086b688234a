#!/usr/bin/env bash
# Two runs writing the same files: the first holds <file>.lock beside each output; a second run
# of the same deck in the same folder, started while the first runs (on 1 and on 2 ranks), is
# refused (exit 2, "another run (process <first's pid> on <host>)", on every rank), writes nothing
# and leaves the first's files alone; the first, stopped by SIGTERM, ends with exit 0 and removes
# its locks. A lock left by a process that has ended (a killed run, a zombie) is taken over
# with a warning; a lock held by a live process is not.
# usage: write_paths_concurrent.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
host=$(hostname)
pd_deck "time: {steps: 1000000000}
output: {interval: 0, history_interval: 100000000}" > busy.yaml
"$exe" --quiet busy.yaml > first.log 2>&1 &
first=$!
for i in $(seq 100); do [ -f busy.restart.h5.lock ] && break; sleep 0.1; done
[ -f busy.e.lock ] && [ -f busy.h5.lock ] && [ -f busy.restart.h5.lock ] ||
  { echo "FAIL: the first run holds no locks: $(ls)"; fail=1; }
# (the first run's initial frame and history written: their sizes settled)
for i in $(seq 60); do
  size=$(stat -c %s busy.e busy.h5 2>/dev/null); sleep 0.5
  [ -n "$size" ] && [ "$size" = "$(stat -c %s busy.e busy.h5 2>/dev/null)" ] && break
done
refused busy.yaml file "another run (process $first on $host)"
out=$(run 2 "$exe" --quiet busy.yaml 2>&1)
[ "$(echo "$out" | grep -c "key 'file'.*another run (process $first on $host)")" = 2 ] ||
  { echo "$out"; echo "FAIL: on 2 ranks the second run is not refused by both ranks"; fail=1; }
kill -TERM $first
wait $first || { cat first.log; echo "FAIL: the first run ended with exit status $?"; fail=1; }
ls ./*.lock > /dev/null 2>&1 && { echo "FAIL: locks left after the run: $(ls ./*.lock)"; fail=1; }

# a lock of an ended process is taken over; one of a live process refuses
sh -c 'exit 0' & dead=$!
wait $dead
pd_deck "output: {file: o.e}" > short.yaml
echo "$host $dead" > o.e.lock
out=$("$exe" --quiet short.yaml 2>&1) || { echo "$out"; echo "FAIL: a stale lock was not taken over"; fail=1; }
echo "$out" | grep -q "o.e.lock' was left by process $dead on $host, which has ended: taken over" ||
  { echo "$out"; echo "FAIL: no warning about the stale lock"; fail=1; }
ls ./*.lock > /dev/null 2>&1 && { echo "FAIL: locks left after the run: $(ls ./*.lock)"; fail=1; }
# a zombie (ended, never reaped: its parent does not wait) is ended too, as a killed MPI rank
# can be for a while
sh -c 'sleep 0.1 & exec sleep 60' & parent=$!
sleep 0.5
zombie=$(pgrep -P $parent)
echo "$host $zombie" > o.e.lock
out=$("$exe" --quiet short.yaml 2>&1) || { echo "$out"; echo "FAIL: a zombie's lock was not taken over"; fail=1; }
echo "$out" | grep -q "o.e.lock' was left by process $zombie on $host, which has ended: taken over" ||
  { echo "$out"; echo "FAIL: no warning about the zombie's lock"; fail=1; }
kill $parent
sleep 60 & live=$!
echo "$host $live" > short.h5.lock
refused short.yaml history_file "another run (process $live on $host)"
kill $live
rm -f short.h5.lock
exit $fail
