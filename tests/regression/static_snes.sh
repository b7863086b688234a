#!/usr/bin/env bash
# The quasi-static solver's Newton method by PETSc (solver.method: snes, sim/solver_snes.c):
#  - every check of static_bar.sh with it: the FE bar against u_x = d x / L to 1e-8 of d, the
#    LPS bar against the same closed form and its energy, the grips' reactions, force control,
#    the refusals; on 1, 2 and 3 ranks at the deck's tolerance 1e-9 the grips' columns within
#    1e-7 of the largest value of their quantity (measured 3.3e-10), not the same bits: PETSc's
#    dot products and norms are MPI sums whose rounding depends on the partition;
#  - on the same deck it needs fewer force evaluations than the relaxation (measured 557 against
#    790, each body damped by its own coefficient; newton_krylov 522);
#  - a deck with walls is refused with it, naming solver.method;
#  - the crack of static_damage.sh's bar (tests/data/static_damage_bar.yaml): the same load step
#    separates it, with the same damage fraction as newton_krylov's within 1e-9 (measured equal).
# usage: static_snes.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
STATIC_BAR_OPTIONS="--set solver.method=snes" STATIC_BAR_PARTITION=tolerance \
  bash regression/static_bar.sh "$exe" "$scratch" || fail=1
deck=$(cd .. && pwd)/inputs/static_bar.yaml
count() { sed -n 's/.* \([0-9]*\) force evaluations.*/\1/p' "$1"; }
sn=$(count "$scratch/deck.log")
"$exe" --output-dir "$scratch/relaxation" "$deck" > "$scratch/relaxation.log" 2>&1
dr=$(count "$scratch/relaxation.log")
[ -n "$dr" ] && [ -n "$sn" ] && [ "$sn" -lt "$dr" ] ||
  { echo "FAIL: force evaluations: snes '$sn', relaxation '$dr'"; fail=1; }
echo "force evaluations: snes $sn, relaxation $dr"
grep -q "snes (PETSc): [0-9]* Newton steps" "$scratch/deck.log" || { echo "FAIL: no snes summary line"; fail=1; }
printf 'walls:\n  - {name: stop, point: [-1, 0, 0], normal: [1, 0, 0]}\n' | cat "$deck" - > "$scratch/walls.yaml"
out=$("$exe" --check --set solver.method=snes "$scratch/walls.yaml" 2>&1); st=$?
[ $st = 2 ] && echo "$out" | grep -q "key 'method': snes does not take walls" ||
  { echo "FAIL: walls with snes: exit $st: $out"; fail=1; }
bar=$(cd .. && pwd)/tests/data/static_damage_bar.yaml
for m in snes newton_krylov; do
  o=$("$exe" --output-dir "$scratch/crack_$m" --set solver.method=$m "$bar" 2>&1) || { echo "FAIL: the crack with $m: $o"; fail=1; }
  echo "$o" | grep '^load step 1[12]/' | sed "s/^/$m: /"
  echo "$o" | grep -q '^load step 11/12 .* damage passes [1-9]' || { echo "FAIL: $m: the bar did not break at load step 11"; fail=1; }
done
source common/mpi_env.sh
"$PY" - "$scratch"/crack_snes/static_damage_bar.h5 "$scratch"/crack_newton_krylov/static_damage_bar.h5 <<'PYEOF' || fail=1
import sys
import h5py
a, b = (h5py.File(f, "r")["damage_fraction"][:] for f in sys.argv[1:])
print("damage fraction at the end: snes %.8g, newton_krylov %.8g" % (a[-1], b[-1]))
sys.exit(0 if a[-1] > 0 and abs(a[-1] - b[-1]) <= 1e-9 else 1)
PYEOF
exit $fail
