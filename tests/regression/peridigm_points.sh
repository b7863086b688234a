#!/usr/bin/env bash
# Peridigm's text discretization (x y z block_id volume, one point a line) read as a body's
# points, in the file's own length unit (geometry.scale). The file is written here by python:
# two blocks of a 10 x 4 x 4 mm lattice of 1 mm cells, block 1 for x < 5 mm and block 2 beyond,
# with volumes that differ from point to point (0.5 to 1.5 mm^3), in millimetres, with comments.
# Checked against what the file itself says, not against perifem:
#  - --check counts the points of the block taken (block: 2) and of the whole file;
#  - the history's kinetic energy at t = 0 is 1/2 rho v^2 times the sum of the volumes the
#    script wrote (mm^3 -> m^3), to 1e-12: every volume and the scale are read;
#  - the same points written in perifem's own columns (x y z volume block, metres) run to the
#    same state digest, on 1 and 2 ranks;
#  - a line with four values, a non-integer block, a negative volume and a bad columns: key are
#    refused naming the file and line, or the key.
# usage: peridigm_points.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
"$PY" - <<'EOF'
import itertools
pts = []
for k, (i, j, l) in enumerate(itertools.product(range(10), range(4), range(4))):
    x, y, z = i + 0.5, j + 0.5, l + 0.5              # mm
    vol = 0.5 + (k * 37 % 101) / 100.0               # mm^3, 0.5 to 1.5
    pts.append((x, y, z, 1 if x < 5 else 2, vol))
with open("disc.txt", "w") as f:
    f.write("# x y z block_id volume (mm, mm^3)\n")
    for p in pts:
        f.write("%.17g %.17g %.17g %d %.17g\n" % p)
with open("disc_si.txt", "w") as f:                  # perifem's columns, metres
    for x, y, z, b, v in pts:
        f.write("%.17g %.17g %.17g %.17g %d\n" % (x * 1e-3, y * 1e-3, z * 1e-3, v * 1e-9, b))
with open("expect.txt", "w") as f:
    f.write("%d %d %.17g %.17g\n" % (len(pts), sum(p[3] == 2 for p in pts),
                                     sum(p[4] for p in pts) * 1e-9, sum(p[4] for p in pts if p[3] == 2) * 1e-9))
EOF
read n_all n_b2 v_all v_b2 < expect.txt
deck() { # FILE COLUMNS SCALE [BLOCK]
  cat <<DECK
materials: {m: {model: pmb, density: 1000, bulk_modulus: 1.0e9}}
bodies:
  - name: b
    material: m
    horizon: 3.01e-3
    geometry: {shape: points_file, file: $1, columns: $2, scale: $3${4:+, block: $4}}
    initial_velocity: ["10", "0", "0"]
time: {steps: 3}
output: {interval: 1, history_interval: 1}
DECK
}
deck disc.txt peridigm 1.0e-3 > pd.yaml
deck disc.txt peridigm 1.0e-3 2 > pd_b2.yaml
deck disc_si.txt perifem 1 > si.yaml
for d in pd pd_b2; do
  want=$n_all; [ $d = pd_b2 ] && want=$n_b2
  got=$("$exe" --check $d.yaml 2>&1 | sed -n 's/.*deck is valid (\([0-9]*\) points.*/\1/p')
  [ "$got" = "$want" ] && echo "ok   $d: $got points" || { echo "FAIL $d: '$got' points, the file has $want"; fail=1; }
done
for d in pd pd_b2; do
  vol=$v_all; [ $d = pd_b2 ] && vol=$v_b2
  "$exe" --quiet $d.yaml --output-dir o_$d > /dev/null 2>&1 || { echo "FAIL $d: the run failed"; fail=1; continue; }
  "$PY" - "o_$d/$d.h5" "$vol" <<'EOF' || fail=1
import sys, h5py
ke = h5py.File(sys.argv[1], "r")["kinetic_energy"][0]
want = 0.5 * 1000 * float(sys.argv[2]) * 10.0 ** 2
ok = abs(ke - want) <= 1e-12 * want
print("%s kinetic energy at t = 0: %.17g J, 1/2 rho V v^2 = %.17g J" % ("ok  " if ok else "FAIL", ke, want))
sys.exit(0 if ok else 1)
EOF
done
ref=$(digest_of "$(run 1 "$exe" --quiet si.yaml --output-dir o_si 2>&1)")
for np in 1 2; do
  got=$(digest_of "$(run $np "$exe" --quiet pd.yaml --output-dir o_pd$np 2>&1)")
  [ -n "$ref" ] && [ "$got" = "$ref" ] && echo "ok   peridigm columns in mm on $np rank(s): the metre file's digest $ref" ||
    { echo "FAIL peridigm columns on $np rank(s): digest '$got', perifem's columns give '$ref'"; fail=1; }
done
refuse() { # WHAT DECK EXPECTED
  local err st
  err=$("$exe" --quiet "$2" 2>&1 >/dev/null); st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$3" <<<"$err"; then echo "FAIL $1: exit $st: $err"; fail=1
  else echo "ok   $1: $err"; fi
}
printf '0 0 0 1\n' > four.txt; deck four.txt peridigm 1 > four.yaml
refuse "four values" four.yaml "four.txt:1: expected 'x y z block_id volume'"
printf '0 0 0 1.5 1\n' > frac.txt; deck frac.txt peridigm 1 > frac.yaml
refuse "non-integer block" frac.yaml "frac.txt:1: expected 'x y z block_id volume' with a positive volume and an integer block"
printf '# c\n0 0 0 1 -1\n' > neg.txt; deck neg.txt peridigm 1 > neg.yaml
refuse "negative volume" neg.yaml "neg.txt:2: expected"
deck disc.txt lammps 1 > cols.yaml
refuse "unknown columns" cols.yaml "key 'columns': perifem or peridigm (got 'lammps')"
exit $fail
