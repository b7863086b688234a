#!/usr/bin/env bash
# The default run's share of tests/regression/slow_restart_all_decks.sh (every shipped deck, slow):
# the features of the shipped decks that tests/regression/mpi_restart.sh does not restart, in one
# small deck - a PMB tube (1728 points) thrown radially at 200 m/s and at 300 m/s onto a wall
# (walls, as the Taylor deck), its bonds breaking (critical stretch 0.003), its broken pieces in
# short-range self-contact (as the disk, tube and panel decks), output.fragments (fragmenting
# cylinder, expanding tube, panels) and output.probes (expanding tube). By the checkpoint at step
# 40 of 60 the wall has stopped the bottom layer, 94 % of the bonds are broken and the pieces
# press on each other (contact energy about 12 J). Written on 1 rank and restarted on 1 and on 3,
# written on 2 and restarted on 2 and on 1: each restart ends with the uninterrupted 1-rank run's
# state digest, writes its history rows from step 40 on (every column: energies and dissipations
# booked, wall force, contact energy, probes; bitwise for 1 -> 1, to 1e-9 of each column's scale
# otherwise) and the same fragments at the last step.
# usage: mpi_restart_decks.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0 SRC=$PWD
source common/mpi_env.sh
source common/restart_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
cat > tube_in.yaml <<'DECK'
materials:
  steel: {model: pmb, density: 7800, bulk_modulus: 160.0e9}
bodies:
  - name: tube
    material: steel
    horizon: 0.0030001
    geometry: {shape: cylinder, center: [0, 0, 0], axis: z, radius: 0.0091, inner_radius: 0.0059,
               height: 0.012, spacing: 0.001, origin: [0.0005, 0.0005, 0.0005]}
    damage: {law: critical_stretch, critical_stretch: 0.003}
    initial_velocity: ["200 * x / sqrt(x^2 + y^2)", "200 * y / sqrt(x^2 + y^2)", "-300"]
walls:
  - {name: floor, point: [0, 0, 0.0003], normal: [0, 0, 1]}
contact:
  pairs:
    - bodies: [tube, tube]
time:
  final_time: 1.0
output:
  interval: 20
  history_interval: 10
  fragments: true
  probes:
    - name: z4
      body: tube
      region: {shape: cylinder, center: [0, 0, 0.003], axis: z, radius: 0.0091, inner_radius: 0.008, height: 0.002}
      quantities: [radial_velocity, radial_displacement, velocity_z, displacement_z]
DECK
restart_decks tube_in.yaml tube 60 40 5 || fail=1
restart_case tube 40 contact_energy "1 1 3" "2 2 1"
cat times.txt >&2
exit $fail
