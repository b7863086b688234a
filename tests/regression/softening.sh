#!/usr/bin/env bash
# Bonds that soften (damage law softening, docs/theory/bond_failure.md §8) in whole runs; the
# bond law itself against its closed forms is tests/unit/test_softening.c.
#  1. Dynamics, tests/data/softening_bar.yaml (an LPS bar pulled apart, s_c = 1.05e-3, r = 4) and
#     its PMB twin: the bar breaks (damage, and its elastic energy at the end below a quarter of its
#     largest: measured 0.028 LPS, 0.12 PMB, whose halves ring); the energy balance (kinetic,
#     elastic, the dissipation the softening books, the grips' work), its largest error over the run
#     within 5e-3 of the work for LPS (measured 3.7e-3) and 2e-3 for PMB (6.7e-4), and for LPS an
#     error of the time step: below 0.6 of it at half the step (measured 0.36); the same state digest
#     on 1, 2 and 3 ranks.
#  2. Quasi-static, tests/data/static_damage_bar.yaml with the law softening (r = 2: s0 = s_c /
#     sqrt2 = 7.42e-4, s1 = 1.48e-3) in 24 load steps of strain 1e-4: nothing dissipated while the
#     strain is below s0 (load steps 1-7), dissipation and damage passes from load step 8 (the
#     damage grows at the checks, and the state relaxes again while it grows: 2 passes in load
#     steps 8 and 9); the bar separates (the pulled grip's reaction at the end below 1e-6 of its
#     peak for LPS, 1e-3 for PMB; measured 7e-8, 6e-8); the energy balance within 1e-4 of the work
#     (1.3e-6); for PMB the dissipation booked at load step 8, before the strain gathers, against
#     the closed form c |xi| Phi(s) V_i V_j of each bond from the output's positions, within
#     [0, +1 %] (measured +0.04 %: bonds that unloaded after the first check had softened at a
#     larger stretch); the same state digest on 1, 2 and 3 ranks; 12 load steps checkpointed at
#     load step 8 on 1 rank and restarted from it on 2: the uninterrupted run's digest.
#  3. Input errors: softening_ratio 1, a material other than pmb and lps, a variable horizon, the
#     sequential solver: exit 2 with a message naming the key.
# usage: softening.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
data=$(cd .. && pwd)/tests/data
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"

# 1. dynamics
cp "$data/softening_bar.yaml" lps.yaml
sed 's/model: lps, density: 2500, bulk_modulus: 50.0e9, shear_modulus: 30.0e9/model: pmb, density: 2500, bulk_modulus: 50.0e9/' \
  lps.yaml > pmb.yaml
for m in lps pmb; do
  for sf in 0.8 0.4; do
    o=$("$exe" --set time.safety_factor=$sf --output-dir $m$sf $m.yaml 2>&1) || { echo "FAIL: $m at safety $sf: $o"; fail=1; }
    [ $sf = 0.8 ] && digest_of "$o" > $m.digest
  done
done
"$PY" - <<'PYEOF' || fail=1
import h5py
import numpy as np
ok, err = True, {}
for m, band in (("lps", 5e-3), ("pmb", 2e-3)):
    for sf in ("0.8", "0.4"):
        h = h5py.File("%s%s/%s.h5" % (m, sf, m), "r")
        W, E = h["external_work"][:], h["elastic_energy"][:]
        err[m, sf] = np.abs(h["energy_error"][:]).max() / W[-1]
        print("%s, safety %s: energy error %.2e of the work; dissipated %.4g J; damage %.4f; elastic energy at the "
              "end %.3g of its largest" % (m, sf, err[m, sf], h["damage_dissipation"][-1], h["damage_fraction"][-1],
                                           E[-1] / E.max()))
        if not (h["damage_fraction"][-1] > 0 and E[-1] < 0.25 * E.max() and h["damage_dissipation"][-1] > 0):
            print("FAIL: %s: the bar did not break" % m); ok = False
    if not err[m, "0.8"] < band:
        print("FAIL: %s: energy error %.3g of the work (band %g)" % (m, err[m, "0.8"], band)); ok = False
if not err["lps", "0.4"] < 0.6 * err["lps", "0.8"]:
    print("FAIL: lps: the energy error does not fall with the step (%.3g at 0.4)" % err["lps", "0.4"]); ok = False
raise SystemExit(0 if ok else 1)
PYEOF
for m in lps pmb; do
  digests=$(cat $m.digest)
  for np in 2 3; do
    o=$(run $np "$exe" --quiet --output-dir $m.np$np $m.yaml 2>&1) || { echo "FAIL: $m on $np ranks: $o"; fail=1; }
    digests="$digests $(digest_of "$o")"
  done
  digests_agree "dynamic $m" $digests || fail=1
done

