#!/usr/bin/env bash
# Quasi-static loading (solver: quasi_static, sim/solver_relaxation.c) on inputs/static_bar.yaml:
# a neo-Hookean FE bar and an LPS bar, each held at one end in x and pulled by d = 1e-4 m at the
# other, lateral faces free, in 4 load steps (docs/examples/static_bar.md). Checks:
#  - the FE bar against the closed form u_x = d x / L: 1e-8 of d (measured 8e-10; the tolerance
#    1e-9 of the residual; a homogeneous deformation is exact in the elements);
#  - the LPS bar against the same closed form: 1 % of d (measured 0.45 %: the PD surface effect,
#    docs/examples/static_bar.md), its mid-half strain within 1.5 % of d / L (measured +0.77 %);
#  - the history: a row per load step, kinetic energy 0, the LPS bar's external work equal to its
#    stored energy within 1e-4 (measured 1.3e-5), the FE bar's work within 1e-3 of E A d^2 / 2L;
#  - the grips' reactions, mean displacements and work at each load step against closed forms
#    (the tolerances and measurements are given where they are checked, below), and the same
#    bits of those columns on 1, 2 and 3 ranks;
#  - a progress line per load step;
#  - force control (the FE bar alone under a body force on its end face): below;
#  - the same state digest on 1, 2 and 3 ranks (2 load steps, tolerance 1e-4: the digests are
#    compared, not the equilibrium; 288 relaxation iterations instead of 788 at the deck's 1e-9);
#  - no boundary condition, an initial velocity and a load step that cannot converge in
#    max_iterations: a message naming the key or the load step and a non-zero exit.
# usage: static_bar.sh PERIFEM SCRATCH   (from the tests/ folder; the options in
# STATIC_BAR_OPTIONS go to every run: static_newton.sh runs it all with newton_krylov;
# STATIC_BAR_PARTITION=tolerance, for a method whose sums depend on the partition (snes): the
# runs on 1, 2 and 3 ranks at the deck's tolerance, the grips' columns within 1e-7 of the largest
# value of their quantity (work, reaction, displacement) in place of the same bits and digests)
set -u
exe=$1 scratch=$2 fail=0
read -r -a opts <<< "${STATIC_BAR_OPTIONS:-}"
deck=$(cd .. && pwd)/inputs/static_bar.yaml
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
out=$("$exe" "${opts[@]}" "$deck" 2>&1) || { echo "FAIL: the deck: $out"; exit 1; }
echo "$out" > deck.log # (its force evaluations: static_newton.sh reads them)
[ "$(echo "$out" | grep -c '^load step [1-4]/4 ')" = 4 ] || { echo "FAIL: not 4 progress lines: $out"; fail=1; }
"$PY" - static_bar.e static_bar.h5 <<'PYEOF' || fail=1
import sys
import h5py
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
X = np.array(e["coordx"][:])
Y = np.array(e["coordy"][:])
ux = np.array(e["vals_nod_var%d" % (names.index("displacement_x") + 1)][-1])
d, L, ok = 1e-4, 0.1, True
fe, pd = Y < 0.02, Y > 0.02  # the FE bar at y in [0, 0.01], the LPS bar at [0.03, 0.05]
err_fe = np.abs(ux[fe] - d * X[fe] / L).max() / d
err_pd = np.abs(ux[pd] - d * X[pd] / L).max() / d
mid = pd & (X > 0.025) & (X < 0.075)
slope = np.polyfit(X[mid], ux[mid], 1)[0] / (d / L)
print("FE bar: max |u_x - d x/L| / d = %.3g; LPS bar: %.3g, mid-half strain / (d/L) = %.5f" % (err_fe, err_pd, slope))
if not err_fe < 1e-8: print("FAIL: the FE bar is off the closed form by %g of d" % err_fe); ok = False
if not err_pd < 1e-2: print("FAIL: the LPS bar is off the closed form by %g of d" % err_pd); ok = False
if not abs(slope - 1) < 0.015: print("FAIL: the LPS bar's mid-half strain is %g of d/L" % slope); ok = False
h = h5py.File(sys.argv[2], "r")
if list(h["step"][:]) != [0, 1, 2, 3, 4]: print("FAIL: history steps %s" % h["step"][:]); ok = False
if np.abs(h["kinetic_energy"][:]).max() != 0: print("FAIL: kinetic energy %s" % h["kinetic_energy"][:]); ok = False
w, u = h["lps_bar_external_work"][-1], h["lps_bar_internal_energy"][-1]
if not abs(w - u) < 1e-4 * w: print("FAIL: LPS bar: work %.8g J, stored %.8g J" % (w, u)); ok = False
w_fe, w_cf = h["fe_bar_external_work"][-1], 200e9 * 1e-4 * d * d / (2 * L)
if not abs(w_fe - w_cf) < 1e-3 * w_cf: print("FAIL: FE bar: work %.8g J, E A d^2/2L %.8g J" % (w_fe, w_cf)); ok = False
# The grips' reactions, displacements and work at each load step (t_k = k T / 4).
# FE bar: a homogeneous uniaxial stress, stretch l1 = 1 + d t / (L T); the neo-Hookean
# Psi = G/2 (tr C - 3) - G ln J + lam/2 (ln J)^2 (Bonet & Wood 2008, 6.4.3) with free lateral
# faces has G (l2^2 - 1) + lam ln(l1 l2^2) = 0, and the nominal stress on the end face
# P = (G (l1^2 - 1) + lam ln J) / l1, so the reaction is A P (E A d t / (L T) to first order in the
# strain: 7.2e-4 below it at d / L = 1e-3; measured within 3e-12 of A P), the mean displacement
# of the pulled face's nodes d t / T; the grips' work is booked by the trapezoidal rule over the
# load steps: equal to the rule applied to the closed-form reactions within 1e-7 (measured
# 5e-11), and to the stored energy A L Psi within 1e-4 (measured 1.5e-5, the rule's error on
# the slightly curved P).
# LPS bar: the reaction against E A d t / (L T), A = 0.02 x 0.02 m: 2 % (measured +1.1 % to
# +1.2 %, the PD surface effect of docs/examples/static_bar.md), held and pulled equal and
# opposite within 1e-6 (measured 3e-9), the grips' mean displacement d x_mean / L t / T exact.
E, nu, A, T = 200e9, 0.25, 1e-4, 1e-3
G, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
def neo_hookean(l1):
    l2 = 1.0
    for _ in range(50):  # Newton on G (l2^2 - 1) + lam ln(l1 l2^2) = 0
        l2 -= (G * (l2 * l2 - 1) + lam * np.log(l1 * l2 * l2)) / (2 * G * l2 + 2 * lam / l2)
    J = l1 * l2 * l2
    psi = G / 2 * (l1 * l1 + 2 * l2 * l2 - 3) - G * np.log(J) + lam / 2 * np.log(J) ** 2
    return A * (G * (l1 * l1 - 1) + lam * np.log(J)) / l1, A * L * psi
