#!/usr/bin/env python3
"""Plot a run's HDF5 history (the .h5 file perifem writes beside the .e file) as PNG files.

    /usr/bin/python3 scripts/plot_history.py RUN.h5 [--out DIR]

Writes, into DIR (default: the history's folder), <stem>_<plot>.png for each plot the history
has data for:
  energies        the kinetic energy, the internal energies (elastic energy plus plastic work),
                  the contact penalty energy, the dissipated energies and the external work,
                  each labelled by what its history column holds
  energy_error    the balance error relative to the largest energy in play (the run's summary)
  damage          the fraction of broken bonds
  velocity        each body's mass-averaged velocity (a projectile's velocity history)
  forces          the forces on indenters, walls and contact pairs
  probes          columns named probe_* (mass-averaged values over regions)
  load_displacement_<name>
                  for each boundary condition <name> with a reaction and a grip displacement
                  (<name>_reaction_*, <name>_displacement_*): its reaction against the mean
                  displacement of its points, one line per component the reaction acts along
                  (quasi-static runs: one point per load step; explicit runs: one per row)
and prints the path of each. Needs numpy, h5py and matplotlib (Debian python3-numpy,
python3-h5py, python3-matplotlib). Exit status 2 for a file that is not a perifem history.
"""
import argparse
import os
import sys

import numpy as np

STORED = ["kinetic_energy", "elastic_energy", "fe_internal_energy", "contact_energy"]
DISSIPATED = ["hourglass_energy", "bulk_viscosity_work", "wall_dissipation", "contact_dissipation",
              "damage_dissipation", "relaxation_dissipation"]
# What each energy column holds (docs/user_guide.md §3.4), as the energies plot's legend says it:
# the column named elastic_energy is the PD bodies' internal energy, plastic work included.
LABELS = {
    "kinetic_energy": "kinetic",
    "elastic_energy": "PD internal (bond elastic + plastic work)",
    "fe_internal_energy": "FE internal (elastic + plastic work)",
    "contact_energy": "contact penalty (stored)",
    "hourglass_energy": "hourglass work",
    "bulk_viscosity_work": "bulk viscosity work (dissipated)",
    "wall_dissipation": "wall impacts (dissipated)",
    "contact_dissipation": "friction work (dissipated)",
    "damage_dissipation": "broken bonds (dissipated)",
    "relaxation_dissipation": "relaxation damping after bonds fail (quasi-static)",
    "external_work": "external work",
}


def read(path):
    import h5py
    try:
        with h5py.File(path, "r") as f:
            cols = {k: np.asarray(f[k][:], dtype=float) for k in f.keys()}
    except OSError as err:
        print("plot_history: %s: cannot read it as HDF5 (%s)" % (path, err), file=sys.stderr)
        sys.exit(2)
    for need in ("time", "kinetic_energy", "energy_error"):
        if need not in cols:
            print("plot_history: %s: not a perifem history (no dataset '%s')" % (path, need), file=sys.stderr)
            sys.exit(2)
    return cols


def relative_error(c):
    """As the run's summary: |error| over max(|E0|, |W_ext|, stored energies)."""
    e0 = sum(c[k][0] for k in STORED + DISSIPATED if k in c) - c.get("external_work", np.zeros(1))[0]
    stored = c["kinetic_energy"] + c.get("elastic_energy", 0) + c.get("contact_energy", 0) + \
        np.abs(c.get("fe_internal_energy", 0))
    scale = np.maximum(np.maximum(abs(e0), np.abs(c.get("external_work", 0))), stored)
    return np.where(scale > 0, np.abs(c["energy_error"]) / np.where(scale > 0, scale, 1), 0.0)


