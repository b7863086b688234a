#!/usr/bin/env bash
# The ballistic limit of the projectile-on-panel problem (inputs/panel_impact.yaml as shipped;
# docs/examples/panel_impact.md, "Bracketing the ballistic limit") against Tupek et al. (2013),
# sec. 3.2: their panel barely stops the sphere at 530 m/s and is perforated at 900 m/s, and they
# place the experimental ballistic limit near 530 m/s. scripts/panel_bisect.py starts from the
# bracket [530, 740] m/s (530 must stop the sphere, as in the paper; 740 must perforate) and
# halves it to 60 m/s or less; the bracket it ends with must lie within 25 % above the paper's
# 530 m/s, i.e. inside [530, 662.5] m/s. (A band, not the model's own earlier shots: those gave
# [582.5, 635] m/s.)
# Each shot stops once its outcome is decided (label slow: four shots, about 11 minutes of CPU per
# rank each on 2 ranks).
# usage: slow_panel_bisect.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
"$PY" ../scripts/panel_bisect.py --deck ../inputs/panel_impact.yaml --ranks 2 --perifem "$exe" \
  --out "$scratch" --stop 530 --perforate 740 --width 60 ||
  { echo "FAIL: [530, 740] m/s is not a bracket of the ballistic limit (Tupek et al.: 530 m/s stopped)"; exit 1; }
"$PY" - "$scratch/bisect.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
stopped = [float(r["impact_velocity"]) for r in rows if not r["outcome"].startswith("perforated")]
through = [float(r["impact_velocity"]) for r in rows if r["outcome"].startswith("perforated")]
lo, hi = max(stopped), min(through)
ok = lo < hi and 530.0 <= lo and hi <= 1.25 * 530.0
print("ballistic limit bracket [%g, %g] m/s; band [530, 662.5] m/s (Tupek et al. 2013 sec. 3.2, +25 %%): %s"
      % (lo, hi, "holds" if ok else "FAIL"))
sys.exit(0 if ok else 1)
PY
