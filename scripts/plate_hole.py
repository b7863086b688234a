#!/usr/bin/env python3
"""The plate with a hole (inputs/plate_hole.yaml, docs/examples/plate_hole.md): CalculiX on
perifem's mesh, the stress concentration, the comparisons and the plot.

  plate_hole.py inp PERIFEM.e CCX.inp [--d 7.5e-6]
      a CalculiX static deck on the mesh of perifem's Exodus output: C3D8 (2x2x2 Gauss points),
      linear elastic E = 200 GPa, nu = 0.3, the ends x = +-L/2 moved by -+d along x, and the
      symmetry lines of the end faces held in y (y = 0) and z (z = 0) against rigid motions
      (zero reactions by symmetry; perifem needs no such constraint: no force drives them).
  plate_hole.py report PERIFEM.e [--ccx CCX.dat] [--fe FE.e] [--table FILE] [--bands [--no-kt]]
      the concentration K = sigma_xx(hole edge, x = 0) / sigma_nom of each run, sigma_nom the
      ends' reaction F / (W t) (perifem: minus the force field summed over the end nodes; the
      coupled plate writes no stress where beta = 0) or, for CalculiX, the mean of sigma_xx over
      the node sections x = +-45 mm (equal to F / (W t) by equilibrium); with --bands,
      exit 1 unless the FE run (--fe, or PERIFEM.e) is within 1 % of CalculiX (edge stress, edge
      strain, displacement field) and each run's K within 3 % of Howland's 3.14 (--no-kt: the
      CalculiX band only, for a coarse mesh). Each run's K is also read from its displacements
      alone ("K strain", edge_strain_stress), as a strain gauge along the hole's edge reads it.
  plate_hole.py plot OUT.png PERIFEM.e [--ccx CCX.dat] [--fe FE.e]
      sigma_xx / sigma_nom along the ligament x = 0 against (r - a) / a, with Kirsch's curve.

Nodal stresses: perifem's Exodus field is, at each node, the volume-weighted mean of the
quadrature points' stresses of the elements round it (fem/body_assembly.c), and at a PD point
the correspondence stress of its own deformation gradient. CalculiX's Gauss-point stresses
(*EL PRINT) are averaged to the nodes by the same rule here, so both are read alike. The hole
edge's value: the nodes' stresses on the ligament at r > a (interior nodes, not one-sided)
fitted by Kirsch's form c0 + c1 s + c2 s^2, s = (a / r)^2, over the first four, and evaluated
at s = 1. Kirsch (1898), Howland (1930), Heywood (1952): docs/bibliography.md.
"""
import argparse
import re
import sys

import numpy as np

E, NU, W, L, T, A = 200.0e9, 0.3, 50e-3, 150e-3, 1e-3, 5e-3
KT_HOWLAND = 3.14                      # Howland (1930), 2a/W = 0.2 (gross section)
KT_HEYWOOD = (2 + (1 - 2 * A / W) ** 3) / (1 - 2 * A / W)   # Heywood (1952): 3.140


def read_exodus(path):
    import netCDF4
    with netCDF4.Dataset(path) as d:
        X = np.stack([np.asarray(d[c][:], dtype=float) for c in ("coordx", "coordy", "coordz")], axis=1)
        conn = np.concatenate([np.asarray(d[k][:], dtype=np.int64) - 1 for k in sorted(d.variables)
                               if re.fullmatch(r"connect\d+", k)])
        names = [b"".join(n).decode().strip("\x00") for n in d["name_nod_var"][:]]
        var = lambda n: np.asarray(d["vals_nod_var%d" % (names.index(n) + 1)][-1], dtype=float)
        u = np.stack([var("displacement_" + c) for c in "xyz"], axis=1)
        sxx = var("stress_xx")
        # the constant fields are nodal attributes, written once (core/output_exodus.c)
        anames = [b"".join(n).decode().strip("\x00") for n in d["nattrib_name"][:]] if "nattrib_name" in d.variables else []
        att = lambda n: np.asarray(d["nattrb"][:, anames.index(n)], dtype=float)
        beta = att("blending_weight") if "blending_weight" in anames else np.zeros(len(X))
        hor = att("horizon") if "horizon" in anames else np.zeros(len(X))
        fx = var("force_x")
    # the ends' reaction: minus the internal force on the prescribed nodes, as a mean stress
    right, left = X[:, 0] > L / 2 - 1e-9, X[:, 0] < -L / 2 + 1e-9
    react = (fx[left].sum() - fx[right].sum()) / (2 * W * T)
    return X, conn, u, sxx, beta, hor, react


