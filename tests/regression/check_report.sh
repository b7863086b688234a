#!/usr/bin/env bash
# `perifem --check` says what the run will be, and refuses or warns before allocating:
#  1. wave_in_bar.yaml on 1 and 2 ranks: points (100 x 10 x 10 from the box and spacing),
#     directed bonds (pairs of lattice sites within the horizon, counted here), horizon/spacing,
#     steps = ceil(final_time / dt), Exodus frames = 1 + ceil(steps / interval), the run time
#     from those steps at the median of 9 timed (check_estimates.sh: against the run); the
#     memory estimate within a factor 2 of the
#     measured set-up memory; on 2 ranks the same bonds and half the estimate per rank;
#  2. the coupled bar (pamgen 30 x 8 x 8) and an FE block (pamgen 10 x 4 x 4): nodes and
#     elements from the mesh divisions, the kind, no bonds for FE; memory within a factor 2;
#  3. unit slips, warned about with the key and its line (exit 0): density 7.8 (g/cm^3),
#     bulk modulus 200 and Young's modulus 200 (MPa/GPa typed for Pa), a horizon of 0.3 m on a
#     0.05 m body; a horizon of 3.1 (mm typed as m) on a 0.05 m body refused (exit 2); the same
#     deck with plausible values warns about nothing;
#  4. under a 4 GB address-space limit, a 0.25 m cube at 2 mm spacing with a 20 mm horizon
#     (2.1e6 points, 4189 bonds each: about 350 GB) refused naming 'horizon' and its line, and
#     a 0.24 m cube at 2 mm with a 3-spacing horizon (1.8e6 points, 9.8 GB) naming 'spacing',
#     each within 2 s (or 0.3 s of a tiny deck's --check on a loaded machine) and before the
#     points are made: peak memory at most a tiny deck's + 30 MB (generating the points first
#     took 140-150 MB and 2.0-2.2 s).
# usage: check_report.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0
here=$(pwd)
source "$here/common/mpi_env.sh"
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
bad() { echo "FAIL: $*"; fail=1; }
# field N of the body line of NAME in report file F
body_field() { awk -v n="$2" -v k="$3" '$1 == n && NF >= 7 {print $k}' "$1"; }
# the memory line's estimate and measured set-up memory, in MB
mem_mb() {
  sed -n 's/.*estimated \([0-9.e+]*\) \([KMG]B\) before.*measured \([0-9.e+]*\) \([KMG]B\) (peak.*/\1 \2 \3 \4/p' "$1" |
    awk '{f["KB"]=1e-3; f["MB"]=1; f["GB"]=1e3; print $1 * f[$2], $3 * f[$4]}'
}
within2() { awk -v a="$1" -v b="$2" 'BEGIN {exit !(a > 0 && b > 0 && a <= 2 * b && b <= 2 * a)}'; }

# ---- 1. the PMB bar ------------------------------------------------------------------------
deck=$here/../inputs/wave_in_bar.yaml
"$exe" --check "$deck" > bar1.txt 2>&1 || bad "wave_in_bar --check exited $?"
run 2 "$exe" --check "$deck" > bar2.txt 2>&1 || bad "wave_in_bar --check on 2 ranks exited $?"
# the lattice: origin lo, spacing h, points lo + k h <= hi in each axis; horizon delta
read -r nx ny nz m bonds <<< "$($PY - <<'PY'
import math
lo, hi, h, delta = [0.00005] * 3, [0.00995, 0.00095, 0.00095], 0.0001, 0.00030001
n = [int(math.floor((b - a) / h + 1e-9)) + 1 for a, b in zip(lo, hi)]
r = int(delta / h) + 1
bonds = 0
for dx in range(-r, r + 1):
    for dy in range(-r, r + 1):
        for dz in range(-r, r + 1):
            if (dx, dy, dz) != (0, 0, 0) and (dx * dx + dy * dy + dz * dz) * h * h <= delta * delta:
                bonds += max(n[0] - abs(dx), 0) * max(n[1] - abs(dy), 0) * max(n[2] - abs(dz), 0)
