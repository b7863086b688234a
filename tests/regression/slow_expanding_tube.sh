#!/usr/bin/env bash
# The expanding tube (inputs/expanding_tube.yaml as shipped; docs/examples/expanding_tube.md)
# against Vogler et al. (2003)'s recovered fragments, and on 1 and 2 ranks:
#  - the run reaches 84.8 us on 2 ranks and on 1 rank with the same state digest;
#  - the tube breaks, and "about half of the tube stayed in one piece": the largest fragment
#    (connected component of intact bonds) holds between 30 % and 70 % of the tube's mass;
#  - "14 fragments heavier than 1 g were recovered": the model has between 5 and 30 such
#    fragments (a qualitative band around the count: the model's fragments are its discrete
#    lattice's, 0.75 mm cells of 3.3 mg, not recovered pieces);
#  - the fragments hold the tube's mass (pi (9.35^2 - 6.35^2) mm^2 x 50.8 mm x 7870 kg/m^3 =
#    59.2 g, to 1e-6: the polar lattice tiles the wall);
#  - the outer surface moves outwards at each probe ring (peak radial velocity above 100 m/s);
#  - conservation (issue 32): with no support and no wall, the linear momentum stays that of the
#    projectile to 1e-6 of it (measured 1.3e-14), and the energy balance closes to 0.5 % of the
#    projectile's kinetic energy at every history row (measured -1.4 J of 6845 J, 0.02 %; 1.1 %
#    before the LPS force kept its energy's gradient after failures, theory/materials.md §1).
# About 1 minute on 2 ranks and 2 on 1 rank, hence label slow.
# usage: slow_expanding_tube.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch/np1" "$scratch/np2"
out2=$(run 2 "$exe" --quiet --output-dir "$scratch/np2" ../inputs/expanding_tube.yaml 2>&1) ||
  { echo "FAIL: 2 ranks: $out2"; exit 1; }
out1=$("$exe" --quiet --output-dir "$scratch/np1" ../inputs/expanding_tube.yaml 2>&1) ||
  { echo "FAIL: 1 rank: $out1"; exit 1; }
d1=$(digest_of "$out1") d2=$(digest_of "$out2")
[ -n "$d1" ] && [ "$d1" = "$d2" ] || { echo "FAIL: digests on 1 rank '$d1' and 2 ranks '$d2' differ"; exit 1; }
"$PY" ../scripts/tube_report.py "$scratch/np2/expanding_tube.h5" --json "$scratch/report.json" ||
  { echo "FAIL: tube_report.py exited $?"; exit 1; }
"$PY" - "$scratch/report.json" <<'PYEOF'
import json, math, sys
s = json.load(open(sys.argv[1]))
ok = True
def check(cond, what):
    global ok
    if not cond:
        print("FAIL:", what)
        ok = False
mass = math.pi * (9.35e-3 ** 2 - 6.35e-3 ** 2) * 50.8e-3 * 7870
check(abs(s["time"] - 84.8e-6) < 1e-6, "last fragments at %g s, not 84.8 us" % s["time"])
check(abs(s["tube_mass"] - mass) < 1e-6 * mass, "fragments hold %g kg, the tube %g kg" % (s["tube_mass"], mass))
check(0.3 <= s["largest_fraction"] <= 0.7, "largest fragment %.2f of the tube (about half)" % s["largest_fraction"])
check(5 <= s["heavier_than_1g"] <= 30, "%d fragments over 1 g (Vogler et al.: 14)" % s["heavier_than_1g"])
for name, r in s["rings"].items():
    check(r["peak_radial_velocity"] > 100, "ring %s: peak radial velocity %g m/s" % (name, r["peak_radial_velocity"]))
sys.exit(0 if ok else 1)
PYEOF
[ $? = 0 ] || exit 1
"$PY" - "$scratch/np2/expanding_tube.h5" <<'PYEOF'
import h5py, numpy as np, sys
h = h5py.File(sys.argv[1], "r")
e0, p0 = h["kinetic_energy"][0], h["momentum_z"][0]
drift = max(np.max(np.abs(h["momentum_" + a][:] - h["momentum_" + a][0])) for a in "xyz")
err = np.max(np.abs(h["energy_error"][:]))
print("momentum drift %.2e of the projectile's; largest energy error %.3g J, %.4f of %.4g J" % (drift / p0, err, err / e0, e0))
ok = drift < 1e-6 * p0 and err < 5e-3 * e0
if not ok: print("FAIL: momentum or energy not conserved to the bounds")
sys.exit(0 if ok else 1)
PYEOF
