#!/usr/bin/env bash
# The plate with a hole (inputs/plate_hole.yaml, docs/examples/plate_hole.md) at a reduced size:
# the coarse mesh (parameters.h = 1 mm along the hole's edge, 1856 hexahedra), its one load step.
#  - elements only (the deck without `peridynamic:`) against CalculiX (ccx, static, C3D8, linear
#    elastic) on the same mesh: the displacement field within 1 % of its largest value and the
#    hole edge's sigma_xx within 1 % (scripts/plate_hole.py report --bands --no-kt; the
#    concentration's 3 % band against Howland needs the deck's finer mesh: slow_plate_hole.sh);
# The coupled plate's digests on 1, 2 and 3 ranks (about 110 s of CPU) are in slow_plate_hole.sh.
# Needs ccx and /usr/bin/python3 with numpy and netCDF4 (exit 77, skipped, without ccx).
# usage: plate_hole.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
root=$(cd .. && pwd)
deck=$root/inputs/plate_hole.yaml
script=$root/scripts/plate_hole.py
command -v ccx >/dev/null || { echo "no ccx: skipped"; exit 77; }
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"/fe && cd "$scratch"
coarse=(--set parameters.h=1.0e-3)
sed -e '/^    peridynamic:/,+2d' -e "s|\.\./meshes/|$root/meshes/|" "$deck" > fe/plate_hole.yaml  # elements only
o=$(cd fe && "$exe" "${coarse[@]}" plate_hole.yaml 2>&1) || { echo "FAIL: elements only: $o"; exit 1; }
echo "$o" | grep -E "quasi-static:"
"$PY" "$script" inp fe/plate_hole.e ccx_plate.inp || fail=1
ccx -i ccx_plate >ccx.log 2>&1 || { echo "FAIL: ccx"; tail ccx.log; exit 1; }
"$PY" "$script" report fe/plate_hole.e --ccx ccx_plate.dat --bands --no-kt || fail=1
exit $fail
