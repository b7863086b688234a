#!/usr/bin/env bash
# output.probes: a PMB tube (inner radius 6 mm, outer 9 mm, 12 mm long, 1 mm lattice) starts with
# the radial velocity V = 50 m/s and the axial velocity W = -10 m/s at every point, and expands.
# Two probes average over rings of the outer surface (8 mm < r <= 9 mm, +-1 mm around z = 4 and
# 8 mm). Checks:
#  - the first history row (t = 0) by hand: radial_velocity = 50, velocity_z = -10,
#    radial_displacement = displacement_z = 0 (every point has those values);
#  - every Exodus step against the same averages recomputed here from the file's own fields
#    (reference coordinates, displacement_*, velocity_*, the points' masses rho h^3) over the
#    ring's points selected here (relative 1e-9: the history's sums are in another order);
#  - the same history on 1 and 2 ranks (relative 1e-12); scripts/plot_history.py draws them;
#  - bad input: a radial quantity on a box region, an unknown quantity, a region holding no
#    point are errors naming the key (exit status 2).
# usage: probes.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch/np1" "$scratch/np2" && cd "$scratch"
cat > tube.yaml <<'DECK'
materials:
  steel: {model: pmb, density: 7800, bulk_modulus: 160.0e9}
bodies:
  - name: tube
    material: steel
    horizon: 0.0030001
    geometry: {shape: cylinder, center: [0, 0, 0], axis: z, radius: 0.0091, inner_radius: 0.0059,
               height: 0.012, spacing: 0.001, origin: [0.0005, 0.0005, 0.0005]}
    initial_velocity: ["50 * x / sqrt(x^2 + y^2)", "50 * y / sqrt(x^2 + y^2)", "-10"]
time: {steps: 60}
output:
  interval: 20
  history_interval: 20
  probes:
    - name: z4
      body: tube
      region: {shape: cylinder, center: [0, 0, 0.003], axis: z, radius: 0.0091, inner_radius: 0.008, height: 0.002}
      quantities: [radial_velocity, radial_displacement, velocity_z, displacement_z]
    - name: z8
      region: {shape: cylinder, center: [0, 0, 0.007], axis: z, radius: 0.0091, inner_radius: 0.008, height: 0.002}
      quantities: [radial_velocity, radial_displacement]
DECK
bad() { echo "FAIL: $*"; fail=1; }
run 1 "$exe" --output-dir np1 tube.yaml > np1.log 2>&1 || bad "1 rank: exit $? ($(tail -2 np1.log))"
run 2 "$exe" --output-dir np2 tube.yaml > np2.log 2>&1 || bad "2 ranks: exit $?"
"$PY" - <<'PYEOF' || fail=1
import sys
import h5py, numpy as np
from netCDF4 import Dataset
h = {k: v[:] for k, v in h5py.File("np1/tube.h5", "r").items()}
h2 = {k: v[:] for k, v in h5py.File("np2/tube.h5", "r").items()}
ok = True
def check(cond, msg):
    global ok
    if not cond:
        print("FAIL:", msg); ok = False
# t = 0 by hand
for col, want in [("probe_z4_radial_velocity", 50.0), ("probe_z4_velocity_z", -10.0),
                  ("probe_z4_radial_displacement", 0.0), ("probe_z4_displacement_z", 0.0),
                  ("probe_z8_radial_velocity", 50.0), ("probe_z8_radial_displacement", 0.0)]:
    check(abs(h[col][0] - want) <= 1e-12 * max(1, abs(want)), "%s at t = 0: %r, expected %r" % (col, h[col][0], want))
for col in h:
    if col.startswith("probe_"):
        check(np.allclose(h[col], h2[col], rtol=1e-12, atol=1e-15), "%s differs on 2 ranks" % col)
# every Exodus step against the fields
e = Dataset("np1/tube.e")
names = [b"".join(n).decode().strip("\x00") for n in e.variables["name_nod_var"][:]]
X = np.stack([e.variables["coordx"][:], e.variables["coordy"][:], e.variables["coordz"][:]], 1)
def field(name, step):
    return np.asarray(e.variables["vals_nod_var%d" % (names.index(name) + 1)][step])
rings = {"z4": 0.003, "z8": 0.007}
for step, t in enumerate(e.variables["time_whole"][:]):
    row = int(np.argmin(abs(h["time"] - t)))
    check(abs(h["time"][row] - t) < 1e-15, "no history row at t = %g" % t)
    u = np.stack([field("displacement_" + a, step) for a in "xyz"], 1)
    v = np.stack([field("velocity_" + a, step) for a in "xyz"], 1)
    y = X + u
    R0, R = np.hypot(X[:, 0], X[:, 1]), np.hypot(y[:, 0], y[:, 1])
    for name, z0 in rings.items():
        sel = (R0 >= 0.008) & (R0 <= 0.0091) & (X[:, 2] >= z0) & (X[:, 2] <= z0 + 0.002)
        check(sel.sum() > 50, "ring %s holds only %d points" % (name, sel.sum()))
        vr = (v[sel, 0] * y[sel, 0] + v[sel, 1] * y[sel, 1]) / R[sel]   # equal masses
        want = {"radial_velocity": vr.mean(), "radial_displacement": (R - R0)[sel].mean()}
        if name == "z4":
            want["velocity_z"], want["displacement_z"] = v[sel, 2].mean(), u[sel, 2].mean()
        for q, w in want.items():
            got = h["probe_%s_%s" % (name, q)][row]
            check(abs(got - w) <= 1e-9 * abs(w) + 1e-15, "%s %s at t = %.3g: %.12g, the fields give %.12g" % (name, q, t, got, w))
    if step == len(e.variables["time_whole"]) - 1:
        print("probes at t = %.3g s: z4 v_r %.4f m/s, u_r %.4e m; z8 v_r %.4f m/s (%d and %d points)" % (
            t, h["probe_z4_radial_velocity"][row], h["probe_z4_radial_displacement"][row],
            h["probe_z8_radial_velocity"][row], sel.sum(), sel.sum()))
sys.exit(0 if ok else 1)
PYEOF
# the plot script draws the probe columns
"$PY" "$OLDPWD/../scripts/plot_history.py" np1/tube.h5 --out png > /dev/null || bad "plot_history.py exited $?"
[ -s png/tube_probes.png ] || bad "no png/tube_probes.png"
# bad input
bad_case() { # label text sed-expression
  sed -E "$3" tube.yaml > bad.yaml
  rm -rf badout && mkdir badout
  "$exe" --output-dir badout bad.yaml > bad.log 2>&1
  local st=$?
  [ $st -eq 2 ] || bad "$1: exit status $st, expected 2"
  grep -qF "$2" bad.log || bad "$1: no '$2' in: $(cat bad.log)"
  [ -z "$(ls badout)" ] || bad "$1: files written: $(ls badout)"
}
bad_case "radial on a box" "the region must be a cylinder" 's/region: \{shape: cylinder, center: \[0, 0, 0.007\].*/region: {shape: box, lo: [-1, -1, 0], hi: [1, 1, 1]}/'
bad_case "unknown quantity" "unknown quantity 'pressure'" 's/quantities: \[radial_velocity, radial_displacement\]$/quantities: [pressure]/'
bad_case "empty region" "key 'region': the probe's region holds no point" 's/center: \[0, 0, 0.003\]/center: [0, 0, 0.5]/'
[ $fail -eq 0 ] && echo "probes: hand values at t = 0, Exodus fields at every output, 1 = 2 ranks, 3 bad decks"
exit $fail
