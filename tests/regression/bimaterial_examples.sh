#!/usr/bin/env bash
# The two bi-material examples as shipped (docs/examples/bimaterial_wave.md, bimaterial_bar.md),
# checked by scripts/bimaterial_plot.py --check against their closed forms:
#  - inputs/bimaterial_wave.yaml, a pulse across a soft -> stiff interface among peridynamic
#    (correspondence) points and a stiff -> soft one among elements: the reflected and transmitted
#    amplitudes from the momenta of the bar's three parts, R = (Z2 - Z1) / (Z1 + Z2) and
#    T = 2 Z2 / (Z1 + Z2) at each interface, and the transmitted energy shares 4 Z1 Z2 / (Z1 + Z2)^2,
#    within 1 % (Graff 1975); the incident momentum against the piston's impulse Z1 A V tau / 2
#    within 1 %; the energy balance within 1e-3 and the momentum balance within 1e-9;
#  - inputs/bimaterial_bar.yaml, quasi-static: the displacement at every node against the
#    series-spring field within 1 % of u(L), the nodal stress against F / A within 1e-6 (no ghost
#    force at the interface).
# The plots are written to the scratch folder (the pages' pictures are made the same way).
# usage: bimaterial_examples.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
source common/measure.sh
top=$(cd .. && pwd)
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
for case in wave bar; do
  out=$(OMP_NUM_THREADS=1 "$exe" --output-dir $case "$top/inputs/bimaterial_$case.yaml" 2>&1) ||
    { echo "FAIL: inputs/bimaterial_$case.yaml: $out"; fail=1; continue; }
  echo "$out" | grep -E '^perifem: ' || true
  res=$("$PY" "$top/scripts/bimaterial_plot.py" $case $case/bimaterial_$case.e --check 2>&1) ||
    { echo "FAIL: bimaterial_plot.py $case --check"; fail=1; }
  echo "$res" | grep -v '^measure '
  echo "$res" | sed -n 's/^measure //p' | while read -r k v; do pf_measure "${case}_$k" "$v" 1; done
done
exit $fail
