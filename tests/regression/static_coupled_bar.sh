#!/usr/bin/env bash
# The coupled bar of quasi-static problem 1 (inputs/static_bar_coupled.yaml; docs/examples/
# static_bar.md, "A coupled bar"): 40 x 4 x 4 bbar hexahedra of neo-Hookean steel whose middle
# 20 mm are peridynamic (correspondence form, horizon 3.01 elements, blended over 10 mm), held
# at one end, pulled by d = 1e-4 m at the other in 4 load steps. Checks, against the homogeneous
# uniaxial stress state of the neo-Hookean bar (Bonet & Wood 2008 §6.4.3: stretch l1 = 1 + d/L,
# lateral stretch l2 from G (l2^2 - 1) + lam ln(l1 l2^2) = 0, reaction A P with
# P = (G (l1^2 - 1) + lam ln J) / l1):
#  - the element part (|x - L/2| >= 20 mm) against u_x = d x / L within 1e-8 of d (measured
#    2.9e-9; tolerance 1e-9 of the reactions), the peridynamic and blended part within 1e-7 of d
#    (3.6e-8): the correspondence form has no surface effect under a homogeneous deformation;
#  - the lateral strain in both parts against l2 - 1 within 1e-5 of it;
#  - the pulled grip's reaction against A P within 1e-6 at every load step;
#  - the set-up made peridynamic points (the consistent form's line), the same state digest on
#    1, 2 and 3 ranks.
# usage: static_coupled_bar.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
deck=$(cd .. && pwd)/inputs/static_bar_coupled.yaml
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
out=$("$exe" "$deck" 2>&1) || { echo "FAIL: the deck: $out"; exit 1; }
echo "$out" | grep -E "consistent form|quasi-static:"
echo "$out" | grep -qE "consistent form, [1-9][0-9]* transition bonds of [1-9][0-9]* points" ||
  { echo "FAIL: no peridynamic points"; fail=1; }
"$PY" - static_bar_coupled.e static_bar_coupled.h5 <<'PYEOF' || fail=1
import sys
import h5py
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
last = lambda n: np.array(e["vals_nod_var%d" % (names.index(n) + 1)][-1])
X, Y = np.array(e["coordx"][:]), np.array(e["coordy"][:])
ux, uy = last("displacement_x"), last("displacement_y")
d, L, T, A = 1e-4, 0.1, 1e-3, 1e-4
E, nu = 200e9, 0.25
G, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
def uniaxial(l1):
    l2 = 1.0
    for _ in range(50):  # Newton on G (l2^2 - 1) + lam ln(l1 l2^2) = 0
        l2 -= (G * (l2 * l2 - 1) + lam * np.log(l1 * l2 * l2)) / (2 * G * l2 + 2 * lam / l2)
    return l2, A * (G * (l1 * l1 - 1) + lam * np.log(l1 * l2 * l2)) / l1
ok = True
fe = np.abs(X - L / 2) >= 0.02 - 1e-9
err = [np.abs(ux[m] - d * X[m] / L).max() / d for m in (fe, ~fe)]
l2, _ = uniaxial(1 + d / L)
lat = [np.polyfit(Y[m], uy[m], 1)[0] / (l2 - 1) - 1 for m in (fe & (X > 0.07), ~fe & (np.abs(X - L / 2) < 0.01))]
print("u_x off d x/L: elements %.3g of d, peridynamic %.3g; lateral strain off l2 - 1: %.2g, %.2g" % (*err, *lat))
if not (err[0] < 1e-8 and err[1] < 1e-7): print("FAIL: off the closed form"); ok = False
if not (abs(lat[0]) < 1e-5 and abs(lat[1]) < 1e-5): print("FAIL: the lateral strain"); ok = False
h = h5py.File(sys.argv[2], "r")
t, R = h["time"][:], h["pulled_reaction_x"][:]
worst = max(abs(R[k] / uniaxial(1 + d * t[k] / (L * T))[1] - 1) for k in range(1, len(t)))
print("pulled reaction off A P by %.3g at most (%d load steps)" % (worst, len(t) - 1))
if not (len(t) == 5 and worst < 1e-6): print("FAIL: the reactions"); ok = False
sys.exit(0 if ok else 1)
PYEOF
digests=$(digest_of "$out")
for np in 2 3; do
  mkdir -p np$np
  o=$(cd np$np && run $np "$exe" --quiet "$deck" 2>&1) || { echo "FAIL: $np ranks: $o"; fail=1; }
  digests="$digests $(digest_of "$o")"
done
digests_agree "the coupled bar" $digests || fail=1
exit $fail