t = h["time"][:]
col = lambda name: np.array(h[name][:])
worst = {"FE reaction": 0.0, "FE grip": 0.0, "LPS grip": 0.0}
for k in range(1, 5):
    R, W = neo_hookean(1 + d * t[k] / (L * T))
    for name, want in (("fe_pulled", R), ("fe_held", -R)):
        err = abs(col(name + "_reaction_x")[k] - want) / R
        worst["FE reaction"] = max(worst["FE reaction"], err)
        if not err < 1e-6: print("FAIL: %s's reaction at load step %d: %.9g N, closed form %.9g N" % (name, k, col(name + "_reaction_x")[k], want)); ok = False
    for name, want in (("fe_pulled", d * t[k] / T), ("fe_held", 0.0)):
        err = abs(col(name + "_displacement_x")[k] - want) / d
        worst["FE grip"] = max(worst["FE grip"], err)
        if not err < 1e-12: print("FAIL: %s's displacement at load step %d: %.9g m, d t/T %.9g m" % (name, k, col(name + "_displacement_x")[k], want)); ok = False
    # the LPS grips: u_x = d x / L t / T on their points, so the mean is d x_mean / L t / T with the
    # lattice's x_mean (points at 0.001 + 0.002 i: 0.003 m in the held layer, 0.097 m in the pulled)
    for name, xm in (("pd_held", 0.003), ("pd_pulled", 0.097)):
        err = abs(col(name + "_displacement_x")[k] - d * xm / L * t[k] / T) / d
        worst["LPS grip"] = max(worst["LPS grip"], err)
        if not err < 1e-12: print("FAIL: %s's displacement at load step %d: %.9g m" % (name, k, col(name + "_displacement_x")[k])); ok = False
    for name in ("fe_pulled", "fe_held", "pd_pulled", "pd_held"):  # the free components carry none
        if col(name + "_reaction_y")[k] != 0 or col(name + "_reaction_z")[k] != 0: print("FAIL: %s: a lateral reaction" % name); ok = False