def hex_volumes(X, conn):
    """Each element's volume by 2x2x2 Gauss quadrature of det J (trilinear hexahedron)."""
    xi = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                   [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    x = X[conn]                                    # [nel, 8, 3]
    vol = np.zeros(len(conn))
    g = 1 / np.sqrt(3)
    for p in xi * g:
        dN = np.empty((8, 3))                      # dN_I / dxi_a
        for a in range(3):
            o = [(1 + xi[:, b] * p[b]) for b in range(3) if b != a]
            dN[:, a] = xi[:, a] * o[0] * o[1] / 8
        J = np.einsum("eia,ib->eab", x, dN)
        vol += np.linalg.det(J)
    return vol


def read_ccx(path, X, conn):
    """Displacements (*NODE PRINT U) and the nodes' sigma_xx from the Gauss points (*EL PRINT S),
    averaged as perifem does."""
    u = np.full((len(X), 3), np.nan)
    s = {}
    mode = None
    with open(path) as f:
        for line in f:
            if "displacements (vx,vy,vz)" in line:
                mode = "u"
                continue
            if "stresses (elem, integ.pnt.,sxx" in line:
                mode = "s"
                continue
            p = line.split()
            if not p:
                continue
            try:
                if mode == "u" and len(p) == 4:
                    u[int(p[0]) - 1] = [float(v) for v in p[1:]]
                elif mode == "s" and len(p) == 8:
                    s.setdefault(int(p[0]) - 1, []).append(float(p[2]))
                else:
                    mode = None
            except ValueError:
                mode = None
    if np.isnan(u).any() or len(s) != len(conn):
        sys.exit(f"{path}: missing displacements or stresses (did ccx run?)")
    se = np.array([np.mean(s[e]) for e in range(len(conn))])
    v = hex_volumes(X, conn)
    num, den = np.zeros(len(X)), np.zeros(len(X))
    np.add.at(num, conn, (v * se)[:, None] * np.ones((1, 8)))
    np.add.at(den, conn, v[:, None] * np.ones((1, 8)))
    return u, num / den


def nominal(X, sxx):
    """The mean of sigma_xx over the node sections nearest x = +-45 mm (trapezoids in y, z)."""
    out = []
    for x0 in (-45e-3, 45e-3):
        xs = X[np.argmin(np.abs(X[:, 0] - x0)), 0]
        m = np.abs(X[:, 0] - xs) < 1e-9
        total = 0.0
        zs = np.unique(np.round(X[m, 2], 12))
        wz = np.array([(zs[min(k + 1, len(zs) - 1)] - zs[max(k - 1, 0)]) / 2 for k in range(len(zs))])
        for z, w in zip(zs, wz):
            mz = m & (np.abs(X[:, 2] - z) < 1e-9)
            o = np.argsort(X[mz, 1])
            y, f = X[mz, 1][o], sxx[mz][o]
            total += w * float(np.sum((f[1:] + f[:-1]) * np.diff(y)) / 2)
        out.append(total / (W * T))
    return float(np.mean(out))


def ligament(X):
    """The mid-plane nodes on x = 0 above and below the hole, by distance r from its centre."""
    m = (np.abs(X[:, 0]) < 1e-9) & (np.abs(X[:, 2]) < 1e-9)
    idx = np.where(m)[0]
    r = np.abs(X[idx, 1])
    return idx, r


def edge_points(X, sxx):
    """A PD point's own stress at the hole's edge (x = 0, r = a): the mean over the two edges'
    nodes through the thickness (each point's correspondence stress from its own family)."""
    m = (np.abs(X[:, 0]) < 1e-9) & (np.abs(np.abs(X[:, 1]) - A) < 1e-9)
    return float(np.mean(sxx[m]))


def edge_stress(X, sxx):
    """sigma_xx at the hole's edge (x = 0, r = a): the mean of the two sides' Kirsch-form fits."""
    idx, r = ligament(X)
    vals, raws = [], []
    for side in (1, -1):
        k = idx[np.sign(X[idx, 1]) == side]
        k = k[np.argsort(np.abs(X[k, 1]))]
        rr = np.abs(X[k, 1])
        s = (A / rr[1:5]) ** 2
        c = np.polyfit(s, sxx[k[1:5]], 2)
        vals.append(np.polyval(c, 1.0))
        raws.append(sxx[k[0]])
    return float(np.mean(vals)), float(np.mean(raws))


def edge_strain_stress(X, u):
    """sigma_xx at the hole's edge (x = 0, r = a) from the displacements alone: at the free edge
    sigma_rr = 0 and, in the thin plate, sigma_zz = 0, so sigma_xx = E eps_tt there, eps_tt the
    strain along the edge. It is read from the chords between the mid-plane's edge nodes k steps
    either side of the ligament's node (the change of their lengths; the chord's mean strain
    falls with its span squared, so (4 e_1 - e_2) / 3 is the node's), the mean of the two edges."""
    r = np.hypot(X[:, 0], X[:, 1])
    vals = []
    for side in (1, -1):
        m = (np.abs(r - A) < 1e-9) & (np.abs(X[:, 2]) < 1e-9) & (np.sign(X[:, 1]) == side)
        idx = np.where(m)[0]
        ang = np.abs(np.arctan2(X[idx, 1], X[idx, 0]) - side * np.pi / 2)
        idx = idx[np.argsort(ang)]  # the ligament's node, then its neighbours pair by pair

        def chord(k):
            i, j = idx[2 * k - 1], idx[2 * k]
            return np.linalg.norm(X[i] + u[i] - X[j] - u[j]) / np.linalg.norm(X[i] - X[j]) - 1
        vals.append(E * (4 * chord(1) - chord(2)) / 3)
    return float(np.mean(vals))


def cmd_inp(a):
    X, conn = read_exodus(a.exodus)[:2]
    lines = ["** plate with a hole: CalculiX on perifem's mesh (scripts/plate_hole.py inp)",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {X[i, 0]:.13g}, {X[i, 1]:.13g}, {X[i, 2]:.13g}" for i in range(len(X))]
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=EALL")
    lines += [f"{e + 1}, " + ", ".join(str(int(k) + 1) for k in conn[e]) for e in range(len(conn))]

    def nset(name, mask):
        ids = np.where(mask)[0] + 1
        lines.append(f"*NSET, NSET={name}")
        lines.extend(", ".join(str(i) for i in ids[k:k + 8]) for k in range(0, len(ids), 8))
    left, right = X[:, 0] < -L / 2 + 1e-9, X[:, 0] > L / 2 - 1e-9
    nset("LEFT", left)
    nset("RIGHT", right)
    nset("ENDY0", (left | right) & (np.abs(X[:, 1]) < 1e-9))
    nset("ENDZ0", (left | right) & (np.abs(X[:, 2]) < 1e-9))
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:.6g}, {NU}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              "*STEP", "*STATIC", "*BOUNDARY",
              f"LEFT, 1, 1, {-a.d:.10g}", f"RIGHT, 1, 1, {a.d:.10g}", "ENDY0, 2, 2, 0", "ENDZ0, 3, 3, 0",
              "*NODE PRINT, NSET=NALL", "U", "*EL PRINT, ELSET=EALL", "S", "*END STEP"]
    with open(a.inp, "w") as f:
        f.write("\n".join(lines) + "\n")


