#!/usr/bin/env bash
# A deck composed of parts (include:, parameters: with ${...}, --set overrides on the command
# line) runs exactly like the same deck written out by hand: the reference is the written-out
# deck's own run (made here with sed from the shipped wave_in_bar.yaml, cut to 0.3 us, not by perifem), and the
# composed deck must give its state digest, on 1 and on 2 ranks.
#  1. a deck that includes its materials from another file and takes density, modulus, spacing
#     and the pulse's speed from parameters (one of them used bare inside an x expression);
#  2. a ${...} of 300 terms (1.9 kB) gives its value, not the value of its first 1023 characters;
#     --set of a material's value, of a body's value by the body's name and by its index, of a
#     parameter, of a key the deck does not give (time.dt), and a list value;
#  3. errors name where the bad value was given, with exit 2: an unknown key given by --set (with
#     the suggestion), --set without '=', an unknown list item, an unknown name in ${...}, a
#     missing included file, a file that includes itself, a value given both in an included file
#     and in the deck (both places named), an unknown key inside an included file (its own
#     file:line), a parameter named x;
#  4. an output named like an included file is refused (nothing overwrites an input).
# usage: deck_compose.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd .. && pwd)/inputs/wave_in_bar.yaml
scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1

# the written-out decks: the shipped bar cut to 1 us, and variants edited by sed
short='s/final_time: 5.0e-6/final_time: 3.0e-7/'
sed "$short" "$src" > ref.yaml
sed "$short; s/density: 2200/density: 2300/" "$src" > ref_rho.yaml
sed "$short; s/horizon: 0.00030001/horizon: 0.00020001/" "$src" > ref_hz.yaml
sed "$short; s/  safety_factor: 0.8/  dt: 1.0e-8/" "$src" > ref_dt.yaml
sed "$short; s/initial_velocity: .*/initial_velocity: [\"x < 0.0003 ? 50 : 0\", \"0\", \"0\"]/" "$src" > ref_v.yaml
grep -q "density: 2300" ref_rho.yaml && grep -q "00020001" ref_hz.yaml && grep -q "dt: 1.0e-8" ref_dt.yaml &&
  grep -q "? 50 :" ref_v.yaml || { echo "FAIL: the shipped deck changed; the sed edits no longer apply"; exit 1; }

# the composed deck: materials from an included file, numbers from parameters
cat > materials.yaml <<'EOF'
materials:
  glass:
    model: pmb
    density: ${rho}
    bulk_modulus: ${K}
EOF
cat > composed.yaml <<'EOF'
include: [materials.yaml]
parameters:
  rho: 2200
  K: 14.9e9
  dx: 1.0e-4
  v0: 100
title: longitudinal wave in a PMB bar
bodies:
  - name: bar
    material: glass
    geometry:
      shape: box
      lo: [0.00005, 0.00005, 0.00005]
      hi: [0.00995, 0.00095, 0.00095]
      origin: [0.00005, 0.00005, 0.00005]
      spacing: ${dx}
    horizon: ${3 * dx + 1e-8}
    initial_velocity: ["x < 3 * dx ? v0 : 0", "0", "0"]
time:
  final_time: 3.0e-7
  safety_factor: 0.8
output:
  interval: 50
  history_interval: 5
EOF

digest() { # NP DECK ARGS...: the run's digest ("" when it fails)
  local np=$1 deck=$2 out
  shift 2
  out=$(run "$np" "$exe" --quiet "$deck" --output-dir "o_$RANDOM" "$@" 2>&1)
  digest_of "$out"
}
same() { # WHAT REF_DIGEST DIGEST
  if [ -z "$3" ] || [ "$2" != "$3" ]; then echo "FAIL $1: digest '$3', the written-out deck gives '$2'"; fail=1
  else echo "ok   $1 ($3)"; fi
}

ref=$(digest 1 ref.yaml)
[ -n "$ref" ] || { echo "FAIL: the written-out deck does not run"; exit 1; }
same "include + parameters, 1 rank" "$ref" "$(digest 1 composed.yaml)"
same "include + parameters, 2 ranks" "$ref" "$(digest 2 composed.yaml)"
same "--set materials.glass.density" "$(digest 1 ref_rho.yaml)" "$(digest 1 ref.yaml --set materials.glass.density=2300)"
same "--set parameters.rho (2 ranks)" "$(digest 1 ref_rho.yaml)" "$(digest 2 composed.yaml --set parameters.rho=2300)"
ref_hz=$(digest 1 ref_hz.yaml)
same "--set bodies.bar.horizon" "$ref_hz" "$(digest 1 ref.yaml --set bodies.bar.horizon=0.00020001)"
same "--set bodies.0.horizon" "$ref_hz" "$(digest 1 ref.yaml --set bodies.0.horizon=0.00020001)"
same "--set time.dt (a key the deck lacks)" "$(digest 1 ref_dt.yaml)" "$(digest 1 ref.yaml --set time.dt=1.0e-8)"
same "--set a list" "$(digest 1 ref_v.yaml)" \
  "$(digest 1 ref.yaml --set 'bodies.bar.initial_velocity=["x < 0.0003 ? 50 : 0", "0", "0"]')"
