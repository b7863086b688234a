#!/usr/bin/env bash
# Every shipped deck, cut to a few steps, runs to the end: exit 0, a state digest, an Exodus
# file that ncdump reads with a SPHERE block for a peridynamic body and a HEX8 block for a
# finite-element body, a history file; and a second run gives the same digest (determinism),
# except for the decks whose reduced copies mpi_digests runs on 1 and 3 ranks (some on 2 as well)
# and compares already, and panel_plate, the main example's model on a flat plate (the main
# example, panel_impact, runs twice: the same set-up, contact and materials).
# usage: run_examples.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
run_once=" disk_impact_rigid fragmenting_cylinder wave_in_bar wave_variable_horizon wave_pd_to_fe taylor_impact panel_plate bimaterial_wave "
rm -rf "$scratch" && mkdir -p "$scratch"
for deck in ../inputs/*.yaml; do
  name=$(basename "$deck" .yaml)
  short="$scratch/$name.yaml"
  # keep the deck, replace the run length by 5 steps
  # and point the decks' relative mesh paths at the source tree's meshes/
  cut='s/^(\s*)final_time:.*/\1steps: 5/'
  # (a quasi-static deck keeps its pseudo-time: one load step, relaxed a few iterations only
  # (tolerance 0.9): what is checked here is that the deck runs and writes, not its equilibrium;
  # by relaxation: a Newton-Krylov step solves its linear system first, 36 s for laminate_hole)
  grep -qE "^\s+type: quasi_static" "$deck" &&
    cut='s/^(\s*)load_steps:.*/\1load_steps: 1/; s/^(\s*)tolerance:.*/\1tolerance: 0.9/; s/^(\s*)method: newton_krylov/\1method: relaxation/'
  sed -E "$cut"'; s#\.\./meshes/#'"$PWD"'/../meshes/#' "$deck" > "$short"
  grep -qE '^\s*(steps: 5|load_steps: 1)$' "$short" ||
    { echo "$name: no 'final_time:' line of its own to cut the run at 5 steps (block style: time:, then final_time: on a line)"; fail=1; continue; }
  runs="1 2"
  [[ "$run_once" == *" $name "* ]] && runs=1
  digest[2]=
  for run in $runs; do
    out=$(cd "$scratch" && "$exe" "$name.yaml" 2>&1) || { echo "$name: exit $?: $out"; fail=1; continue; }
    digest[$run]=$(echo "$out" | sed -n 's/^state digest: //p')
  done
  [ "$runs" = 1 ] && digest[2]=${digest[1]:-}
  [ -n "${digest[1]:-}" ] || { echo "$name: no state digest"; fail=1; continue; }
  [ "${digest[1]}" = "${digest[2]}" ] || { echo "$name: digests differ: ${digest[1]} ${digest[2]}"; fail=1; }
  exo=$(ls "$scratch"/*.e 2>/dev/null | grep -F "$(grep -E '^\s*file:' "$short" | sed -E 's/.*file:\s*//' | head -1)" | head -1)
  [ -n "$exo" ] || exo="$scratch/$name.e"
  ncdump -h "$exo" > "$scratch/$name.cdl" 2>&1 || { echo "$name: ncdump cannot read $exo"; fail=1; continue; }
  if grep -q "geometry:" "$short"; then  # a PD body (an FE body with `peridynamic:` is HEX8 only)
    grep -q 'SPHERE' "$scratch/$name.cdl" || { echo "$name: no SPHERE block in $exo"; fail=1; }
  fi
  if grep -q "type: finite_element" "$short"; then
    grep -q 'HEX8' "$scratch/$name.cdl" || { echo "$name: no HEX8 block in $exo"; fail=1; }
  fi
  grep -q "num_nod_var" "$scratch/$name.cdl" || { echo "$name: no nodal variables in $exo"; fail=1; }
  ls "$scratch"/*.h5 > /dev/null 2>&1 || { echo "$name: no history file"; fail=1; }
  rm -f "$scratch"/*.e "$scratch"/*.h5
done
exit $fail