def measure(path):
    X, conn, u, sxx, beta, hor, sn = read_exodus(path)
    fit, raw = edge_stress(X, sxx)
    if beta.max() > 0:  # PD at the hole: the edge points' own stress (the interior zig-zags)
        fit = raw = edge_points(X, sxx)
    sn = sn if sn != 0 else float("nan")
    return dict(X=X, conn=conn, u=u, sxx=sxx, beta=beta, hor=hor, sn=sn, K=fit / sn, Kraw=raw / sn,
                Ke=edge_strain_stress(X, u) / sn)


def cmd_report(a):
    runs = {"perifem": measure(a.perifem)}
    if a.fe:
        runs["perifem FE"] = measure(a.fe)
    fe = runs.get("perifem FE", runs["perifem"])
    X, conn = fe["X"], fe["conn"]
    rows, ok = [], True
    if a.ccx:
        uc, sc = read_ccx(a.ccx, X, conn)
        sn = nominal(X, sc)
        fit, raw = edge_stress(X, sc)
        runs["CalculiX"] = dict(u=uc, sxx=sc, sn=sn, K=fit / sn, Kraw=raw / sn, Ke=edge_strain_stress(X, uc) / sn)
    print(f"{'run':<12} {'sigma_nom (Pa)':>15} {'K (fit)':>9} {'K/3.14-1':>9} {'K edge node':>12} {'K strain':>9}")
    for name, r in runs.items():
        print(f"{name:<12} {r['sn']:15.6g} {r['K']:9.4f} {r['K'] / KT_HOWLAND - 1:+9.4f} {r['Kraw']:12.4f} "
              f"{r['Ke']:9.4f}")
        rows.append((name, r["sn"], r["K"], r["K"] / KT_HOWLAND - 1))
        if not a.no_kt and not abs(r["K"] / KT_HOWLAND - 1) <= 0.03:
            print(f"  {name}: K = {r['K']:.4f} misses Howland's {KT_HOWLAND} by more than 3 %")
            ok = False
    if a.ccx:
        c = runs["CalculiX"]
        for name in [n for n in runs if n != "CalculiX"]:
            r = runs[name]
            du = np.abs(r["u"] - c["u"]).max() / np.abs(c["u"]).max()
            dk = r["K"] * r["sn"] / (c["K"] * c["sn"]) - 1
            de = r["Ke"] * r["sn"] / (c["Ke"] * c["sn"]) - 1
            print(f"{name} vs CalculiX: max |du| / max |u| = {du:.4g}, edge stress {dk:+.4g}, "
                  f"sigma_nom {r['sn'] / c['sn'] - 1:+.4g}, edge strain {de:+.4g}")
            if name == ("perifem FE" if a.fe else "perifem") and not (du <= 0.01 and abs(dk) <= 0.01 and abs(de) <= 0.01):
                print(f"  {name}: more than 1 % off CalculiX")
                ok = False
    print(f"Heywood's K = {KT_HEYWOOD:.4f}, Howland's {KT_HOWLAND}")
    if a.table:
        with open(a.table, "w") as f:
            f.write("run\tsigma_nom_Pa\tK\tK_vs_Howland\n")
            f.writelines(f"{n}\t{s:.6g}\t{k:.5f}\t{d:+.5f}\n" for n, s, k, d in rows)
    sys.exit(0 if ok or not a.bands else 1)


