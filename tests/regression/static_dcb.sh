#!/usr/bin/env bash
# Willberg's double cantilever beam loaded quasi-statically (inputs/dcb.yaml with the grips under
# displacement control and solver.type quasi_static; docs/examples/dcb.md, "Loaded
# quasi-statically"), reduced: spacing 1 mm (3,000 points, 3 layers through B), horizon 2.01
# spacings, critical energy G0 = 12 J/m^2, the grips opened to 57.5 um in 20 load steps,
# tolerance 1e-5. Run with each solver.failure: at_equilibrium (bonds checked at the load steps'
# equilibria; about 9 s of CPU) and sequential (the state scaled to each bond's limit before it
# fails; about 16 s). Checks, for both:
#  - the crack grows by repeated equilibria: damage passes in at least 3 load steps, and the
#    energy release rate comes from at least 3 load steps past one horizon of growth
#    (scripts/dcb_energy_release.py --quasi-static, or --sequential);
#  - Clapeyron's theorem (a linear elastic body at equilibrium holds half the work its loads do
#    on their displacements): at every load step, before and after the crack has grown, the
#    history's elastic energy equals (R_upper u_upper + R_lower u_lower) / 2 from the grips'
#    reaction and displacement columns within 1e-3 of the largest elastic energy; hence G from
#    the energy (D = W - E_el) and from the force-opening curve alone (D = W - F Delta / 2) within
#    1 %;
#  - the grips' work columns equal int F dDelta off their reaction and displacement columns
#    until the crack grows (the script refuses otherwise: 1e-6); at_equilibrium: they stay above
#    it after (in a load step where the crack grows the grips move first, to a force above the
#    row's);
#  - the energy balance closes within 1e-4 of the grips' work at every load step (measured
#    3.2e-6 and 3.7e-6), what the bonds do not take when a bond fails at a fixed opening being
#    the history's relaxation_dissipation (> 0); per crack area, G = G_bonds + G_relaxation
#    within 1 % (the slopes of damage_dissipation and relaxation_dissipation; measured 10.17 +
#    4.88 = 15.05 at equilibrium, 9.09 + 3.70 = 12.79 sequential);
#  - the bonds' energy booked at failure (damage_dissipation) per crack area is at least what the
#    lattice's crossing bonds hold at w_c, G0 S with S = 0.702 (scripts/dcb_lattice_share.py
#    --layers 3 --horizons 2.01: independent of the code; every failed bond holds >= w_c), less
#    5 % for the crack-area count; and G >= that (the relaxation's damping takes what a bond's
#    failure releases beyond it);
#  - softening (the law softening, r = 2, at Willberg's s_c; about 19 s): the bonds' dissipation
#    per crack area (G_bonds) within 5 % of the opening count of the 3-layer lattice at that s_c,
#    1.010 G0 (scripts/dcb_stretch_count.py --form willberg --layers 3 --horizons 2.01; every bond
#    that softens through to s1 dissipates what the brittle bond holds at s_c); measured 12.08
#    against 12.12 (-0.3 %), G 14.91;
#  - sequential only: G within 10 % of G0 (Willberg's band; measured 12.79, +6.6 %; at
#    equilibrium 15.05, +25 %, the bonds found past their limit). (Its digests on 1, 2 and 3
#    ranks: static_damage.sh, on a bar: a relaxation's 20,000 iterations of sums on 3 ranks over
#    2 cores take minutes.)
# usage: static_dcb.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") scratch=$2 fail=0
deck=$(cd .. && pwd)/inputs/dcb.yaml
src=$(cd .. && pwd)
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"

# quasi_static MODE NP: the reduced beam in $scratch/MODE<NP>, its output in $out (MODE: a
# solver.failure, or softening: at equilibrium with the law softening at Willberg's s_c)
quasi_static() {
  local failure=$1 law=()
  [ "$1" = softening ] && failure=at_equilibrium law=(--set 'bodies.beam.damage={law: softening, critical_stretch: "${s_c}"}')
  mkdir -p "$scratch/$1$2" && cd "$scratch/$1$2"
  out=$(run "$2" "$exe" "$deck" --set parameters.dx=1e-3 --set parameters.m=2.01 "${law[@]}" \
    --set 'boundary_conditions.upper.displacement=[free, "0.5 * 57.5e-6 * t / 600e-6", free]' \
    --set 'boundary_conditions.lower.displacement=[free, "-0.5 * 57.5e-6 * t / 600e-6", free]' \
    --set "solver={type: quasi_static, load_steps: 20, tolerance: 1.0e-5, failure: $failure}" \
    --set output.interval=1 --set output.history_interval=1 2>&1)
}

