#!/usr/bin/env python3
"""The [0/90]s laminate in tension (inputs/laminate.yaml, docs/examples/laminate.md) against
classical laminate theory (CLT; docs/theory/laminate.md §2), from the run's own output.

  laminate.py check RUN.h5 [--band 0.02]
      the laminate's A11 = N_x / eps_x and A21 = N_y / eps_x from the history's last row: the
      reactions of the faces x = L (fx_reaction_x) and y = L (fy_reaction_y) over the face's
      width L, eps_x = fx_displacement_x / L (the plate is square, so A11 = fx_reaction_x /
      fx_displacement_x); exit 1 unless both are within --band of CLT's A11 = 2 t (Q11 + Q22) and
      A21 = 4 t Q12.
  laminate.py plot RUN.h5 RUN.e OUT.png
      left: N_x against eps_x at each load step, beside CLT's line N_x = A11 eps_x; right: the
      nodal sigma_xx and sigma_yy of the last frame through the thickness, beside CLT's ply
      stresses (0 plies: sigma_x = Q11 eps, 90 plies: Q22 eps; both sigma_y = Q12 eps, as
      eps_y = 0). The nodes of the ply interfaces z = +-t are the mean of two plies' elements.

The lamina's constants and CLT are scripts/laminate_hole.py's (T300/914C, Soden, Hinton & Kaddour
1998; Jones 1999, sec. 2.5, 4.2).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import laminate_hole as lh  # noqa: E402


def clt_a():
    """CLT's A11 and A21 of the [0/90]s laminate (N/m) and the plies' (Qbar11, Qbar12)."""
    q = lh.clt()[3]
    return 2 * lh.TP * (q[0][0] + q[90][0]), 4 * lh.TP * q[0][1], q


def history(path):
    import h5py
    with h5py.File(path, "r") as h:
        return {k: np.asarray(h[k][:], dtype=float) for k in ("fx_reaction_x", "fy_reaction_y", "fx_displacement_x")}


def measured(h):
    """A11, A21 from the last row (a square plate: the width over the length cancels)."""
    u = h["fx_displacement_x"][-1]
    return h["fx_reaction_x"][-1] / u, h["fy_reaction_y"][-1] / u


def cmd_check(a):
    a11, a21 = measured(history(a.history))
    c11, c21 = clt_a()[:2]
    ok = True
    for name, got, want in (("A11", a11, c11), ("A21", a21, c21)):
        dev = got / want - 1
        print(f"{name}: {got / 1e6:.6g} MN/m (CLT {want / 1e6:.6g}, {dev:+.1e})")
        if not abs(dev) < a.band:
            print(f"FAIL: {name} is {100 * dev:+.3f} % from CLT (band {100 * a.band:g} %)")
            ok = False
    return 0 if ok else 1


def nodal(path):
    """Coordinates and the last frame's nodal variables of an Exodus file."""
    import netCDF4
    with netCDF4.Dataset(path) as e:
        names = ["".join(c.decode() for c in n if c) for n in e["name_nod_var"][:].data]
        X = np.stack([np.asarray(e[c][:]) for c in ("coordx", "coordy", "coordz")], axis=1)
        v = {n: np.asarray(e["vals_nod_var%d" % (k + 1)][-1]) for k, n in enumerate(names)}
    return X, v


def cmd_plot(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    h = history(a.history)
    X, v = nodal(a.exodus)
    L = X[:, 0].max() - X[:, 0].min()
    c11, c21, q = clt_a()
    eps = h["fx_displacement_x"] / L
    a11, a21 = measured(h)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.2))
    e = np.linspace(0, eps[-1], 2)
    ax1.plot(e * 1e6, c11 * e / 1e3, "k-", label=f"CLT $A_{{11}}$ = {c11 / 1e6:.3f} MN/m")
    ax1.plot(e * 1e6, c21 * e / 1e3, "k--", label=f"CLT $A_{{21}}$ = {c21 / 1e6:.4f} MN/m")
    ax1.plot(eps * 1e6, h["fx_reaction_x"] / L / 1e3, "o", color="C0",
             label=f"perifem $N_x$ ($A_{{11}}$ {a11 / c11 - 1:+.1e})")
    ax1.plot(eps * 1e6, h["fy_reaction_y"] / L / 1e3, "s", color="C1",
             label=f"perifem $N_y$ ($A_{{21}}$ {a21 / c21 - 1:+.1e})")
    ax1.set_xlabel(r"$\varepsilon_x$ (1e-6)")
    ax1.set_ylabel("force per width (N/mm)")
    ax1.set_title("reactions at each load step")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    z = X[:, 2] * 1e3
    e_end = eps[-1]
    ax2.plot(v["stress_xx"] / 1e6, z, "o", color="C0", ms=4, label=r"perifem $\sigma_{xx}$ (nodes)")
    ax2.plot(v["stress_yy"] / 1e6, z, "s", color="C1", ms=4, label=r"perifem $\sigma_{yy}$ (nodes)")
    t = lh.TP * 1e3
    sx = {0: q[0][0] * e_end, 90: q[90][0] * e_end}
    zs = [-2 * t, -t, t, 2 * t]
    for k, (z0, z1, ply) in enumerate(((zs[0], zs[1], 0), (zs[1], zs[2], 90), (zs[2], zs[3], 0))):
        ax2.plot([sx[ply] / 1e6] * 2, [z0, z1], "k-", label=r"CLT $\sigma_x$ per ply" if k == 0 else None)
        ax2.plot([q[ply][1] * e_end / 1e6] * 2, [z0, z1], "k--", label=r"CLT $\sigma_y$" if k == 0 else None)
    for zz in zs[1:3]:
        ax2.axhline(zz, color="0.7", lw=0.8)
    ax2.text(sx[0] / 1e6, 1.5 * t, "0° ", va="center", ha="right")
    ax2.text(sx[90] / 1e6, 0.5 * t, " 90°", va="center")
    ax2.set_xlim(-0.05 * sx[0] / 1e6, 1.1 * sx[0] / 1e6)
    ax2.set_xlabel("stress (MPa)")
    ax2.set_ylabel("z (mm)")
    ax2.set_title(rf"through the thickness at $\varepsilon_x$ = {e_end:.0e} (interfaces: two plies' mean)", fontsize=10)
    ax2.legend(fontsize=8, loc="lower right")
    fig.suptitle("[0/90]s T300/914C laminate, FE plies, in tension: against classical laminate theory")
    fig.tight_layout()
    fig.savefig(a.png, dpi=100)
    print(f"A11 {a11 / 1e6:.6g} MN/m (CLT {c11 / 1e6:.6g}), A21 {a21 / 1e6:.6g} MN/m (CLT {c21 / 1e6:.6g}); wrote {a.png}")
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    s = p.add_subparsers(dest="cmd", required=True)
    c = s.add_parser("check")
    c.add_argument("history")
    c.add_argument("--band", type=float, default=0.02)
    c = s.add_parser("plot")
    c.add_argument("history")
    c.add_argument("exodus")
    c.add_argument("png")
    a = p.parse_args()
    return cmd_check(a) if a.cmd == "check" else cmd_plot(a)


if __name__ == "__main__":
    sys.exit(main())
