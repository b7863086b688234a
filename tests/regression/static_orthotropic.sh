#!/usr/bin/env bash
# The orthotropic model (material/material_orthotropic.c; docs/theory/fem_materials.md §8) in
# hexahedra and in correspondence peridynamics, quasi-statically, against closed forms:
#  - tests/data/static_orthotropic.yaml: FE bars of a T300/5208 ply, fibre at +30 degrees
#    (Euler angles) and -60 degrees (axes) from x in the x-y plane, pulled along x by a strain
#    of 1e-5 (why so small: the deck) with free lateral faces. E_x = (reaction / A) / (d / L) within 1 % of Jones's
#    1/E_x = m^4/E1 + (1/G12 - 2 nu12/E1) m^2 n^2 + n^4/E2 (measured -8e-6 and -9e-6); the
#    shear coupling gamma_xy / eps_x and the contraction eps_y / eps_x, least-squares slopes of
#    the nodes' u_y, within 1 % of S16/S11 and S12/S11 (Jones 1999, sec. 2.6, the transformed
#    compliances; -1.3515 and +0.4016 for the coupling, whose sign the angle's sign sets;
#    measured -8.3e-4 and -7.2e-4; the contraction within 5e-5);
#  - the same state digest on 1, 2 and 3 ranks;
#  - the same deck run explicitly: the first time step is 0.8 h / sqrt(C11 / rho), the fastest
#    wave being the fibres' P wave (K + 4G/3 = C11, theory §8; 0.8 the default safety factor);
#  - tests/data/static_orthotropic_pd.yaml: a correspondence bar of the ply along x (E_x = E1)
#    and across (angles [90, 0, 0], E_x = E2): the mean sigma_xx over the points of the middle
#    8 mm over their strain (the slope of u_x there) within 2 % of E1 and E2 (measured +1.0 %
#    and -0.06 %).
# usage: static_orthotropic.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
deck=$(pwd)/data/static_orthotropic.yaml
deck_pd=$(pwd)/data/static_orthotropic_pd.yaml
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
digests=""
for np in 1 2 3; do
  mkdir -p np$np
  o=$(cd np$np && run $np "$exe" "$deck" 2>&1) || { echo "FAIL: $np ranks: $o"; fail=1; }
  digests="$digests $(digest_of "$o")"
done
# shellcheck disable=SC2086
digests_agree "FE bars" $digests || fail=1
# explicit dynamics on the same deck: the first step is the safety factor 0.8 times the element
# size (5 mm cubes: V / A_max = 5 mm) over the fastest wave speed, sqrt(C11 / rho) for this ply
o=$("$exe" --output-dir dynamic --set solver.type=explicit --set time.final_time=1e-6 "$deck" 2>&1) ||
  { echo "FAIL: the explicit run: $o"; fail=1; }
t1=$(echo "$o" | sed -n 's/^step 1 .* t = \([0-9.e+-]*\) .*/\1/p')
"$PY" - "$t1" <<'PYEOF' || fail=1
import sys
E1, E2, nu12, nu23 = 181e9, 10.3e9, 0.28, 0.4  # E3 = E2, nu13 = nu12 (transversely isotropic)
n21, n32 = nu12 * E2 / E1, nu23            # nu32 = nu23 E3 / E2 = nu23; nu31 = nu21
delta = 1 - nu12 * n21 - nu23 * n32 - n21 * nu12 - 2 * n21 * n32 * nu12
C11 = E1 * (1 - nu23 * n32) / delta       # Jones 1999, sec. 2.3
want = 0.8 * 0.005 / (C11 / 1600) ** 0.5
got = float(sys.argv[1]) if sys.argv[1] else float("nan")
print("explicit: first step %.5g s, 0.8 h / sqrt(C11 / rho) %.5g s" % (got, want))
if not abs(got / want - 1) < 1e-4: print("FAIL: the first step is not 0.8 h / sqrt(C11 / rho)"); sys.exit(1)
PYEOF
for a in 0 90; do
  o=$("$exe" --output-dir pd$a --set "materials.ply.angles=[$a, 0, 0]" "$deck_pd" 2>&1) ||
    { echo "FAIL: the correspondence bar at $a degrees: $o"; fail=1; }
done
"$PY" - np1/static_orthotropic pd0/static_orthotropic_pd pd90/static_orthotropic_pd <<'PYEOF' || fail=1
import sys
import h5py
import netCDF4
import numpy as np
# T300/5208 (tests/data/static_orthotropic.yaml): the in-plane constants the closed forms need
E1, E2, G12, nu12 = 181e9, 10.3e9, 7.17e9, 0.28
S11, S22, S12, S66 = 1 / E1, 1 / E2, -nu12 / E1, 1 / G12
ok = True
def nodal(path):
    e = netCDF4.Dataset(path + ".e")
    names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
    var = lambda k: np.array(e["vals_nod_var%d" % (names.index(k) + 1)][-1])
    return [np.array(e[c][:]) for c in ("coordx", "coordy", "coordz")], var
def check(label, got, want, tol):
    global ok
    err = got / want - 1
    print("%s: %.6g, closed form %.6g (%+.2e)" % (label, got, want, err))
    if not abs(err) < tol: print("FAIL: %s off by more than %g" % (label, tol)); ok = False
(X, Y, Z), var = nodal(sys.argv[1])
h = h5py.File(sys.argv[1] + ".h5", "r")
L, d, A = 0.1, 1e-6, 1e-4
for name, deg, y0 in (("30", 30, 0.0), ("m60", -60, 0.03)):
    m, n = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    Ex = 1 / (m**4 / E1 + (S66 - 2 * nu12 / E1) * m * m * n * n + n**4 / E2)
    S16 = (2 * S11 - 2 * S12 - S66) * m**3 * n - (2 * S22 - 2 * S12 - S66) * m * n**3
    S12t = (S11 + S22 - S66) * m * m * n * n + S12 * (m**4 + n**4)
    check("bar %s: E_x (Pa)" % name, h["pulled_%s_reaction_x" % name][-1] / A / (d / L), Ex, 0.01)
    on = (Y > y0 - 1e-6) & (Y < y0 + 0.01 + 1e-6)
    # u_y = a + gamma_xy x + eps_y y + c z (the free rotation about x enters through z)
    M = np.column_stack([np.ones(on.sum()), X[on], Y[on] - y0, Z[on]])
    a, gxy, ey, _ = np.linalg.lstsq(M, var("displacement_y")[on], rcond=None)[0]
    # (the transformed S11 is 1 / E_x)
    check("bar %s: gamma_xy / eps_x" % name, gxy / (d / L), S16 * Ex, 0.01)
    check("bar %s: eps_y / eps_x" % name, ey / (d / L), S12t * Ex, 0.01)
# correspondence: the middle 8 mm of the 40 mm bar
for path, Eref, label in ((sys.argv[2], E1, "along the fibres, E1"), (sys.argv[3], E2, "across, E2")):
    (X, Y, Z), var = nodal(path)
    mid = (X > 0.016) & (X < 0.024)
    eps = np.polyfit(X[mid], var("displacement_x")[mid], 1)[0]
    check("correspondence bar %s (Pa)" % label, var("stress_xx")[mid].mean() / eps, Eref, 0.02)
sys.exit(0 if ok else 1)
PYEOF
exit $fail
