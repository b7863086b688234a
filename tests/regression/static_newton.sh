#!/usr/bin/env bash
# The quasi-static solver's Newton-Krylov method (solver.method: newton_krylov,
# sim/solver_newton.c):
#  - every check of static_bar.sh with it: the FE bar against u_x = d x / L to 1e-8 of d, the
#    LPS bar against the same closed form and its energy, the grips' reactions, force control,
#    the same digest on 1, 2 and 3 ranks, the refusals;
#  - on the same deck it needs fewer force evaluations than the relaxation (measured 522 against
#    790, each body damped by its own coefficient);
#  - a deck with walls is refused with it, naming solver.method (walls are projections between
#    relaxation iterations);
#  - the correspondence bar (the deck's PD bar with model neo_hookean, the continuum model through
#    the correspondence form) against the same closed form: u_x within 2 % of d (measured 1.5 %),
#    the mid-half strain within 2 % of d / L (+1.35 %), the lateral contraction at mid-length
#    within 3 % of nu e (0.2532 e against 0.25 e), its work and stored energy within 1e-3
#    (1.6e-5); the PD surface effect of docs/examples/static_bar.md;
#  - plasticity (the necking bar of elements, 8 elements along, to 2 % in 2 load steps; past the
#    peak, to 8 % in 4, was measured the same on 1, 2 and 3 ranks too, 20 s a run) and
#    correspondence (the PD necking bar to 3 % in 2 load steps): the same digest on 1, 2 and 3
#    ranks (tolerance 1e-4: the digests are compared, not the equilibrium; fewer iterations, each
#    a round of reductions that three ranks on two busy cores wait for).
# usage: static_newton.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
STATIC_BAR_OPTIONS="--set solver.method=newton_krylov" bash regression/static_bar.sh "$exe" "$scratch" || fail=1
deck=$(cd .. && pwd)/inputs/static_bar.yaml
# The force evaluations of the two methods on the full deck (4 load steps). newton_krylov's are
# those of the run of the deck static_bar.sh made just above (the same deck, options and
# executable: its log, deck.log); the relaxation's those of static_bar's own run of the deck in
# this ctest run (static_bar runs first: DEPENDS in tests/CMakeLists.txt) when its log is newer
# than this perifem and the deck, else of a run here. (Each was a second run of the same deck.)
count() { sed -n 's/.* \([0-9]*\) force evaluations.*/\1/p' "$1"; }
evaluations() { "$exe" --output-dir "$scratch/$1" --set solver.method=$1 "$deck" > "$scratch/$1.log" 2>&1; count "$scratch/$1.log"; }
nk=$(count "$scratch/deck.log")
saved=${3:-}/work_static_bar/deck.log dr=""
[ -s "$saved" ] && [ "$saved" -nt "$exe" ] && [ "$saved" -nt "$deck" ] && dr=$(count "$saved")
[ -n "$dr" ] && echo "relaxation: the force evaluations of static_bar's run ($saved)" || dr=$(evaluations relaxation)
[ -n "$dr" ] && [ -n "$nk" ] && [ "$nk" -lt "$dr" ] ||
  { echo "FAIL: force evaluations: newton_krylov '$nk', relaxation '$dr'"; fail=1; }
echo "force evaluations: newton_krylov $nk, relaxation $dr"
printf 'walls:\n  - {name: stop, point: [-1, 0, 0], normal: [1, 0, 0]}\n' | cat "$deck" - > "$scratch/walls.yaml"
out=$("$exe" --check --set solver.method=newton_krylov "$scratch/walls.yaml" 2>&1); st=$?
[ $st = 2 ] && echo "$out" | grep -q "key 'method': newton_krylov does not take walls" ||
  { echo "FAIL: walls with newton_krylov: exit $st: $out"; fail=1; }
source common/mpi_env.sh
o=$("$exe" --output-dir "$scratch/corr" --set solver.method=newton_krylov --set materials.steel_pd.model=neo_hookean \
    "$deck" 2>&1) || { echo "FAIL: the correspondence bar: $o"; fail=1; }
"$PY" - "$scratch/corr/static_bar.e" "$scratch/corr/static_bar.h5" <<'PYEOF' || fail=1
import sys
import h5py
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
last = lambda n: np.array(e["vals_nod_var%d" % (names.index(n) + 1)][-1])
X, Y = np.array(e["coordx"][:]), np.array(e["coordy"][:])
ux, uy = last("displacement_x"), last("displacement_y")
d, L, nu = 1e-4, 0.1, 0.25
pd = Y > 0.02  # the PD bar, y in [0.03, 0.05]
err = np.abs(ux[pd] - d * X[pd] / L).max() / d
mid = pd & (X > 0.025) & (X < 0.075)
strain = np.polyfit(X[mid], ux[mid], 1)[0] / (d / L)
centre = pd & (X > 0.04) & (X < 0.06)
lateral = -np.polyfit(Y[centre], uy[centre], 1)[0] / (d / L)
h = h5py.File(sys.argv[2], "r")
w, u = h["lps_bar_external_work"][-1], h["lps_bar_internal_energy"][-1]
print("correspondence bar: max |u_x - d x/L| / d = %.4g, mid-half strain / (d/L) = %.5f, lateral contraction "
      "%.4f e (nu e = %.2f e), work / stored - 1 = %.2g" % (err, strain, lateral, nu, w / u - 1))
ok = err < 0.02 and abs(strain - 1) < 0.02 and abs(lateral / nu - 1) < 0.03 and abs(w / u - 1) < 1e-3
sys.exit(0 if ok else 1)
PYEOF
root=$(cd .. && pwd)
for deck in necking necking_pd; do
  if [ $deck = necking ]; then args=(--set parameters.nz=8 --set parameters.stretch=0.02 --set solver.load_steps=2)
  else args=(--set parameters.stretch=0.03 --set solver.load_steps=2); fi
  digests=""
  for np in 1 2 3; do
    mkdir -p "$scratch/$deck$np"
    o=$(cd "$scratch/$deck$np" && run $np "$exe" --quiet --set solver.method=newton_krylov \
        --set solver.tolerance=1e-4 "${args[@]}" \
        "$root/inputs/$deck.yaml" 2>&1) || { echo "FAIL: $deck on $np ranks: $o"; fail=1; }
    digests="$digests $(digest_of "$o")"
  done
  digests_agree "$deck with newton_krylov" $digests || fail=1
done
exit $fail
