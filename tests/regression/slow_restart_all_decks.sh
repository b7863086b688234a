#!/usr/bin/env bash
# Restarts of every shipped explicit deck (inputs/*.yaml; the quasi-static ones restart at a load
# step's end in mpi_static_restart.sh), each cut short with one checkpoint in the middle:
# written on 1 rank and restarted on 1 and on 3, written on 2 and restarted on 2 and on 1.
# Each restart must end with the uninterrupted 1-rank run's state digest and write the same
# history rows from the checkpoint's step on (bitwise for 1 -> 1, to 1e-9 of each column's scale
# on other rank counts, whose sums round otherwise). The checkpoint comes after something has
# happened where the deck has anything to happen: the indenter, the sphere or the Lexan in contact
# (their force non-zero at the checkpoint), bonds broken (damage), the Taylor bar on its wall; the
# test says so or fails. Labelled slow (about 15 minutes on 2 cores: the disk and panel decks take
# most of it); tests/regression/mpi_restart_decks.sh is the default run's reduced version.
# usage: slow_restart_all_decks.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0 SRC=$PWD
source common/mpi_env.sh
source common/restart_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
runs=("1 1 3" "2 2 1") # (written on 1, restarted on 1 and 3; written on 2, restarted on 2 and 1)
# deck, steps, checkpoint step, the history column that must be non-zero at the checkpoint
cases="wave_in_bar 30 20 kinetic_energy
wave_pd_to_fe 30 20 kinetic_energy
wave_variable_horizon 30 20 kinetic_energy
taylor_impact 60 40 wall_force_z
disk_impact_rigid 60 40 sphere_force_z
disk_impact_elastic 60 40 sphere_disk_force_z
fragmenting_cylinder 80 50 damage_fraction
fragmenting_cylinder_exodus 80 50 damage_fraction
expanding_tube 60 40 lexan_tube_force_z
expanding_tube_two_bodies 60 40 projectile_plug_force_z
panel_plate 50 30 sphere_panel_force_z
panel_impact 50 30 sphere_panel_force_z
dcb 30 20 upper_reaction_y
glass_branching 60 40 top_traction_impulse_y
cluster_collision 30 20 kinetic_energy
bimaterial_wave 30 20 kinetic_energy"
explicit=$(grep -L -E "^ +type: quasi_static" "$SRC"/../inputs/*.yaml | wc -l)
[ "$(echo "$cases" | wc -l)" = "$explicit" ] ||
  { echo "inputs/ has $explicit explicit decks, this test covers $(echo "$cases" | wc -l)"; fail=1; }
# (PF_RESTART_DECKS="name ...": only those, for a run by hand)
while read -r name steps ck col; do
  [ -z "${PF_RESTART_DECKS:-}" ] || [[ " $PF_RESTART_DECKS " == *" $name "* ]] || continue
  restart_decks "$SRC/../inputs/$name.yaml" $name $steps $ck 5 || { fail=1; continue; }
  restart_case $name $ck $col "${runs[@]}" < /dev/null # (mpirun would read the list)
done <<< "$cases"
cat times.txt >&2
# every deck through every restart (a helper once let the first deck's loop overwrite the list)
full=$(grep -c ": 1->1 1->3 2->2 2->1: " times.txt)
[ -n "${PF_RESTART_DECKS:-}" ] || [ "$full" = "$(echo "$cases" | wc -l)" ] ||
  { echo "only $full of $(echo "$cases" | wc -l) decks went through 1->1 1->3 2->2 2->1"; fail=1; }
exit $fail
