#!/usr/bin/env bash
# The output fields that never change in a run (horizon, region, blending_weight) are written
# once, as Exodus nodal attributes of the same names, not as nodal variables in every frame:
#  - the shipped bar cut to 20 steps, a frame every 5 (5 frames): nodal variables are the 9
#    built-ins and damage; the attributes are horizon (the deck's 0.30001 mm at every point) and
#    region; the file is no larger than 5 frames of those 10 variables plus the 2 attributes
#    once (the header aside), and the --check estimate says "and 2 written once";
#  - output.fields: [displacement, horizon]: displacement_x/y/z as variables, horizon alone as
#    an attribute;
#  - tests/data/coupled_bar.yaml (FE with a PD part, a variable horizon and a blending weight) for
#    20 steps: horizon and blending_weight are attributes, blending_weight 1 at x < 14 mm and 0
#    beyond 20 mm, the horizon 3.01 mm at x < 8 mm;
#  - spread on 2 ranks: each piece holds the attributes of its own points, the joined file's by
#    global id.
# usage: exodus_constant_fields.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
src=$(cd .. && pwd)
rm -rf "$scratch" && mkdir -p "$scratch"
bad() { echo "FAIL: $*"; fail=1; }
sed -E 's/^(\s*)final_time:.*/\1steps: 20/; s/^  interval: 50$/  interval: 5/' "$src/inputs/wave_in_bar.yaml" > "$scratch/bar.yaml"
sed -E 's#(file: )(\.\./)#\1'"$src"'/tests/data/\2#; s/steps: 60/steps: 20/' "$src/tests/data/coupled_bar.yaml" > "$scratch/cb.yaml"
cd "$scratch" || exit 1
"$exe" --quiet --output-dir all bar.yaml > all.log 2>&1 || bad "the bar run exited $?"
"$exe" --quiet --output-dir two --set "output.fields=[displacement, horizon]" bar.yaml > two.log 2>&1 || bad "fields: exit $?"
"$exe" --quiet --output-dir cb cb.yaml > cb.log 2>&1 || bad "the coupled bar exited $?: $(tail -3 cb.log)"
run 2 "$exe" --quiet --output-dir spread --set output.layout=spread bar.yaml > spread.log 2>&1 || bad "spread: exit $?"
"$exe" --check bar.yaml > check.log 2>&1
grep -q "5 frames x 10 nodal variables x 10000 points x 8 bytes, and 2 written once" check.log ||
  bad "--check: $(grep 'output:' check.log)"
"$PY" - <<'EOF' || fail=1
import os, sys
import numpy as np, netCDF4
ok = True
def fail(msg):
    global ok
    print("FAIL: " + msg); ok = False
def names(d, var):
    return [str(netCDF4.chartostring(n)) for n in d.variables[var][:]] if var in d.variables else []
def attr(d, name):
    return np.asarray(d.variables["nattrb"][:, names(d, "nattrib_name").index(name)])
builtins = ["%s_%s" % (v, c) for v in ("displacement", "velocity", "force") for c in "xyz"]
d = netCDF4.Dataset("all/bar.e")
if names(d, "name_nod_var") != builtins + ["damage"]: fail("bar: nodal variables %s" % names(d, "name_nod_var"))
if names(d, "nattrib_name") != ["horizon", "region"]: fail("bar: nodal attributes %s" % names(d, "nattrib_name"))
elif not (np.all(attr(d, "horizon") == 0.00030001) and np.all(attr(d, "region") == 0)):
    fail("bar: horizon %s, region %s" % (np.unique(attr(d, "horizon")), np.unique(attr(d, "region"))))
frames, n = len(d.dimensions["time_step"]), d.dimensions["num_nodes"].size
budget = 8 * n * (3 + 1 + frames * 10 + 2) + 200000  # coordinates, the id map, frames, attributes; the header
size = os.path.getsize("all/bar.e")
print("bar: %d frames, %d bytes (at most %d; with the constant fields in every frame: %d more)"
      % (frames, size, budget, 8 * n * 2 * (frames - 1)))
if frames != 5 or size > budget: fail("bar: %d frames, %d bytes > %d" % (frames, size, budget))
d = netCDF4.Dataset("two/bar.e")
if names(d, "name_nod_var") != builtins[:3] or names(d, "nattrib_name") != ["horizon"]:
    fail("fields: variables %s, attributes %s" % (names(d, "name_nod_var"), names(d, "nattrib_name")))
d = netCDF4.Dataset("cb/cb.e")
x = np.asarray(d.variables["coordx"][:])
if "blending_weight" in names(d, "name_nod_var") or "horizon" in names(d, "name_nod_var"):
    fail("coupled bar: a constant field among the variables %s" % names(d, "name_nod_var"))
elif not {"horizon", "blending_weight"} <= set(names(d, "nattrib_name")):
    fail("coupled bar: attributes %s" % names(d, "nattrib_name"))
else:
    beta, h = attr(d, "blending_weight"), attr(d, "horizon")
    if not (np.all(beta[x < 0.014 - 1e-9] == 1) and np.all(beta[x > 0.020 + 1e-9] == 0)):
        fail("coupled bar: blending weight not 1 before 14 mm and 0 beyond 20 mm")
    if not np.allclose(h[(x < 0.008 - 1e-9) & (beta > 0)], 3.01e-3, rtol=1e-12):
        fail("coupled bar: horizon at x < 8 mm %s" % np.unique(h[(x < 0.008 - 1e-9) & (beta > 0)]))
j = netCDF4.Dataset("all/bar.e")
ref = dict(zip(j.variables["node_num_map"][:], attr(j, "region") + 10 * attr(j, "horizon")))
seen = {}
for r in range(2):
    p = netCDF4.Dataset("spread/bar.e.2.%d" % r)
    seen.update(zip(p.variables["node_num_map"][:], attr(p, "region") + 10 * attr(p, "horizon")))
if seen != ref: fail("spread: the pieces' attributes are not the joined file's (%d and %d points)" % (len(seen), len(ref)))
sys.exit(0 if ok else 1)
EOF
exit $fail