def cmd_plot(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = {"perifem, PD round the hole": measure(a.perifem)}
    if a.fe:
        runs["perifem, elements only"] = measure(a.fe)
    fe = list(runs.values())[-1]
    if a.ccx:
        uc, sc = read_ccx(a.ccx, fe["X"], fe["conn"])
        runs["CalculiX (C3D8)"] = dict(X=fe["X"], sxx=sc, sn=nominal(fe["X"], sc))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    rr = np.linspace(A, 3 * A, 200)
    ax.plot((rr - A) / A, 1 + A ** 2 / (2 * rr ** 2) + 1.5 * A ** 4 / rr ** 4, "k-", lw=1,
            label="Kirsch (infinite plate)")
    ax.plot([0], [KT_HOWLAND], "k*", ms=9, label="Howland, 2a/W = 0.2")
    marks = iter(["o", "s", "x"])
    for name, r in runs.items():
        idx, rad = ligament(r["X"])
        up = idx[r["X"][idx, 1] > 0]
        o = np.argsort(rad[r["X"][idx, 1] > 0])
        k = up[o]
        k = k[r["sxx"][k] != 0]  # the coupled plate writes a stress at its PD points only
        ax.plot((np.abs(r["X"][k, 1]) - A) / A, r["sxx"][k] / r["sn"], marker=next(marks), ms=4,
                lw=0.8, mfc="none", label=name)
    ax.set_xlim(0, 2)
    ax.set_xlabel("(r - a) / a along the ligament x = 0")
    ax.set_ylabel("sigma_xx / sigma_nom (nodal values)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    s = p.add_subparsers(dest="cmd", required=True)
    c = s.add_parser("inp")
    c.add_argument("exodus")
    c.add_argument("inp")
    c.add_argument("--d", type=float, default=7.5e-6)
    c = s.add_parser("report")
    c.add_argument("perifem")
    c.add_argument("--ccx")
    c.add_argument("--fe")
    c.add_argument("--table")
    c.add_argument("--bands", action="store_true")
    c.add_argument("--no-kt", action="store_true", help="with --bands: the CalculiX band only")
    c = s.add_parser("plot")
    c.add_argument("out")
    c.add_argument("perifem")
    c.add_argument("--ccx")
    c.add_argument("--fe")
    a = p.parse_args()
    {"inp": cmd_inp, "report": cmd_report, "plot": cmd_plot}[a.cmd](a)


if __name__ == "__main__":
    main()
