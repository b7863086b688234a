"""Plots of double cantilever beam runs (inputs/dcb.yaml): force against opening, and the
recovered energy release rate against the horizon with Willberg's published values.

    /usr/bin/python3 scripts/dcb_plot.py OUT.png LABEL:M:H5:JSON [LABEL:M:H5:JSON ...]

Each run is given as its label, its horizon in spacings m, its history file and the line that
scripts/dcb_energy_release.py --json printed for it, saved to a file. Labels that start with
"energy" are drawn as the critical-energy law, the others as critical stretch; a label ending
in "willberg" (the critical stretch of Willberg's slides) gets an open marker.
"""
import json
import math
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

G0 = 12.0
# Willberg's DCB table (DLR slides): G0 recovered at the four horizons, two columns
WILLBERG_M = [2.01, 3.01, 4.01, 5.01]
WILLBERG_A = [12.8, 13.1, 11.1, 11.2]
WILLBERG_B = [11.4, 12.9, 11.3, 11.9]


def slab_share(m, layers=6):
    """Bonds crossing a plane per unit area on the cubic lattice of `layers` layers through the
    thickness (offsets (i, j, k), j > 0, within m spacings), over the continuum's pi m^4 / 4."""
    r = int(m)
    off = [(i, j, k) for i in range(-r, r + 1) for j in range(1, r + 1) for k in range(-r, r + 1)
           if i * i + j * j + k * k <= m * m]
    s = sum(j for i, j, k in off for kz in range(layers) if 0 <= kz + k < layers) / layers
    return s / (math.pi * m ** 4 / 4)


def main():
    out, runs = sys.argv[1], [a.split(":") for a in sys.argv[2:]]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    for label, m, h5, js in runs:
        with h5py.File(h5, "r") as f:
            force = 0.5 * (f["upper_reaction_y"][:] - f["lower_reaction_y"][:])
            opening = f["probe_upper_displacement_y"][:] - f["probe_lower_displacement_y"][:]
        energy = label.startswith("energy")
        ax1.plot(1e6 * opening, force, "-" if energy else "--", lw=1, label="%s, m = %s" % (label, m))
        g = json.load(open(js))["G"]
        ax2.plot([float(m)], [g], "o" if energy else "s", color="C0" if energy else "C1", ms=8,
                 mfc="none" if label.endswith("willberg") else None)
    ax1.set_xlabel("opening of the grips, both arms [um]")
    ax1.set_ylabel("force on each arm [N]")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=8)
    ms = np.linspace(1.9, 5.2, 200)
    ax2.plot(WILLBERG_M, WILLBERG_A, "k^", label="Willberg, table column 1")
    ax2.plot(WILLBERG_M, WILLBERG_B, "kv", label="Willberg, table column 2")
    ax2.plot([], [], "o", color="C0", label="perifem, critical energy")
    ax2.plot([], [], "s", color="C1", label="perifem, critical stretch (LPS closed form)")
    ax2.plot([], [], "s", color="C1", mfc="none", label="perifem, critical stretch (Willberg's s_c)")
    lat = [2.01, 3.015, 4.01, 5.01]
    ax2.plot(lat, [G0 * slab_share(m) for m in lat], "x", color="C0", ms=9,
             label="critical energy: G0 x the lattice's crossing bonds (6 layers)")
    ax2.axhline(G0, color="k", lw=0.8)
    ax2.fill_between(ms, 0.9 * G0, 1.1 * G0, color="k", alpha=0.08, label="G0 = 12 J/m^2 +- 10 %")
    ax2.set_xlabel("horizon / spacing")
    ax2.set_ylabel("recovered G [J/m^2]")
    ax2.set_ylim(7.5, 19.5)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
