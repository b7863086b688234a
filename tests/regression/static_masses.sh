#!/usr/bin/env bash
# The quasi-static solver's fictitious masses where a face cuts the families short
# (docs/theory/quasi_static.md section 2): an LPS bond's stiffness goes as 1/m of its ends'
# families, a correspondence point's as its shape tensor's inverse, so a point near a face or an
# edge is stiffer than the bulk's bound says. Checks:
#  - tests/data/static_lps_thin_bar.yaml, an LPS bar 2 x 2 points across (no point has a whole
#    family), at the default time.safety_factor: it converges in each of its 4 load steps (before
#    the masses took the families' shortfall it diverged in the first); the reaction is linear in
#    the pull (each load step's reaction over its pull within 1e-3 of the last's: strain 1e-4);
#    the held end's reaction balances the pulled end's within 1e-6; Clapeyron's theorem, the
#    elastic energy = R d / 2, within 1e-3 at every load step; the same state digest on 1, 2 and
#    3 ranks;
#  - Willberg's double cantilever beam (inputs/dcb.yaml) on the 1 mm lattice (3 layers through
#    its 3 mm) at 5.01 spacings (a horizon of 5 mm: every family is cut by both faces), LPS and
#    correspondence, no damage, opened by 2 load steps: each converges, and at each load step the
#    elastic energy is (R_upper u_upper + R_lower u_lower) / 2 within 1e-3 (Clapeyron);
#  - the same bar pulled 1e155 m (its forces overflow): the run stops with a non-zero status and
#    a message naming the point of the largest out-of-balance force, instead of going on with a
#    residual it cannot form (it printed "residual 0" and finished with status 0);
#  - the same bar in explicit dynamics (tests/data/lps_thin_bar_explicit.yaml), stretched by an
#    initial velocity, at the default safety factor and at 1 (the stable step's estimate itself):
#    the run ends, kinetic + elastic energy stay within 5 % of the initial kinetic energy (the
#    kinetic energy is at the half steps), which turns into elastic energy and back, and the
#    ledger's balance within 1e-4 (before the stable step took the families' shortfall the motion
#    guard stopped it at step 7).
# usage: static_masses.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") scratch=$2 fail=0
data=$(pwd)/data inputs=$(cd .. && pwd)/inputs
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"

# clapeyron H5 CONDITIONS... : at every history row, the elastic energy against half the sum of
# reaction x displacement over the conditions (each "name:component"), within 1e-3 of the largest
clapeyron() {
  "$PY" - "$@" <<'PY'
import sys
import h5py
import numpy as np
f = h5py.File(sys.argv[1], "r")
half = sum(0.5 * f[n + "_reaction_" + c][:] * f[n + "_displacement_" + c][:]
           for n, c in (a.split(":") for a in sys.argv[2:]))
el = f["elastic_energy"][:]
gap = np.abs(el - half).max() / np.abs(el).max()
print("%s: elastic energy against R u / 2 at %d rows: largest gap %.2e of the largest energy" % (sys.argv[1], len(el), gap))
sys.exit(0 if gap <= 1e-3 else 1)
PY
}

# 1. the thin LPS bar
if out=$("$exe" --output-dir bar "$data/static_lps_thin_bar.yaml" 2>&1); then
  echo "$out" | grep -E '^load step'
  "$PY" - <<'PY' || fail=1
import sys
import h5py
import numpy as np
f = h5py.File("bar/static_lps_thin_bar.h5", "r")
R, d, H = f["pull_reaction_x"][:], f["pull_displacement_x"][:], f["held_reaction_x"][:]
k = R[1:] / d[1:]
print("stiffness R/d at each load step:", " ".join("%.6e" % v for v in k))
ok = True
if np.abs(k / k[-1] - 1).max() > 1e-3:
    print("FAIL: the reaction is not linear in the pull"); ok = False
