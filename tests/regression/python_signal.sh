#!/usr/bin/env bash
# Ctrl-C during the Python package's run(): a run of tests/library/free_body.yaml made 10^8 steps
# long (hours) gets SIGINT 1 s after it started; the script must end within 5 s with
# KeyboardInterrupt, after the library checkpointed the step it stopped at (the deck's
# restart.file) and closed its files, as the command line does on SIGINT; a simulation restarted
# from that checkpoint is at that step. (Before: the signal waited for run() to end.) The script
# puts back Python's own SIGINT handler: a background job of a shell without job control starts
# with SIGINT ignored, which the library leaves ignored.
# usage: python_signal.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" && cp "$tests/library/free_body.yaml" .
fail() { echo "FAIL: $*"; exit 1; }
export PYTHONPATH="$tests/../python" PERIFEM_LIBRARY="$build/libperifem.so.0"
cat > long_run.py <<'PY'
import signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)
import perifem
sets = {"time.steps": 10**8, "output.interval": 10**9, "output.history_interval": 10**9,
        "restart.file": "stopped.h5"}
sim = perifem.Simulation("free_body.yaml", overrides=sets, output_dir="out", progress="plain")
sim.step(0)
print("running", flush=True)
try:
    sim.run()
except KeyboardInterrupt:
    print("KeyboardInterrupt at step %d" % sim.step_count, flush=True)
    sim.close()
    sys.exit(130)
print("run() ended at step %d without KeyboardInterrupt" % sim.step_count, flush=True)
PY
"$PY" long_run.py > run.log 2>&1 &
pid=$!
for _ in $(seq 100); do grep -q running run.log && break; sleep 0.1; done
grep -q running run.log || { kill -9 $pid; cat run.log; fail "the run did not start"; }
sleep 1
kill -INT $pid
t0=$(date +%s.%N)
for _ in $(seq 50); do kill -0 $pid 2> /dev/null || break; sleep 0.1; done
if kill -0 $pid 2> /dev/null; then kill -9 $pid; wait $pid; cat run.log; fail "still running 5 s after SIGINT"; fi
wait $pid
status=$?
took=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
cat run.log
[ $status -eq 130 ] || fail "exit status $status, expected 130 (KeyboardInterrupt caught)"
step=$(sed -n 's/^KeyboardInterrupt at step //p' run.log)
[ -n "$step" ] && [ "$step" -gt 0 ] || fail "no KeyboardInterrupt after steps"
ckpt=$(find . -name stopped.h5 | head -1)
[ -n "$ckpt" ] || fail "no checkpoint stopped.h5 written"
grep -q "signal 2: stopped at step $step" run.log || fail "the library's message 'signal 2: stopped at step $step' is missing"
got=$("$PY" -c "
import perifem
sim = perifem.Simulation('free_body.yaml', restart_from='$ckpt', output=False, quiet=True,
                         overrides={'time.steps': 10**8})
print(sim.step_count)" 2>&1) || { echo "$got"; fail "restart from $ckpt"; }
[ "$(echo "$got" | tail -1)" = "$step" ] || fail "restarted at step $got, stopped at $step"
echo "SIGINT after 1 s of run(): KeyboardInterrupt at step $step, $took s after the signal; checkpoint $ckpt"
exit 0
