#!/usr/bin/env bash
# The cluster-cluster collision of Ruestes et al. (2012, sec. 4.2; inputs/cluster_collision.yaml,
# docs/examples/cluster_collision.md): two PMB clusters of 280 um radius meet at 5 m/s with an
# impact parameter of one radius. Against the paper's Fig. 6 and its text:
#  - the clusters touch between 0.05 and 0.1 ms (the first contact energy or broken bond);
#  - "clusters are completely fragmented into single grains 0.3 ms after contact begins": the
#    broken-bond share is above 0.95 by then, and at the end (0.4 ms) most grains (more than
#    3/4) are fragments of one grain, none larger than 10 % of a cluster;
# and the balances of an isolated system of central forces:
#  - the total momentum stays zero to round-off (below 1e-12 of one cluster's);
#  - the angular momentum about the origin, sum m y x v over the grains from the first and last
#    Exodus frames, changes by less than 1e-10 of itself (pair forces along the line of centres,
#    velocity Verlet: the torque is zero to round-off), and so does the history's
#    angular_momentum at every row, which starts at the frames' value;
#  - the energy balance closes within 1e-3 of the initial kinetic energy;
# and the same state digest on 1, 2 and 3 ranks for the first 0.08 ms (the first contact
# included). About 40 s on 2 cores (label slow).
# usage: slow_cluster_collision.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
deck=$PWD/../inputs/cluster_collision.yaml
rm -rf "$scratch" && mkdir -p "$scratch/full" "$scratch/d1" "$scratch/d2" "$scratch/d3"
out=$(cd "$scratch/full" && "$exe" --set output.interval=0 "$deck" 2>&1) || { echo "FAIL: the full run: $out"; exit 1; }
echo "$out" | grep -E "^  fragments of|final damage|time loop"
echo "$out" | grep -E "^  fragments of" | sed -E 's/^  fragments of ([a-z_]+): ([0-9]+).*/\1 \2/' > "$scratch/fragments.txt"
for np in 1 2 3; do
  o=$(cd "$scratch/d$np" && run "$np" "$exe" --quiet --set time.final_time=8e-5 --set output.interval=0 "$deck" 2>&1) ||
    { echo "FAIL: $np rank(s): $o"; exit 1; }
  d[$np]=$(digest_of "$o")
done
digests_agree cluster_collision "${d[1]}" "${d[2]}" "${d[3]}" || fail=1
"$PY" - "$scratch/full/cluster_collision.h5" "$scratch/full/cluster_collision.e" <<'PYEOF' || fail=1
import collections, sys
import h5py, netCDF4, numpy as np
h = h5py.File(sys.argv[1], "r")
t, dmg = h["time"][:], h["damage_fraction"][:]
touch = t[(dmg > 0) | (h["contact_energy"][:] > 0)]
bad = 0
def check(ok, what):
    global bad
    print(("ok:   " if ok else "FAIL: ") + what)
    bad += not ok
t0 = touch[0] if len(touch) else np.inf
check(0.05e-3 <= t0 <= 0.1e-3, f"first contact at {t0 * 1e3:.4f} ms (Fig. 6: between 0.05 and 0.1 ms)")
later = dmg[t >= t0 + 0.3e-3]
check(len(later) > 0 and later[0] > 0.95,
      f"broken-bond share {later[0] if len(later) else float('nan'):.4f} 0.3 ms after contact (completely fragmented: > 0.95)")
m1 = 2000 * 1.44e-15
p_cluster = abs(h["cluster_a_momentum_x"][0])
p = np.sqrt(h["momentum_x"][:] ** 2 + h["momentum_y"][:] ** 2 + h["momentum_z"][:] ** 2).max()
check(p <= 1e-12 * p_cluster, f"total momentum at most {p:.3e} kg m/s (one cluster's {p_cluster:.4e}: < 1e-12 of it)")
ke = h["kinetic_energy"][0]
err = np.abs(h["energy_error"][:]).max() / ke
check(err <= 1e-3, f"energy balance error at most {err:.3e} of the initial kinetic energy (< 1e-3)")
ds = netCDF4.Dataset(sys.argv[2])
names = ["".join(c.decode() for c in row if c).strip() for row in ds.variables["name_nod_var"][:]]
nod = lambda n, f: np.asarray(ds.variables[f"vals_nod_var{names.index(n) + 1}"][f, :], dtype=float)
X = [np.asarray(ds.variables[f"coord{c}"][:], dtype=float) for c in "xyz"]
last = len(ds.variables["time_whole"][:]) - 1
L = []
for f in (0, last):
    y = np.array([X[a] + nod(f"displacement_{c}", f) for a, c in enumerate("xyz")])
    v = np.array([nod(f"velocity_{c}", f) for c in "xyz"])
    L.append(m1 * np.cross(y.T, v.T).sum(axis=0))
dL = np.linalg.norm(L[1] - L[0]) / np.linalg.norm(L[0])
check(dL <= 1e-10, f"angular momentum {np.linalg.norm(L[0]):.6e} kg m^2/s, changed by {dL:.2e} of itself (< 1e-10)")
Lh = np.array([h[f"angular_momentum_{c}"][:] for c in "xyz"])
dLh = np.abs(Lh - Lh[:, :1]).max() / np.linalg.norm(Lh[:, 0])
check(dLh <= 1e-10, f"the history's angular_momentum changes by at most {dLh:.2e} of itself over every row (< 1e-10)")
agree = np.linalg.norm(Lh[:, 0] - L[0]) / np.linalg.norm(L[0])
check(agree <= 1e-9, f"the history's angular_momentum at t = 0 is the frames' sum m y x v to {agree:.2e} (< 1e-9)")
size = collections.Counter(nod("fragment", last))
grains = sum(size.values())
single = sum(1 for n in size.values() if n == 1) / grains
largest = max(size.values()) / (grains / 2)
check(single > 0.75, f"{single:.3f} of the grains single at 0.4 ms (most: > 3/4)")
check(largest < 0.10, f"largest fragment {largest:.3f} of a cluster (< 0.10)")
print(f"fragments {len(size)} of {grains} grains; sizes of the largest ten: {sorted(size.values(), reverse=True)[:10]}")
sys.exit(1 if bad else 0)
PYEOF
exit $fail
