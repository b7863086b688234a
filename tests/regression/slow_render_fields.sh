#!/usr/bin/env bash
# Pictures of the fields (scripts/render_fields.py under ParaView's pvbatch, off-screen through
# xvfb-run; Debian paraview, python3-paraview, xvfb, xauth, which scripts/setup.sh does not
# install, hence label slow): a mixed run (a PD plate and an FE bar, tests/data/mixed_pd_fe.yaml)
# is drawn coloured by damage and by velocity_z, and clipped; each PNG has the size asked for and
# is not one flat colour (the bodies were drawn), also with --keep damage,0,0.99; a field the
# file lacks is refused (exit 2).
# usage: slow_render_fields.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
for tool in pvbatch xvfb-run; do
  command -v $tool > /dev/null || { echo "$tool not found: apt-get install paraview python3-paraview xvfb xauth"; exit 1; }
done
rm -rf "$scratch" && mkdir -p "$scratch"
cp data/mixed_pd_fe.yaml "$scratch/mixed.yaml"
"$exe" --quiet --output-dir "$scratch" "$scratch/mixed.yaml" > /dev/null || { echo "FAIL: the run"; exit 1; }
# xvfb-run -a can lose the race for a display number to another X server starting at the same
# moment ("bad X server connection"): try again, up to three times
pv() {
  local try out st
  for try in 1 2 3; do
    out=$(env -i PATH=/usr/bin:/bin HOME="$scratch" xvfb-run -a pvbatch ../scripts/render_fields.py "$@" 2>&1)
    st=$?
    grep -q "bad X server connection" <<< "$out" || break
  done
  echo "$out"
  return $st
}
bad() { echo "FAIL: $*"; fail=1; }
pv "$scratch/mixed.e" "$scratch/damage.png" --field damage --size 640 480 > "$scratch/log" 2>&1 || bad "damage: $(tail -3 "$scratch/log")"
pv "$scratch/mixed.e" "$scratch/vz.png" --field velocity_z --view front --step 0 --size 640 480 >> "$scratch/log" 2>&1 || bad "velocity_z"
pv "$scratch/mixed.e" "$scratch/clip.png" --field damage --clip-y 0 --view side --size 640 480 >> "$scratch/log" 2>&1 || bad "clip"
pv "$scratch/mixed.e" "$scratch/keep.png" --field velocity --keep damage,0,0.99 --size 640 480 >> "$scratch/log" 2>&1 || bad "keep"
for p in damage vz clip keep; do
  "$PY" - "$scratch/$p.png" <<'PYEOF' || bad "$p.png"
import sys
import matplotlib.image as mpimg
import numpy as np
img = mpimg.imread(sys.argv[1])
assert img.shape[:2] == (480, 640), img.shape
colours = len(np.unique((img[..., :3] * 255).astype(int).reshape(-1, 3), axis=0))
assert colours > 20, "only %d colours" % colours
print("%s: %dx%d, %d colours" % (sys.argv[1], img.shape[1], img.shape[0], colours))
PYEOF
done
pv "$scratch/mixed.e" "$scratch/none.png" --field no_such_field > "$scratch/none.log" 2>&1
[ $? -eq 2 ] || bad "an unknown field: exit status not 2"
grep -q "has no point field 'no_such_field'" "$scratch/none.log" || bad "no clear message for an unknown field"
exit $fail
