#!/usr/bin/env bash
# A small mixed PD/FE run under valgrind memcheck: no invalid read or write, no use of
# uninitialised values, and no leak through perifem's own code (the MPI stack's allocations at
# start-up are its own). Needs a build without -march=native (valgrind does not decode
# AVX-512): it configures build-valgrind/ with PERIFEM_NATIVE=OFF.
#   bash scripts/valgrind.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cmake -S . -B build-valgrind -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPERIFEM_NATIVE=OFF >/dev/null
cmake --build build-valgrind -j"$(nproc)" --target perifem 2>&1 | grep -v "^\[" || true
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/small.yaml" <<'DECK'
materials:
  glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}
  copper: {model: j2, density: 8930, youngs_modulus: 117.0e9, poissons_ratio: 0.35, yield_stress: 400.0e6, hardening_modulus: 100.0e6}
bodies:
  - {name: plate, material: glass, horizon: 0.0015001, damage: {law: critical_stretch, critical_stretch: 0.0005},
     initial_velocity: ["0", "0", "-20 * z / 0.0025"],
     geometry: {shape: box, lo: [0, 0, 0], hi: [0.004, 0.004, 0.0015], spacing: 0.0005}}
  - name: bar
    type: finite_element
    material: copper
    initial_velocity: ["0", "0", "-200"]
    mesh:
      pamgen: |
        mesh
          rectilinear
            nx = 2
            ny = 2
            nz = 4
            bx = 1
            by = 1
            bz = 1
            gmin = 0.0 0.0 0.004
            gmax = 0.002 0.002 0.008
          end
        end
walls:
  - {name: floor, point: [0, 0, 0.0039], normal: [0, 0, 1], bodies: [bar]}
time: {steps: 20}
output: {interval: 10}
restart: {interval: 10}
DECK
(cd "$work" && valgrind --error-exitcode=9 --leak-check=full --show-leak-kinds=definite \
   --errors-for-leak-kinds=none --track-origins=yes \
   --suppressions=/usr/share/openmpi/openmpi-valgrind.supp \
   "$OLDPWD/build-valgrind/perifem" --quiet small.yaml) > "$work/log" 2>&1 || {
  echo "valgrind: memcheck errors:"; grep -E "Invalid|uninitialised|ERROR SUMMARY" "$work/log" | head -20; exit 1; }
# definite leaks whose stack passes through perifem (functions pf_*)
if awk '/definitely lost in loss record/ { rec = 1; next } /^==[0-9]+== $/ { rec = 0 } rec && / pf_/ { found = 1 } END { exit !found }' "$work/log"; then
  echo "valgrind: a leak through perifem's code:"; grep -A12 "definitely lost in loss record" "$work/log" | head -40; exit 1
fi
grep -E "ERROR SUMMARY|definitely lost:" "$work/log"
echo "valgrind: clean"