if np.abs(R + H).max() > 1e-6 * np.abs(R).max():
    print("FAIL: the held end's reaction does not balance the pulled end's: %s %s" % (R, H)); ok = False
sys.exit(0 if ok else 1)
PY
  clapeyron bar/static_lps_thin_bar.h5 pull:x || { echo "FAIL: thin bar: Clapeyron"; fail=1; }
else
  echo "FAIL: the thin LPS bar did not converge: $(echo "$out" | grep -E 'error|load step' | head -3)"
  fail=1
fi
cp "$data/static_lps_thin_bar.yaml" . && static_digests "$exe" static_lps_thin_bar || fail=1

# 2. the double cantilever beam at 5.01 spacings on the 1 mm lattice, LPS and correspondence
for model in lps elastic; do
  out=$("$exe" --output-dir dcb_$model "$inputs/dcb.yaml" --set parameters.dx=1e-3 --set parameters.m=5.01 \
    --set materials.epoxy.model=$model --set 'bodies.beam.damage={law: none}' --set time.final_time=60e-6 \
    --set 'boundary_conditions.upper.displacement=[free, "0.5 * 57.5e-6 * t / 600e-6", free]' \
    --set 'boundary_conditions.lower.displacement=[free, "-0.5 * 57.5e-6 * t / 600e-6", free]' \
    --set 'solver={type: quasi_static, load_steps: 2, tolerance: 1.0e-5, max_iterations: 5000}' \
    --set output.interval=1 --set output.history_interval=1 2>&1) ||
    { echo "FAIL: the beam ($model) did not converge: $(echo "$out" | grep -E 'error' | head -2)"; fail=1; continue; }
  echo "$out" | grep -E '^load step' | sed "s/^/$model: /"
  clapeyron dcb_$model/dcb.h5 upper:y lower:y || { echo "FAIL: beam ($model): Clapeyron"; fail=1; }
done

# 3. forces that overflow stop the run, naming the point
out=$("$exe" --output-dir overflow "$data/static_lps_thin_bar.yaml" \
  --set 'boundary_conditions.pull.displacement=["1e155 * t", free, free]' 2>&1)
st=$?
msg=$(echo "$out" | grep 'perifem error')
echo "overflow: status $st: $msg"
if [ $st = 0 ] || ! echo "$msg" | grep -q "not finite.*on point [0-9]* (body 'bar') at (" ||
  echo "$out" | grep -q '^load step'; then
  echo "FAIL: forces that overflow did not stop the run with the point named"
  fail=1
fi
crash_in "$out" && { echo "FAIL: overflow: a crash"; fail=1; }

# 4. the bar in explicit dynamics, at the default safety factor and at 1
for sf in 0.8 1.0; do
  out=$("$exe" --output-dir explicit_$sf "$data/lps_thin_bar_explicit.yaml" --set time.safety_factor=$sf 2>&1) ||
    { echo "FAIL: the explicit bar at safety factor $sf: $(echo "$out" | grep -m2 'perifem error')"; fail=1; continue; }
  "$PY" - explicit_$sf/lps_thin_bar_explicit.h5 $sf <<'PY' || fail=1
import sys
import h5py
import numpy as np
f = h5py.File(sys.argv[1], "r")
k, e, err = f["kinetic_energy"][:], f["elastic_energy"][:], f["energy_error"][:]
spread = np.abs(k + e - k[0]).max() / k[0]
print("explicit bar, safety factor %s: %d rows, elastic energy up to %.3f of the initial kinetic, "
      "kinetic + elastic within %.2e of it, ledger balance %.2e" % (sys.argv[2], len(k), e.max() / k[0], spread,
                                                                   np.abs(err).max() / k[0]))
ok = e.max() > 0.5 * k[0] and spread < 5e-2 and np.abs(err).max() < 1e-4 * k[0]
sys.exit(0 if ok else 1)
PY
done

[ $fail = 0 ] && echo "PASS"
exit $fail
