#!/usr/bin/env bash
# Soft contact pairs (`soft: true`, docs/theory/contact.md §4a): a pair's stiffness lowered at the
# set-up until its stable step is the smaller of its two bodies'. tests/data/contact_soft.yaml: a
# polycarbonate block of hexahedra pressed onto a PMB steel plate, whose default penalty (K h of
# the steel on the light polymer nodes) would set the time step. Checked:
#  - `perifem --check` without `soft`: the pair's stable step S0 below both bodies' (the premise);
#    with it: the logged change k0 -> k and S0 -> S1, S1 the smaller body step of the report's
#    stable-steps line and the pair's step there, and k / k0 = (S0 / S1)^2 (every penalty's
#    omega^2 is linear in its stiffness: the step 2 / omega goes as k^-1/2; 2e-3, the printed
#    digits);
#  - the runs: the adaptive step count falls by S1 / S0 (5 %: the step follows the elements);
#    the energy balance within 2 % (1.1 %; the default stiffness's 0.68 %: the block's whole face
#    meets the plate in one step);
#  - the same state digest on 1, 2 and 3 ranks; restarted from a checkpoint on 1, 2 and 3 ranks,
#    the uninterrupted run's, with the plate as shipped and as a correspondence body (whose
#    stable step at a restart's set-up is its points' last, not the reference one: the
#    checkpoint carries the pair's stiffness; without it that restart's digest differs);
#  - a short-range pair (PD self-contact, C in N/m^7) soft too: kept at the default spring constant
#    (its step is not below the plate's), lowered alike at k_s = 1e13 Pa; a pair whose step ties
#    its body's leaves the body named as the smallest;
#  - refused by the quasi_static solver, naming the pair's `soft` and its line.
# usage: contact_soft.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") scratch=$2 fail=0
data=$(cd data && pwd)
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
bad() { echo "FAIL: $*"; fail=1; }
cp "$data/contact_soft.yaml" soft.yaml
sed 's/- {bodies: \[block, plate\], soft: true}/- {bodies: [block, plate]}/' soft.yaml > stiff.yaml
grep -q "plate\], soft: true" stiff.yaml && bad "could not take soft out of the deck"

# ---- the fit, from --check -----------------------------------------------------------------
"$exe" --check stiff.yaml > stiff.txt 2>&1 || bad "stiff --check exited $?: $(tail -3 stiff.txt)"
"$exe" --check soft.yaml > soft.txt 2>&1 || bad "soft --check exited $?: $(tail -3 soft.txt)"
# step NAME FILE: the stable step of NAME in FILE's stable-steps line
step() { sed -n 's/^  stable steps: //p' "$2" | tr ',' '\n' | sed -n "s/^ *$1 \([0-9.e+-]*\) s.*/\1/p"; }
s0=$(step "contact pairs" stiff.txt) p0=$(step plate stiff.txt) b0=$(step block stiff.txt)
s1=$(step "contact pairs" soft.txt) p1=$(step plate soft.txt) b1=$(step block soft.txt)
read -r k0 k sa sb <<< "$(sed -n "s/^contact pair 'block_plate' (soft): stiffness \([0-9.e+-]*\) -> \([0-9.e+-]*\) N\/m, its stable step \([0-9.e+-]*\) -> \([0-9.e+-]*\) s, that of body 'plate'$/\1 \2 \3 \4/p" soft.txt)"
echo "stable steps without soft: pair $s0, plate $p0, block $b0; with soft: pair $s1, plate $p1, block $b1; k $k0 -> $k"
[ -n "$s0" ] && [ -n "$s1" ] && [ -n "$k" ] || bad "no stable steps or soft line: $(grep -E 'stable steps|soft' stiff.txt soft.txt)"
awk -v s="$s0" -v p="$p0" -v b="$b0" 'BEGIN {exit !(s < p && s < b)}' || bad "premise: the default pair's step $s0 is not below the bodies' ($p0, $b0)"
awk -v a="$sa" -v s0="$s0" -v b="$sb" -v s1="$s1" -v p="$p1" -v q="$b1" \
  'function rel(x, y) {return (x > y ? x - y : y - x) / y} BEGIN {exit !(rel(a, s0) < 2e-3 && rel(b, s1) < 2e-3 && rel(s1, (p < q ? p : q)) < 1e-9)}' ||
  bad "the soft pair's step $sb (logged from $sa) is not the smaller body step of ($p1, $b1), or $sa is not the default's $s0"
awk -v k0="$k0" -v k="$k" -v a="$sa" -v b="$sb" 'BEGIN {r = (k / k0) / ((a / b) ^ 2); exit !(r > 0.998 && r < 1.002)}' ||
  bad "k / k0 = $k / $k0 is not (S0 / S1)^2 = ($sa / $sb)^2"

