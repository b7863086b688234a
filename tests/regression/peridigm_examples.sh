#!/usr/bin/env bash
# Three of Peridigm's own examples, from their own files (tests/data/peridigm, Peridigm
# 82c6ad8f, BSD licence in LICENSE.md there), through scripts/peridigm_to_perifem.py:
#  - wave_in_bar (text discretization, two node-set text files, an initial velocity on one and a
#    fixed end on the other): the whole run, 5 us, on 1 and 2 ranks (same digest); the kinetic
#    energy at t = 0 is 1/2 rho v^2 times the volumes the files list for node set 1 (1e-12); the
#    fixed end's reaction between 1 and 4.8 us (before the wave reflected at the free end comes
#    back) is the 1-D impact stress rho c v times the bar's section, c = sqrt(E / rho) with
#    E = 9KG / (3K + G), within 3 %;
#  - fragmenting_cylinder (points written by Peridigm's own generator script, a node set of
#    every point, velocity expressions with atan2 and ^): 3 steps; the kinetic energy at t = 0
#    against the expressions evaluated here in numpy at the file's points (1e-12);
#  - disk_impact (Exodus: a HEX8 disk and a TET4 sphere, short-range contact, an initial
#    velocity on node set nodelist_1): 30 steps; at t = 0 the sphere moves, the disk does not,
#    and the kinetic energy is 1/2 rho v^2 times the sphere's tetrahedra's volumes computed here
#    from the Exodus file (1e-12), which are a 5 mm sphere's to 3 % (the faceted surface lies
#    inside the sphere: 2.3 % less).
# The same wave_in_bar deck as an XML parameter list translates to the same perifem deck.
# And the translator's refusals: an unknown material model, two solvers, an undefined node set
# (exit 2, naming the key, nothing written), the input named as the output; perifem's
# node_set_files: a point number beyond the point file, and not a number (exit 2, file:line).
# usage: peridigm_examples.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0 tests=$(pwd)
source common/mpi_env.sh
translate="$PY $tests/../scripts/peridigm_to_perifem.py"
rm -rf "$scratch" && mkdir -p "$scratch" && cp -r data/peridigm/* "$scratch"/ && cd "$scratch" || exit 1
(cd fragmenting_cylinder && "$PY" fragmenting_cylinder_generate_mesh.py > /dev/null) ||
  { echo "FAIL: Peridigm's cylinder generator"; exit 1; }
for e in wave_in_bar fragmenting_cylinder disk_impact; do
  $translate $e/$e.yaml $e/perifem.yaml 2> $e/left_out.txt || { cat $e/left_out.txt; echo "FAIL: $e not translated"; fail=1; }
  grep -q "left out: .*Output Variables" $e/left_out.txt || { echo "FAIL: $e: the output variables left out are not named"; fail=1; }
done

# the XML parameter list of the same deck (written here from the YAML, as Peridigm's
# ParameterList: doubles, ints and strings typed) translates to the same perifem deck
"$PY" - wave_in_bar/wave_in_bar.yaml wave_in_bar/wave_in_bar.xml <<'EOF'
import sys, yaml
from xml.sax.saxutils import quoteattr
def plist(name, d, pad):
    out = [f'{pad}<ParameterList name={quoteattr(name)}>']
    for k, v in d.items():
        if isinstance(v, dict):
            out += plist(k, v, pad + "  ")
            continue
        t = "bool" if isinstance(v, bool) else "int" if isinstance(v, int) else "double" if isinstance(v, float) else "string"
        out.append(f'{pad}  <Parameter name={quoteattr(k)} type="{t}" value={quoteattr(str(v).lower() if t == "bool" else str(v))}/>')
    return out + [f"{pad}</ParameterList>"]
d = yaml.safe_load(open(sys.argv[1]))["Peridigm"]
open(sys.argv[2], "w").write("\n".join(plist("Peridigm", d, "")) + "\n")
EOF
$translate wave_in_bar/wave_in_bar.xml wave_in_bar/from_xml.yaml 2> /dev/null &&
  diff <(sed 1d wave_in_bar/perifem.yaml) <(sed 1d wave_in_bar/from_xml.yaml) ||
  { echo "FAIL: the XML parameter list translates to another deck"; fail=1; }

# wave_in_bar, whole, on 1 and 2 ranks
(cd wave_in_bar && run 1 "$exe" --quiet --set output.interval=0 --set output.history_interval=1 perifem.yaml > run1.log 2>&1 &&
  run 2 "$exe" --quiet --set output.interval=0 --set output.file=two.e --set output.history_file=two.h5 perifem.yaml > run2.log 2>&1) ||
  { cat wave_in_bar/run*.log; echo "FAIL: wave_in_bar did not run"; fail=1; }
d1=$(digest_of "$(cat wave_in_bar/run1.log)") d2=$(digest_of "$(cat wave_in_bar/run2.log)")
[ -n "$d1" ] && [ "$d1" = "$d2" ] || { echo "FAIL: wave_in_bar digests '$d1' (1 rank) '$d2' (2 ranks)"; fail=1; }
"$PY" - wave_in_bar <<'EOF' || fail=1
import sys, h5py, numpy as np
d = sys.argv[1]
pts = np.loadtxt(f"{d}/wave_in_bar.txt")
s1 = np.loadtxt(f"{d}/node_set_1.txt", dtype=int) - 1
h = h5py.File(f"{d}/perifem.h5", "r")
rho, v, K, G = 2200.0, 100.0, 14.90e9, 8.94e9
ke, want = h["kinetic_energy"][0], 0.5 * rho * v * v * pts[s1, 4].sum()
ok = abs(ke - want) <= 1e-12 * want
print("%s wave_in_bar kinetic energy at t = 0: %.15g J, 1/2 rho v^2 V(node set 1) = %.15g J" % ("ok  " if ok else "FAIL", ke, want))
E = 9 * K * G / (3 * K + G)
xs = np.unique(pts[:, 0])
area = pts[:, 4].sum() / (xs[-1] - xs[0] + np.diff(xs).min())  # volume / length
t, r = h["time"][:], h["node_set_2_displacement_reaction_x"][:]
sel = (t >= 1e-6) & (t <= 4.8e-6)
mean, ref = -r[sel].mean(), rho * np.sqrt(E / rho) * v * area
ok2 = abs(mean / ref - 1) <= 0.03
print("%s wave_in_bar fixed-end reaction, mean over 1-4.8 us: %.1f N, rho c v A = %.1f N (%+.2f %%)"
      % ("ok  " if ok2 else "FAIL", mean, ref, 100 * (mean / ref - 1)))
sys.exit(0 if ok and ok2 else 1)
EOF

# fragmenting_cylinder: the initial velocity expressions at the generator's points
(cd fragmenting_cylinder && "$exe" --quiet --set time.final_time=5e-7 --set output.interval=0 perifem.yaml > run.log 2>&1) ||
  { cat fragmenting_cylinder/run.log; echo "FAIL: fragmenting_cylinder did not run"; fail=1; }
"$PY" - fragmenting_cylinder <<'EOF' || fail=1
import sys, h5py, numpy as np
d = sys.argv[1]
x, y, z, _, vol = np.loadtxt(f"{d}/fragmenting_cylinder.txt").T
a = 200 - 50 * ((z / 0.05) - 1) ** 2
v2 = (a * np.cos(np.arctan2(y, x))) ** 2 + (a * np.sin(np.arctan2(y, x))) ** 2 + (100 * ((z / 0.05) - 1)) ** 2
ke, want = h5py.File(f"{d}/perifem.h5", "r")["kinetic_energy"][0], 0.5 * 7800.0 * (vol * v2).sum()
ok = abs(ke - want) <= 1e-12 * want
print("%s fragmenting_cylinder kinetic energy at t = 0: %.15g J, from the expressions at the points %.15g J"
      % ("ok  " if ok else "FAIL", ke, want))
sys.exit(0 if ok else 1)
EOF

# disk_impact: the sphere's initial velocity on nodelist_1, the disk at rest
(cd disk_impact && "$exe" --quiet --set time.final_time=3.5e-6 --set output.interval=0 perifem.yaml > run.log 2>&1) ||
  { cat disk_impact/run.log; echo "FAIL: disk_impact did not run"; fail=1; }
"$PY" - disk_impact <<'EOF' || fail=1
import sys, h5py, netCDF4, numpy as np
d = sys.argv[1]
g = netCDF4.Dataset(f"{d}/disk_impact.g")
X = np.stack([g.variables[k][:] for k in ("coordx", "coordy", "coordz")], axis=1)
tet = X[g.variables["connect2"][:] - 1]
vol = np.abs(np.einsum("ij,ij->i", tet[:, 1] - tet[:, 0], np.cross(tet[:, 2] - tet[:, 0], tet[:, 3] - tet[:, 0]))) / 6
h = h5py.File(f"{d}/perifem.h5", "r")
ke, want = h["ball_block_kinetic_energy"][0], 0.5 * 7700.0 * 100.0 ** 2 * vol.sum()
sphere = 4 / 3 * np.pi * 0.005 ** 3
ok = abs(ke - want) <= 1e-12 * want and h["disk_block_kinetic_energy"][0] == 0 and abs(vol.sum() / sphere - 1) < 0.03
print("%s disk_impact at t = 0: sphere %.15g J, 1/2 rho v^2 V(tetrahedra) %.15g J (V/V(5 mm sphere) = %.4f), disk %g J"
      % ("ok  " if ok else "FAIL", ke, want, vol.sum() / sphere, h["disk_block_kinetic_energy"][0]))
sys.exit(0 if ok else 1)
EOF

# the translator's refusals: exit 2, the key named, nothing written
refused() { # DECK_TEXT EXPECTED
  printf '%s\n' "$1" > bad.yaml
  rm -f bad_out.yaml
  out=$($translate bad.yaml bad_out.yaml 2>&1); st=$?
  [ $st = 2 ] && echo "$out" | grep -q "$2" && [ ! -e bad_out.yaml ] ||
    { echo "FAIL: translator: exit $st, expected 2 and '$2', nothing written: $out"; fail=1; }
}
base=$(sed -n '/^Peridigm:/,$p' wave_in_bar/wave_in_bar.yaml | sed 's#"wave_in_bar.txt"#"wave_in_bar/wave_in_bar.txt"#; s#"node_set_\([12]\).txt"#"wave_in_bar/node_set_\1.txt"#')
refused "$(echo "$base" | sed 's/Material Model: "Elastic"/Material Model: "Viscoelastic"/')" "Materials.My Elastic Material.Material Model: 'Viscoelastic'"
refused "$(echo "$base"; printf '  Solver2:\n      Final Time: 1.0\n      Verlet:\n          Safety Factor: 0.8\n')" "Solver and Solver2: perifem runs one solver"
refused "$(echo "$base" | sed 's/Node Set: "Node Set Two"/Node Set: "Node Set Three"/')" "Node Set: 'Node Set Three' is not defined"
out=$($translate wave_in_bar/wave_in_bar.yaml wave_in_bar/wave_in_bar.yaml 2>&1) &&
  { echo "FAIL: the input deck named as the output was accepted"; fail=1; }
grep -q "^Peridigm:" wave_in_bar/wave_in_bar.yaml || { echo "FAIL: the input deck was overwritten"; fail=1; }

# perifem's node_set_files: bad point numbers name the file and the line
cd wave_in_bar
printf '1\n2\n10001\n' > beyond.txt
printf '1\n2 x3\n' > word.txt
for f in beyond word; do
  sed "s#node_set_files: \[.*\]#node_set_files: [node_set_1.txt, node_set_2.txt, $f.txt]#" perifem.yaml > $f.yaml
  out=$("$exe" --check $f.yaml 2>&1); st=$?
  want="$f.txt:[23]: "
  [ $st = 2 ] && echo "$out" | grep -q "key 'node_set_files'.*$want" ||
    { echo "FAIL: node_set_files $f: exit $st, expected 2 naming key and $want: $out"; fail=1; }
done
[ $fail = 0 ] && echo "ok   translator refusals and node-set file errors"
exit $fail
