#!/usr/bin/env bash
# Several materials in one FE body (`material_regions`, fem/materials.c; docs/theory/fem.md §9c):
#  - inputs/bimaterial_bar.yaml, quasi-static: a steel half and an aluminium half in
#    series under an end force F, nu = 0. The end displacement against the series springs'
#    u(L) = F (L1 / (E1 A) + L2 / (E2 A)) within 1 %, and the nodal stress sigma_xx = F / A at every
#    node, the interface's included, within 1e-6 (no jump at the interface: one stress in both
#    halves is what equilibrium of the bar asks);
#  - the same static deck and tests/data/bimaterial_bar_mixed.yaml (three materials, two of them
#    elastic and one J2, blocks and a region) on 1, 2 and 3 ranks: one state digest each;
#  - the mixed deck restarted from its checkpoint at step 100 ends with the straight run's digest.
# usage: fe_material_regions.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
data=$(pwd)/data
source common/mpi_env.sh
source common/measure.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
cp "$data/../../inputs/bimaterial_bar.yaml" static.yaml
out=$("$exe" static.yaml 2>&1) || { echo "FAIL: the static deck: $out"; exit 1; }
res=$("$PY" - static.e static.h5 <<'PYEOF'
import sys
import h5py
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
nodal = lambda name: np.array(e["vals_nod_var%d" % (names.index(name) + 1)][-1])
X = np.array(e["coordx"][:])
ux, sxx = nodal("displacement_x"), nodal("stress_xx")
F, A, L1, L2, E1, E2 = 2.0e3, 1.0e-4, 0.05, 0.05, 200.0e9, 70.0e9
u_cf = F * (L1 / (E1 * A) + L2 / (E2 * A))  # the two halves as springs in series
uL = ux[X > 0.0999].mean()
jump = np.abs(sxx / (F / A) - 1).max()
iface = np.abs(sxx[np.abs(X - L1) < 1e-9] / (F / A) - 1).max()
h = h5py.File(sys.argv[2], "r")
w, u = h["external_work"][-1], h["fe_internal_energy"][-1]
print("u(L) = %.9g m, series springs %.9g m (%+.4f %%); max |sigma_xx A/F - 1| = %.3g (interface nodes %.3g); work %.9g J, stored %.9g J"
      % (uL, u_cf, 100 * (uL / u_cf - 1), jump, iface, w, u))
print("MEASURE end_displacement_error %.6g" % (uL / u_cf - 1))
print("MEASURE stress_deviation %.6g" % jump)
ok = abs(uL / u_cf - 1) < 0.01 and jump < 1e-6 and abs(w - u) < 1e-4 * w
if not abs(uL / u_cf - 1) < 0.01: print("FAIL: the end displacement is off the series-spring closed form")
if not jump < 1e-6: print("FAIL: the stress is not F/A at every node (a jump at the interface?)")
if not abs(w - u) < 1e-4 * w: print("FAIL: the load's work is not the stored energy")
sys.exit(0 if ok else 1)
PYEOF
) || fail=1
echo "$res" | grep -v '^MEASURE'
echo "$res" | sed -n 's/^MEASURE //p' | while read -r k v; do pf_measure "$k" "$v" 1; done
for deck in static mixed; do
  [ $deck = mixed ] && cp "$data/bimaterial_bar_mixed.yaml" mixed.yaml
  digests=""
  for np in 1 2 3; do
    mkdir -p ${deck}_np$np
    o=$(cd ${deck}_np$np && run $np "$exe" --quiet ../$deck.yaml 2>&1) || { echo "FAIL: $deck on $np ranks: $o"; fail=1; }
    digests="$digests $(digest_of "$o")"
  done
  digests_agree "$deck" $digests || fail=1
done
# the mixed deck stopped at its checkpoint of step 100, then restarted to step 200
ref=$(digest_of "$(cd mixed_np1 && "$exe" --quiet ../mixed.yaml 2>&1)")
mkdir -p restart && cd restart
o=$("$exe" --quiet --set time.steps=100 ../mixed.yaml 2>&1) || { echo "FAIL: the run to step 100: $o"; fail=1; }
ck=$(ls ./*.restart.h5 2>/dev/null | head -1)
d=$(digest_of "$("$exe" --quiet --restart "$ck" ../mixed.yaml 2>&1)")
echo "mixed: restarted at step 100: digest $d, straight run $ref"
[ -n "$d" ] && [ "$d" = "$ref" ] || { echo "FAIL: the restart's digest differs from the straight run's"; fail=1; }
exit $fail