[ "$ref" != "$(digest 1 ref_rho.yaml)" ] || { echo "FAIL: the density edit does not change the digest"; fail=1; }
# a ${...} of any length: 2200 - 200 and 300 terms "+ 1.0" (1.9 kB, once cut at 1023 characters
# to a smaller density without a word) is the density 2300 of the written-out deck
terms=$(printf ' + 1.0%.0s' $(seq 300))
sed "s/    density: \${rho}/    density: \${rho - 200$terms}/" materials.yaml > materials_long.yaml
sed 's/\[materials.yaml\]/[materials_long.yaml]/' composed.yaml > composed_long.yaml
[ "$(grep -c ' + 1.0' materials_long.yaml)" = 1 ] && [ "$(wc -c < materials_long.yaml)" -gt 1800 ] ||
  { echo "FAIL: the long expression was not written"; fail=1; }
same "a \${...} of 1.9 kB (300 terms)" "$(digest 1 ref_rho.yaml)" "$(digest 1 composed_long.yaml)"

refuse() { # WHAT DECK EXPECTED-TEXT [ARGS...]: exit 2 and the text on stderr
  local what=$1 deck=$2 want=$3 err st
  shift 3
  err=$("$exe" --quiet "$deck" "$@" 2>&1 >/dev/null)
  st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$want" <<<"$err"; then
    echo "FAIL $what: exit $st, stderr lacks '$want': $err"; fail=1
  else echo "ok   $what: $err"; fi
}
refuse "unknown key by --set" ref.yaml "--set materials.glass.densty=2300: key 'densty': unknown key in materials.glass — did you mean 'density'?" \
  --set materials.glass.densty=2300
refuse "--set without =" ref.yaml "--set time.dt: expected KEY.PATH=VALUE" --set time.dt
refuse "unknown list item" ref.yaml "--set bodies.plate.horizon=1: 'plate' names no item of the list" \
  --set bodies.plate.horizon=1
sed 's/spacing: ${dx}/spacing: ${dxx}/' composed.yaml > bad_name.yaml
refuse "unknown parameter" bad_name.yaml "bad_name.yaml:16:16: key 'spacing': bad expression 'dxx'"
sed 's/\[materials.yaml\]/[nowhere.yaml]/' composed.yaml > bad_missing.yaml
refuse "missing include" bad_missing.yaml "bad_missing.yaml:1:11: key 'include': cannot open 'nowhere.yaml'"
printf 'include: [cycle_b.yaml]\n' > cycle_a.yaml
printf 'include: [cycle_a.yaml]\n' > cycle_b.yaml
refuse "include cycle" cycle_a.yaml "'cycle_a.yaml' includes itself (a cycle of 2 files)"
sed 's/^title: .*/title: t\nmaterials:\n  glass:\n    density: 3000/' composed.yaml > bad_twice.yaml
refuse "a value given twice" bad_twice.yaml "bad_twice.yaml:10:14: key 'density': given again at materials.yaml:4:14"
sed 's/    density: ${rho}/    density: ${rho}\n    densty: 1/' materials.yaml > bad_materials.yaml
sed 's/\[materials.yaml\]/[bad_materials.yaml]/' composed.yaml > bad_inner.yaml
refuse "unknown key in an included file" bad_inner.yaml "bad_materials.yaml:5:5: key 'densty': unknown key"
sed 's/  rho: 2200/  x: 1\n  rho: 2200/' composed.yaml > bad_param.yaml
refuse "a parameter named x" bad_param.yaml "bad_param.yaml:3:6: key 'x': a parameter's name"
sed 's/  history_interval: 5/  history_interval: 5\n  file: materials.yaml/' composed.yaml > bad_out.yaml
refuse "an output named like an included file" bad_out.yaml "an included deck"
grep -q 'density: ${rho}' materials.yaml || { echo "FAIL: materials.yaml was overwritten"; fail=1; }
exit $fail
