#!/usr/bin/env bash
# The output files say what made them. A run of a small FE deck that includes a part and takes
# an override on the command line; its Exodus file and its HDF5 history are read back (netCDF4,
# h5py) and checked against the inputs themselves:
#  - the Exodus title and the history's "title" are the deck's title: key;
#  - the Exodus QA record is perifem's name and version (perifem --version) and today's date;
#  - the info records and the history's "provenance" hold the version with the git commit the
#    build came from (git describe of the source tree, when it is a git checkout), the number of
#    ranks, the command line as given, and the deck's and the included file's text line by line;
#  - the history's "columns" attribute lists every column dataset, time and step first;
#  - the stress is written as stress_xx, _yy, _zz, _xy, _yz, _zx, in that order (the names and
#    order by which ParaView joins six variables into one symmetric tensor);
#  - a body named fe, whose column fe_internal_energy would take the global column's name, is
#    refused at set-up (exit 2, the column named, no output file).
# usage: output_provenance.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd .. && pwd)
mesh=$(cd data/mesh && pwd)/two_hexes.msh
scratch=$2
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
cat > steel.yaml <<EOF
materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}
EOF
cat > prov.yaml <<EOF
title: two hexahedra, pulled
include: [steel.yaml]
bodies:
  - {name: bar, type: finite_element, material: steel, mesh: {file: $mesh}, initial_velocity: ["x", "0", "0"]}
time: {steps: 3}
output: {interval: 1, history_interval: 1}
EOF
# a body named so that one of its columns takes a global column's name is refused, nothing written
sed 's/name: bar,/name: fe,/' prov.yaml > fe.yaml
out=$(run 1 "$exe" --quiet fe.yaml 2>&1); status=$?
if [ $status -ne 2 ] || ! echo "$out" | grep -q "two columns named 'fe_internal_energy'" || ls fe.h5 fe.e > /dev/null 2>&1; then
  echo "FAIL: a body named fe: exit $status (expected 2, the column named, nothing written):"; echo "$out" | head -5; exit 1
fi
run 2 "$exe" --quiet prov.yaml --set time.steps=4 > run.log 2>&1 || { echo "FAIL: the run failed"; cat run.log; exit 1; }
version=$("$exe" --version | sed -n 's/^perifem \([^ ]*\).*/\1/p')
git=$(git -C "$src" describe --always --dirty --abbrev=12 2>/dev/null || echo unknown)
"$PY" - "$version" "$git" "$exe" <<'EOF'
import datetime, sys
import h5py, netCDF4
version, git, exe = sys.argv[1:4]
fail = []
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok: fail.append(what)
deck = open("prov.yaml").read().splitlines()
part = open("steel.yaml").read().splitlines()
e = netCDF4.Dataset("prov.e")
check(e.title == "two hexahedra, pulled", "Exodus title '%s'" % e.title)
qa = [b"".join(r).decode().rstrip("\0").strip() for r in e.variables["qa_records"][0]]
today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
check(qa[0] == "perifem" and qa[1] == version and qa[2] == today, "QA record %s" % qa)
info = [b"".join(r).decode().rstrip("\0") for r in e.variables["info_records"][:]]
names = [b"".join(r).decode().rstrip("\0") for r in e.variables["name_nod_var"][:]]
h = h5py.File("prov.h5", "r")
title = h.attrs["title"]
title = title.decode() if isinstance(title, bytes) else title
check(title == "two hexahedra, pulled", "history title '%s'" % title)
prov = h.attrs["provenance"]
prov = (prov.decode() if isinstance(prov, bytes) else prov).splitlines()
check(prov[0] == "perifem %s, git %s" % (version, git), "version and commit: '%s' (git describe of the source: %s; a build older than the source fails here: rebuild)" % (prov[0], git))
check(prov[1].endswith("on 2 MPI ranks"), "ranks: '%s'" % prov[1])
check(prov[2] == "command: %s --quiet prov.yaml --set time.steps=4" % exe, "command line: '%s'" % prov[2])
i = prov.index("---- deck prov.yaml ----")
check(prov[i + 1:i + 1 + len(deck)] == deck, "the deck's text, line by line")
j = prov.index("---- included steel.yaml ----")
check(prov[j + 1:j + 1 + len(part)] == part, "the included file's text")
check(info[:3] == [l[:80] for l in prov[:2]] + [prov[2][:80]], "Exodus info records begin like the history's provenance")
check(all(len(l) <= 80 for l in info) and "".join(info).replace(" ", "") .find("".join(deck).replace(" ", "")) >= 0,
      "Exodus info records hold the deck (folded at 80 characters)")
cols = [c.decode() if isinstance(c, bytes) else c for c in h.attrs["columns"]]
check(cols[:2] == ["time", "step"] and sorted(cols) == sorted(k for k in h.keys()), "history columns in order: %s ..." % cols[:4])
s = [n for n in names if n.startswith("stress_")]
check(s == ["stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_yz", "stress_zx"], "stress variables %s" % s)
sys.exit(1 if fail else 0)
EOF
