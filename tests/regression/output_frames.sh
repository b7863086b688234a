#!/usr/bin/env bash
# Output frames by time as well as by steps (output.time_interval, output.frames and the
# history's history_time_interval, history_frames):
#  - the shipped Taylor bar (FE, adaptive step) cut to 2 us, output.time_interval 0.25 us: a
#    frame at t = 0, at the first step whose time reaches each multiple of 0.25 us (from the
#    step-by-step history of the same run), and at the last step; output.frames: 4 gives a frame
#    at the first step reaching each quarter of the run; history_time_interval the same for rows;
#  - a restart keeps the schedule: checkpoint at step 20 of a 1.2 us run, restarted to 2 us: the
#    restarted file's frames after its first are the uninterrupted run's after that time;
#  - quasi-static (inputs/static_bar.yaml at twice the spacing, 4 load steps over the pseudo-time
#    T = 1 ms): time_interval T/2 and frames: 2 each write load steps 0, 2, 4;
#  - refused naming file:line and the key (exit 2): interval and time_interval; history_interval
#    and history_frames; a time interval of 0 or .inf; frames: 0.
# usage: output_frames.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
src=$(cd .. && pwd)/inputs
rm -rf "$scratch" && mkdir -p "$scratch"
bad() { echo "FAIL: $*"; fail=1; }
sed -E 's#\.\./meshes/#'"$src"'/../meshes/#; /^  interval: 200$/d' "$src/taylor_impact.yaml" > "$scratch/taylor.yaml"
grep -q "^  history_interval: 20$" "$scratch/taylor.yaml" && ! grep -q "^  interval:" "$scratch/taylor.yaml" ||
  { echo "FAIL: the shipped Taylor deck changed; the sed edit no longer applies"; exit 1; }
cd "$scratch" || exit 1
short="--quiet --set time.final_time=2e-6"
"$exe" $short --set output.time_interval=2.5e-7 --set output.history_interval=1 --output-dir by_time taylor.yaml \
  > by_time.log 2>&1 || bad "time_interval: the run exited $?: $(tail -3 by_time.log)"
# (the same steps: output does not change the state)
sed 's/^  history_interval: 20$/  history_time_interval: 2.5e-7/' taylor.yaml > rows.yaml
"$exe" $short --set output.frames=4 --output-dir rows rows.yaml > rows.log 2>&1 || bad "frames, history_time_interval: exit $?"
# the restart: checkpoint at step 20 (the only one of a 1.2 us run), restarted to 2 us
"$exe" --quiet --set time.final_time=1.2e-6 --set output.time_interval=2.5e-7 --set restart.file=ck.h5 \
  --set restart.interval=20 --output-dir first taylor.yaml > first.log 2>&1 || bad "the checkpoint run exited $?"
"$exe" $short --set output.time_interval=2.5e-7 --output-dir restarted --restart first/ck.h5 taylor.yaml \
  > restarted.log 2>&1 || bad "the restart exited $?: $(tail -3 restarted.log)"
"$PY" - <<'EOF' || fail=1
import sys
import h5py, netCDF4
import numpy as np
ok = True
def frames(path):
    with netCDF4.Dataset(path) as d:
        return np.asarray(d["time_whole"][:], dtype=float)
def expect(label, got, steps, period):
    """t = 0, the first step reaching each multiple of period, the last step."""
    global ok
    want = [steps[0]] + [steps[np.argmax(steps >= k * period * (1 - 1e-9))] for k in
                         range(1, int(np.floor(steps[-1] / period + 1e-9)) + 1)]
    want = np.unique(np.append(want, steps[-1]))
    if len(got) != len(want) or np.any(got != want):
        print("FAIL %s: times %s, want %s" % (label, got, want)); ok = False
with h5py.File("by_time/taylor.h5", "r") as h:
    steps = np.asarray(h["time"][:], dtype=float)
if not (np.ptp(np.diff(steps)) > 0 and len(steps) > 30):
    print("FAIL: the history is not step by step with a varying step: %d rows" % len(steps)); ok = False
expect("time_interval 0.25 us", frames("by_time/taylor.e"), steps, 2.5e-7)
if len(frames("by_time/taylor.e")) != 9: print("FAIL: time_interval: %d frames, want 9" % len(frames("by_time/taylor.e"))); ok = False
expect("frames: 4", frames("rows/rows.e"), steps, 2e-6 / 4)
with h5py.File("rows/rows.h5", "r") as h:
    expect("history_time_interval", np.asarray(h["time"][:], dtype=float), steps, 2.5e-7)
full, rest = frames("by_time/taylor.e"), frames("restarted/taylor-restart20.e")
after = full[full > rest[0]]
if not (len(rest) > 2 and len(after) == len(rest) - 1 and np.all(after == rest[1:])):
    print("FAIL restart: frames %s after t = %.6e, the uninterrupted run's %s" % (rest[1:], rest[0], after)); ok = False
sys.exit(0 if ok else 1)
EOF
# quasi-static: pseudo-time
sed -E 's/spacing: 0.002/spacing: 0.004/; s/origin: \[0.001, 0.031, 0.001\]/origin: [0.002, 0.032, 0.002]/;
        s/horizon: 0.00603/horizon: 0.01206/; s/hi: \[0.006, 1, 1\]/hi: [0.012, 1, 1]/;
        s/lo: \[0.094, -1, -1\]/lo: [0.088, -1, -1]/; s/^  interval: 0$/  precision: double/' "$src/static_bar.yaml" > bar.yaml
for v in "time_interval=5e-4" "frames=2"; do
  "$exe" --quiet --set output.$v --output-dir "qs_${v%%=*}" bar.yaml > "qs_${v%%=*}.log" 2>&1 ||
    { bad "quasi-static $v: exit $?: $(tail -3 "qs_${v%%=*}.log")"; continue; }
  got=$("$PY" -c "import netCDF4, sys; d = netCDF4.Dataset(sys.argv[1]); print(' '.join('%g' % t for t in d['time_whole'][:]))" \
        "qs_${v%%=*}/bar.e")
  [ "$got" = "0 0.0005 0.001" ] || bad "quasi-static $v: frames at $got, want 0 0.0005 0.001 (load steps 0, 2, 4)"
done
# refused decks: each names its file, line and key
refuse() { # NAME KEY LINES...
  local name=$1 key=$2; shift 2
  cp taylor.yaml "$name.yaml"
  printf '%s\n' "$@" >> "$name.yaml"
  "$exe" --check "$name.yaml" > "$name.txt" 2>&1
  local st=$?
  [ $st -eq 2 ] && grep -q "^perifem error: $name.yaml:[0-9]*:[0-9]*: key '$key'" "$name.txt" ||
    bad "$name: exit $st (expected 2 naming '$key' with file:line): $(cat "$name.txt")"
}
refuse both time_interval "  interval: 10" "  time_interval: 1.0e-7"
refuse history history_frames "  history_frames: 10"
refuse zero time_interval "  time_interval: 0"
refuse infinite time_interval "  time_interval: .inf"
refuse no_frames frames "  frames: 0"
exit $fail
