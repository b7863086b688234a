#!/usr/bin/env bash
# Contact with a coupled body (tests/data/sphere_on_coupled_block.yaml): an FE sphere hits an FE
# glass block whose nodes carry peridynamics near the impact, so the block's nodes are the
# particles the sphere's surface meets and its fragments meet each other by short-range forces.
# Checks, on 1, 2 and 3 ranks:
#  - the same state digest;
#  - the history's per-body columns: m_ball v_ball + m_block v_block = momentum (every row, to
#    1e-12 of the initial momentum; m_block = rho x the 16 x 16 x 4 mm box, m_ball from the
#    initial momentum, the block starting at rest), and the centre of mass of the block
#    starting at its box's centre (0, 0, -2 mm);
#  - the contact acted and the block broke: the sphere has lost over 10 % of its 200 m/s, the
#    block moves down, and the summary lists more than one fragment;
#  - with beta = 1 on every node (no blending zone, whose force blending does not conserve
#    momentum: docs/theory/coupling.md §3.3) momentum is conserved to 1e-12: the contact forces
#    between the FE surface and the coupled particles are equal and opposite.
# usage: coupled_contact.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
sed -E 's#\.\./\.\./meshes/#'"$OLDPWD"'/../meshes/#' "$OLDPWD/data/sphere_on_coupled_block.yaml" > blend.yaml
sed -E 's/blending: .*/blending: "1"/' blend.yaml > whole.yaml
for deck in blend whole; do
  for np in 1 2 3; do
    mkdir -p $deck$np
    if ! out=$(run $np "$exe" --output-dir $deck$np $deck.yaml 2>&1); then
      echo "FAIL: $deck on $np ranks: $out"; fail=1; continue
    fi
    d[$np]=$(digest_of "$out")
    n=$(echo "$out" | sed -n 's/.*fragments of block: \([0-9]*\).*/\1/p')
    [ "${n:-0}" -gt 1 ] || { echo "FAIL: $deck on $np ranks: the block did not break (fragments: ${n:-none})"; fail=1; }
    $PY - $deck$np/$deck.h5 $deck <<'PY' || fail=1
import sys
import h5py
import numpy as np
h = h5py.File(sys.argv[1], "r")
p, vb, vk = h["momentum_z"][:], h["ball_velocity_z"][:], h["block_velocity_z"][:]
m_block = 2200 * 0.016 * 0.016 * 0.004
m_ball = p[0] / vb[0]
ok = True
def check(cond, what):
    global ok
    if not cond:
        print("FAIL: %s: %s" % (sys.argv[1], what)); ok = False
check(vk[0] == 0 and abs(vb[0] + 200) < 1e-9, "initial velocities (ball %g, block %g)" % (vb[0], vk[0]))
err = np.abs(m_ball * vb + m_block * vk - p).max()
check(err <= 1e-12 * abs(p[0]), "per-body momentum vs momentum_z: %g" % err)
check(abs(h["block_position_z"][0] + 0.002) < 1e-15 and abs(h["block_position_x"][0]) < 1e-15,
      "block centre (%g, %g)" % (h["block_position_x"][0], h["block_position_z"][0]))
check(vb[-1] > -180 and vk[-1] < 0, "contact acted: ball %g m/s, block %g m/s" % (vb[-1], vk[-1]))
if sys.argv[2] == "whole":
    drift = np.abs(p - p[0]).max()
    check(drift <= 1e-12 * abs(p[0]), "momentum drift %g of %g" % (drift, p[0]))
sys.exit(0 if ok else 1)
PY
  done
  [ -n "${d[1]:-}" ] && [ "${d[1]}" = "${d[2]:-}" ] && [ "${d[1]}" = "${d[3]:-}" ] ||
    { echo "FAIL: $deck: digests differ over 1, 2, 3 ranks: ${d[*]:-}"; fail=1; }
done
[ $fail = 0 ] && echo "coupled_contact: FE sphere on a coupled block, same digest on 1, 2, 3 ranks, momentum checks pass"
exit $fail