print(*n, "%.3f" % (delta / h), bonds)
PY
)"
points=$((nx * ny * nz))
[ "$(body_field bar1.txt bar 3)" = "$points" ] || bad "bar points $(body_field bar1.txt bar 3), expected $points"
[ "$(body_field bar1.txt bar 4)" = "$bonds" ] || bad "bar bonds $(body_field bar1.txt bar 4), expected $bonds"
[ "$(body_field bar2.txt bar 4)" = "$bonds" ] || bad "bar bonds on 2 ranks $(body_field bar2.txt bar 4), expected $bonds"
[ "$(body_field bar1.txt bar 2)" = "PD" ] || bad "bar kind $(body_field bar1.txt bar 2), expected PD"
[ "$(body_field bar1.txt bar 6)" = "$m" ] || bad "bar horizon/spacing $(body_field bar1.txt bar 6), expected $m"
dt=$(sed -n 's/^  time step: \([0-9.e+-]*\) s (fixed), \([0-9]*\) steps.*/\1/p' bar1.txt)
steps=$(sed -n 's/^  time step: \([0-9.e+-]*\) s (fixed), \([0-9]*\) steps.*/\2/p' bar1.txt)
expect=$(awk -v dt="$dt" 'BEGIN {s = 5.0e-6 / dt; n = int(s); if (n < s - 1e-9) n++; print n}')
[ -n "$steps" ] && [ "$steps" = "$expect" ] || bad "bar steps '$steps' for dt '$dt', expected $expect"
frames=$(awk -v n="$steps" 'BEGIN {f = n / 50; k = int(f); if (k < f) k++; print k + 1}')
grep -q "(${frames} frames x" bar1.txt || bad "bar Exodus frames: expected $frames: $(grep Exodus bar1.txt)"
grep -q "^  run time: about .* on 1 rank(s) (CPU time per rank: set-up .*, $steps steps x .* (the median of 9 steps" bar1.txt ||
  bad "bar run time: expected $steps steps at the median of 9 timed: $(grep 'run time' bar1.txt)"
read -r est used <<< "$(mem_mb bar1.txt)"
within2 "$est" "$used" || bad "bar memory estimate $est MB against $used MB measured"
read -r est2 used2 <<< "$(mem_mb bar2.txt)"
awk -v a="$est" -v b="$est2" 'BEGIN {exit !(b > 0.45 * a && b < 0.55 * a)}' ||
  bad "bar memory per rank on 2 ranks $est2 MB, expected half of $est MB"

# ---- 2. coupled and FE bodies --------------------------------------------------------------
"$exe" --check "$here/data/coupled_bar.yaml" > coupled.txt 2>&1 || bad "coupled_bar --check exited $?"
[ "$(body_field coupled.txt bar 2)" = "coupled" ] || bad "coupled bar kind $(body_field coupled.txt bar 2)"
[ "$(body_field coupled.txt bar 3)" = "$((31 * 9 * 9))" ] || bad "coupled bar nodes $(body_field coupled.txt bar 3)"
[ "$(body_field coupled.txt bar 5)" = "$((30 * 8 * 8))" ] || bad "coupled bar elements $(body_field coupled.txt bar 5)"
[ "$(body_field coupled.txt bar 4)" -gt 0 ] 2>/dev/null || bad "coupled bar has no bonds"
read -r est used <<< "$(mem_mb coupled.txt)"
within2 "$est" "$used" || bad "coupled bar memory estimate $est MB against $used MB measured"
cat > fe.yaml <<'DECK'
materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}
bodies:
  - name: block
    type: finite_element
    material: steel
    mesh:
      pamgen: |
        mesh
          rectilinear
            nx = 40
            ny = 16
            nz = 16
            bx = 1
            by = 1
            bz = 1
            gmin = 0 0 0
            gmax = 0.04 0.016 0.016
          end
        end
time: {steps: 25}
output: {interval: 10}
DECK
"$exe" --check fe.yaml > fe.txt 2>&1 || bad "FE block --check exited $?"
[ "$(body_field fe.txt block 2)" = "FE" ] || bad "FE block kind $(body_field fe.txt block 2)"
[ "$(body_field fe.txt block 3)" = "$((41 * 17 * 17))" ] || bad "FE block nodes $(body_field fe.txt block 3)"
[ "$(body_field fe.txt block 4)" = "0" ] || bad "FE block bonds $(body_field fe.txt block 4)"
[ "$(body_field fe.txt block 5)" = "$((40 * 16 * 16))" ] || bad "FE block elements $(body_field fe.txt block 5)"
grep -q "about 25 steps" fe.txt || bad "FE block: 25 steps expected: $(grep 'time step' fe.txt)"
grep -q "(4 frames x" fe.txt || bad "FE block: 4 Exodus frames expected: $(grep Exodus fe.txt)"
read -r est used <<< "$(mem_mb fe.txt)"
within2 "$est" "$used" || bad "FE block memory estimate $est MB against $used MB measured"

