#!/usr/bin/env bash
# The Taylor bar (inputs/taylor_impact.yaml at 0.8 mm: 4,305 one-point hexahedra) in perifem and
# in CalculiX on the same mesh: ccx explicit dynamics with C3D8R elements and its own finite-strain
# J2 plasticity, the impact face held at u_z = 0 (the roller that perifem's `separation: false`
# wall is). The largest radius of the impact-face rim and the final length at 80 us agree within
# 1 % (bench/calculix/README.md, "The Taylor bar in CalculiX"; measured: 0.01 % and 0.23 %; the
# wall that lets the rim lift off differs by 1.28 %). Label slow: about 3 minutes on 2 cores.
# Needs ccx (Debian calculix-ccx) and /usr/bin/python3 with numpy and netCDF4 (or PY=...).
# usage: slow_calculix_taylor.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
py=${PY:-/usr/bin/python3} ccx=${CCX:-ccx}
command -v "$ccx" > /dev/null || { echo "SKIP: $ccx not found (apt-get install calculix-ccx)"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch" || exit 1
sed -E 's/^(\s*)element_size:.*/\1element_size: 0.8e-3/; s#\.\./meshes/#'"$PWD"'/../meshes/#; s/^(\s*)interval:.*/\1interval: 1000000/' \
  ../inputs/taylor_impact.yaml > "$scratch/taylor.yaml"
"$exe" --output-dir "$scratch" "$scratch/taylor.yaml" > "$scratch/perifem.log" 2>&1 \
  || { tail -20 "$scratch/perifem.log"; echo "FAIL: perifem"; exit 1; }
"$py" ../bench/calculix/ccx_taylor.py inp "$scratch/taylor.e" "$scratch/taylor_ccx.inp" \
  || { echo "FAIL: ccx_taylor.py inp"; exit 1; }
(cd "$scratch" && OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} "$ccx" -i taylor_ccx > ccx.log 2>&1) \
  || { tail -20 "$scratch/ccx.log"; echo "FAIL: ccx"; exit 1; }
"$py" ../bench/calculix/ccx_taylor.py compare "$scratch/taylor_ccx.frd" "$scratch/taylor.e" \
  || { echo "FAIL: the two codes differ (above)"; exit 1; }
