#!/usr/bin/env bash
# perifem and CalculiX (ccx, explicit dynamics, C3D8R) on the same mesh: an elastic steel bar
# 20 x 2 x 2 mm (0.5 mm hexahedra) driven at one end by a smooth displacement ramp to 10 m/s;
# the axial displacement histories at three probe nodes agree within 2 % of their maximum
# (bench/calculix/README.md; the benchmark's 0.25 mm mesh and the timings are not run here).
# Also: the shipped deck bench/calculix/bar.yaml is what the generator writes.
# Needs ccx (Debian calculix-ccx) and /usr/bin/python3 with numpy, netCDF4 and h5py (or PY=...).
# usage: calculix_compare.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
py=${PY:-/usr/bin/python3}
source common/measure.sh
out=$(bash ../bench/calculix/run_calculix_compare.sh --quick --no-perf --work "$scratch" "$exe" 2>&1) \
  || { echo "$out"; exit 1; }
pf_measure worst_difference "$(echo "$out" | sed -n 's/^worst relative difference \([0-9.]*\)%.*/\1/p' | head -1)" "%"
"$py" ../bench/calculix/ccx_compare.py deck "$scratch/bar_default.yaml" \
  || { echo "ccx_compare.py deck failed"; exit 1; }
cmp -s "$scratch/bar_default.yaml" ../bench/calculix/bar.yaml \
  || { echo "bench/calculix/bar.yaml differs from 'ccx_compare.py deck' output:"; diff "$scratch/bar_default.yaml" ../bench/calculix/bar.yaml; exit 1; }
exit 0
