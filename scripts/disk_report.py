#!/usr/bin/env python3
"""The outcome of a disk impact run (inputs/disk_impact_rigid.yaml and its variants,
docs/examples/disk_impact.md "Which contact to trust"), read from its history (.h5) and the last
step of its Exodus file (.e):

  damage       final damage_fraction (broken bonds over all bonds) and the fraction of points
               fully damaged (damage >= 0.999)
  sphere       work W done by the rigid sphere and its impulse, both from the history, and W
               again integrated here from the history's force and the sphere's velocity (the
               trapezoidal rule over the history rows: an independent check of the booking)
  energy       kinetic, elastic, contact energy, damage dissipation, contact dissipation and the
               balance error, absolute and over W
  closest      the two closest points at the end, over the lattice spacing h: over all points,
               and over points of different fragments when the run wrote the field 'fragment'
               (output.fragments: true)

usage: disk_report.py RUN.h5 RUN.e --spacing H [--speed V] [--json OUT]
Needs numpy, h5py and netCDF4 (/usr/bin/python3 here)."""
import argparse
import json
import sys

import h5py
import netCDF4
import numpy as np


def exodus_last_step(path):
    """Deformed positions and the nodal fields of the last step of an Exodus file."""
    d = netCDF4.Dataset(path)
    names = [b"".join(c for c in row if c).decode() for row in d["name_nod_var"][:].data]
    fields = {n: np.asarray(d["vals_nod_var%d" % (i + 1)][-1, :], dtype=float) for i, n in enumerate(names)}
    x = np.stack([np.asarray(d["coord" + a][:], dtype=float) + fields["displacement_" + a] for a in "xyz"], axis=1)
    t = float(d["time_whole"][-1])
    d.close()
    return t, x, fields


def closest_pair(x, cell, label=None):
    """The smallest distance between two points (of different labels when label is given) and
    the two points, searched in a grid of cells of edge `cell`: pairs farther apart than `cell`
    may be missed, so the answer is exact when it is below `cell` and (inf, -1, -1) otherwise."""
    ijk = np.floor((x - x.min(axis=0)) / cell).astype(np.int64) + 1
    span = ijk.max(axis=0) + 2
    key = (ijk[:, 0] * span[1] + ijk[:, 1]) * span[2] + ijk[:, 2]
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    best = (np.inf, -1, -1)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            for dk in (-1, 0, 1):
                other = key + (di * span[1] + dj) * span[2] + dk
                lo = np.searchsorted(sorted_key, other, "left")
                hi = np.searchsorted(sorted_key, other, "right")
                for m in range(int((hi - lo).max(initial=0))):
                    i = np.nonzero(lo + m < hi)[0]
                    j = order[lo[i] + m]
                    keep = j != i if label is None else label[i] != label[j]
                    i, j = i[keep], j[keep]
                    if i.size:
                        dist = np.sqrt(((x[i] - x[j]) ** 2).sum(axis=1))
                        m = int(dist.argmin())
                        best = min(best, (float(dist[m]), int(i[m]), int(j[m])))
    return best


def report(h5_path, exo_path, spacing, speed):
    h = h5py.File(h5_path, "r")
    col = lambda n: np.asarray(h[n][:], dtype=float)
    t, fz = col("time"), col("sphere_force_z")
    w_integrated = float(np.sum(0.5 * (fz[1:] + fz[:-1]) * speed * np.diff(t)))
    last = lambda n: float(h[n][-1]) if n in h else 0.0
    W = last("sphere_work")
    r = {
        "time": last("time"),
        "damage_fraction": last("damage_fraction"),
        "sphere_work": W,
        "sphere_work_integrated": w_integrated,
        "sphere_impulse_z": last("sphere_impulse_z"),
        "peak_force_z": float(np.abs(fz).max()),
        "kinetic_energy": last("kinetic_energy"),
        "elastic_energy": last("elastic_energy"),
        "contact_energy": last("contact_energy"),
        "damage_dissipation": last("damage_dissipation"),
        "contact_dissipation": last("contact_dissipation"),
        "energy_error": last("energy_error"),
    }
    r["energy_error_relative"] = r["energy_error"] / W if W else float("nan")
    h.close()
    te, x, fields = exodus_last_step(exo_path)
    r["exodus_time"] = te
    r["fully_damaged"] = float(np.mean(fields["damage"] >= 0.999))
    dist, i, j = closest_pair(x, spacing)
    r["closest_over_h"] = dist / spacing
    if i >= 0:
        r["closest_at_radius"] = float(np.hypot(*(0.5 * (x[i, :2] + x[j, :2]))))
        r["closest_at_z"] = float(0.5 * (x[i, 2] + x[j, 2]))
    if "fragment" in fields:
        r["closest_fragments_over_h"] = closest_pair(x, spacing, fields["fragment"])[0] / spacing
        r["fragments"] = int(np.unique(fields["fragment"]).size)
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5")
    ap.add_argument("exodus")
    ap.add_argument("--spacing", type=float, required=True, help="lattice spacing h [m]")
    ap.add_argument("--speed", type=float, default=100.0, help="the sphere's speed, downwards [m/s]")
    ap.add_argument("--json", help="also write the numbers to this file")
    a = ap.parse_args()
    r = report(a.h5, a.exodus, a.spacing, a.speed)
    for k, v in r.items():
        print("%-26s %.6g" % (k, v))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(r, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
