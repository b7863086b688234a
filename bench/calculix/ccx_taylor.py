#!/usr/bin/env python3
"""The Taylor bar of inputs/taylor_impact.yaml in CalculiX, on perifem's own mesh (README.md,
"The Taylor bar in CalculiX").

  ccx_taylor.py inp EXODUS OUT.inp [--dt DT] [--frequency N]
      writes a CalculiX deck from the mesh of a perifem run (its Exodus file): the same nodes and
      HEX8 connectivity as C3D8R elements, copper with J2 plasticity and linear hardening
      (E = 117 GPa, nu = 0.35, rho = 8930, yield 400 MPa, H = 100 MPa: *PLASTIC from
      (400 MPa, 0) to (1400 MPa, 10)), 227 m/s along -z on every node off the impact face,
      the impact face (z = 0) held at u_z = 0 (the roller of the benchmark, perifem's
      `separation: false`), explicit central differences (*DYNAMIC, EXPLICIT, ALPHA=0) with a
      fixed increment DT to 80 us, displacements written every N increments (N must divide the
      number of increments so that 80 us is written).
  ccx_taylor.py compare FRD EXODUS [--tolerance T]
      the impact-face rim (the face's nodes on the outer circle) of both codes at 80 us:
      CalculiX's from the last displacement block of its .frd, perifem's from the last step of
      its Exodus file. Prints each rim's largest, mean and smallest radius and the bar's length
      (as test_taylor measures them) and exits 1 when the largest radii or the lengths differ
      by more than T (relative, default 0.01) or a run did not reach 80 us.
"""
import argparse
import os
import sys

import netCDF4
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ccx_compare import mesh_cards, nset_card, read_exodus_mesh  # noqa: E402

V0, T_END = 227.0, 80e-6


def write_inp(a):
    x, conn = read_exodus_mesh(a.exodus)
    steps = T_END / a.dt
    if abs(steps - round(steps)) > 1e-6 or round(steps) % a.frequency:
        sys.exit(f"80 us / dt = {steps:g} increments: not a multiple of --frequency {a.frequency}")
    face = np.where(x[:, 2] == 0)[0] + 1
    moving = np.where(x[:, 2] != 0)[0] + 1
    with open(a.out, "w") as f:
        w = lambda s: f.write(s + "\n")
        w(f"** Taylor bar on the mesh of {a.exodus} (bench/calculix/ccx_taylor.py)")
        w("*HEADING")
        w("Taylor bar, copper J2, 227 m/s, roller on z = 0")
        mesh_cards(w, x, conn)
        nset_card(w, "FACE", face)
        nset_card(w, "MOVING", moving)
        w("*MATERIAL, NAME=COPPER")
        w("*ELASTIC")
        w("117.e9, 0.35")
        w("*PLASTIC")
        w("400.e6, 0.")
        w("1400.e6, 10.")
        w("*DENSITY")
        w("8930.")
        w("*SOLID SECTION, ELSET=EALL, MATERIAL=COPPER")
        w("*INITIAL CONDITIONS, TYPE=VELOCITY")
        w(f"MOVING, 3, {-V0}")
        w("*BOUNDARY")
        w("FACE, 3, 3")
        w(f"*STEP, NLGEOM, INC={int(round(steps)) + 10}")
        w("*DYNAMIC, EXPLICIT, ALPHA=0")
        w(f"{a.dt:.6g}, {T_END:.6g}, 0, {a.dt:.6g}")
        w(f"*NODE FILE, FREQUENCY={a.frequency}")
        w("U")
        w("*END STEP")


def last_displacements(path):
    """The time and {node: (ux, uy, uz)} of the last DISP block of an ASCII .frd file."""
    t, block, last = None, None, None
    for line in open(path):
        if line.startswith("  100CL"):
            t = float(line[12:24])
        elif line.startswith(" -4  DISP"):
            block = {}
        elif block is not None and line.startswith(" -1"):
            block[int(line[3:13])] = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(3)]
        elif block is not None and line.startswith(" -3"):
            last, block = (t, block), None
    if last is None:
        sys.exit(f"{path}: no displacement block")
    return last


def measures(x, u):
    """Largest, mean and smallest rim radius and the length (mm) of the deformed bar x + u."""
    y = x + u
    r0, face = np.hypot(x[:, 0], x[:, 1]), x[:, 2] == 0
    ring = face & (r0 > r0[face].max() * (1 - 1e-9))
    r = np.hypot(y[ring, 0], y[ring, 1]) * 1e3
    return r.max(), r.mean(), r.min(), (y[:, 2].max() - y[:, 2].min()) * 1e3


def compare(a):
    x, _ = read_exodus_mesh(a.exodus)
    t_ccx, disp = last_displacements(a.frd)
    d = netCDF4.Dataset(a.exodus)
    names = [str(n).strip() for n in netCDF4.chartostring(d["name_nod_var"][:])]
    u_pf = np.stack([d["vals_nod_var%d" % (names.index("displacement_" + c) + 1)][-1] for c in "xyz"], 1)
    t_pf = float(d["time_whole"][-1])
    rows = [("perifem", t_pf, measures(x, u_pf)),
            ("CalculiX", t_ccx, measures(x, np.array([disp[i + 1] for i in range(len(x))])))]
    for name, t, (rmax, rmean, rmin, length) in rows:
        print(f"{name:9s} t = {t * 1e6:6.2f} us: rim max {rmax:.3f} mm, mean {rmean:.3f} mm, min {rmin:.3f} mm; "
              f"length {length:.3f} mm")
    (_, _, p), (_, _, c) = rows
    dr, dl = abs(p[0] - c[0]) / c[0], abs(p[3] - c[3]) / c[3]
    print(f"largest radius differs by {100 * dr:.2f} %, length by {100 * dl:.2f} % (tolerance {100 * a.tolerance:g} %)")
    if min(t_pf, t_ccx) < T_END * (1 - 1e-3) or dr > a.tolerance or dl > a.tolerance:
        sys.exit(1)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    q = sub.add_parser("inp")
    q.add_argument("exodus")
    q.add_argument("out")
    q.add_argument("--dt", type=float, default=5e-9)
    q.add_argument("--frequency", type=int, default=4000)
    q = sub.add_parser("compare")
    q.add_argument("frd")
    q.add_argument("exodus")
    q.add_argument("--tolerance", type=float, default=0.01)
    a = p.parse_args()
    write_inp(a) if a.cmd == "inp" else compare(a)


if __name__ == "__main__":
    main()
