#!/usr/bin/env bash
# Necking of a round tensile bar at a reduced size (inputs/necking.yaml, inputs/necking_pd.yaml;
# docs/examples/necking.md): the first load steps past yield, where the whole run takes minutes
# (slow_necking.sh).
#  - finite elements (8 elements along the bar), pulled to 1 % in 2 load steps: each load step's
#    engineering stress within 2 % of CalculiX's static solver (ccx, NLGEOM, C3D8I) on the same
#    mesh with the same hardening curve, and within 2 % of the homogeneous bar's closed form
#    (scripts/necking.py report --bands);
#  - correspondence peridynamics (h = 0.75 mm, horizon 3.015 h), pulled to 1.5 % in 2 load steps:
#    within 2 % of the homogeneous bar;
#  - the same state digest on 1, 2 and 3 ranks for each (one load step, tolerance 1e-4).
# Needs ccx and /usr/bin/python3 with numpy and netCDF4 (exit 77, skipped, without ccx).
# usage: static_necking.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
root=$(cd .. && pwd)
script=$root/scripts/necking.py
command -v ccx >/dev/null || { echo "no ccx: skipped"; exit 77; }
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"/fe "$scratch"/pd && cd "$scratch"
fe=(--set parameters.nz=8 --set parameters.stretch=0.01 --set solver.load_steps=2)
pd=(--set parameters.stretch=0.015 --set solver.load_steps=2)
o=$(cd fe && "$exe" "${fe[@]}" "$root/inputs/necking.yaml" 2>&1) || { echo "FAIL: elements: $o"; exit 1; }
echo "$o" | grep -E "quasi-static:"
o=$(cd pd && "$exe" "${pd[@]}" "$root/inputs/necking_pd.yaml" 2>&1) || { echo "FAIL: points: $o"; exit 1; }
echo "$o" | grep -E "quasi-static:"
"$PY" "$script" inp fe/necking.e ccx_necking.inp --steps 2 --stretch 0.01 || fail=1
ccx -i ccx_necking >ccx.log 2>&1 || { echo "FAIL: ccx"; tail ccx.log; exit 1; }
"$PY" "$script" report fe/necking.e --ccx ccx_necking.dat --stretch 0.01 --bands --verbose || fail=1
"$PY" "$script" report pd/necking_pd.e --bands || fail=1
short=(--quiet --set solver.load_steps=1 --set solver.tolerance=1e-4)
for deck in necking necking_pd; do
  args=("${fe[@]}")
  [ $deck = necking_pd ] && args=("${pd[@]}")
  digests=""
  for np in 1 2 3; do
    mkdir -p $deck$np
    o=$(cd $deck$np && run $np "$exe" "${args[@]}" "${short[@]}" "$root/inputs/$deck.yaml" 2>&1) ||
      { echo "FAIL: $deck on $np ranks: $o"; fail=1; }
    digests="$digests $(digest_of "$o")"
  done
  digests_agree "$deck" $digests || fail=1
done
exit $fail