def plots(c):
    """(name, title, ylabel, [(label, y)], logy) for each plot there is data for."""
    t = c["time"]
    out = []
    lines = [(LABELS[k], c[k]) for k in STORED + DISSIPATED + ["external_work"] if k in c and np.any(c[k] != 0)]
    total = sum(c[k] for k in STORED + DISSIPATED if k in c) - c.get("external_work", 0)
    lines.append(("sum of the above - external work", total))
    out.append(("energies", "Energy balance", "energy (J)", lines, False))
    out.append(("energy_error", "Energy balance error", "relative error", [("|error| / scale", relative_error(c))],
                True))
    if "damage_fraction" in c:
        out.append(("damage", "Damage", "broken bond fraction", [("damage fraction", c["damage_fraction"])], False))
    vel = [(k[: -len("_velocity_x")] + " v" + k[-1], c[k]) for k in sorted(c)
           if k[:-1].endswith("_velocity_") and k.split("_velocity_")[0] != "" and np.any(c[k] != 0)]
    if vel:
        out.append(("velocity", "Mean velocity of each body", "velocity (m/s)", vel, False))
    forces = [(k.replace("_", " "), c[k]) for k in sorted(c) if "_force_" in k and np.any(c[k] != 0)]
    if forces:
        out.append(("forces", "Forces", "force (N)", forces, False))
    probes = [(k[len("probe_"):].replace("_", " "), c[k]) for k in sorted(c) if k.startswith("probe_")]
    if probes:
        out.append(("probes", "Probes", "value (SI)", probes, False))
    return t, out


def load_displacement(c):
    """{condition: [(component, grip displacement, reaction)]} for each condition whose history has
    both columns, the components along which its reaction is not 0 at every row."""
    out = {}
    for k in sorted(c):
        if not k.endswith("_reaction_x"):
            continue
        name = k[: -len("_reaction_x")]
        curves = [(a, c["%s_displacement_%s" % (name, a)], c["%s_reaction_%s" % (name, a)]) for a in "xyz"
                  if "%s_displacement_%s" % (name, a) in c and "%s_reaction_%s" % (name, a) in c]
        curves = [cv for cv in curves if np.any(cv[2] != 0)]
        if curves:
            out[name] = curves
    return out


def plot_load_displacement(plt, c, stem, out):
    """One PNG per condition: reaction (kN) against grip displacement (mm)."""
    for name, curves in load_displacement(c).items():
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for a, u, r in curves:
            ax.plot(u * 1e3, r * 1e-3, "o-" if len(u) <= 50 else "-", ms=3, label="%s: reaction %s" % (name, a))
        ax.set_xlabel("grip displacement (mm)")
        ax.set_ylabel("reaction (kN)")
        ax.set_title("%s — %s: load against displacement" % (stem, name))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        path = os.path.join(out, "%s_load_displacement_%s.png" % (stem, name))
        fig.savefig(path, dpi=110)
        plt.close(fig)
        print(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("history", help="the run's .h5 history file")
    ap.add_argument("--out", help="folder for the PNG files (default: the history's folder)")
    a = ap.parse_args()
    if not os.path.isfile(a.history):
        print("plot_history: %s: no such file" % a.history, file=sys.stderr)
        sys.exit(2)
    c = read(a.history)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out = a.out or os.path.dirname(os.path.abspath(a.history))
    os.makedirs(out, exist_ok=True)
    stem = os.path.splitext(os.path.basename(a.history))[0]
    t, figs = plots(c)
    for name, title, ylabel, lines, logy in figs:
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for label, y in lines:
            y = np.broadcast_to(y, t.shape)
            if logy:
                ax.semilogy(t * 1e6, np.maximum(y, 1e-16), label=label)
            else:
                ax.plot(t * 1e6, y, label=label)
        ax.set_xlabel("time (µs)")
        ax.set_ylabel(ylabel)
        ax.set_title("%s — %s" % (stem, title))
        ax.grid(alpha=0.3)
        if len(lines) > 1:
            ax.legend(fontsize=7, ncol=2)
        fig.tight_layout()
        path = os.path.join(out, "%s_%s.png" % (stem, name))
        fig.savefig(path, dpi=110)
        plt.close(fig)
        print(path)
    plot_load_displacement(plt, c, stem, out)


if __name__ == "__main__":
    main()