# a short-range pair (C in N/m^7) soft as well: at the default spring constant its step is not
# below the plate's and it keeps its stiffness; at k_s = 1e13 Pa it is, and it is lowered alike
sed 's/    - {bodies: \[block, plate\], soft: true}/&\n    - {bodies: [plate, plate], soft: true}/' soft.yaml > self.yaml
sed 's/{bodies: \[plate, plate\], soft: true}/{bodies: [plate, plate], soft: true, spring_constant: 1.0e13}/' self.yaml > self_stiff.yaml
"$exe" --check self.yaml > self.txt 2>&1 || bad "self --check exited $?: $(tail -3 self.txt)"
"$exe" --check self_stiff.yaml > self_stiff.txt 2>&1 || bad "self_stiff --check exited $?: $(tail -3 self_stiff.txt)"
grep -q "^contact pair 'plate_plate'" self.txt && bad "the short-range pair at the default spring constant was lowered: $(grep plate_plate self.txt)"
read -r c0 c sa2 sb2 <<< "$(sed -n "s/^contact pair 'plate_plate' (soft): stiffness \([0-9.e+-]*\) -> \([0-9.e+-]*\) N\/m^7, its stable step \([0-9.e+-]*\) -> \([0-9.e+-]*\) s, that of body 'plate'$/\1 \2 \3 \4/p" self_stiff.txt)"
echo "short-range pair at k_s = 1e13 Pa: C $c0 -> $c N/m^7, its step $sa2 -> $sb2 s"
awk -v k0="$c0" -v k="$c" -v a="$sa2" -v b="$sb2" -v p="$p1" 'BEGIN {r = (k / k0) / ((a / b) ^ 2); exit !(r > 0.998 && r < 1.002 && (b - p) ^ 2 < (2e-3 * p) ^ 2)}' ||
  bad "short-range: C / C0 = $c / $c0 is not (S0 / S1)^2 = ($sa2 / $sb2)^2, or $sb2 is not the plate's $p1"
grep -q "^  stable steps: plate [0-9.e+-]* s (the smallest)" self.txt || bad "a tie of the pair with its body names the pair: $(grep 'stable steps' self.txt)"

# ---- the runs ------------------------------------------------------------------------------
steps_of() { echo "$1" | sed -n 's/^perifem: \([0-9]*\) steps of .*/\1/p'; }
rel_error() { echo "$1" | sed -n 's/.*energy balance error .* J (relative \([0-9.e+-]*\);.*/\1/p'; }
o_stiff=$("$exe" --output-dir stiff stiff.yaml 2>&1) || bad "stiff run exited $?: $(echo "$o_stiff" | tail -3)"
ref=$("$exe" --output-dir soft --set restart.interval=60 --set restart.file=ck.h5 soft.yaml 2>&1) || bad "soft run exited $?: $(echo "$ref" | tail -3)"
n0=$(steps_of "$o_stiff") n1=$(steps_of "$ref") e0=$(rel_error "$o_stiff") e1=$(rel_error "$ref")
echo "steps $n0 -> $n1 (S1 / S0 = $(awk -v a="$s1" -v b="$s0" 'BEGIN {printf "%.3f", a / b}')); energy balance $e0 -> $e1"
awk -v n0="$n0" -v n1="$n1" -v s0="$s0" -v s1="$s1" 'BEGIN {r = (n0 / n1) / (s1 / s0); exit !(r > 0.95 && r < 1.05)}' ||
  bad "the step count fell from $n0 to $n1, not by S1 / S0 = $s1 / $s0"
awk -v e="$e1" 'BEGIN {exit !(e > -0.02 && e < 0.02)}' || bad "soft run's energy balance $e1 beyond 2 %"

# restart_digests NAME DECK REF: DECK on 1, 2, 3 ranks and restarted from ck.h5 (step 60) on 1, 2, 3
# ranks: one digest, REF's (the uninterrupted run's output)
restart_digests() {
  local name=$1 deck=$2 ref=$3 np o d r
  d="" r=""
  for np in 1 2 3; do
    mkdir -p "$name/np$np" "$name/rs$np"
    o=$(cd "$name/np$np" && run $np "$exe" --quiet "../../$deck" 2>&1) || bad "$name on $np ranks: $o"
    d="$d $(digest_of "$o")"
    o=$(cd "$name/rs$np" && run $np "$exe" --quiet --restart ../ck.h5 "../../$deck" 2>&1) || bad "$name restarted on $np ranks: $o"
    r="$r $(digest_of "$o")"
  done
  digests_agree "$name" $d || fail=1
  digests_agree "$name restarted at step 60" $r || fail=1
  [ "$(digest_of "$ref")" = "$(echo $r | cut -d' ' -f1)" ] || bad "$name: the restart's digest is not the uninterrupted run's $(digest_of "$ref")"
}
mkdir -p pmb && cp soft/ck.h5 pmb/
restart_digests pmb soft.yaml "$ref"
# the plate as a correspondence body
sed -E 's/steel: \{model: pmb, density: 7870, bulk_modulus: 162.0e9\}/steel: {model: elastic, density: 7870, youngs_modulus: 200.0e9, poissons_ratio: 0.29}/' soft.yaml > corr.yaml
grep -q "model: elastic, density: 7870" corr.yaml || bad "could not make the plate a correspondence body"
ref=$("$exe" --output-dir corr --set restart.interval=60 --set restart.file=ck.h5 corr.yaml 2>&1) || bad "corr run exited $?: $(echo "$ref" | tail -3)"
restart_digests corr corr.yaml "$ref"

# ---- refused under the quasi-static solver ----------------------------------------------------
printf 'boundary_conditions:\n  - {name: push, region: {shape: box, lo: [-1, -1, 0.004], hi: [1, 1, 1]}, displacement: ["0", "0", "-1.0e-4 * t"]}\nsolver: {type: quasi_static, load_steps: 2}\n' > qs_tail.yaml
sed '/initial_velocity/d; s/^time: {final_time: 20.0e-6}/time: {final_time: 1.0}/' soft.yaml > qs.yaml
cat qs_tail.yaml >> qs.yaml
line=$(grep -n "plate\], soft: true" qs.yaml | cut -d: -f1)
o=$("$exe" --check qs.yaml 2>&1)
st=$?
[ $st = 2 ] && echo "$o" | grep -q "qs.yaml:$line:[0-9]*: key 'soft': a soft pair's stiffness is set by the bodies' stable time step" ||
  bad "soft under quasi_static: exit $st (want 2 naming qs.yaml:$line and 'soft'): $o"

[ $fail = 0 ] || exit 1
