#!/usr/bin/env bash
# SIGTERM during a quasi-static load step (docs/theory/quasi_static.md §4.2): the relaxation
# stops at the next iteration on every rank, the state goes back to the last load step's
# equilibrium (displacements, the bodies' history, forces), the run writes that checkpoint,
# says so and exits 0; the restart takes the load step again and ends with the uninterrupted
# run's state digest. The deck: tests/data/static_plastic_pd.yaml (elastic-plastic bar: PD
# history) at tolerance 1e-10 with a checkpoint file. Checks:
#  - 1 rank and 2 ranks: SIGTERM to every rank once load step 1 is reported;
#    the run says "abandoned" and "stopped at step 1", exits 0, its history's last row is load
#    step 1's (the energy balance as at load step 1: a row at the abandoned iterate had the
#    centred kinetic energy of its residual forces, -7e7 J);
#  - the checkpoint written on 1 rank restarted on 3, the one written on 2 restarted on 1: the
#    reference digest.
# usage: static_signal.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
export OMP_NUM_THREADS=1
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
sed -e 's/^output:/restart: {file: ck.h5}\noutput:/' -e 's/tolerance: 1.0e-8/tolerance: 1.0e-10/' \
  "$OLDPWD/data/static_plastic_pd.yaml" > bar.yaml
mkdir ref && ref=$(cd ref && "$exe" --quiet ../bar.yaml 2>&1) || { echo "FAIL: the reference run: $ref"; exit 1; }
ref=$(digest_of "$ref")
echo "reference digest $ref"
for np in 1 2; do
  rm -rf w$np && mkdir w$np && cd w$np
  ( run $np "$exe" ../bar.yaml > run.log 2>&1; echo "exit $?" >> run.log ) &
  for _ in $(seq 600); do grep -q '^load step 1/' run.log 2>/dev/null && break; sleep 0.05; done
  pkill -TERM -f "^$exe ../bar.yaml" # (every rank, as a batch system signals them)
  wait
  grep -q '^load step 2/4 abandoned' run.log && grep -q 'stopped at step 1,' run.log && grep -q '^exit 0' run.log ||
    { echo "FAIL: $np ranks: not abandoned at load step 2 with exit 0:"; grep -vE '^step' run.log | tail -8; fail=1; cd ..; continue; }
  "$PY" - <<'PYEOF' || fail=1
import h5py
import numpy as np
h = h5py.File("bar.h5", "r")
step, err, w = (np.array(h[k]) for k in ("step", "energy_error", "external_work"))
print("rows at steps %s, energy error / work at the last: %.3g" % (list(step.astype(int)), abs(err[-1]) / w[-1]))
if not (step[-1] == 1 and abs(err[-1]) < 1e-3 * w[-1]): print("FAIL: the last row is not load step 1's"); raise SystemExit(1)
PYEOF
  rp=$((np == 1 ? 3 : 1))
  {
    o=$(run $rp "$exe" --quiet --restart ck.h5 --output-dir r$rp ../bar.yaml 2>&1) || { echo "FAIL: restart on $rp: $o"; fail=1; }
    d=$(digest_of "$o")
    [ "$d" = "$ref" ] || { echo "FAIL: written on $np, restarted on $rp: digest $d, reference $ref"; fail=1; }
    echo "written on $np ranks, restarted on $rp: digest $d"
  }
  cd ..
done
exit $fail
