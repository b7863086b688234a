#!/usr/bin/env bash
# python/examples/disk_sweep.py, the critical-stretch sweep through the Python package, on a small
# disk (radius 6 mm, 150 steps): the damage fraction falls as the critical stretch s00 rises
# (Silling-Askari: a bond breaks past s0 = s00 - alpha s_min), and with s00 = 100 (a stretch no
# bond reaches in 15 us: 50 mm of relative motion over a 0.5 mm bond) nothing breaks and no
# energy is released.
# usage: python_sweep.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch"
out=$(cd "$scratch" && PERIFEM_LIBRARY="$build/libperifem.so.0" "$PY" "$tests/../python/examples/disk_sweep.py" \
      --deck "$tests/../inputs/disk_impact_rigid.yaml" --radius 0.006 --final-time 1.5e-5 \
      --s00 2.5e-4 5e-4 1e-3 100 --out sweep.csv 2>&1) || { echo "$out"; echo "FAIL: disk_sweep.py"; exit 1; }
"$PY" - "$scratch/sweep.csv" <<'PYEOF' || { echo "$out"; exit 1; }
import csv, sys
rows = [[float(x) for x in r] for r in list(csv.reader(open(sys.argv[1])))[1:]]
d = [r[1] for r in rows]
bad = []
if len(rows) != 4: bad.append("%d rows" % len(rows))
elif not (d[0] > d[1] > d[2] > 0): bad.append("damage fractions %s do not fall as s00 rises" % d[:3])
elif d[3] != 0 or rows[3][2] != 0: bad.append("s00 = 100: damage %g, released %g J" % (d[3], rows[3][2]))
for b in bad: print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