# check FAILURE: the checks above on $scratch/FAILURE1
check() {
  local mode=$1 opt=--quasi-static
  [ "$mode" = sequential ] && opt=--sequential
  quasi_static "$mode" 1 || { echo "FAIL: $mode: run: $out"; return 1; }
  echo "$out" | grep -E '^  (quasi-static|sequential failure):'
  local passes grown
  passes=$(echo "$out" | sed -n 's/^load step.*damage passes \([0-9]*\).*/\1/p')
  [ "$(echo "$passes" | wc -l)" = 20 ] || { echo "FAIL: $mode: not 20 load steps: $out"; return 1; }
  grown=$(echo "$passes" | awk '$1 > 0' | wc -l)
  echo "$mode: load steps with damage passes: $grown of 20"
  [ "$grown" -ge 3 ] || { echo "FAIL: $mode: the crack grew by damage passes in $grown load steps"; return 1; }
  "$PY" "$src/scripts/dcb_energy_release.py" dcb.h5 dcb.e --dx 1e-3 --horizon 2.01e-3 $opt \
    --json > G.json || { echo "FAIL: $mode: dcb_energy_release.py: $(cat G.json)"; return 1; }
  cat G.json
  "$PY" - "$mode" <<'PYEOF'
import json
import sys
import h5py
import numpy as np
mode, ok = sys.argv[1], True
g = json.load(open("G.json"))
with h5py.File("dcb.h5", "r") as f:
    el = f["elastic_energy"][:]
    half = 0.5 * (f["upper_reaction_y"][:] * f["upper_displacement_y"][:]
                  + f["lower_reaction_y"][:] * f["lower_displacement_y"][:])
    frac = f["damage_fraction"][:]
    err, work, relax = f["energy_error"][:], f["external_work"][:], f["relaxation_dissipation"][:]
    bonds = f["damage_dissipation"][-1]
print("%s: energy balance: largest |error| %.3g of the work; relaxation dissipation %.4g J, bonds %.4g J"
      % (mode, np.abs(err).max() / work[-1], relax[-1], bonds))
if not (np.abs(err).max() < 1e-4 * work[-1] and relax[-1] > 0):
    print("FAIL: energy balance: error %.3g J, relaxation dissipation %.3g J" % (np.abs(err).max(), relax[-1])); ok = False
gap = np.abs(el - half).max() / el.max()
print("%s: Clapeyron: largest |E_el - sum R u / 2| %.3g of the largest E_el (%d load steps, %d with damage)"
      % (mode, gap, len(el), np.count_nonzero(frac)))
if not (gap < 1e-3 and np.count_nonzero(frac) >= 3):
    print("FAIL: Clapeyron's theorem: %.3g" % gap); ok = False
if abs((g["G_bonds"] + g["G_relaxation"]) / g["G"] - 1) > 0.01:
    print("FAIL: G %.4g against bonds %.4g + relaxation %.4g" % (g["G"], g["G_bonds"], g["G_relaxation"])); ok = False
if abs(g["G_secant"] / g["G"] - 1) > 0.01:
    print("FAIL: G %.4g and G_secant %.4g" % (g["G"], g["G_secant"])); ok = False
if mode == "softening":  # every bond across the plane softened through to s1: the opening count
    count = 12.0 * 1.010
    print("softening: G %.4g J/m^2 (%+.1f %% of G0); bonds %.4g J/m^2, %+.2f %% of the opening count %.4g"
          % (g["G"], 100 * (g["G"] / 12.0 - 1), g["G_bonds"], 100 * (g["G_bonds"] / count - 1), count))
    if not (g["outputs_fitted"] >= 3 and abs(g["G_bonds"] / count - 1) < 0.05):
        print("FAIL: softening: the bonds' dissipation is not the opening count"); ok = False
    raise SystemExit(0 if ok else 1)
bound = 0.95 * 12.0 * 0.702
if not (g["outputs_fitted"] >= 3 and g["G_bonds"] >= bound and g["G"] >= g["G_bonds"]):
    print("FAIL: G %.4g, bonds %.4g J/m^2 against the lattice's G0 S %.4g (less 5 %%), %d load steps fitted"
          % (g["G"], g["G_bonds"], 12.0 * 0.702, g["outputs_fitted"])); ok = False
if mode == "sequential":
    print("sequential: G %.4g J/m^2, %+.1f %% of G0 = 12 (band 10 %%)" % (g["G"], 100 * (g["G"] / 12.0 - 1)))
    if abs(g["G"] / 12.0 - 1) > 0.10:
        print("FAIL: sequential: G outside 10 % of G0"); ok = False
raise SystemExit(0 if ok else 1)
PYEOF
}

check at_equilibrium || fail=1
check sequential || fail=1
check softening || fail=1
exit $fail
