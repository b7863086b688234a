#!/usr/bin/env bash
# output.fragments: a 12 x 4 x 4 mm LPS bar on a 1 mm lattice (192 points, rho = 2000 kg/m^3,
# points of 2e-6 kg) cut through by two pre-cracks at x = 3 mm and x = 7 mm is three fragments of
# 3, 4 and 5 lattice columns (48, 64, 80 points: 9.6e-5, 1.28e-4, 1.6e-4 kg) - counted by hand
# from the lattice, not by the code. Each third is given its own velocity (-1, 0, +1 m/s along x)
# and nothing acts between them, so each fragment's mean velocity stays that. Beside it an FE
# cube, which has no bonds: not labelled (-1), not in the CSV. Checks, on 1, 2 and 3 ranks: the
# CSV's rows (count, points, masses, velocities, centres); the Exodus field "fragment" is the
# smallest global id of each third (the file lists points by global id); the summary line; and
# the CSV is the same file on every rank count.
# usage: fragments.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
cat > bar.yaml <<'DECK'
materials:
  m: {model: lps, density: 2000, bulk_modulus: 1.0e9, shear_modulus: 0.6e9}
  e: {model: elastic, density: 2000, youngs_modulus: 1.0e9, poissons_ratio: 0.25}
bodies:
  - name: bar
    material: m
    horizon: 0.0021
    initial_velocity: ["x < 0.003 ? -1 : (x > 0.007 ? 1 : 0)", "0", "0"]
    geometry: {shape: box, lo: [0.0005, 0.0005, 0.0005], hi: [0.0115, 0.0035, 0.0035], spacing: 0.001,
               origin: [0.0005, 0.0005, 0.0005]}
    precracks:
      - {shape: rectangle, corner: [0.003, -0.001, -0.001], edge_a: [0, 0.006, 0], edge_b: [0, 0, 0.006]}
      - {shape: rectangle, corner: [0.007, -0.001, -0.001], edge_a: [0, 0.006, 0], edge_b: [0, 0, 0.006]}
  - name: cube
    type: finite_element
    material: e
    mesh:
      pamgen: |
        mesh
          rectilinear
            nx = 2
            ny = 2
            nz = 2
            bx = 1
            by = 1
            bz = 1
            gmin = 0.02 0 0
            gmax = 0.022 0.002 0.002
          end
        end
time: {steps: 5}
output: {interval: 0, fragments: true}
DECK
for np in 1 2 3; do
  mkdir -p r$np
  if ! run $np "$exe" --output-dir r$np bar.yaml > r$np/log 2>&1; then
    echo "FAIL: $np ranks: perifem failed"; cat r$np/log; fail=1; continue
  fi
  if ! grep -q "fragments of bar: 3 (largest 0.16, 0.128, 0.096 g)" r$np/log; then
    echo "FAIL: $np ranks: summary line"; cat r$np/log; fail=1
  fi
  $PY - r$np <<'PY' || fail=1
import csv, sys
import netCDF4
import numpy as np
d = sys.argv[1]
rows = [r for r in csv.DictReader(open(d + "/bar.fragments.csv"))]
ok = True
def check(cond, what):
    global ok
    if not cond:
        print("FAIL: %s: %s" % (d, what)); ok = False
times = sorted(set(float(r["time"]) for r in rows))
check(len(times) == 2, "two Exodus steps in the CSV (got %d)" % len(times))
last = sorted((r for r in rows if float(r["time"]) == times[-1]), key=lambda r: float(r["x"]))
check([r["body"] for r in last] == ["bar"] * 3, "three fragments of the bar only: %s" % [r["body"] for r in last])
want = [(48, 9.6e-5, -1.0, 1.5e-3), (64, 1.28e-4, 0.0, 5.0e-3), (80, 1.6e-4, 1.0, 9.5e-3)]
for r, (n, m, vx, x0) in zip(last, want):
    check(int(r["points"]) == n, "points %s, want %d" % (r["points"], n))
    check(abs(float(r["mass"]) - m) <= 1e-12 * m, "mass %s, want %g" % (r["mass"], m))
    check(abs(float(r["vx"]) - vx) <= 1e-12, "vx %s, want %g" % (r["vx"], vx))
    # centre of mass: the lattice columns' mean x, moved by vx t
    check(abs(float(r["x"]) - (x0 + vx * times[-1])) <= 1e-12, "x %s, want %g" % (r["x"], x0 + vx * times[-1]))
e = netCDF4.Dataset(d + "/bar.e")
names = [str(netCDF4.chartostring(n)) for n in e.variables["name_nod_var"][:]]
frag = e.variables["vals_nod_var%d" % (names.index("fragment") + 1)][-1]
X = e.variables["coordx"][:]
bar = np.arange(192)
third = np.where(X[bar] < 3e-3, 0, np.where(X[bar] > 7e-3, 2, 1))
for k in range(3):
    ids = bar[third == k]
    check(np.all(frag[ids] == ids.min()), "field 'fragment' of third %d is its smallest id %d" % (k, ids.min()))
check(np.all(frag[192:] == -1), "the FE cube is not labelled")
sys.exit(0 if ok else 1)
PY
done
for np in 2 3; do
  cmp -s r1/bar.fragments.csv r$np/bar.fragments.csv || { echo "FAIL: CSV on $np ranks differs from 1 rank"; fail=1; }
done
# scripts/fragment_sizes.py on the same list: the thirds of 48 and 64 points in the class 33-64
# (mass share (9.6e-5 + 1.28e-4) / 3.84e-4 = 0.5833), the third of 80 in 65-128 (0.4167)
sizes=$($PY "$OLDPWD/../scripts/fragment_sizes.py" r1/bar.fragments.csv --body bar --png r1/sizes.png 2>&1)
echo "$sizes" | grep -Eq '^ +33-64 +2 +0\.5833$' && echo "$sizes" | grep -Eq '^ +65-128 +1 +0\.4167$' &&
  echo "$sizes" | grep -q 'largest ten: \[80, 64, 48\]' && [ -s r1/sizes.png ] ||
  { echo "FAIL: fragment_sizes.py: $sizes"; fail=1; }
[ $fail = 0 ] && echo "fragments: 3 fragments, masses and velocities exact, same on 1, 2 and 3 ranks"
exit $fail