# ---- 3. unit slips -------------------------------------------------------------------------
slip_deck() { # $1 density, $2 bulk modulus, $3 Young's modulus, $4 spacing, $5 horizon
  cat <<DECK
materials:
  glass:
    model: pmb
    density: $1
    bulk_modulus: $2
  steel: {model: elastic, density: 7800, youngs_modulus: $3, poissons_ratio: 0.3}
bodies:
  - name: cube
    material: glass
    geometry: {shape: box, lo: [0, 0, 0], hi: [0.05, 0.05, 0.05], spacing: $4}
    horizon: $5
time: {steps: 10}
DECK
}
# expect_warn FILE KEY LINE: a warning naming the deck, the line and the key
expect_warn() {
  grep -q "^perifem warning: $1:$3:[0-9]*: key '$2'" "$1.txt" || bad "$1: no warning on key '$2' at line $3: $(cat "$1.txt")"
}
slip_deck 7.8 200 200 0.005 0.0151 > slips.yaml
"$exe" --check slips.yaml > slips.yaml.txt 2>&1 || bad "slips.yaml --check exited $?"
expect_warn slips.yaml density 4
expect_warn slips.yaml bulk_modulus 5
expect_warn slips.yaml youngs_modulus 6
slip_deck 2200 14.9e9 200.0e9 0.01 0.3 > wide.yaml
"$exe" --check wide.yaml > wide.yaml.txt 2>&1 || bad "wide.yaml --check exited $?"
expect_warn wide.yaml horizon 11
slip_deck 2200 14.9e9 200.0e9 0.005 3.1 > mm.yaml
"$exe" --check mm.yaml > mm.yaml.txt 2>&1
st=$?
[ $st -eq 2 ] && grep -q "^perifem error: mm.yaml:11:[0-9]*: key 'horizon'" mm.yaml.txt ||
  bad "mm.yaml: exit $st (expected 2 naming 'horizon' at line 11): $(cat mm.yaml.txt)"

# ---- 4. refused before allocating ----------------------------------------------------------
big_deck() { # $1 edge, $2 spacing, $3 horizon
  cat <<DECK
materials: {glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}
bodies:
  - name: block
    material: glass
    geometry:
      shape: box
      lo: [0, 0, 0]
      hi: [$1, $1, $1]
      spacing: $2
    horizon: $3
time: {steps: 10}
DECK
}
slip_deck 2200 14.9e9 200.0e9 0.005 0.0151 > good.yaml
big_deck 0.25 0.002 0.02 > wide_horizon.yaml
big_deck 0.24 0.002 0.006 > fine_spacing.yaml
# peak_run DECK: "EXIT SECONDS PEAK_KB" of a --check under a 4 GB address space, output in DECK.txt
peak_run() {
  (ulimit -v 4000000
   s=$(date +%s.%N)
   "$exe" --check "$1" > "$1.txt" 2>&1 & pid=$!
   peak=0
   while kill -0 $pid 2>/dev/null; do
     kb=$(awk '/^VmHWM/ {print $2}' /proc/$pid/status 2>/dev/null)
     [ -n "$kb" ] && [ "$kb" -gt "$peak" ] && peak=$kb
     sleep 0.02
   done
   wait $pid
   st=$?
   echo "$st $(awk -v s="$s" -v e="$(date +%s.%N)" 'BEGIN {print e - s}') $peak")
}
read -r st0 t0 base <<< "$(peak_run good.yaml)"
[ "$st0" = 0 ] || bad "good.yaml under 4 GB: exit $st0"
! grep -q warning good.yaml.txt || bad "good.yaml warned: $(grep warning good.yaml.txt)"
for c in "wide_horizon.yaml horizon 10" "fine_spacing.yaml spacing 9"; do
  read -r d key line <<< "$c"
  read -r st t peak <<< "$(peak_run "$d")"
  [ "$st" = 2 ] && grep -q "^perifem error: $d:$line:[0-9]*: key '$key': the lattice would make about" "$d.txt" ||
    bad "$d: exit $st (expected 2 naming '$key' at line $line): $(cat "$d.txt")"
  grep -q "GB on each of 1 rank(s)).*more than the memory available" "$d.txt" || bad "$d: no estimate in the message"
  awk -v t="$t" -v t0="$t0" 'BEGIN {exit !(t < 2 || t < t0 + 0.3)}' ||
    bad "$d: refused after $t s (expected < 2 s, or on a loaded machine < 0.3 s more than a tiny deck's $t0 s)"
  [ -n "${PF_TEST_VERBOSE:-}" ] && echo "$d: exit $st in $t s, peak $peak KB (a tiny deck: $t0 s, $base KB)"
  [ "$peak" -le $((base + 30000)) ] || bad "$d: peak memory $peak KB, a tiny deck's is $base KB: allocated before refusing"
done
[ $fail -eq 0 ] || { echo "(outputs in $scratch)"; exit 1; }
exit 0
