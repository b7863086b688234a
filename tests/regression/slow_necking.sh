#!/usr/bin/env bash
# Necking of a round tensile bar (inputs/necking.yaml, inputs/necking_pd.yaml;
# docs/examples/necking.md), whole: about 14 minutes of CPU
# (the elements 6.5, the finer PD bar 5).
#  - finite elements, pulled to 12 % in 24 load steps, past the peak into the neck: the
#    engineering-stress peak within 2 % of the closed form (Considere, the homogeneous bar:
#    scripts/necking.py considere), each load step up to the peak within 2 % of the homogeneous bar
#    and of CalculiX's static solver on the same mesh with the same hardening curve;
#  - correspondence peridynamics at two resolutions and two horizons (h = 0.75 mm and 0.5 mm at
#    horizon 3.015 h; h = 0.75 mm at 4 h), pulled to 9 % in 12 load steps: the same two bands
#    against the closed form; the neck (smallest over largest radius at 9 %) reported beside the
#    elements' (not a band: it depends on the horizon, which is the point).
# The plot of all five curves is left in SCRATCH/necking.png. Digests on 1, 2, 3 ranks:
# static_necking.sh. Needs ccx and /usr/bin/python3 with numpy, netCDF4, matplotlib.
# usage: slow_necking.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
root=$(cd .. && pwd)
script=$root/scripts/necking.py
command -v ccx >/dev/null || { echo "no ccx: skipped"; exit 77; }
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
perifem() { # perifem FOLDER DECK ARGS...: run in FOLDER, stop the test on failure
  local dir=$1 deck=$2; shift 2
  mkdir -p "$dir"
  o=$(cd "$dir" && "$exe" "$@" "$root/inputs/$deck.yaml" 2>&1) || { echo "FAIL: $dir: $o"; exit 1; }
  echo "$dir: $(echo "$o" | grep -E "quasi-static:")"
}
perifem fe necking
perifem pd_h0.75_m3 necking_pd
perifem pd_h0.5_m3 necking_pd --set parameters.h=0.5e-3
perifem pd_h0.75_m4 necking_pd --set parameters.m=4
"$PY" "$script" inp fe/necking.e ccx_necking.inp --steps 24 --stretch 0.12 || fail=1
ccx -i ccx_necking >ccx.log 2>&1 || { echo "FAIL: ccx"; tail ccx.log; exit 1; }
"$PY" "$script" report fe/necking.e --ccx ccx_necking.dat --stretch 0.12 --bands --verbose || fail=1
"$PY" "$script" report pd_*/necking_pd.e --bands || fail=1
"$PY" "$script" plot necking.png fe/necking.e pd_h0.75_m3/necking_pd.e pd_h0.5_m3/necking_pd.e \
  pd_h0.75_m4/necking_pd.e --ccx ccx_necking.dat \
  --labels "elements" "PD h = 0.75 mm, 3.015 h" "PD h = 0.5 mm, 3.015 h" "PD h = 0.75 mm, 4 h" || fail=1
exit $fail
