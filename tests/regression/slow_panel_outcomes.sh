#!/usr/bin/env bash
# The projectile-on-panel problem (inputs/panel_impact.yaml as shipped; docs/examples/panel_impact.md)
# against Tupek et al. 2013's qualitative outcomes (sec. 3.2): at 370 m/s the sphere is
# well below the ballistic limit (the panel stops it); at 530 m/s it perforates the top face and
# the bottom face stops it; at 900 m/s it perforates both, leaving with a residual velocity
# between 0 and its impact velocity. 740 m/s, which the paper does not describe, must run to its
# end (it once threw points out at 38 km/s; docs/theory/materials.md §2) with physical bounds only:
# a residual velocity below its impact velocity and not above the 900 m/s shot's.
# scripts/panel_sweep.py runs the four velocities on 2 ranks (about 16 minutes on 2 cores, hence
# label slow) and judges each outcome from the sphere's path.
# usage: slow_panel_outcomes.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
"$PY" ../scripts/panel_sweep.py --deck ../inputs/panel_impact.yaml --ranks 2 --perifem "$exe" \
  --out "$scratch" --velocities 370 530 740 900 || { echo "FAIL: panel_sweep.py exited $?"; exit 1; }
"$PY" - "$scratch/sweep.csv" <<'PYEOF'
import csv, sys
rows = {float(r["impact_velocity"]): r for r in csv.DictReader(open(sys.argv[1]))}
want = {370: ("any", "False"), 530: ("True", "False"), 900: ("True", "True")}
ok = True
for v, (top, through) in want.items():
    r = rows[v]
    if (top != "any" and r["top_face_perforated"] != top) or r["panel_perforated"] != through:
        print("FAIL: %g m/s: top face perforated %s, panel perforated %s; the paper: %s, %s" %
              (v, r["top_face_perforated"], r["panel_perforated"], top, through))
        ok = False
vr = float(rows[900]["residual_velocity"])
if not 0 < vr < 900:
    print("FAIL: residual velocity at 900 m/s %g m/s" % vr)
    ok = False
v7 = float(rows[740]["residual_velocity"])
if not 0 <= v7 < 740 or v7 > vr:
    print("FAIL: residual velocity at 740 m/s %g m/s (900 m/s: %g)" % (v7, vr))
    ok = False
print("panel outcomes: 370 stopped, 530 top face perforated and stopped, 740 residual %.0f m/s, 900 through at %.0f m/s" % (v7, vr) if ok else "")
sys.exit(0 if ok else 1)
PYEOF
