#!/usr/bin/env bash
# The glass disk's self-contact (inputs/disk_impact_rigid.yaml; docs/examples/disk_impact.md,
# "Which contact to trust"), on the shipped deck reduced to a disk of radius 12 mm and 450 steps
# (45 us: the sphere is 4.4 mm deep, through the 2.5 mm plate, and the crushed column under it is
# thousands of fragments):
#  - the deck's pair is LAMMPS pair peri/pmb's short-range force: every two points (all_points),
#    radius 1.35 h, C = 15 x 18 K / (pi delta^5), computed here from the deck's own K, delta, h;
#  - no two points of different fragments (connected components of intact bonds, output field
#    'fragment') are closer than h/2 at the end: a cell's centre never enters the next cell. The
#    same deck without the pair breaks this (two points 0.2 h apart): the check can fail;
#  - energy: the work of the sphere, integrated here from the history's force and its 100 m/s,
#    equals the kinetic energy summed here from the Exodus velocities (rho h^3 a point) plus the
#    elastic and contact energies and the dissipation, to 1 % of the work (measured 0.17 %); and
#    that integral equals the booked sphere_work to 1e-3 (rows every 10 steps);
#  - the run ends with the same state digest on 1, 2 and 3 ranks, fragments in contact included.
# About 25 s of CPU (five runs), a minute or two of wall time on loaded cores, hence label slow.
# usage: slow_disk_contact.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"/{np1,np2,np3,none}
deck=../inputs/disk_impact_rigid.yaml
reduce='s/radius: 0.037/radius: 0.012/; s/^(\s*)final_time:.*/\1steps: 450/; s/^output:/output:\n  fragments: true/; s/^(\s*)interval: 100/\1interval: 450/'
sed -E "$reduce" $deck > "$scratch/disk.yaml"
# the same without the contact section (the lines from 'contact:' to the one before 'time:')
sed -E '/^contact:/,/^time:/{/^time:/!d}' "$scratch/disk.yaml" > "$scratch/none.yaml"
grep -q '^contact:' "$scratch/disk.yaml" && ! grep -q '^contact:' "$scratch/none.yaml" ||
  { echo "FAIL: the shipped deck has no contact section to remove"; exit 1; }
out3=$(run 3 "$exe" --quiet --output-dir "$scratch/np3" "$scratch/disk.yaml" 2>&1) || { echo "FAIL: 3 ranks: $out3"; exit 1; }
out2=$(run 2 "$exe" --quiet --output-dir "$scratch/np2" "$scratch/disk.yaml" 2>&1) || { echo "FAIL: 2 ranks: $out2"; exit 1; }
out1=$("$exe" --quiet --output-dir "$scratch/np1" "$scratch/disk.yaml" 2>&1) || { echo "FAIL: 1 rank: $out1"; exit 1; }
outn=$("$exe" --quiet --output-dir "$scratch/none" "$scratch/none.yaml" 2>&1) || { echo "FAIL: no contact: $outn"; exit 1; }
d1=$(digest_of "$out1") d2=$(digest_of "$out2") d3=$(digest_of "$out3")
[ -n "$d1" ] && [ "$d1" = "$d2" ] && [ "$d1" = "$d3" ] ||
  { echo "FAIL: digests on 1, 2 and 3 ranks differ: '$d1' '$d2' '$d3'"; exit 1; }
echo "ok:   state digest $d1 on 1, 2 and 3 ranks"
"$PY" - "$deck" "$scratch" <<'PYEOF'
import math, re, sys
import numpy as np
sys.path.insert(0, "../scripts")
from disk_report import report
deck, scratch = open(sys.argv[1]).read(), sys.argv[2]
num = lambda key: float(re.search(r"^\s*%s:\s*([0-9.eE+-]+)" % key, deck, re.M).group(1))
K, delta, h, rho = num("bulk_modulus"), num("horizon"), num("spacing"), num("density")
pair = deck[deck.index("\ncontact:"):deck.index("\ntime:")]
pnum = lambda key: float(re.search(r"^\s*%s:\s*([0-9.eE+-]+)" % key, pair, re.M).group(1))
ok = True
def check(cond, what):
    global ok
    print(("ok:   " if cond else "FAIL: ") + what)
    ok = ok and bool(cond)
C = 15 * 18 * K / (math.pi * delta ** 5)
check(re.search(r"bodies:\s*\[disk, disk\]", pair) and re.search(r"all_points:\s*true", pair),
      "the pair is the disk with itself, all points")
check(abs(pnum("radius") - 1.35 * h) < 1e-9 * h, "radius %g = 1.35 h = %g" % (pnum("radius"), 1.35 * h))
check(abs(pnum("stiffness") / C - 1) < 1e-4, "stiffness %g = 15 x 18 K / (pi delta^5) = %g" % (pnum("stiffness"), C))
on = report(scratch + "/np1/disk_impact_rigid.h5", scratch + "/np1/disk_impact_rigid.e", h, 100.0)
off = report(scratch + "/none/disk_impact_rigid.h5", scratch + "/none/disk_impact_rigid.e", h, 100.0)
check(on["fragments"] > 100, "%d fragments at the end (the contact has fragments to act on)" % on["fragments"])
check(on["closest_fragments_over_h"] >= 0.5,
      "with contact the closest points of different fragments are %.3f h apart (>= 0.5)" % on["closest_fragments_over_h"])
check(off["closest_fragments_over_h"] < 0.5,
      "without contact they are %.3f h apart (< 0.5: the check can fail)" % off["closest_fragments_over_h"])
from disk_report import exodus_last_step
t, x, f = exodus_last_step(scratch + "/np1/disk_impact_rigid.e")
ke = 0.5 * rho * h ** 3 * float(np.sum(f["velocity_x"] ** 2 + f["velocity_y"] ** 2 + f["velocity_z"] ** 2))
W = on["sphere_work_integrated"]
held = ke + on["elastic_energy"] + on["contact_energy"] + on["damage_dissipation"] + on["contact_dissipation"]
check(abs(W - held) < 0.01 * W, "work of the sphere %.4f J, held or dissipated %.4f J (kinetic %.4f from the "
      "velocities): %.2f %%" % (W, held, ke, 100 * abs(W - held) / W))
check(abs(W / on["sphere_work"] - 1) < 1e-3, "integrated work %.5f J, booked %.5f J" % (W, on["sphere_work"]))
print("damage fraction %.4f with contact, %.4f without" % (on["damage_fraction"], off["damage_fraction"]))
sys.exit(0 if ok else 1)
PYEOF
