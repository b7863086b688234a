#!/usr/bin/env bash
# Checkpoint and restart of a quasi-static run at a load-step boundary. The deck: inputs/
# static_bar.yaml (an FE bar and an LPS bar pulled in 4 load steps) with the LPS lattice at twice
# the spacing (and horizon, and grip layers), `restart: {file: ck.h5, interval: 2}`. The
# reference is the uninterrupted 1-rank run. A run is killed (SIGKILL, through the Python
# package: perifem.Simulation.step(2), then the process kills itself) right after the checkpoint
# at load step 2, on 1 rank and (with mpi4py) on 2; each checkpoint is restarted on 1, 2 and 3
# ranks. Checks:
#  - the restarted runs end with the reference's state digest;
#  - load steps 3 and 4 take the same relaxation iterations as in the reference (the predictor's
#    increment, point field load_step_increment, comes back from the checkpoint: without it load
#    step 3 starts from no prediction and takes more);
#  - the restarted history's rows at load steps 2 to 4 have the reference's bits in every
#    grip column (<bc>_reaction_*, _displacement_*, _work: sums independent of the ranks, the
#    running work carried by the checkpoint) and the summary names the load steps it took;
#  - a restart whose deck changes the solver section is refused naming it.
# usage: mpi_static_restart.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
exe=$1 scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd) fail=0
source common/mpi_env.sh
export OMP_NUM_THREADS=1
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
sed -E 's/spacing: 0.002/spacing: 0.004/; s/origin: \[0.001, 0.031, 0.001\]/origin: [0.002, 0.032, 0.002]/;
        s/horizon: 0.00603/horizon: 0.01206/; s/hi: \[0.006, 1, 1\]/hi: [0.012, 1, 1]/;
        s/lo: \[0.094, -1, -1\]/lo: [0.088, -1, -1]/; s/^output:/restart: {file: ck.h5, interval: 2}\noutput:/' \
  "$tests/../inputs/static_bar.yaml" > bar.yaml
[ "$(diff "$tests/../inputs/static_bar.yaml" bar.yaml | grep -c '^>')" = 6 ] || { echo "FAIL: the deck was not made"; exit 1; }
mkdir ref && ref_out=$(cd ref && "$exe" ../bar.yaml 2>&1) || { echo "FAIL: the reference run: $ref_out"; exit 1; }
ref=$(digest_of "$ref_out")
iterations() { echo "$1" | sed -n 's/^load step \([34]\)\/4 .* iterations \([0-9]*\) .*/\1:\2/p' | tr '\n' ' '; }
ref_it=$(iterations "$ref_out")
echo "reference: digest $ref, load steps 3 and 4 in $ref_it iterations"
[ -n "$ref" ] && [ "$(echo $ref_it | wc -w)" = 2 ] || { echo "FAIL: no digest or progress lines"; exit 1; }

# stop.py DECK [--mpi]: load steps 1 and 2 (the checkpoint at 2), then SIGKILL to itself
cat > stop.py <<'PYEOF'
import os
import signal
import sys
comm = None
if "--mpi" in sys.argv:
    from mpi4py import MPI
    comm = MPI.COMM_WORLD.Dup()
import perifem  # noqa: E402  (after mpi4py, which starts MPI)
sim = perifem.Simulation(sys.argv[1], quiet=True, comm=comm)
sim.step(2)
if comm is not None:
    comm.Barrier()
os.kill(os.getpid(), signal.SIGKILL)
PYEOF
pyenv="PYTHONPATH=$tests/../python PERIFEM_LIBRARY=$build/libperifem.so.0"
writers="1"
"$PY" -c "import mpi4py" 2>/dev/null && writers="1 2" || echo "(no mpi4py: the checkpoint is written on 1 rank only)"
for w in $writers; do
  rm -f ck.h5
  if [ $w = 1 ]; then env $pyenv "$PY" stop.py bar.yaml > stop$w.log 2>&1
  else run $w -x PYTHONPATH="$tests/../python" -x PERIFEM_LIBRARY="$build/libperifem.so.0" "$PY" stop.py bar.yaml --mpi > stop$w.log 2>&1
  fi
  step=$("$PY" -c "import h5py; print(int(h5py.File('ck.h5', 'r').attrs['step']))" 2>/dev/null)
  [ "$step" = 2 ] || { echo "FAIL: written on $w ranks: no checkpoint of load step 2 (step '$step'): $(tail -5 stop$w.log)"; fail=1; continue; }
  mv ck.h5 ck_w$w.h5
  for np in 1 2 3; do
    mkdir -p w${w}_np$np
    out=$(cd w${w}_np$np && run $np "$exe" --progress plain --restart ../ck_w$w.h5 ../bar.yaml 2>&1)
    d=$(digest_of "$out") it=$(iterations "$out")
    echo "written on $w ranks, restarted on $np: digest $d, load steps 3 and 4 in $it iterations"
    [ "$d" = "$ref" ] || { echo "FAIL: the digest is not the uninterrupted run's $ref: $(echo "$out" | tail -5)"; fail=1; }
    [ "$it" = "$ref_it" ] || { echo "FAIL: the iterations are not the uninterrupted run's ($ref_it)"; fail=1; }
    echo "$out" | grep -q "quasi-static: load steps 3 to 4 of 4" || { echo "FAIL: the summary does not say load steps 3 to 4"; fail=1; }
    "$PY" - ref/bar.h5 w${w}_np$np/bar-restart2.h5 <<'PYEOF' || fail=1
import sys
import h5py
import numpy as np
ref, got = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
rows = [list(ref["step"][:]).index(s) for s in got["step"][:]]
cols = [g + c for g in ("fe_held", "fe_pulled", "pd_held", "pd_pulled")
        for c in ["_work"] + ["_%s_%s" % (q, a) for q in ("reaction", "displacement") for a in "xyz"]]
bad = [c for c in cols if not np.array_equal(ref[c][:][rows], got[c][:])]
if list(got["step"][:]) != [2, 3, 4] or bad:
    print("FAIL: the restarted history (steps %s) differs from the uninterrupted one in %s" % (list(got["step"][:]), bad))
    sys.exit(1)
PYEOF
  done
done
# a changed solver section is refused, naming it
out=$("$exe" --restart ck_w1.h5 --set solver.tolerance=1e-8 bar.yaml 2>&1)
rc=$?
[ $rc = 2 ] && echo "$out" | grep -q "'solver' differs from the deck the checkpoint" || { echo "FAIL: a changed solver: exit $rc: $out"; fail=1; }
exit $fail
