#!/usr/bin/env bash
# Every log message is one line (issue 48: "(residual 9.0e-14)boundary condition 'held' ...", the
# consistent form's line continued by the next message). The set-up and run logs of
#  1. the coupled PD/FE bar in the consistent form (tests/data/coupled_bar.yaml) with a boundary
#     condition given by --set, under --check and for 3 steps;
#  2. a quasi-static run (tests/data/static_plastic_bar.yaml: load steps, the solver's lines);
#  3. --check of the PD/FE quasi-static bar (inputs/static_bar.yaml: the report's lines);
# must have no message starting inside another line, the consistent form's line ending at its
# residual, and the report's lines whole.
# usage: cli_log_lines.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
root=$(cd .. && pwd)
scratch=$2 fail=0
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1

held='boundary_conditions=[{name: held, body: bar, region: {shape: box, lo: [0.029, -1, -1], hi: [1, 1, 1]},
  displacement: ["0", "free", "free"]}]'
# a message's start found after the first character of a line
glued="[^ ](boundary condition '|body '|mesh |load step [0-9]|solver: |perifem: |health: |state digest: |step [0-9]+/)"

lines() { # WHAT LOG: no glued messages in LOG
  if grep -nE "$glued" "$2" > glued.txt; then
    echo "FAIL $1: a message continues another line:"; cut -c1-200 glued.txt; fail=1
  else echo "ok   $1: $(wc -l < "$2") lines, one message each"; fi
}
has() { # WHAT LOG REGEX: a line of LOG matches REGEX
  if grep -qE -- "$3" "$2"; then echo "ok   $1"; else echo "FAIL $1: no line matches '$3'"; fail=1; fi
}

"$exe" --check --set "$held" "$root/tests/data/coupled_bar.yaml" > check_coupled.log 2>&1 ||
  { echo "FAIL: --check of the coupled bar: $(head -3 check_coupled.log)"; fail=1; }
lines "--check, coupled bar" check_coupled.log
has "the consistent form's line ends at its residual" check_coupled.log \
  "^body 'bar': consistent form, .* \(residual [0-9.e+-]+\)$"
has "the boundary condition's line" check_coupled.log "^boundary condition 'held' \(--set boundary_conditions=.*\): 162 points$"

"$exe" --output-dir run --set time.steps=3 --set "$held" "$root/tests/data/coupled_bar.yaml" > run_coupled.log 2>&1 ||
  { echo "FAIL: 3 steps of the coupled bar: $(head -3 run_coupled.log)"; fail=1; }
lines "3 steps, coupled bar" run_coupled.log

"$exe" --output-dir static "$root/tests/data/static_plastic_bar.yaml" > run_static.log 2>&1 ||
  { echo "FAIL: the quasi-static bar: $(head -3 run_static.log)"; fail=1; }
lines "quasi-static run" run_static.log
has "a load step's line" run_static.log "^load step 1/[0-9]+  t = .*  damage [0-9.e+-]+$"

"$exe" --check "$root/inputs/static_bar.yaml" > check_static.log 2>&1 ||
  { echo "FAIL: --check of static_bar.yaml: $(head -3 check_static.log)"; fail=1; }
lines "--check, static_bar.yaml" check_static.log
has "the report's time step line" check_static.log "^  time step: .* steps to 0.001 s$"
has "the report's memory line" check_static.log "^  memory per rank: estimated .* measured .* a rank may use [0-9.e+]+ [KMGT]?B$"
has "the report's output line" check_static.log "^  output: Exodus .* history .* columns\)$"
has "the report's checkpoint line" check_static.log "^  checkpoint: .* each \(none written: restart.interval is 0\)$"
has "the report's run time line" check_static.log "^  rough run time: .* contact and output not counted; a quasi-static run.s load steps are not timed\)$"
exit $fail
