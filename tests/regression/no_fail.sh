#!/usr/bin/env bash
# bodies[i].damage.no_fail (pd/damage.c): regions whose points start with no stretch limit, so a
# bond fails only at the critical stretch of an end outside them (the no-fail zones of Ha &
# Bobaru 2010 along loaded edges). A PMB bar (2 x 2 x 20 mm, 0.5 mm lattice, critical stretch
# 1e-3) pulled apart at 20 m/s from both ends (nominal strain rate 2000 /s, so s0 is passed
# within a few microseconds):
#  - without no_fail bonds break (damage_fraction > 0.001 at the end);
#  - with no_fail over the whole bar none does: damage_fraction = 0 and no point is damaged;
#  - with no_fail over two boxes, z < 10 mm and z > 10 mm less a gap of 2 mm about z = 10 mm,
#    bonds break, and every damaged point lies within one horizon (1.5 mm) of the gap: a bond
#    with both ends in the zones never fails (checked on the Exodus damage field);
#  - no_fail under another law is an input error naming the key (exit status 2).
# usage: no_fail.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
deck() { # deck NAME NO_FAIL_LINES LAW
  cat > "$1.yaml" <<DECK
materials:
  glass: {model: pmb, density: 2440, bulk_modulus: 48.0e9}
bodies:
  - name: bar
    material: glass
    horizon: 1.5001e-3
    geometry: {shape: box, lo: [0, 0, 0], hi: [0.002, 0.002, 0.02], spacing: 0.5e-3,
               origin: [0.25e-3, 0.25e-3, 0.25e-3]}
    damage:
      $3
$2
boundary_conditions:
  - {region: {shape: box, lo: [-1, -1, -1], hi: [1, 1, 0.001]}, velocity: [free, free, "-20"]}
  - {region: {shape: box, lo: [-1, -1, 0.019], hi: [1, 1, 1]}, velocity: [free, free, "20"]}
time: {steps: 400}
output: {interval: 0, history_interval: 400, fields: [damage]}
DECK
}
deck plain "" "law: critical_stretch
      critical_stretch: 1.0e-3"
deck whole "      no_fail: [{shape: box, lo: [-1, -1, -1], hi: [1, 1, 1]}]" "law: critical_stretch
      critical_stretch: 1.0e-3"
deck gap "      no_fail:
        - {shape: box, lo: [-1, -1, -1], hi: [1, 1, 0.009]}
        - {shape: box, lo: [-1, -1, 0.011], hi: [1, 1, 1]}" "law: critical_stretch
      critical_stretch: 1.0e-3"
deck other "      no_fail: [{shape: box, lo: [-1, -1, -1], hi: [1, 1, 1]}]" "law: silling_askari
      s00: 1.0e-3"
for name in plain whole gap; do
  out=$("$exe" --quiet $name.yaml 2>&1) || { echo "FAIL: $name: $out"; fail=1; }
done
"$PY" - <<'PYEOF' || fail=1
import sys
import h5py
import numpy as np
from netCDF4 import Dataset
ok = True
def check(cond, what):
    global ok
    if not cond:
        print("FAIL:", what)
        ok = False
def final(name):
    h = h5py.File(name + ".h5", "r")
    with Dataset(name + ".e") as e:
        z = np.asarray(e["coordz"][:])
        d = np.asarray(e["vals_nod_var1"][-1])
    return h["damage_fraction"][-1], z, d
f, z, d = final("plain")
check(f > 1e-3, "without no_fail only %g of the bonds broke" % f)
f, z, d = final("whole")
check(f == 0 and d.max() == 0, "no_fail over the whole bar: damage_fraction %g, largest damage %g" % (f, d.max()))
f, z, d = final("gap")
far = np.abs(z - 0.010) > 0.001 + 1.5001e-3
check(f > 0, "no_fail but a 2 mm gap: no bond broke")
check(d[far].max() == 0, "a point %.2f mm from the gap's middle is damaged (%g)"
      % (1e3 * np.abs(z[far][np.argmax(d[far])] - 0.010), d[far].max()))
sys.exit(0 if ok else 1)
PYEOF
msg=$("$exe" other.yaml 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "other.yaml:.*no_fail.*not a parameter of damage law 'silling_askari'" ||
  { echo "FAIL: no_fail with silling_askari: exit $rc: $msg"; fail=1; }
exit $fail
