#!/usr/bin/env python3
"""Necking of a round tensile bar (inputs/necking.yaml, docs/examples/necking.md): the closed
form, CalculiX on perifem's mesh, the comparison and the plot.

  necking.py considere
      the homogeneous bar's engineering-stress peak and the strain at it (below).
  necking.py inp PERIFEM.e CCX.inp [--steps N]
      a CalculiX static deck (NLGEOM, C3D8I) on the mesh of perifem's Exodus output: the same
      elastic constants and the same hardening curve A + B eqps^n (Johnson-Cook with the rate
      and temperature terms off) as a *PLASTIC table, the end z = 0 held, the end z = L moved
      along z by the deck's stretch x L in N equal increments (the deck's load steps).
  necking.py report PERIFEM.e [--ccx CCX.dat] [--bands] [--csv FILE]
      the engineering stress F / A0 against the engineering strain d / L of each run (F: minus
      the internal force summed over the pulled end's nodes; A0: the mesh's cross-section, its
      volume / L), the peak and the strain at it beside the closed form; the neck (the outer
      surface's smallest radius over its largest one in the gauge's middle three quarters) at
      the strain --neck-at (0.09) and at the end. With --bands: exit 1 unless, for each run,
      the peak is within 2 % of the closed form's (when the run has passed its peak) and every
      load step up to the peak within 2 % of the homogeneous bar at its strain (past 1.2 times
      the yield strain), and, with --ccx, the first run's load steps up to its peak within 2 % of
      CalculiX's.
  necking.py plot OUT.png PERIFEM.e [PERIFEM2.e ...] [--ccx CCX.dat]

The closed form (Considere 1885): a bar that stays homogeneous carries F = sigma A, A the
current section; F is largest where d ln sigma = -d ln A. With sigma = A_jc + B e^n (e the
plastic strain), an elastic axial strain sigma / E and lateral strain -nu sigma / E (small
elastic strains, logarithmic strains throughout), A = A0 exp(-e - 2 nu sigma / E), so the
engineering stress is S(e) = sigma(e) exp(-e - 2 nu sigma(e) / E), largest where
d sigma / d e = sigma / (1 - 2 nu sigma / E); without elasticity this is n B e^(n-1) = A + B e^n,
e = 0.0619 for the deck's steel. The engineering strain at the peak is exp(e + sigma / E) - 1.
"""
import argparse
import re
import sys

import numpy as np

# inputs/necking.yaml: 4340 steel, Johnson & Cook (1983) Table 1 (rate and temperature off)
E, NU = 200.0e9, 0.29
A_JC, B_JC, N_JC = 792.0e6, 510.0e6, 0.26
L, R = 24.0e-3, 3.0e-3


def flow(e):
    return A_JC + B_JC * np.power(e, N_JC)


def homogeneous(e):
    """Engineering strain and stress of the homogeneous bar at plastic strain e (docstring)."""
    s = flow(e)
    return np.expm1(e + s / E), s * np.exp(-e - 2 * NU * s / E)


def homogeneous_at(strain):
    """The homogeneous bar's engineering stress at engineering strain `strain` (bisection on e)."""
    lo, hi = 0.0, max(strain, 1e-12)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if homogeneous(mid)[0] < strain else (lo, mid)
    return float(homogeneous(0.5 * (lo + hi))[1])


def considere():
    """The peak of the homogeneous engineering stress: bisection on dS/de = 0."""
    lo, hi = 1e-8, 1.0
    dS = lambda e: np.diff(homogeneous(np.array([e * (1 - 1e-7), e * (1 + 1e-7)]))[1])[0]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if dS(mid) > 0 else (lo, mid)
    e = 0.5 * (lo + hi)
    strain, stress = homogeneous(e)
    return e, float(strain), float(stress)


def read_exodus(path):
    import netCDF4
    with netCDF4.Dataset(path) as d:
        X = np.stack([np.asarray(d[c][:], dtype=float) for c in ("coordx", "coordy", "coordz")], axis=1)
        conn = [np.asarray(d[k][:], dtype=np.int64) - 1 for k in sorted(d.variables)
                if re.fullmatch(r"connect\d+", k)]
        names = [b"".join(n).decode().strip("\x00") for n in d["name_nod_var"][:]]
        var = lambda n: np.asarray(d["vals_nod_var%d" % (names.index(n) + 1)][:], dtype=float)
        t = np.asarray(d["time_whole"][:], dtype=float)
        u = np.stack([var("displacement_" + c) for c in "xyz"], axis=2)   # [step, node, 3]
        fz = var("force_z")
    return X, (np.concatenate(conn) if conn else None), t, u, fz


