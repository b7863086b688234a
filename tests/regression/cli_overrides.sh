#!/usr/bin/env bash
# Every --set form is applied or refused (issue 49), and what it says names the override:
#  1. --set parameters.NAME applies to a parameter the deck declares (the point count of --check
#     follows the spacing) and refuses one it does not (a sweep over a misspelt name would give N
#     identical runs), listing the deck's parameters and the nearest one; a deck without
#     parameters: refuses any;
#  2. a key path with an empty part (.a, a..b, a.), an empty key (=3), include: (merged before the
#     overrides, so a new value would be dropped), a path below a single value: exit 2 with the
#     reason, none of them applied in silence;
#  3. a warning about a value given by --set names the override ("--set materials.glass.density=50:
#     key 'density'"), one about a value in an included file names that file and line, never
#     "deck.yaml:0:0".
# usage: cli_overrides.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd .. && pwd)/inputs/wave_in_bar.yaml
scratch=$2 fail=0
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1

cp "$src" plain.yaml
sed 's/^title: /parameters:\n  dx: 1.0e-4\n  v0: 100\ntitle: /; s/spacing: 0.0001/spacing: ${dx}/; s/horizon: 0.00030001/horizon: ${3 * dx + 1e-8}/' \
  "$src" > params.yaml
grep -q 'spacing: ${dx}' params.yaml && grep -q 'horizon: ${3 \* dx' params.yaml ||
  { echo "FAIL: the shipped deck changed; the sed edits no longer apply"; exit 1; }

points() { # DECK ARGS...: the point count --check reports ("" when it fails)
  local deck=$1
  shift
  "$exe" --check "$deck" "$@" 2>/dev/null | sed -n 's/.*deck is valid (\([0-9]*\) points.*/\1/p'
}
applied() { # WHAT WANT GOT
  if [ -n "$3" ] && [ "$2" = "$3" ]; then echo "ok   $1 ($3 points)"
  else echo "FAIL $1: $3 points, expected $2"; fail=1; fi
}
refuse() { # WHAT DECK EXPECTED-TEXT [ARGS...]: exit 2 and the text on stderr
  local what=$1 deck=$2 want=$3 err st
  shift 3
  err=$("$exe" --check "$deck" "$@" 2>&1 >/dev/null)
  st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$want" <<<"$err"; then
    echo "FAIL $what: exit $st, stderr lacks '$want': $err"; fail=1
  else echo "ok   $what: $err"; fi
}

# 1. parameters
applied "params.yaml as given" 10000 "$(points params.yaml)"
applied "--set parameters.dx=2e-4" 1250 "$(points params.yaml --set parameters.dx=2e-4)"
refuse "--set parameters.dX (misspelt)" params.yaml \
  "--set parameters.dX=2e-4: 'dX' is not one of the deck's parameters (dx, v0) — did you mean 'dx'?" \
  --set parameters.dX=2e-4
refuse "--set parameters.spacing (no near name)" params.yaml \
  "--set parameters.spacing=2e-4: 'spacing' is not one of the deck's parameters (dx, v0)" \
  --set parameters.spacing=2e-4
refuse "--set parameters.dx on a deck without parameters" plain.yaml \
  "--set parameters.dx=2e-4: the deck declares no parameters:" --set parameters.dx=2e-4

# 2. key paths
refuse "--set =3" plain.yaml "--set =3: expected KEY.PATH=VALUE" --set =3
refuse "--set .time.final_time" plain.yaml "--set .time.final_time=1e-7: an empty part in the key path" \
  --set .time.final_time=1e-7
refuse "--set time..final_time" plain.yaml "--set time..final_time=1e-7: an empty part in the key path" \
  --set time..final_time=1e-7
refuse "--set time.final_time." plain.yaml "--set time.final_time.=1e-7: an empty part in the key path" \
  --set time.final_time.=1e-7
refuse "--set include" plain.yaml "--set include=[other.yaml]: include: cannot be set from the command line" \
  --set 'include=[other.yaml]'
refuse "--set include.0" plain.yaml "--set include.0=other.yaml: include: cannot be set from the command line" \
  --set include.0=other.yaml
refuse "--set below a single value" plain.yaml \
  "--set time.final_time.value=1e-7: 'value' is below a single value ('5.0e-6')" --set time.final_time.value=1e-7
refuse "--set below a list item's single value" plain.yaml \
  "--set bodies.bar.horizon.x=1: 'x' is below a single value" --set bodies.bar.horizon.x=1

# 3. where a warning points
warn_at() { # WHAT DECK WANT [ARGS...]: --check passes and its warning starts with WANT
  local what=$1 deck=$2 want=$3 err
  shift 3
  err=$("$exe" --check "$deck" "$@" 2>&1 >/dev/null)
  if [ $? -ne 0 ] || ! grep -qF -- "perifem warning: $want" <<<"$err" || grep -q ':0:0' <<<"$err"; then
    echo "FAIL $what: stderr lacks 'perifem warning: $want' (or says :0:0): $err"; fail=1
  else echo "ok   $what: $err"; fi
}
warn_at "a warning about a --set value" plain.yaml \
  "--set materials.glass.density=50: key 'density': material 'glass': 50 kg/m^3 is below" \
  --set materials.glass.density=50
warn_at "a warning about a --set value in a list item" plain.yaml "--set bodies.0.horizon=0.012: key 'horizon':" \
  --set bodies.bar.geometry.spacing=0.001 --set bodies.0.horizon=0.012
sed 's/density: 2200/density: 50/' "$src" > light_own.yaml
warn_at "a warning about the deck's own value" light_own.yaml "light_own.yaml:10:14: key 'density'"
printf 'materials:\n  glass:\n    model: pmb\n    density: 50\n    bulk_modulus: 14.9e9\n' > light.yaml
sed '/^materials:/,/^$/d; s/^title: /include: [light.yaml]\ntitle: /' "$src" > included.yaml
warn_at "a warning about an included value" included.yaml "light.yaml:4:14: key 'density'"
exit $fail
