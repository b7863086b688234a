#!/usr/bin/env bash
# SIGTERM during a quasi-static load step (docs/theory/quasi_static.md §4.2): the relaxation
# stops at the next iteration on every rank, the state goes back to the last load step's
# equilibrium (displacements, the bodies' history, forces), the run writes that checkpoint,
# says so and exits 0; the restart takes the load step again and ends with the uninterrupted
# run's state digest. The deck: tests/data/static_plastic_pd.yaml (elastic-plastic bar: PD
# history) at tolerance 1e-10 with a checkpoint file. Checks:
#  - 1 rank: SIGTERM to every rank once load step 1 is reported, 2 ranks: once load step 2 is
#    (the bar has yielded: the checkpoint holds plastic history); the run says "load step L/4
#    abandoned" (L = 2 and 3 as a rule; later when the signal was slow to come: the test then
#    checks L) and "stopped at step L - 1", exits 0, its history's last row is load step L - 1's
#    (the energy balance as that load step's row: a row at the abandoned iterate had the
#    centred kinetic energy of its residual forces, -7e7 J);
#  - the checkpoint written on 1 rank restarted on 3, the one written on 2 restarted on 1: the
#    reference digest;
#  - a load step whose damage passes had failed bonds when the signal came (the reduced double
#    cantilever beam, below): back to its start, bonds and ledger included; restarted on 2 ranks,
#    the uninterrupted digest.
# usage: static_signal.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") scratch=$2 fail=0
src=$(cd .. && pwd)
source common/mpi_env.sh
export OMP_NUM_THREADS=1
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
sed -e 's/^output:/restart: {file: ck.h5}\noutput:/' -e 's/tolerance: 1.0e-8/tolerance: 1.0e-10/' \
  "$OLDPWD/data/static_plastic_pd.yaml" > signal_bar.yaml
mkdir ref && ref=$(cd ref && "$exe" --quiet ../signal_bar.yaml 2>&1) || { echo "FAIL: the reference run: $ref"; exit 1; }
ref=$(digest_of "$ref")
echo "reference digest $ref"
for np in 1 2; do
  rm -rf w$np && mkdir w$np && cd w$np
  ( run $np "$exe" ../signal_bar.yaml > run.log 2>&1; echo "exit $?" >> run.log ) &
  # (1 rank: once load step 1 is reported, 2 ranks: load step 2, when the bar has yielded, so that
  # the checkpoint holds plastic history)
  for _ in $(seq 600); do grep -q "^load step $np/" run.log 2>/dev/null && break; sleep 0.05; done
  # (every rank, as a batch system signals them; the deck's name is this test's alone, so that no
  # other test's run is signalled when ctest runs tests side by side)
  pkill -TERM -f "^$exe ../signal_bar.yaml"
  wait
  # (the load step the signal caught: 2 as a rule, a later one when this script was slow to send it)
  L=$(sed -n 's|^load step \([0-9]\)/4 abandoned.*|\1|p' run.log)
  [ -n "$L" ] && [ "$L" -ge 2 ] && grep -q "stopped at step $((L - 1))," run.log && grep -q '^exit 0' run.log ||
    { echo "FAIL: $np ranks: not abandoned at a load step after the first with exit 0:"; grep -vE '^step' run.log | tail -8; fail=1; cd ..; continue; }
  LAST=$((L - 1)) "$PY" - <<'PYEOF' || fail=1
import os
import h5py
import numpy as np
last = int(os.environ["LAST"])
h = h5py.File("signal_bar.h5", "r")
step, err, w = (np.array(h[k]) for k in ("step", "energy_error", "external_work"))
print("abandoned at load step %d; rows at steps %s" % (last + 1, list(step.astype(int))))
# the last row is at load step last's equilibrium, as that load step's own row (not at the
# abandoned iterate, whose centred kinetic energy put the balance off by -7e7 J)
if not (step[-1] == last and abs(err[-1] - err[step == last][0]) < 1e-3 * w[-1]): print("FAIL: the last row is not load step %d's" % last); raise SystemExit(1)
PYEOF
  rp=$((np == 1 ? 3 : 1))
  {
    o=$(run $rp "$exe" --quiet --restart ck.h5 --output-dir r$rp ../signal_bar.yaml 2>&1) || { echo "FAIL: restart on $rp: $o"; fail=1; }
    d=$(digest_of "$o")
    [ "$d" = "$ref" ] || { echo "FAIL: written on $np, restarted on $rp: digest $d, reference $ref"; fail=1; }
    echo "written on $np ranks, restarted on $rp: digest $d"
  }
  cd ..