def run_curve(path):
    """Engineering strain and stress at each output step, the section A0 and the neck ratio."""
    X, conn, t, u, fz = read_exodus(path)
    top = X[:, 2] > L - 1e-9
    d = u[:, top, 2].mean(axis=1)
    if conn is not None and conn.shape[1] == 8:
        A0 = section_area(X, conn)
    else:  # points of a polar lattice, which tiles the cylinder of radius R exactly
        A0 = np.pi * R ** 2
    S = -fz[:, top].sum(axis=1) / A0
    # the neck: the outer surface's smallest radius over its largest one, within the gauge's
    # middle three quarters (1: no neck), at each output step
    r0 = np.hypot(X[:, 0], X[:, 1])
    outer = (r0 > r0.max() * (1 - 1e-6)) & (np.abs(X[:, 2] - L / 2) < 3 * L / 8)
    x = X[None, outer] + u[:, outer]
    r = np.hypot(x[:, :, 0], x[:, :, 1])
    neck, zneck = r.min(axis=1) / r.max(axis=1), x[-1, np.argmin(r[-1]), 2]
    return dict(t=t, e=d / L, S=S, A0=A0, neck=neck, zneck=zneck)


def section_area(X, conn):
    """The mesh's volume / L: each hexahedron as six tetrahedra about its 0-6 diagonal."""
    x = X[conn]
    vol = 0.0
    for a, b in ((1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1)):
        vol += np.einsum("ei,ei->e", x[:, a] - x[:, 0],
                         np.cross(x[:, b] - x[:, 0], x[:, 6] - x[:, 0])).sum() / 6
    return abs(vol) / L


def read_ccx(path, nsteps):
    """The pulled end's total reaction along z at each increment (*NODE PRINT, TOTALS=ONLY)."""
    text = open(path).read()
    blocks = re.findall(r"total force \(fx,fy,fz\) for set TOP and time\s+(\S+)\s*\n\s*\n?\s*(\S+)\s+(\S+)\s+(\S+)", text)
    t = np.array([float(b[0]) for b in blocks])
    fz = np.array([float(b[3]) for b in blocks])
    return t, fz


def homogeneous_deviation(c, k):
    """The largest |S / S_homogeneous - 1| over the steps up to k past 1.2 times the yield strain."""
    yield_strain = np.expm1(A_JC / E)
    devs = [abs(c["S"][i] / homogeneous_at(c["e"][i]) - 1) for i in range(1, k + 1)
            if c["e"][i] > 1.2 * yield_strain]
    return max(devs) if devs else float("nan")


def cmd_considere(a):
    e, strain, stress = considere()
    print("homogeneous bar: engineering-stress peak %.6g MPa at plastic strain %.6g, "
          "engineering strain %.6g" % (stress / 1e6, e, strain))


def cmd_inp(a):
    X, conn = read_exodus(a.exodus)[:2]
    lines = ["** necking of a round bar: CalculiX on perifem's mesh (scripts/necking.py inp)",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {X[i, 0]:.13g}, {X[i, 1]:.13g}, {X[i, 2]:.13g}" for i in range(len(X))]
    lines.append("*ELEMENT, TYPE=C3D8I, ELSET=EALL")
    lines += [f"{e + 1}, " + ", ".join(str(int(k) + 1) for k in conn[e]) for e in range(len(conn))]
    for name, mask in (("BOTTOM", X[:, 2] < 1e-9), ("TOP", X[:, 2] > L - 1e-9)):
        ids = np.where(mask)[0] + 1
        lines.append(f"*NSET, NSET={name}")
        lines.extend(", ".join(str(i) for i in ids[k:k + 8]) for k in range(0, len(ids), 8))
    # 81 points: CalculiX 2.20 does not read a long table whole (measured: with 401 points from
    # 1e-6 the first load step carried 7 % less stress than with 41 or 81, which agree)
    ep = np.concatenate([[0.0], np.geomspace(1e-5, 2.0, 80)])
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:.6g}, {NU}", "*PLASTIC"]
    lines += [f"{flow(e):.10g}, {e:.10g}" for e in ep]
    dz = a.stretch * L
    lines += ["*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              "*STEP, NLGEOM, INC=100000", "*STATIC, DIRECT", f"{1.0 / a.steps:.10g}, 1.0",
              "*BOUNDARY", "BOTTOM, 1, 3, 0", "TOP, 1, 2, 0", f"TOP, 3, 3, {dz:.10g}",
              "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF", "*NODE FILE", "U", "*END STEP"]
    with open(a.inp, "w") as f:
        f.write("\n".join(lines) + "\n")


def peak(e, S):
    k = int(np.argmax(S))
    return k, float(e[k]), float(S[k])


