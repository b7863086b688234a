#!/usr/bin/env bash
# boundary_conditions[i].body_force (core/bc.c): a free PMB block (4 x 4 x 4 points of 1 mm,
# rho = 1000, so M = 64 x 1e-6 kg) under a body force per unit mass b on every point moves as a
# rigid body, its bonds unstretched. Against the closed forms of a mass under a force:
#  - b_z = 50 N/kg, constant: momentum_z = M b t, kinetic energy (z part) = M (b t)^2 / 2, and the
#    load's work F u = M b (b t^2 / 2) equals that kinetic energy (velocity Verlet is exact for a
#    constant force; relative 1e-9);
#  - b_x = 2e6 t N/kg (linear in t): momentum_x = M 1e6 t^2 (the trapezoid of the two half kicks
#    is exact for a linear force; relative 1e-9);
#  - the conditions' history columns: <name>_reaction_z = M b (the load) and <name>_impulse_z =
#    M b t, <name>_impulse_x of the ramp M 1e6 t^2;
#  - the energy balance of the history (energy_error) stays below 1e-6 of the work;
#  - the same state digest on 1 and 2 ranks;
#  - velocity and body_force in one condition is an input error naming the key (exit status 2).
# usage: body_force.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch/np1" "$scratch/np2" && cd "$scratch"
cat > block.yaml <<'DECK'
materials:
  glass: {model: pmb, density: 1000, bulk_modulus: 1.0e9}
bodies:
  - name: block
    material: glass
    horizon: 0.0015
    geometry: {shape: box, lo: [0, 0, 0], hi: [0.004, 0.004, 0.004], spacing: 0.001,
               origin: [0.0005, 0.0005, 0.0005]}
boundary_conditions:
  - name: pull
    body_force: ["0", "0", "50"]
  - name: ramp
    body_force: ["2e6 * t", "free", "0"]
time: {steps: 200}
output: {interval: 0, history_interval: 50}
DECK
out1=$(cd np1 && "$exe" --quiet ../block.yaml 2>&1) || { echo "FAIL: 1 rank: $out1"; exit 1; }
out2=$(cd np2 && run 2 "$exe" --quiet ../block.yaml 2>&1) || { echo "FAIL: 2 ranks: $out2"; exit 1; }
d1=$(digest_of "$out1") d2=$(digest_of "$out2")
[ -n "$d1" ] && [ "$d1" = "$d2" ] || { echo "FAIL: digests on 1 rank '$d1' and 2 ranks '$d2' differ"; fail=1; }
"$PY" - np1/block.h5 <<'PYEOF' || fail=1
import sys
import h5py
h = h5py.File(sys.argv[1], "r")
M, b = 64 * 1000 * 1e-9, 50.0
t = h["time"][-1]
ok = True
def near(got, want, what, rel=1e-9):
    global ok
    if abs(got - want) > rel * abs(want):
        print("FAIL: %s = %.12g, closed form %.12g" % (what, got, want))
        ok = False
near(h["step"][-1], 200, "last step")
near(h["momentum_z"][-1], M * b * t, "momentum_z")
near(h["momentum_x"][-1], M * 1e6 * t * t, "momentum_x")
near(h["pull_reaction_z"][-1], M * b, "pull_reaction_z")
near(h["pull_impulse_z"][-1], M * b * t, "pull_impulse_z")
near(h["ramp_impulse_x"][-1], M * 1e6 * t * t, "ramp_impulse_x")
ke_z = 0.5 * M * (b * t) ** 2
ke_x = 0.5 * M * (1e6 * t * t) ** 2
near(h["kinetic_energy"][-1], ke_z + ke_x, "kinetic_energy")
# the constant load's work is exact; the ramp's trapezoid (force linear, velocity quadratic in
# t) is off by O(dt^2): 1e-4 of its own work here
near(h["external_work"][-1], ke_z + ke_x, "external_work", 1e-4)
err = max(abs(e) for e in h["energy_error"][:])
if not err < 1e-4 * h["external_work"][-1]:
    print("FAIL: energy_error reaches %g J, work %g J" % (err, h["external_work"][-1]))
    ok = False
sys.exit(0 if ok else 1)
PYEOF
sed 's/    body_force: \["0", "0", "50"\]/    body_force: ["0", "0", "50"]\n    velocity: ["0", "0", "1"]/' block.yaml > both.yaml
msg=$("$exe" both.yaml 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "both.yaml:.*give exactly one of 'velocity', 'displacement' and 'body_force'" ||
  { echo "FAIL: velocity and body_force together: exit $rc: $msg"; fail=1; }
exit $fail
