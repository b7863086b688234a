#!/usr/bin/env bash
# The coupled plate (plate_coupled.yaml: PD strip, elements elsewhere) beside the all-PD plate
# (plate_pd.yaml), one after the other, one rank each: wall time of the time loop, peak memory
# (resident set), and the crack: its tip and its centre line in the PD strip
# (docs/theory/coupling.md §4).
# usage: bash bench/coupling/run_coupling.sh [path/to/perifem]   (default: build/perifem)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
exe=$(realpath "${1:-$here/../../build/perifem}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for deck in plate_pd plate_coupled; do
  /usr/bin/python3 - "$exe" "$here/$deck.yaml" > "$deck.log" 2>&1 <<'PY'
import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
print(r.stdout)
print("peak resident set: %.1f MB" % (resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024))
sys.exit(r.returncode)
PY
done
/usr/bin/python3 - plate_pd plate_coupled <<'PY'
import re, sys, netCDF4, numpy as np
def crack(name):
    d = netCDF4.Dataset(name + ".e")
    names = [str(netCDF4.chartostring(n)) for n in d.variables["name_nod_var"][:]]
    x, y, z = (d.variables[c][:] for c in ("coordx", "coordy", "coordz"))
    phi = d.variables["vals_nod_var%d" % (names.index("damage") + 1)][-1]
    strip = (abs(z - 0.001) < 1e-6) & (abs(y - 0.0305) < 0.008)
    cracked = strip & (phi > 0.35)
    xs = np.round(x * 1e3).astype(int)
    tip = xs[cracked].max()
    centre = {c: np.average(y[strip & (xs == c)], weights=phi[strip & (xs == c)]) * 1e3
              for c in range(16, tip + 1) if phi[strip & (xs == c)].sum() > 0}
    log = open(name + ".log").read()
    loop = float(re.search(r"time loop ([0-9.]+) s", log).group(1))
    mem = float(re.search(r"peak resident set: ([0-9.]+) MB", log).group(1))
    bonds = int(re.search(r"directed bonds (\d+)", log).group(1))
    return tip, centre, loop, mem, bonds
pd, cp = crack(sys.argv[1]), crack(sys.argv[2])
for label, r in (("all PD ", pd), ("coupled", cp)):
    print("%s: time loop %.2f s, peak memory %.1f MB, directed bonds %d, crack tip x = %d mm"
          % (label, r[2], r[3], r[4], r[0]))
common = sorted(set(pd[1]) & set(cp[1]))
dev = max(abs(pd[1][c] - cp[1][c]) for c in common)
print("coupled / all PD: time %.2f, memory %.2f; crack tip %+d mm; centre lines differ by at most %.2f mm "
      "over x = %d..%d mm" % (cp[2] / pd[2], cp[3] / pd[3], cp[0] - pd[0], dev, common[0], common[-1]))
PY