def cmd_report(a):
    e_p, e_ref, S_ref = considere()
    print("closed form (homogeneous bar, Considere): peak %.2f MPa at engineering strain %.4f" %
          (S_ref / 1e6, e_ref))
    ok = True
    runs = [(p, run_curve(p)) for p in a.perifem]
    for p, c in runs:
        k, ek, Sk = peak(c["e"], c["S"])
        at = np.argmin(np.abs(c["e"] - a.neck_at))
        print("%s: peak %.2f MPa (%+.2f %% of the closed form) at engineering strain %.4f "
              "(closed form %.4f); neck (smallest / largest radius) %.4f at strain %.4f, %.4f at "
              "%.4f, at z = %.2f mm" % (p, Sk / 1e6, 100 * (Sk / S_ref - 1), ek, e_ref, c["neck"][at],
                                        c["e"][at], c["neck"][-1], c["e"][-1], 1e3 * c["zneck"]))
        if a.bands and k == len(c["e"]) - 1:
            print("(the last load step carries the most: no peak yet; its stress is not compared with the peak's)")
        elif a.bands and not abs(Sk / S_ref - 1) < 0.02:
            print("FAIL: the peak is off the closed form by more than 2 %"); ok = False
        dev = homogeneous_deviation(c, k)
        print("  up to the peak, largest difference from the homogeneous bar: %.3f %%" % (100 * dev))
        if a.bands and not dev < 0.02:
            print("FAIL: off the homogeneous bar by more than 2 % before the peak"); ok = False
    if a.ccx:
        c = runs[0][1]
        t, fz = read_ccx(a.ccx, len(c["t"]))
        Sc = np.abs(fz) / c["A0"]
        kc, ekc, Skc = peak(t * a.stretch, Sc)
        print("CalculiX: peak %.2f MPa (%+.2f %% of the closed form) at engineering strain %.4f" %
              (Skc / 1e6, 100 * (Skc / S_ref - 1), ekc))
        k = peak(c["e"], c["S"])[0]
        worst = 0.0
        for i in range(1, k + 1):
            j = np.argmin(np.abs(t - c["t"][i]))
            if abs(t[j] - c["t"][i]) > 1e-6:
                continue
            dev = abs(c["S"][i] / Sc[j] - 1)
            worst = max(worst, dev)
            if a.verbose:
                print("  t %.4f: perifem %.2f MPa, CalculiX %.2f MPa (%+.3f %%)" %
                      (c["t"][i], c["S"][i] / 1e6, Sc[j] / 1e6, 100 * (c["S"][i] / Sc[j] - 1)))
        print("perifem against CalculiX up to the peak: largest difference %.3f %%" % (100 * worst))
        after = [abs(c["S"][i] / Sc[j] - 1) for i in range(k + 1, len(c["t"]))
                 for j in [int(np.argmin(np.abs(t - c["t"][i])))] if abs(t[j] - c["t"][i]) < 1e-6]
        if after:
            print("after the peak (not compared with a band): largest difference %.3f %%" % (100 * max(after)))
        if a.bands and not worst < 0.02:
            print("FAIL: perifem is off CalculiX by more than 2 % before the peak"); ok = False
    if a.csv:
        with open(a.csv, "w") as f:
            for p, c in runs:
                for x, s in zip(c["e"], c["S"]):
                    f.write("%s,%.8g,%.8g\n" % (p, x, s))
    return 0 if ok else 1


def cmd_plot(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ep = np.linspace(1e-6, 0.3, 600)
    eh, Sh = homogeneous(ep)
    ax.plot(eh, Sh / 1e6, "k:", label="homogeneous bar (closed form)")
    e_p, e_ref, S_ref = considere()
    ax.plot([e_ref], [S_ref / 1e6], "ko", label="Considère peak")
    for p, lab in zip(a.perifem, a.labels or a.perifem):
        c = run_curve(p)
        ax.plot(c["e"], c["S"] / 1e6, "-", marker=".", label=lab)
    if a.ccx:
        c = run_curve(a.perifem[0])
        t, fz = read_ccx(a.ccx, 0)
        ax.plot(t * a.stretch, np.abs(fz) / c["A0"] / 1e6, "--", label="CalculiX (C3D8I)")
    ax.set_xlim(0, a.stretch)
    ax.set_ylim(0.5 * A_JC / 1e6, 1.08 * S_ref / 1e6)
    ax.set_xlabel("engineering strain d / L")
    ax.set_ylabel("engineering stress F / A0 (MPa)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("considere")
    p = sub.add_parser("inp")
    p.add_argument("exodus"), p.add_argument("inp")
    p.add_argument("--steps", type=int, default=24)
    p.add_argument("--stretch", type=float, default=0.12)
    p = sub.add_parser("report")
    p.add_argument("perifem", nargs="+")
    p.add_argument("--ccx"), p.add_argument("--csv")
    p.add_argument("--stretch", type=float, default=0.12)
    p.add_argument("--bands", action="store_true"), p.add_argument("--verbose", action="store_true")
    p.add_argument("--neck-at", type=float, default=0.09, help="the strain to compare the necks at")
    p = sub.add_parser("plot")
    p.add_argument("out"), p.add_argument("perifem", nargs="+")
    p.add_argument("--labels", nargs="*"), p.add_argument("--ccx")
    p.add_argument("--stretch", type=float, default=0.12)
    a = ap.parse_args()
    return {"considere": cmd_considere, "inp": cmd_inp, "report": cmd_report, "plot": cmd_plot}[a.cmd](a) or 0


if __name__ == "__main__":
    sys.exit(main())