# 2. quasi-static
sed 's/law: critical_stretch/law: softening\n      softening_ratio: 2/' "$data/static_damage_bar.yaml" > qlps.yaml
sed 's/model: lps/model: pmb/' qlps.yaml > qpmb.yaml
q=(--set solver.load_steps=24 --set parameters.emax=2.4e-3)
for m in qlps qpmb; do
  o=$("$exe" "${q[@]}" $m.yaml 2>&1) || { echo "FAIL: $m: $o"; fail=1; }
  echo "$o" | grep '^load step' > $m.progress
  digest_of "$o" > $m.digest
  passes=$(sed -n 's/.*damage passes \([0-9]*\).*/\1/p' $m.progress | tr '\n' ' ')
  echo "$m: damage passes per load step: $passes"
  set -- $passes
  [ $# = 24 ] && [ "$1$2$3$4$5$6$7" = 0000000 ] && [ "$8" -gt 0 ] || { echo "FAIL: $m: damage passes $passes"; fail=1; }
done
"$PY" - <<'PYEOF' || fail=1
import h5py
import netCDF4
import numpy as np
ok = True
sc, K, delta, V = 1.05e-3, 50.0e9, 0.003015, 1e-9
s0, s1 = sc / np.sqrt(2), sc * np.sqrt(2)
for m, band in (("qlps", 1e-6), ("qpmb", 1e-3)):
    h = h5py.File(m + ".h5", "r")
    D, W, err = h["damage_dissipation"][:], h["external_work"][:], h["energy_error"][:]
    R = np.abs(h["pulled_reaction_x"][:])
    print("%s: dissipation at load steps 7, 8, 24: %.4g, %.4g, %.4g J; reaction peak %.4g N, at the end %.3g of it; "
          "energy error %.2e of the work" % (m, D[7], D[8], D[-1], R.max(), R[-1] / R.max(), np.abs(err).max() / W[-1]))
    if not (D[:8].max() == 0 and D[8] > 0 and R[-1] < band * R.max() and h["damage_fraction"][-1] > 0):
        print("FAIL: %s: dissipation %s, reactions %s" % (m, D, R)); ok = False
    if not np.abs(err).max() < 1e-4 * W[-1]:
        print("FAIL: %s: energy error %s" % (m, err)); ok = False
# PMB at load step 8: each bond's closed form from the output's positions
e = netCDF4.Dataset("qpmb.e")
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
X = np.stack([np.array(e["coord" + c][:]) for c in "xyz"], 1)
u = np.stack([np.array(e["vals_nod_var%d" % (names.index("displacement_" + c) + 1)][8]) for c in "xyz"], 1)
i, j = np.triu_indices(len(X), 1)
r0 = np.linalg.norm(X[j] - X[i], axis=1)
fuse = lambda x: np.abs(x - 0.01) < 0.0016  # a bond softens when an end is in the section
keep = (r0 <= delta) & (fuse(X[i, 0]) | fuse(X[j, 0]))
i, j, r0 = i[keep], j[keep], r0[keep]
s = (np.linalg.norm(X[j] + u[j] - X[i] - u[i], axis=1) - r0) / r0
c = 18 * K / (np.pi * delta ** 4)
ref = (c * r0 * s0 * s1 * (np.clip(s, s0, s1) - s0) / (2 * (s1 - s0)) * V * V).sum()
got = h5py.File("qpmb.h5", "r")["damage_dissipation"][8]
print("qpmb at load step 8: %d bonds past s0; dissipation %.6g J, closed form from the positions %.6g J (%+.2e)"
      % ((s > s0).sum(), got, ref, got / ref - 1))
if not (ref > 0 and 0 <= got / ref - 1 < 0.01):
    print("FAIL: qpmb: the dissipation at load step 8 is not the bonds' closed form"); ok = False
raise SystemExit(0 if ok else 1)
PYEOF
digests=$(cat qlps.digest)
for np in 2 3; do
  o=$(run $np "$exe" --quiet "${q[@]}" --output-dir qlps.np$np qlps.yaml 2>&1) || { echo "FAIL: qlps on $np ranks: $o"; fail=1; }
  digests="$digests $(digest_of "$o")"
done
digests_agree "quasi-static lps" $digests || fail=1
# 12 load steps (the same first 12), checkpointed at load step 8 alone (its bonds softened; the bar
# separates at 9), and restarted from it on 2 ranks: the uninterrupted run's digest
ck=(--set solver.load_steps=12 --set parameters.emax=1.2e-3 --set 'restart={file: ck.h5, interval: 8}')
o=$("$exe" "${ck[@]}" --output-dir ck qlps.yaml 2>&1) || { echo "FAIL: qlps with a checkpoint: $o"; fail=1; }
d12=$(digest_of "$o")
o=$(run 2 "$exe" "${ck[@]}" --restart ck/ck.h5 --output-dir restarted qlps.yaml 2>&1) || { echo "FAIL: qlps restarted: $o"; fail=1; }
echo "$o" | grep -q 'load steps 9 to 12 of 12' || { echo "FAIL: the restart did not take load steps 9 to 12: $o"; fail=1; }
echo "quasi-static lps, 12 load steps: digest $d12; restarted on 2 ranks from load step 8: $(digest_of "$o")"
[ -n "$d12" ] && [ "$(digest_of "$o")" = "$d12" ] || { echo "FAIL: not the uninterrupted run's"; fail=1; }

# 3. input errors
expect() { # expect STATUS PATTERN ARGS...: the run exits with STATUS, its output matches PATTERN
  local want=$1 pattern=$2; shift 2
  local msg rc
  msg=$("$exe" "$@" 2>&1); rc=$?
  [ $rc -eq "$want" ] && echo "$msg" | grep -q "$pattern" || { echo "FAIL: $*: exit $rc: $msg"; fail=1; }
}
expect 2 "key 'softening_ratio': must be a number above 1" --set bodies.bar.damage.softening_ratio=1 qlps.yaml
sed 's/model: lps/model: elastic_plastic\n    yield_stress: 1.0e8/' qlps.yaml > qep.yaml
expect 2 "key 'law': law 'softening' is built for the materials pmb and lps (body 'bar' has elastic_plastic)" qep.yaml
expect 2 "key 'law': law 'softening' needs a PD body of one horizon" --set 'bodies.bar.horizon="0.003015 + 0 * x"' qlps.yaml
expect 2 "key 'failure': .*body 'bar' has bonds that soften" --set solver.failure=sequential qlps.yaml
exit $fail
