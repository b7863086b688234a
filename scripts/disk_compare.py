#!/usr/bin/env python3
"""The elastic sphere against the rigid ones on the glass disk (docs/examples/disk_impact.md,
"Results"): reads each run's history (.h5) and the last step of its Exodus file (.e), prints the
page's two tables and draws its plot.

  damage table   damage_fraction (broken bonds over all bonds) interpolated in the history every
                 8 us from 8 to 80 us
  outcome table  at the end: the fraction of the disk's points fully damaged (damage >= 0.999),
                 their mean damage, the peak z force on the sphere over the history rows, the impulse
                 given to the disk (the time integral of that force over the history rows, the
                 trapezoidal rule), the energy given to the disk, energy_error, steps
  plot           damage_fraction and the z force against time, one curve per run

usage: disk_compare.py NAME=RUN.h5 [NAME=RUN.h5 ...] [--plot OUT.png]
  each RUN.h5 with RUN.e beside it; the force is the history's '<rigid or FE pair>_force_z':
  'sphere_disk_force_z' (the FE pair) or 'sphere_force_z' (a rigid surface named sphere)
Needs numpy, h5py, netCDF4 and, for the plot, matplotlib (/usr/bin/python3 here)."""
import argparse
import sys

import h5py
import netCDF4
import numpy as np


def last_damage(exodus, block="disk"):
    """The nodal field 'damage' at the last step of an Exodus file, on the nodes of one block."""
    d = netCDF4.Dataset(exodus)
    names = [netCDF4.chartostring(n).item() for n in d.variables["name_nod_var"][:]]
    blocks = [netCDF4.chartostring(n).item() for n in d.variables["eb_names"][:]]
    nodes = np.unique(np.asarray(d.variables["connect%d" % (blocks.index(block) + 1)][:]).ravel()) - 1
    k = names.index("damage") + 1
    return np.asarray(d.variables["vals_nod_var%d" % k][-1, :])[nodes]


def force_key(h):
    for key in ("sphere_disk_force_z", "sphere_force_z"):
        if key in h:
            return key
    sys.exit("no sphere force in the history (sphere_disk_force_z or sphere_force_z)")


def outcome(path):
    h = h5py.File(path, "r")
    t, dmg, err = h["time"][:], h["damage_fraction"][:], h["energy_error"][:]
    fz = h[force_key(h)][:]
    points = last_damage(path[:-3] + ".e")
    impulse = float(np.sum(0.5 * (fz[1:] + fz[:-1]) * np.diff(t)))
    disk_ke = h["disk_kinetic_energy"][-1] if "disk_kinetic_energy" in h else float("nan")
    return {"t": t, "damage": dmg, "fz": fz, "error": err[-1], "steps": int(h["step"][-1]),
            "full": float(np.mean(points >= 0.999)), "mean": float(np.mean(points)),
            "peak": float(fz.max()), "t_peak": float(t[fz.argmax()]), "impulse": impulse,
            "disk_ke": float(disk_ke)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="NAME=RUN.h5")
    ap.add_argument("--plot", help="draw damage_fraction and the force against time into this file")
    args = ap.parse_args()
    runs = {}
    for r in args.runs:
        name, _, path = r.partition("=")
        runs[name] = outcome(path)
    print("| t [µs] | " + " | ".join(runs) + " |")
    print("|---:|" + "---:|" * len(runs))
    for s in range(8, 81, 8):
        print("| %d | " % s + " | ".join("%.4f" % np.interp(s * 1e-6, o["t"], o["damage"]) for o in runs.values()) + " |")
    print()
    rows = [("damage_fraction at the end", lambda o: "%.4f" % o["damage"][-1]),
            ("points fully damaged (damage >= 0.999)", lambda o: "%.3f" % o["full"]),
            ("mean point damage", lambda o: "%.3f" % o["mean"]),
            ("peak z force on the sphere", lambda o: "%.2f kN at %.1f µs" % (o["peak"] / 1e3, o["t_peak"] * 1e6)),
            ("impulse given to the disk", lambda o: "%.3f N s" % o["impulse"]),
            ("kinetic energy of the disk at the end", lambda o: "%.2f J" % o["disk_ke"]),
            ("energy_error at the end", lambda o: "%.4f J" % o["error"]),
            ("steps", lambda o: "%d" % o["steps"])]
    print("| at the end | " + " | ".join(runs) + " |")
    print("|---|" + "---:|" * len(runs))
    for label, fmt in rows:
        print("| %s | " % label + " | ".join(fmt(o) for o in runs.values()) + " |")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(11, 4))
        for name, o in runs.items():
            ax[0].plot(o["t"] * 1e6, o["damage"], label=name)
            ax[1].plot(o["t"] * 1e6, o["fz"] / 1e3, label=name)
        ax[0].set(xlabel="t [µs]", ylabel="damage_fraction")
        ax[1].set(xlabel="t [µs]", ylabel="z force on the sphere [kN]")
        for a in ax:
            a.grid(alpha=0.3)
            a.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)


if __name__ == "__main__":
    main()
