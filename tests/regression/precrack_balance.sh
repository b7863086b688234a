#!/usr/bin/env bash
# A pre-crack cuts a bond from both of its ends or from neither (pd/family.c, crosses): Newton's
# third law holds for the cut families. Willberg's double cantilever beam (inputs/dcb.yaml) at 4.51
# and 5.01 spacings on its 0.5 mm lattice has bonds that cross the mid-plane exactly on the
# pre-crack's front (x = a0, between two columns of points), where the crossing point computed
# from one end and from the other differed in the last bit: the bond was cut in one family only,
# and the one-sided forces pushed the whole beam along x (momentum_x 1.8e-9 kg m/s after 10 us,
# 8e-4 of the grips' impulse; a quasi-static load step could not converge, its residual the
# beam's rigid drift). The grips prescribe u_y only, so against the closed form of a body loaded
# in y alone, over 10 us of the dynamic run:
#  - momentum_x and momentum_z stay at round-off: at most 1e-12 of the largest grip impulse;
#  - momentum_y equals the two grips' impulses, upper_impulse_y + lower_impulse_y, within 1e-12
#    of the largest;
# and the quasi-static run's first load step converges (1e-5) at 5.01 spacings.
# usage: precrack_balance.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
deck=$(cd .. && pwd)/inputs/dcb.yaml
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
for m in 4.51 5.01; do
  if ! "$exe" --output-dir "m$m" "$deck" --set parameters.m=$m --set time.final_time=10e-6 \
    --set output.history_interval=1 > "m$m.log" 2>&1; then
    echo "FAIL: the deck at $m spacings did not run:"; tail -n 5 "m$m.log"; fail=1; continue
  fi
  /usr/bin/python3 - "m$m/dcb.h5" "$m" <<'PY' || fail=1
import sys, h5py, numpy as np
h = h5py.File(sys.argv[1], "r")
imp = h["upper_impulse_y"][:] + h["lower_impulse_y"][:]
scale = max(abs(h["upper_impulse_y"][:]).max(), abs(h["lower_impulse_y"][:]).max())
px, pz = abs(h["momentum_x"][:]).max(), abs(h["momentum_z"][:]).max()
dy = abs(h["momentum_y"][:] - imp).max()
print(f"{sys.argv[2]} spacings: |p_x| {px:.3e}, |p_z| {pz:.3e}, |p_y - impulses| {dy:.3e} kg m/s; grip impulse {scale:.3e}")
bad = [n for n, v in (("momentum_x", px), ("momentum_z", pz), ("momentum_y - impulses", dy)) if not v <= 1e-12 * scale]
for n in bad:
    print(f"FAIL: {n} is more than 1e-12 of the grips' impulse")
sys.exit(1 if bad or not scale > 0 else 0)
PY
done
if ! "$exe" --output-dir qs "$deck" --set parameters.m=5.01 --set time.final_time=15e-6 \
  --set 'solver={type: quasi_static, load_steps: 1, tolerance: 1.0e-5, max_iterations: 2000}' \
  --set 'boundary_conditions.upper.displacement=[free, "0.5 * 57.5e-6 * t / 600e-6", free]' \
  --set 'boundary_conditions.lower.displacement=[free, "-0.5 * 57.5e-6 * t / 600e-6", free]' > qs.log 2>&1; then
  echo "FAIL: the quasi-static load step at 5.01 spacings did not converge:"; grep -m1 error qs.log; fail=1
fi
[ $fail -eq 0 ] && echo "precrack_balance: ok"
exit $fail