R, W = neo_hookean(1 + d / L)
Rk = [neo_hookean(1 + d * t[k] / (L * T))[0] for k in range(5)]
W_rule = sum((Rk[k] + Rk[k + 1]) / 2 * d * (t[k + 1] - t[k]) / T for k in range(4))
w_grips = col("fe_pulled_work")[-1] + col("fe_held_work")[-1]
print("FE bar: reactions off the closed form by %.3g (relative), grip displacement by %.3g of d; grips' work %.10g J, trapezoidal rule on A P %.10g J, A L Psi %.10g J" % (worst["FE reaction"], worst["FE grip"], w_grips, W_rule, W))
if not abs(w_grips - W_rule) < 1e-7 * W: print("FAIL: the FE grips' work %.10g J, the rule on the closed form %.10g J" % (w_grips, W_rule)); ok = False
if not abs(w_grips - W) < 1e-4 * W: print("FAIL: the FE grips' work %.9g J, closed form %.9g J" % (w_grips, W)); ok = False
if not abs(w_grips - h["fe_bar_external_work"][-1]) < 1e-12 * W: print("FAIL: the FE grips' work is not the bar's external work"); ok = False
# LPS bar: the reaction against E A d / L (A = 0.02 x 0.02 m), the same at both ends
r_pd = col("pd_pulled_reaction_x")[1:] / (E * 4e-4 * d / L * t[1:] / T)
balance = np.abs(col("pd_pulled_reaction_x")[1:] + col("pd_held_reaction_x")[1:]).max() / col("pd_pulled_reaction_x")[-1]
print("LPS bar: reaction / (E A d t / (L T)) = %s, held + pulled %.3g of it; grip displacement off by %.3g of d" % (np.array2string(r_pd, precision=5), balance, worst["LPS grip"]))
LPS_BAND = 0.02
if not (np.abs(r_pd - 1) < LPS_BAND).all(): print("FAIL: the LPS bar's reaction is off E A d / L by more than %g" % LPS_BAND); ok = False
if not balance < 1e-6: print("FAIL: the LPS bar's grips' reactions do not balance"); ok = False
sys.exit(0 if ok else 1)
PYEOF
digests="" bitwise=1 ranks_opts=(--set solver.load_steps=2 --set solver.tolerance=1e-4)
[ "${STATIC_BAR_PARTITION:-}" = tolerance ] && bitwise=0 ranks_opts=()
for np in 1 2 3; do
  mkdir -p np$np
  o=$(cd np$np && run $np "$exe" --quiet "${opts[@]}" "${ranks_opts[@]}" "$deck" 2>&1) || { echo "FAIL: $np ranks: $o"; fail=1; }
  digests="$digests $(digest_of "$o")"