done

# The crack of the reduced double cantilever beam (static_dcb.sh's: 1 mm, 2.01 spacings, critical
# energy, failure: sequential, a checkpoint file; its first 11 load steps of 20, those through the
# crack's start: 3 s instead of 12): SIGTERM once load step 9 is
# reported plus a delay, longer at each try (up to 4), until the signal catches a load step after
# at least one damage pass failed bonds ("abandoned after N iterations and P damage passes", P >=
# 1). The run goes back to the load step's start, bonds and ledger included; restarted on 2 ranks,
# it ends with the uninterrupted run's digest (before the bonds were put back: another digest and
# an energy error of 3-4 % of the energy in play at the next load step).
beam=("$src/inputs/dcb.yaml" --set parameters.dx=1e-3 --set parameters.m=2.01
  --set 'boundary_conditions.upper.displacement=[free, "0.5 * 57.5e-6 * t / 600e-6", free]'
  --set 'boundary_conditions.lower.displacement=[free, "-0.5 * 57.5e-6 * t / 600e-6", free]'
  --set "solver={type: quasi_static, load_steps: 11, tolerance: 1.0e-5, failure: sequential}"
  --set time.final_time=330e-6 --set restart.file=ck.h5 --set output.interval=0)
dcb_run() { "$exe" "${beam[@]}" "$@"; }
mkdir dref && ref=$(cd dref && dcb_run --quiet 2>&1) || { echo "FAIL: the beam's reference run: $ref"; exit 1; }
ref=$(digest_of "$ref")
echo "beam: reference digest $ref"
caught=0
for delay in 0.2 0.5 0.8 1.2; do
  rm -rf dsig && mkdir dsig && cd dsig
  "$exe" "${beam[@]}" > run.log 2>&1 &
  pid=$! # (this run alone: static_dcb runs the same deck beside it)
  # (load step 10 relaxes 1,933 iterations over 8 damage passes, about 1 s alone: a wide window
  # reached in about 1.5 s)
  for _ in $(seq 1200); do grep -q "^load step 9/" run.log 2>/dev/null && break; sleep 0.05; done
  sleep $delay
  kill -TERM $pid
  wait $pid
  echo "exit $?" >> run.log
  P=$(sed -n 's|^load step [0-9]*/11 abandoned after [0-9]* iterations and \([0-9]*\) damage passes.*|\1|p' run.log)
  grep -q '^exit 0' run.log || { echo "FAIL: beam: the signalled run did not exit 0:"; tail -5 run.log; fail=1; break; }
  if [ -n "$P" ] && [ "$P" -ge 1 ]; then caught=1; break; fi
  echo "beam: the signal after $delay s caught no load step after a damage pass ($(grep -E 'abandoned|stopped' run.log | head -1)); again"
  cd ..
done
if [ $caught = 1 ]; then
  grep -E "abandoned" run.log
  o=$(run 2 "$exe" "${beam[@]}" --quiet --restart ck.h5 --output-dir r2 2>&1) || { echo "FAIL: beam: restart on 2: $o"; fail=1; }
  d=$(digest_of "$o")
  [ "$d" = "$ref" ] || { echo "FAIL: beam: restarted on 2 ranks: digest $d, reference $ref"; fail=1; }
  echo "beam: written on 1 rank in a load step with damage passes, restarted on 2: digest $d"
  cd ..
elif [ $fail = 0 ]; then
  echo "FAIL: beam: four signals caught no load step after a damage pass"; fail=1
fi
exit $fail
