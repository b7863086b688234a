#!/usr/bin/env python3
"""The fibre-matrix cell (inputs/fibre_rve.yaml, docs/examples/fibre_rve.md): a picture of the
run and of the moduli the test measures.

  fibre_rve.py plot RUN.e TEST.log OUT.png [--a 1e-3] [--vf 0.5]
      left: the strain eps_xx over eps on the cell's layer of the deck's run X (RUN.e, its last
      frame), from the points' displacement_x by central differences along x on the lattice
      (spacing h, read from the coordinates), with the fibre's circle (radius a sqrt(vf / pi));
      right: E1 and E2 of the FE and PD cells beside the rule of mixtures and CalculiX, read from
      the lines "fe n N: E1 ... GPa (rule of mixtures ..., ...), E2 ... GPa (ccx ..., ...)" and
      "pd n N: ..." that `PF_TEST_VERBOSE=1 test_fibre_rve` prints (TEST.log).
"""
import argparse
import re
import sys

import numpy as np


def read_run(path):
    """The points' coordinates and the last frame's displacement_x."""
    import netCDF4
    with netCDF4.Dataset(path) as e:
        names = ["".join(c.decode() for c in n if c) for n in e["name_nod_var"][:].data]
        X = np.stack([np.asarray(e[c][:]) for c in ("coordx", "coordy", "coordz")], axis=1)
        ux = np.asarray(e["vals_nod_var%d" % (names.index("displacement_x") + 1)][-1])
    return X, ux


def strain_xx(X, ux, a):
    """eps_xx at the cell's points of the layer z = h / 2 (central differences along x), with
    their x, y; h the lattice spacing and eps the layer's mean strain (the points beyond the
    face x = a follow u_x = eps x)."""
    h = np.min(np.diff(np.unique(np.round(X[:, 0], 12))))
    layer = np.abs(X[:, 2] - h / 2) < 1e-3 * h
    i = np.rint(X[layer, 0] / h - 0.5).astype(int)
    j = np.rint(X[layer, 1] / h - 0.5).astype(int)
    i0, j0 = i.min(), j.min()
    U = np.full((i.max() - i0 + 1, j.max() - j0 + 1), np.nan)
    U[i - i0, j - j0] = ux[layer]
    E = (U[2:, :] - U[:-2, :]) / (2 * h)  # at the lattice's rows i0 + 1 .. i.max() - 1
    n = int(round(a / h))
    ii, jj = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    e = E[ii - i0 - 1, jj - j0]
    mean = np.nanmean(U[n - i0, :]) / ((n + 0.5) * h)  # the first layer beyond x = a: u_x = eps x
    return (ii + 0.5) * h, (jj + 0.5) * h, e, mean, n


def read_moduli(path):
    """{fe, pd: (E1, rule of mixtures, E2, CalculiX)} in GPa from the test's verbose lines."""
    pat = re.compile(r"^(fe|pd) n (\d+): E1 (\S+) GPa \(rule of mixtures (\S+), \S+ %\), E2 (\S+) GPa \(ccx (\S+), \S+ %\)")
    out = {}
    for line in open(path):
        m = pat.match(line)
        if m:
            out[m.group(1)] = tuple(float(m.group(k)) for k in (3, 4, 5, 6))
            out["n"] = int(m.group(2))
    if "fe" not in out or "pd" not in out:
        sys.exit(f"{path}: no 'fe n ...' and 'pd n ...' lines (run the test with PF_TEST_VERBOSE=1)")
    return out


def cmd_plot(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    X, ux = read_run(a.exodus)
    e, eps, n = strain_xx(X, ux, a.a)[2:]
    mod = read_moduli(a.log)
    fig = plt.figure(figsize=(10, 4.4))
    ax = fig.add_axes([0.05, 0.12, 0.36, 0.78])
    edges = np.arange(n + 1) * a.a / n * 1e3
    sc = ax.pcolormesh(edges, edges, (e / eps).T, cmap="viridis", shading="flat")
    r = a.a * np.sqrt(a.vf / np.pi)
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot((a.a / 2 + r * np.cos(t)) * 1e3, (a.a / 2 + r * np.sin(t)) * 1e3, "w-", lw=1.2)
    ax.set_aspect("equal")
    ax.set_xlim(0, a.a * 1e3), ax.set_ylim(0, a.a * 1e3)
    ax.set_xlabel("x (mm)"), ax.set_ylabel("y (mm)")
    ax.set_title(rf"LPS cell, run X: $\varepsilon_{{xx}}/\bar\varepsilon$ ({n} x {n} points)", fontsize=10)
    fig.colorbar(sc, ax=ax, fraction=0.046, pad=0.03)
    labels = ["rule of\nmixtures", "FE", "LPS", "CalculiX", "FE", "LPS"]
    fe, pd = mod["fe"], mod["pd"]
    for k, (vals, ref, title, cols) in enumerate(
            (((fe[1], fe[0], pd[0]), "rule of mixtures", r"$E_1$ (GPa), along the fibres", ("0.5", "C0", "C1")),
             ((fe[3], fe[2], pd[2]), "CalculiX", r"$E_2$ (GPa), across the fibres", ("0.5", "C0", "C1")))):
        axb = fig.add_axes([0.53 + 0.24 * k, 0.12, 0.19, 0.78])
        bars = axb.bar(range(3), vals, color=cols)
        for b, v in zip(bars, vals):
            dev = "" if b is bars[0] else f"\n{100 * (v / vals[0] - 1):+.2f} %"
            axb.text(b.get_x() + b.get_width() / 2, v, f"{v:.4g}{dev}", ha="center", va="bottom", fontsize=8)
        axb.set_xticks(range(3))
        axb.set_xticklabels(labels[3 * k:3 * k + 3], fontsize=8)
        axb.set_ylim(0, 1.25 * max(vals))
        axb.set_title(title, fontsize=10)
    fig.suptitle(f"Fibre-matrix cell, fibre fraction 0.5 (T300 / 914C epoxy), {mod['n']} x {mod['n']}: "
                 "against the rule of mixtures and CalculiX")
    fig.savefig(a.png, dpi=100)
    print(f"eps_xx / eps on the cell: {np.nanmin(e) / eps:.3g} .. {np.nanmax(e) / eps:.3g}; wrote {a.png}")
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    s = p.add_subparsers(dest="cmd", required=True)
    c = s.add_parser("plot")
    c.add_argument("exodus")
    c.add_argument("log")
    c.add_argument("png")
    c.add_argument("--a", type=float, default=1e-3)
    c.add_argument("--vf", type=float, default=0.5)
    return cmd_plot(p.parse_args())


if __name__ == "__main__":
    sys.exit(main())