done
set -- $digests
[ $# = 3 ] && { [ $bitwise = 0 ] || { [ "$1" = "$2" ] && [ "$1" = "$3" ]; }; } || { echo "FAIL: digests on 1, 2, 3 ranks:$digests"; fail=1; }
echo "digests on 1, 2, 3 ranks:$digests"
# the grips' columns are the same bits on 1, 2 and 3 ranks (pf_sim_solver_sums)
"$PY" - $bitwise np1/static_bar.h5 np2/static_bar.h5 np3/static_bar.h5 <<'PYEOF' || fail=1
import sys
import h5py
import numpy as np
bitwise = sys.argv[1] == "1"
h = [h5py.File(f, "r") for f in sys.argv[2:]]
cols = [g + c for g in ("fe_held", "fe_pulled", "pd_held", "pd_pulled")
        for c in ["_work"] + ["_%s_%s" % (q, a) for q in ("reaction", "displacement") for a in "xyz"]]
# (a column's gap over the largest value of its quantity, work, reaction or displacement, over the grips)
quantity = lambda k: next(q for q in ("_work", "_reaction", "_displacement") if q in k)
scale = lambda k: max(np.abs(h[0][j][:]).max() for j in cols if quantity(j) == quantity(k))
gap = lambda k, o: np.abs(h[0][k][:] - o[k][:]).max() / max(scale(k), 1e-300)
same = (lambda k, o: np.array_equal(h[0][k][:], o[k][:])) if bitwise else (lambda k, o: gap(k, o) <= 1e-7)
bad = [k for k in cols for o in h[1:] if not same(k, o)]
if bad: print("FAIL: the grips' columns differ between 1, 2 and 3 ranks: %s (of %d)" % (bad, len(cols))); sys.exit(1)
worst = max(gap(k, o) for k in cols for o in h[1:])
print("the grips' %d columns on 1, 2 and 3 ranks: %s" % (len(cols), "the same bits" if bitwise else
      "within %.2g of the largest value of its quantity" % worst))
PYEOF
# force control: the FE bar alone, its end face's nodes loaded by a body force of F = 2e4 N in all
# (b = F / (rho A h/2), the face nodes' lumped mass), held at x = 0: u_x linear in x within 1e-8 of
# u_x(L), u_x(L) within 1e-3 of F L / (E A) = 1e-4 m (neo-Hookean at strain 1e-3; measured
# 1.00073), the load's work equal to the stored energy within 1e-4 (measured 1.1e-5)
sed -n '/^materials:/,/^  steel_pd:/p' "$deck" | sed '$d' > force.yaml
sed -n '/^  - name: fe_bar/,/^  - name: lps_bar/p' "$deck" | sed '$d' | sed '1s/^/bodies:\n/' >> force.yaml
cat >> force.yaml <<'DECK'
boundary_conditions:
  - name: held
    region: {shape: box, lo: [-0.001, -1, -1], hi: [0.001, 1, 1]}
    displacement: ["0", "free", "free"]
  - name: load
    region: {shape: box, lo: [0.099, -1, -1], hi: [0.101, 1, 1]}
    body_force: ["2.0e4 / (7800 * 1e-4 * 0.0025) * t", "free", "free"]
solver: {type: quasi_static, load_steps: 4, tolerance: 1.0e-9}
time: {final_time: 1.0}
output: {interval: 0}
DECK
o=$("$exe" "${opts[@]}" force.yaml 2>&1) || { echo "FAIL: force control: $o"; fail=1; }
"$PY" - force.e force.h5 <<'PYEOF' || fail=1
import sys
import h5py
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
X = np.array(e["coordx"][:])
ux = np.array(e["vals_nod_var%d" % (names.index("displacement_x") + 1)][-1])
uL = ux[X > 0.099].mean()
lin = np.abs(ux - uL * X / 0.1).max() / uL
h = h5py.File(sys.argv[2], "r")
w, u = h["external_work"][-1], h["fe_internal_energy"][-1]
print("force control: u_x(L) / (F L/EA) = %.6f, off linear %.3g, work %.8g J, stored %.8g J" % (uL / 1e-4, lin, w, u))
ok = lin < 1e-8 and abs(uL / 1e-4 - 1) < 1e-3 and abs(w - u) < 1e-4 * w
if not ok: print("FAIL: force control")
# the load's column is its force, F t (the face nodes' lumped masses sum to rho A h / 2), against
# the mean displacement of its nodes, the end face's u_x(L); its work is the bar's external work
t, F = h["time"][:], h["load_reaction_x"][:]
if not np.allclose(F, 2e4 * t, rtol=1e-12, atol=0): print("FAIL: the load's column %s, F t %s" % (F, 2e4 * t)); ok = False
if not abs(h["load_displacement_x"][-1] - uL) < 1e-12 * uL: print("FAIL: the load's displacement %g, u_x(L) %g" % (h["load_displacement_x"][-1], uL)); ok = False
if not abs(h["load_work"][-1] - w) < 1e-12 * w: print("FAIL: the load's work %.10g J, external work %.10g J" % (h["load_work"][-1], w)); ok = False
sys.exit(0 if ok else 1)
PYEOF
# bad input: each a message and a non-zero exit
expect() { # expect STATUS PATTERN ARGS...: the run exits with STATUS, its output matches PATTERN
  local want=$1 pattern=$2; shift 2
  local msg rc
  msg=$("$exe" "${opts[@]}" "$@" 2>&1); rc=$?
  [ $rc -eq "$want" ] && echo "$msg" | grep -q "$pattern" || { echo "FAIL: $*: exit $rc: $msg"; fail=1; }
}
sed '/^boundary_conditions:/,/^solver:/{/^solver:/!d}' "$deck" > nobc.yaml
expect 2 "nobc.yaml:.*key 'type': a quasi_static solver needs a load" nobc.yaml
sed 's/^    material: steel_pd/    material: steel_pd\n    initial_velocity: ["1", "0", "0"]/' "$deck" > moving.yaml
expect 2 "moving.yaml:.*key 'initial_velocity': a quasi_static solver starts at rest" moving.yaml
expect 1 "load step 1 of 4 .* did not converge: the residual is .* after 20 iterations" --set solver.max_iterations=20 "$deck"
expect 2 "key 'tolerance': must be in (0, 1)" --set solver.tolerance=0 "$deck"
exit $fail
