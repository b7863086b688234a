#!/usr/bin/env bash
# The energy balance of every shipped deck and every tests/data deck, one line each:
#   DECK  STEPS  MAX|energy_error|/scale  FINAL energy_error (J)  WARNINGS
# where scale is the largest energy in play over the run, max(|external_work|, kinetic + elastic +
# contact + |FE internal|) (the measure of the run summary's relative error, taken over the whole
# run), from the history file, and WARNINGS the run-health warnings printed.
# Run it with the binary before and after a change to the bookkeeping and compare:
#   bash scripts/balance_table.sh OLD/perifem > before.txt
#   bash scripts/balance_table.sh build/perifem > after.txt && paste before.txt after.txt
# Each deck runs on one rank for BALANCE_STEPS steps (default 200), mesh paths made absolute.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
steps=${BALANCE_STEPS:-200}
work=$(mktemp -d /tmp/perifem_balance.XXXXXX)
trap 'rm -rf "$work"' EXIT
source "$here/tests/common/mpi_env.sh"
for f in "$here"/inputs/*.yaml "$here"/tests/data/*.yaml; do
  name=$(basename "$f" .yaml)
  sed -E "s/^(\s*)final_time:.*/\1steps: $steps/; s/final_time: [0-9.eE+-]+/steps: $steps/; s/steps: [0-9]+/steps: $steps/; \
          s#\.\./\.\./meshes/#$here/meshes/#; s#\.\./meshes/#$here/meshes/#" "$f" > "$work/$name.yaml"
  log=$(cd "$work" && "$exe" --progress plain --output-dir out --set output.interval=0 --set output.history_interval=1 \
        "$name.yaml" 2>&1)
  warnings=$(echo "$log" | grep -c "perifem warning")
  h5=$(ls "$work"/out/"$name"*.h5 2>/dev/null | head -1)
  if [ -z "$h5" ]; then echo "$name - - - no-history"; continue; fi
  "$PY" - "$h5" "$name" "$warnings" <<'PY'
import sys, h5py, numpy as np
path, name, warnings = sys.argv[1:4]
with h5py.File(path, "r") as f:
    col = {k: np.asarray(f[k][:], dtype=float) for k in f.keys()}
n = len(col["step"])
g = lambda k: col.get(k, np.zeros(n))
play = g("kinetic_energy") + g("elastic_energy") + g("contact_energy") + np.abs(g("fe_internal_energy"))
scale = max(np.max(np.abs(g("external_work"))), np.max(play))
err = g("energy_error")
rel = np.max(np.abs(err)) / scale if scale > 0 else 0.0
print(f"{name} {int(g('step')[-1])} {rel:.3e} {err[-1]:+.4e} {warnings}")
PY
  rm -rf "$work/out"
done
