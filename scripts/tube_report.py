"""The expanding tube's numbers (inputs/expanding_tube.yaml; docs/examples/expanding_tube.md)
from a finished run, beside what Vogler et al. (2003) published.

  /usr/bin/python3 scripts/tube_report.py RUN.h5 [--plot OUTDIR] [--json FILE]

RUN.h5 is the run's history; RUN.fragments.csv (written with `output.fragments: true`) must lie
beside it. Printed:
  - the tube's fragments at the last output (connected components of intact bonds): how many,
    how many heavier than 1 g (Vogler et al. recovered 14), and the largest one's share of the
    tube's mass (about half the tube stayed in one piece);
  - per probe ring (probe_<name>_radial_velocity / _radial_displacement columns): the peak
    outward radial velocity of the outer surface and the radial displacement at the end.
With --plot it writes OUTDIR/expanding_tube_probes.png (radial velocity and displacement of the
probe rings against time) and OUTDIR/expanding_tube_fragments.png (the fragments heavier than
1 g by mass, and the count of fragments over time). With --json the numbers go to FILE too (the
slow test reads them)."""
import argparse
import collections
import csv
import json
import os
import sys

import h5py
import numpy as np


def fragments(csv_path, body="tube"):
    """{time: [masses of body's fragments, heaviest first]}"""
    by_time = collections.defaultdict(list)
    with open(csv_path) as f:
        for row in csv.DictReader(f):
            if row["body"] == body:
                by_time[float(row["time"])].append(float(row["mass"]))
    return {t: sorted(m, reverse=True) for t, m in sorted(by_time.items())}


def probes(h5):
    """{ring name: (radial velocity, radial displacement)} from the history's columns."""
    out = {}
    for key in h5:
        if key.startswith("probe_") and key.endswith("_radial_velocity"):
            name = key[len("probe_"):-len("_radial_velocity")]
            out[name] = (h5[key][:], h5["probe_%s_radial_displacement" % name][:])
    return out


def summary(h5_path):
    csv_path = h5_path[:-len(".h5")] + ".fragments.csv"
    if not os.path.exists(csv_path):
        sys.exit("tube_report: %s not found (run the deck with output.fragments: true)" % csv_path)
    frag = fragments(csv_path)
    t_end = max(frag)
    m = frag[t_end]
    total = sum(m)
    with h5py.File(h5_path, "r") as h5:
        t = h5["time"][:]
        rings = {k: (v, u) for k, (v, u) in probes(h5).items()}
    s = {"time": t_end, "fragments": len(m), "heavier_than_1g": sum(1 for x in m if x > 1e-3),
         "largest_fraction": m[0] / total, "largest_mass": m[0], "tube_mass": total,
         "masses_over_1g": [x for x in m if x > 1e-3], "rings": {}}
    for name, (v, u) in sorted(rings.items()):
        k = int(np.argmax(v))
        s["rings"][name] = {"peak_radial_velocity": float(v[k]), "peak_time": float(t[k]),
                            "final_radial_displacement": float(u[-1])}
    return s, frag, t, rings


def plot(outdir, frag, t, rings, s):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(outdir, exist_ok=True)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for name, (v, u) in sorted(rings.items()):
        label = "%s mm from the plug end" % name.lstrip("z")
        ax[0].plot(t * 1e6, v, label=label)
        ax[1].plot(t * 1e6, u * 1e3, label=label)
    ax[0].set_xlabel("time (us)"), ax[0].set_ylabel("radial velocity (m/s)")
    ax[1].set_xlabel("time (us)"), ax[1].set_ylabel("radial displacement (mm)")
    ax[0].legend(fontsize=8)
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle("Outer surface of the tube, mass averages over +-0.4 mm rings")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "expanding_tube_probes.png"), dpi=110)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    heavy = s["masses_over_1g"]
    ax[0].bar(range(1, len(heavy) + 1), [x * 1e3 for x in heavy])
    ax[0].set_xlabel("fragment (heaviest first)"), ax[0].set_ylabel("mass (g)")
    ax[0].set_title("%d fragments over 1 g at %.1f us (Vogler et al.: 14)" % (len(heavy), s["time"] * 1e6),
                    fontsize=9)
    times = sorted(frag)
    ax[1].plot([x * 1e6 for x in times], [sum(1 for m in frag[x] if m > 1e-3) for x in times], label="over 1 g")
    ax[1].plot([x * 1e6 for x in times], [frag[x][0] / sum(frag[x]) * 10 for x in times],
               label="largest / tube mass x 10")
    ax[1].set_xlabel("time (us)"), ax[1].legend(fontsize=8), ax[1].grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "expanding_tube_fragments.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("history")
    ap.add_argument("--plot")
    ap.add_argument("--json")
    a = ap.parse_args()
    s, frag, t, rings = summary(a.history)
    print("fragments at %.1f us: %d, of which %d heavier than 1 g (Vogler et al. 2003: 14); the largest "
          "%.2f g, %.0f %% of the tube's %.2f g (Vogler et al.: about half the tube stayed intact)"
          % (s["time"] * 1e6, s["fragments"], s["heavier_than_1g"], s["largest_mass"] * 1e3,
             100 * s["largest_fraction"], s["tube_mass"] * 1e3))
    for name, r in s["rings"].items():
        print("ring %s: peak radial velocity %.0f m/s at %.1f us, radial displacement at the end %.2f mm"
              % (name, r["peak_radial_velocity"], r["peak_time"] * 1e6, r["final_radial_displacement"] * 1e3))
    if a.plot:
        plot(a.plot, frag, t, rings, s)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(s, f, indent=1)


if __name__ == "__main__":
    main()
