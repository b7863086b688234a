#!/usr/bin/env bash
# Friction under the quasi-static solver (docs/theory/quasi_static_methods.md §8): a tangential
# penalty k_t with a stick/slip return mapping from each point's slip, committed at converged load
# steps only, on a rigid surface (contact/rigid.c, pf_rigid_force_static) and between the bodies
# of a contact pair, on the slip relative to the surface point a point meets (contact/pairs.c,
# static_friction). Two decks, one load path: tests/data/static_friction_block.yaml, an FE block
# (one bbar hexahedron, its n = 4 bottom nodes on a rigid plane, linear law k = k_t = 1e7 N/m,
# mu = 0.3), and tests/data/static_friction_pair.yaml, the same block on a held FE base (a pair,
# FE <-> FE surfaces, the same k, k_t and mu a node), each pressed down by its top in 2 load steps,
# pushed along x in 6, pushed back in 2 (the decks' headers). Checked on each, with T and N the
# tangential and normal force on the plane (the base) and u the bottom nodes' mean motion along x:
#  - pressing: T = 0 (1e-9 of mu N);
#  - sticking from rest (load step 3): T = n k_t u (Coulomb's law holds the springs: 1e-6), T < mu N;
#  - sliding (load steps 4 to 8): T = mu N (1e-6; measured 2.2e-16); the friction work of load
#    steps 5 to 8 mu N times the bottom's motion (1e-6);
#  - pushed back (9, 10): T falls from its last sliding value by n k_t times the bottom's motion
#    back (1e-6), |T| < mu N, no friction work: the springs hold the slip the sliding left;
#  - the energy balance: the ledger's error is the trapezoidal rule's own error on the force's
#    kink at the stick/slip transition (load step 4; computed from T, u and n k_t of load steps 3
#    and 4 with the four nodes alike: 2 %; measured 0.22 %), and changes by less than 1e-6 of the
#    work over every other load step;
#  - the same forces by newton_krylov (1e-6 of mu N);
#  - the same state digest on 1, 2 and 3 ranks, and restarted from the checkpoint of load step 9
#    (pushed back: the springs hold the slip the sliding left) on 1, 2 and 3 ranks: the slip is in
#    the checkpoint (without it, a restart from a sliding load step ends alike: the return mapping
#    forgets the slip of a point that slides).
# The pair deck again with the block 1e-6 m above the base, pressed and pushed together from the
# start: T = min(mu N, n k_t u) at every load step (1e-6), sticking from rest in load step 1, where
# it meets the base (each point's slip is set at the start, and at each equilibrium to its
# displacement relative to the nearest surface point within the search's reach).
# Then tests/data/static_friction_pd.yaml: an FE block (2 x 2 hexahedra) pressed on a PMB base and
# pushed along x, 100 particles under its face (FE <-> PD surface pair, friction on the particles'
# slips): |T| never above mu N (1e-9), T_x at least 0.999 mu N while it slides (the base's
# particles tilt their friction out of x by their own sideways motion: measured 0.99952), no
# tangential force while pressing, the same digest on 1, 2 and 3 ranks.
# Refused: the quadratic law with friction and no tangential_stiffness (an input error naming the
# key); a short-range pair's friction under this solver, and tangential_stiffness on such a pair.
# usage: static_friction.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
data=$(cd data && pwd)
source common/mpi_env.sh
source common/measure.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
# one_deck NAME DECK WORK: the closed forms (WORK: the history column of the friction work), by
# relaxation and newton_krylov, and the digests on 1, 2, 3 ranks, uninterrupted and restarted
one_deck() {
  local name=$1 deck=$2 work=$3 st=0 o ref res
  mkdir -p "$name" && cd "$name" && cp "$data/$deck" "$name.yaml"
  ref=$("$exe" --quiet --set restart.interval=9 --set restart.file=ck.h5 "$name.yaml" 2>&1) || { echo "FAIL: $name: $ref"; st=1; }
  mkdir -p nk
  o=$(cd nk && "$exe" --quiet --set solver.method=newton_krylov "../$name.yaml" 2>&1) || { echo "FAIL: $name by newton_krylov: $o"; st=1; }
  res=$("$PY" - "$name.h5" "nk/$name.h5" "$work" <<'PYEOF'
import sys
import h5py
import numpy as np
ok = True
n, kt, mu = 4, 1e7, 0.3
h = h5py.File(sys.argv[1], "r")
T = h["floor_force_x"][1:]  # the points' force on the plane (the base) along x
N = -h["floor_force_z"][1:]
u = h["bottom_displacement_x"][1:]
W = h[sys.argv[3]][1:]
err = h["energy_error"][1:]
work = h["external_work"][-1]
press, stick, slide, back = slice(0, 2), 2, slice(3, 8), slice(8, 10)
e_press = np.abs(T[press]).max() / (mu * N[1])
e_stick = abs(T[stick] / (n * kt * u[stick]) - 1)
e_slide = np.abs(T[slide] / (mu * N[slide]) - 1).max()
dW = W[4:8] - W[3:7]
e_work = np.abs(dW / (mu * N[4:8] * (u[4:8] - u[3:7])) - 1).max()
e_back = np.abs((T[back] - T[7]) / (n * kt * (u[back] - u[7])) - 1).max()
# the trapezoid's own error on the kink of load step 4: the work of T along u from load step 3
# (sticking, T3 = n k_t u3) to 4 (sliding at T4 = mu N), exactly: the springs up to T4, then T4
T3, T4, u3, u4 = T[2], T[3], u[2], u[3]
exact = (T4 ** 2 - T3 ** 2) / (2 * n * kt) + T4 * (u4 - T4 / (n * kt))
defect = exact - 0.5 * (T3 + T4) * (u4 - u3)
e_defect = abs(err[-1] / defect - 1)
drift = max(np.abs(np.diff(err[:3])).max(), np.abs(np.diff(err[3:])).max()) / work  # (all but load step 4)
print("pressed: T %.2g of mu N; sticking: T / (n k_t u) - 1 = %.2g, T / mu N = %.4f" % (e_press, e_stick, T[stick] / (mu * N[stick])))
print("sliding: T / (mu N) - 1 up to %.2g; friction work per load step / (mu N du) - 1 up to %.2g" % (e_slide, e_work))
print("back: (T - T8) / (n k_t (u - u8)) - 1 up to %.2g, T / mu N = %s" % (e_back, np.array2string(T[back] / (mu * N[back]), precision=4)))
print("energy error %.4g J, the trapezoid's defect at the kink %.4g J (%.2g off); other load steps change it by %.2g of the work %.4g J"
      % (err[-1], defect, e_defect, drift, work))
print("MEASURE slide_error %.6g" % e_slide)
print("MEASURE energy_defect_error %.6g" % e_defect)
if not e_press < 1e-9: print("FAIL: a tangential force while pressing"); ok = False
if not (e_stick < 1e-6 and T[stick] < mu * N[stick]): print("FAIL: sticking from rest: not the tangential springs"); ok = False
if not e_slide < 1e-6: print("FAIL: sliding: T is not mu N"); ok = False
if not e_work < 1e-6: print("FAIL: sliding: the friction work is not mu N times the slip"); ok = False
if not (e_back < 1e-6 and (np.abs(T[back]) < mu * N[back]).all()): print("FAIL: pushed back: not the springs unloading"); ok = False
if not (W[9] == W[7]): print("FAIL: pushed back: friction work while sticking"); ok = False
if not (e_defect < 0.02 and drift < 1e-6): print("FAIL: the energy balance"); ok = False
k = h5py.File(sys.argv[2], "r")
e_nk = np.abs(k["floor_force_x"][1:] - T).max() / (mu * N[-1])
print("newton_krylov: T within %.2g of mu N of relaxation's" % e_nk)
if not e_nk < 1e-6: print("FAIL: newton_krylov's forces differ"); ok = False
sys.exit(0 if ok else 1)
PYEOF
) || st=1
  echo "$res" | sed "/^MEASURE/d; s/^/$name: /"
  local prefix="${name}_"
  [ "$name" = block ] && prefix=""
  echo "$res" | sed -n 's/^MEASURE //p' | while read -r k v; do pf_measure "$prefix$k" "$v" 1; done
  restart_digests "$name" 9 "$ref" || st=1
  cd ..
  return $st
}
# restart_digests NAME STEP REF: NAME.yaml's digest on 1, 2, 3 ranks, and restarted from ck.h5 (the
# checkpoint of load step STEP) on 1, 2, 3 ranks, against the uninterrupted run's (REF's output);
# STEP -: no restart
restart_digests() {
  local name=$1 step=$2 ref=$3 np o st=0 digests="" restarts=""
  for np in 1 2 3; do
    mkdir -p np$np rs$np
    o=$(cd np$np && run $np "$exe" --quiet "../$name.yaml" 2>&1) || { echo "FAIL: $name on $np ranks: $o"; st=1; }
    digests="$digests $(digest_of "$o")"
    [ "$step" = - ] && continue
    o=$(cd rs$np && run $np "$exe" --quiet --restart ../ck.h5 --set restart.interval=$step --set restart.file=ck.h5 "../$name.yaml" 2>&1) || { echo "FAIL: $name's restart on $np ranks: $o"; st=1; }
    restarts="$restarts $(digest_of "$o")"
  done
  digests_agree "$name" $digests || st=1
  [ "$step" = - ] && return $st
  digests_agree "$name restarted at load step $step" $restarts || st=1
  [ "$(digest_of "$ref")" = "$(echo $restarts | cut -d' ' -f1)" ] || { echo "FAIL: $name: the restart's digest is not the uninterrupted run's $(digest_of "$ref")"; st=1; }
  return $st
}
one_deck block static_friction_block.yaml floor_friction_work || fail=1
one_deck pair static_friction_pair.yaml contact_dissipation || fail=1
# the pair with the block 1e-6 m above the base, pressed and pushed along x together from the start
# (1e-5 m t): it meets the base in load step 1 and, its slip there being the start's, sticks from
# rest at once, T = min(mu N, n k_t u) at every load step (a point whose slip waited for its first
# equilibrium in contact carried nothing in load step 1)
mkdir -p gap && cd gap
sed 's/gmin = 0 0 0/gmin = 0 0 1.0e-6/; s/gmax = 0.01 0.01 0.01$/gmax = 0.01 0.01 0.010001/
     s/lo: \[-1, -1, 0.009\]/lo: [-1, -1, 0.0095]/; s/hi: \[1, 1, 0.001\]}/hi: [1, 1, 0.0005]}/
     s/displacement: \["t <= 0.2 ? 0 : [^"]*"/displacement: ["1.0e-5 * t"/' "$data/static_friction_pair.yaml" > gap.yaml
