#!/usr/bin/env bash
# The energies plot's legends say what each history column holds (scripts/plot_history.py, on
# made-up columns, no run): every energy column has a legend of its own, none is the bare
# column name; elastic_energy, which holds the plastic work of elastic_plastic bonds and the
# stress work of correspondence points, and fe_internal_energy are labelled as internal energies
# with plastic work; and the user guide's table says the same of the two columns.
# usage: energy_legends.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
source common/mpi_env.sh
"$PY" - <<'EOF'
import re, sys
import numpy as np
sys.path.insert(0, "../scripts")
import plot_history as ph
ok = True
def fail(msg):
    global ok
    print("FAIL: " + msg); ok = False
names = ph.STORED + ph.DISSIPATED
def legend(k):
    """The energies plot's legend of column k (the only non-zero energy column)."""
    c = {n: np.zeros(2) for n in names + ["external_work"]}
    c.update({k: np.array([0.0, 1.0]), "time": np.array([0.0, 1e-6]), "energy_error": np.zeros(2)})
    _, figs = ph.plots(c)
    return [f for f in figs if f[0] == "energies"][0][3][0][0]
labels = {k: legend(k) for k in names}
for k in names:
    if labels[k] == k.replace("_", " "): fail("the column %s is labelled by its bare name" % k)
if len(set(labels.values())) != len(names): fail("two columns share a legend: %s" % labels)
for k in ("elastic_energy", "fe_internal_energy"):
    if not ("internal" in labels[k] and "plastic work" in labels[k]):
        fail("the legend of %s, '%s', does not say it holds internal energy with plastic work" % (k, labels[k]))
guide = open("../docs/user_guide.md").read()
for k in ("elastic_energy", "fe_internal_energy"):
    row = re.search(r"^\| `%s` \| J \| (.*)$" % k, guide, re.M)
    if not row or "plastic" not in row.group(1) or labels[k] not in row.group(1):
        fail("docs/user_guide.md's row for %s does not give its plastic work and its legend" % k)
sys.exit(0 if ok else 1)
EOF
