#!/usr/bin/env python3
"""The single fibre's load-displacement curves (inputs/single_fibre.yaml,
docs/examples/single_fibre.md): the reaction of the cell against its strain, one curve a run.

  single_fibre.py OUT.png RUN.h5 [RUN.h5 ...] [--ccx K_BONDED,K_HOLE] [--cell A]
  single_fibre.py OUT.png TEST.log [--ccx K_BONDED,K_HOLE]

Each RUN.h5 is a run's history and RUN.e, beside it, its Exodus output; or TEST.log, the output
of `PF_TEST_VERBOSE=1 test_single_fibre 16 curve` (its lines `curve LAW M STRAIN LOAD DAMAGE`:
the same runs, both laws at both horizons). The load is the history's
mx_reaction_x (the reaction of the roller layer beyond x = A); the cell strain is the layer's
mean displacement mx_displacement_x over its points' mean reference x, read from RUN.e (every
point of the layer follows u_x = e x). A curve is labelled by its file's stem. --ccx draws the
lines F = k e A of CalculiX's cell with the fibre bonded and with the fibre a hole (N/m, as
verification/test_single_fibre prints them). Prints, per run, the debond load (the largest load
before the largest drop) and the tangent over the last four load steps.
"""
import argparse
import os

import numpy as np


def layer_mean_x(exodus, a):
    """The mean reference x of the points of the condition mx: x > a, 0 < y < a, 0 < z < h."""
    import netCDF4
    with netCDF4.Dataset(exodus) as d:
        x, y, z = (np.asarray(d[c][:], dtype=float) for c in ("coordx", "coordy", "coordz"))
    h = np.diff(np.unique(np.round(z / a, 9) * a)).min()
    mx = (x > a) & (y > 0) & (y < a) & (z > 0) & (z < h)
    return x[mx].mean()


def read_run(path, a):
    import h5py
    with h5py.File(path, "r") as f:
        R = np.asarray(f["mx_reaction_x"][:], dtype=float)
        u = np.asarray(f["mx_displacement_x"][:], dtype=float)
    return u / layer_mean_x(os.path.splitext(path)[0] + ".e", a), R


def read_log(path):
    """The curves of verification/test_single_fibre_curve's verbose output, by law and horizon."""
    curves = {}
    for line in open(path):
        w = line.split()
        if len(w) == 6 and w[0] == "curve":
            name = "%s, horizon %s h" % (("critical stretch", "critical energy")[int(w[1])], w[2])
            curves.setdefault(name, []).append((float(w[3]), float(w[4])))
    return [(name, *map(np.array, zip(*rows))) for name, rows in curves.items()]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("runs", nargs="+")
    p.add_argument("--ccx", help="K_BONDED,K_HOLE: CalculiX's stiffnesses, N/m")
    p.add_argument("--cell", type=float, default=1e-3, help="the cell's side A, m (1e-3)")
    args = p.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5), dpi=125)
    emax = 0
    runs = []
    for path in args.runs:
        if path.endswith(".log"):
            runs += read_log(path)
        else:
            runs.append((os.path.splitext(os.path.basename(path))[0], *read_run(path, args.cell)))
    for name, e, R in runs:
        fall = int(np.argmax(R[:-1] - R[1:]))  # the largest drop: the debond runs
        drop = int(np.argmax(R[:fall + 1])) if R[fall + 1] < R[fall] else None  # the peak before it
        tangent = (R[-1] - R[-5]) / ((e[-1] - e[-5]) * args.cell)
        peak = "no drop" if drop is None else "debond load %.4g N at strain %.4g" % (R[drop], e[drop])
        print("%s: %s; tangent at the end %.4g N/m" % (name, peak, tangent))
        ax.plot(e * 1e3, R, ".-", label=name)
        emax = max(emax, e.max())
    if args.ccx:
        for k, style, what in zip(map(float, args.ccx.split(",")), ("k--", "k:"),
                                  ("CalculiX, fibre bonded", "CalculiX, fibre a hole")):
            ax.plot([0, emax * 1e3], [0, k * emax * args.cell], style, lw=1, label=what)
    ax.set_xlabel("cell strain across the fibre (1e-3)")
    ax.set_ylabel("load on the cell's face (N, one spacing thick)")
    ax.set_ylim(0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out)


if __name__ == "__main__":
    main()