o=$("$exe" --quiet gap.yaml 2>&1) || { echo "FAIL: gap: $o"; fail=1; }
"$PY" - gap.h5 <<'PYEOF' || fail=1
import sys
import h5py
import numpy as np
n, kt, mu = 4, 1e7, 0.3
h = h5py.File(sys.argv[1], "r")
T, N, u = h["floor_force_x"][1:], -h["floor_force_z"][1:], h["bottom_displacement_x"][1:]
closed = np.minimum(mu * N, n * kt * u)
e = np.abs(T / closed - 1).max()
print("gap: T against min(mu N, n k_t u) within %.2g (load step 1: T / mu N = %.4f, sticking)" % (e, T[0] / (mu * N[0])))
ok = e < 1e-6 and T[0] < mu * N[0]
if not ok: print("FAIL: the block arriving from a gap: not Coulomb's springs from rest")
sys.exit(0 if ok else 1)
PYEOF
cd ..
# the block on a PD base
mkdir -p pd && cd pd && cp "$data/static_friction_pd.yaml" pd.yaml
ref=$("$exe" --quiet pd.yaml 2>&1) || { echo "FAIL: pd: $ref"; fail=1; }
res=$("$PY" - pd.h5 <<'PYEOF'
import sys
import h5py
import numpy as np
mu = 0.3
h = h5py.File(sys.argv[1], "r")
Tx, Ty = h["floor_force_x"][1:], h["floor_force_y"][1:]  # the base's force on the block
N = h["floor_force_z"][1:]
over = (np.hypot(Tx, Ty) / (mu * N)).max()
slide = (-Tx[3:] / (mu * N[3:])).min()
press = np.abs(Tx[:2] / (mu * N[:2])).max()
print("pd: |T| / mu N at most %.10f; sliding T_x / mu N at least %.5f; pressing %.2g" % (over, slide, press))
print("MEASURE pd_slide %.6g" % slide)
ok = over <= 1 + 1e-9 and slide >= 0.999 and press < 1e-3
if not ok: print("FAIL: the PD base's friction is not Coulomb's")
sys.exit(0 if ok else 1)
PYEOF
) || fail=1
echo "$res" | grep -v '^MEASURE'
echo "$res" | sed -n 's/^MEASURE //p' | while read -r k v; do pf_measure "$k" "$v" 1; done
restart_digests pd - "$ref" || fail=1
cd ..
sed 's/      law: linear/      law: quadratic/; s/      stiffness: 1.0e7/      stiffness: 1.0e17/' block/block.yaml > quadratic.yaml
msg=$("$exe" quadratic.yaml 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "quadratic.yaml:.*key 'tangential_stiffness': .*needs 'tangential_stiffness'" ||
  { echo "FAIL: the quadratic law without tangential_stiffness: exit $rc: $msg"; fail=1; }
sed 's/friction: 0.3}/friction: 0.3}\n    - {name: fragments, bodies: [base, base], friction: 0.2}/' pd/pd.yaml > short_range.yaml
msg=$("$exe" short_range.yaml 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "short_range.yaml:[0-9]*:.*key 'friction': the friction of short-range pairs (PD <-> PD) is not supported with the quasi_static solver" ||
  { echo "FAIL: a short-range pair's friction under the quasi-static solver: exit $rc: $msg"; fail=1; }
sed 's/friction: 0.3}/friction: 0.3}\n    - {name: fragments, bodies: [base, base], tangential_stiffness: 1.0e7}/' pd/pd.yaml > short_range_kt.yaml
msg=$("$exe" short_range_kt.yaml 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "short_range_kt.yaml:[0-9]*:.*key 'tangential_stiffness': 'tangential_stiffness' is a key of pairs with an FE body" ||
  { echo "FAIL: tangential_stiffness on a short-range pair: exit $rc: $msg"; fail=1; }
exit $fail
