"""Energy release rate of a double cantilever beam run (inputs/dcb.yaml), from its force-opening
curve and its crack area.

    /usr/bin/python3 scripts/dcb_energy_release.py RUN.h5 RUN.e --dx DX --horizon DELTA
        [--a0 0.005] [--B 0.003] [--L 0.050] [--h 0.020] [--partial-volumes]
        [--quasi-static | --sequential] [--json] [--csv FILE]

Reads from the history the force on each arm, F = (F_upper - F_lower)/2 (the reactions of the
conditions 'upper' and 'lower'), and the opening Delta = u_upper - u_lower (the probes 'upper'
and 'lower' over the grips), and from the Exodus file the damage of the points next to the
crack plane y = 0 at each output.

Energy (Irwin & Kies 1954: G = dD/dA, D the energy the crack has taken, A its area): the work
of the grips read off the force-opening curve is W = int F dDelta, and
    D = W - E_el - K_c,
E_el and K_c the elastic and kinetic energy the body holds (the history's elastic_energy and
kinetic_energy): what the grips put in and the body does not hold, the body having no other
sink. G is the slope of D against A over the outputs where the crack runs (A at least one
horizon times B beyond the pre-crack), fitted by least squares; G_total = D / A at the end.

G_secant is the same from the force-opening curve alone: a linear elastic body at rest unloads
along its secant, so it holds E_el = F Delta / 2. Once the crack has jumped off the sharp
pre-crack the arms vibrate (the run is not slow enough to damp that out), and the vibration's
elastic energy, about as large as its kinetic energy, is then counted in D: G_secant is
between 4 % below and 31 % above G in the runs of docs/examples/dcb.md.

--quasi-static: a run with solver.type quasi_static (docs/examples/dcb.md, "Loaded
quasi-statically"). Every history row is an equilibrium (load step k at pseudo-time t_k), so
K_c = 0 and D = W - E_el; the opening is read from the grips' own displacement columns
(upper_displacement_y - lower_displacement_y). W is the grips' work columns (upper_work +
lower_work): in a load step where the crack grows the grips first move with the crack as it
was, to a force above the row's, and then stay while it grows, so the rows' trapezoid int F
dDelta misses the peak of each saw-tooth; it is checked to equal the columns (1e-6) until the
crack grows (or, under the damage law softening, its bonds start to soften) and to stay below them
after. There G_secant is the area method: at each
equilibrium a linear body holds F Delta / 2 (Clapeyron), so D = W - F Delta / 2 is the area
between the loading path and the secant to the current state.

G_bonds is the slope of the history's damage_dissipation (the energy each bond held when it
failed) against A over the same outputs: what the bonds take. What a crack advance releases
beyond it stays in the body as waves in a dynamic run (in E_el + K_c, so not in D: G = G_bonds
there within about 1 %), and is removed by the relaxation's damping in a quasi-static one (so it
is in D: G - G_bonds >= 0 is that share). --quasi-static also gives G_relaxation, the slope of
the history's relaxation_dissipation (what the damping took after bonds failed at a fixed
opening): G = G_bonds + G_relaxation, the balance closing.

--sequential: a quasi-static run with solver.failure sequential. Within a load step the grips
go back to where the most critical bond meets its limit, at each bond that fails, and forward
again: the columns book the work along that path, which may be above or below the rows'
trapezoid once the crack grows; they are checked to equal it before.

Crack area: a point next to the plane (|y| = dx/2, x > a0) has N bonds, Nc of them crossing the
plane; when the crack has passed it, those Nc are broken and its damage (the broken share of
its bonds, all cells having the same volume) is Nc/N. Its crossing bonds broken are therefore
c = min(1, damage N / Nc), and the crack area is A = sum c dx^2 / 2 over the points of both
faces. N and Nc are counted here on the lattice (cell-centred, spacing dx, bonds up to the
horizon, none across the pre-crack), independently of the code.

Beam theory (G = 12 F^2 a^2 / (E B^2 (h/2)^3) for pin-loaded arms) is no cross-check here: the
arms are short (a / (h/2) = 0.5 at the start) and the grips, which move a 1 mm length of each
arm as one, hold the arm's end partly against rotation; docs/examples/dcb.md compares it.
"""
import argparse
import json
import math
import sys

import h5py
import netCDF4
import numpy as np


def history(path, quasi_static=False, sequential=False):
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        force = 0.5 * (f["upper_reaction_y"][:] - f["lower_reaction_y"][:])
        if quasi_static:
            # the grips' own displacement columns (every point of a grip moves as one in y)
            opening = f["upper_displacement_y"][:] - f["lower_displacement_y"][:]
            kinetic = np.zeros_like(t)  # every row is an equilibrium
        else:
            opening = f["probe_upper_displacement_y"][:] - f["probe_lower_displacement_y"][:]
            kinetic = f["kinetic_energy"][:]
        elastic = f["elastic_energy"][:]
        booked = f["upper_work"][:] + f["lower_work"][:] if quasi_static else None
        # (bonds that soften dissipate before any fails: their process zone counts as damage)
        damaged = (f["damage_fraction"][:] > 0) | (f["damage_dissipation"][:] > 0)
    if quasi_static and t[0] > 0:  # the rows are the load steps; the unloaded state comes first
        t, force, opening, elastic, booked = (np.concatenate(([0.0], c)) for c in (t, force, opening, elastic, booked))
        damaged = np.concatenate(([False], damaged))
        kinetic = np.zeros_like(t)
    work = np.concatenate(([0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(opening))))
    if quasi_static:
        gap, tol = booked - work, 1e-6 * np.abs(booked).max()
        if np.abs(gap[~damaged]).max() > tol or (gap.min() < -tol and not sequential):
            sys.exit("dcb_energy_release: the grips' work columns are not the force-opening curve's before the "
                     "crack grows, or fall below it after (by %.3g of the work)" % (np.abs(gap).max() / np.abs(booked).max()))
        work = booked
    return t, force, opening, work, kinetic, elastic


def exodus_damage(path):
    e = netCDF4.Dataset(path)
    x = np.asarray(e.variables["coordx"][:])
    y = np.asarray(e.variables["coordy"][:])
    z = np.asarray(e.variables["coordz"][:])
    names = [b"".join(n.compressed()).decode() for n in e.variables["name_nod_var"][:]]
    k = names.index("damage") + 1
    damage = np.asarray(e.variables["vals_nod_var%d" % k][:])
    times = np.asarray(e.variables["time_whole"][:])
    e.close()
    return times, x, y, z, damage


def partial_volume(offset, delta, dx):
    """The share of the cell of spacing dx centred at offset that lies within delta of the
    origin, by the rule the code uses (all eight corners in: 1; all out: 0; else the share of
    16^3 sub-cell midpoints inside; docs/theory/pd.md, "Partial volumes")."""
    corners = offset + 0.5 * dx * np.array([(a, b, c) for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)])
    inside = np.sum(corners * corners, axis=1) <= delta * delta
    if inside.all():
        return 1.0
    if not inside.any():
        return 0.0
    sub = ((np.arange(16) + 0.5) / 16 - 0.5) * dx
    sx, sy, sz = np.meshgrid(offset[0] + sub, offset[1] + sub, offset[2] + sub, indexing="ij")
    return float(np.count_nonzero(sx * sx + sy * sy + sz * sz <= delta * delta)) / 4096.0


def bond_offsets(dx, delta, partial_volumes):
    """The offsets of a family on the lattice and their weights: 1 within the horizon, or with
    partial volumes the share of the neighbour's cell inside it."""
    if not partial_volumes:
        r = int(math.floor(delta / dx))
        off = np.array([(i, j, k) for i in range(-r, r + 1) for j in range(-r, r + 1) for k in range(-r, r + 1)
                        if 0 < i * i + j * j + k * k and math.sqrt(i * i + j * j + k * k) * dx <= delta],
                       dtype=float) * dx
        return off, np.ones(len(off))
    r = int(math.floor(delta / dx + math.sqrt(3) / 2))
    off = np.array([(i, j, k) for i in range(-r, r + 1) for j in range(-r, r + 1) for k in range(-r, r + 1)
                    if 0 < i * i + j * j + k * k], dtype=float) * dx
    w = np.array([partial_volume(o, delta, dx) for o in off])
    return off[w > 0], w[w > 0]


def bond_counts(x, y, z, dx, delta, a0, lo, hi, partial_volumes=False):
    """N and Nc of points (x, y, z) on the cell-centred lattice of the box [lo, hi] (with partial
    volumes, the neighbours' volume shares summed instead of counted, as the damage weighs them)."""
    off, weight = bond_offsets(dx, delta, partial_volumes)
    n = np.zeros(len(x))
    nc = np.zeros(len(x))
    for p in range(len(x)):
        q = np.array([x[p], y[p], z[p]]) + off
        inside = np.all((q >= lo) & (q <= hi), axis=1)
        cross = (q[:, 1] * y[p]) < 0
        # where the bond meets y = 0, and whether the pre-crack (x < a0) is there
        with np.errstate(divide="ignore", invalid="ignore"):
            s = y[p] / (y[p] - q[:, 1])
            xc = x[p] + s * (q[:, 0] - x[p])
        cut = cross & (xc < a0)
        bond = inside & ~cut
        n[p] = np.sum(weight[bond])
        nc[p] = np.sum(weight[bond & cross])
    return n, nc


def crack_areas(exo, dx, delta, a0, B, L, h, partial_volumes=False):
    times, x, y, z, damage = exodus_damage(exo)
    face = (np.abs(y) < 0.75 * dx) & (x > a0)
    lo = np.array([0.0, -h / 2, 0.0])
    hi = np.array([L, h / 2, B])
    n, nc = bond_counts(x[face], y[face], z[face], dx, delta, a0, lo, hi, partial_volumes)
    share = np.minimum(1.0, damage[:, face] * n / nc)
    return times, share.sum(axis=1) * dx * dx / 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("h5")
    ap.add_argument("exodus")
    ap.add_argument("--dx", type=float, required=True)
    ap.add_argument("--horizon", type=float, required=True)
    ap.add_argument("--a0", type=float, default=0.005)
    ap.add_argument("--B", type=float, default=0.003)
    ap.add_argument("--L", type=float, default=0.050)
    ap.add_argument("--h", type=float, default=0.020)
    ap.add_argument("--partial-volumes", action="store_true",
                    help="the run had partial_volumes: true (the damage weighs the neighbours by it)")
    ap.add_argument("--quasi-static", action="store_true",
                    help="the run had solver.type quasi_static: every row an equilibrium (no kinetic "
                         "energy), the opening from the grips' displacement columns")
    ap.add_argument("--sequential", action="store_true",
                    help="the run had solver.failure sequential (implies --quasi-static)")
    ap.add_argument("--json", action="store_true", help="print one JSON line")
    ap.add_argument("--csv", help="write time, opening, force, crack area, D per output")
    a = ap.parse_args()
    a.quasi_static = a.quasi_static or a.sequential

    t, force, opening, work, kinetic, elastic = history(a.h5, a.quasi_static, a.sequential)
    et, area = crack_areas(a.exodus, a.dx, a.horizon, a.a0, a.B, a.L, a.h, a.partial_volumes)
    rows = [int(np.argmin(np.abs(t - ti))) for ti in et]
    if max(abs(t[r] - ti) for r, ti in zip(rows, et)) > 1e-3 * (t[-1] - t[0]):
        sys.exit("dcb_energy_release: the Exodus outputs are not at history rows (make "
                 "output.interval a multiple of output.history_interval)")
    F, Dl, W, Kc = force[rows], opening[rows], work[rows], kinetic[rows]
    D = W - elastic[rows] - Kc
    D_secant = W - 0.5 * F * Dl - Kc
    run = area >= a.horizon * a.B
    if np.count_nonzero(run) < 3:
        sys.exit("dcb_energy_release: the crack ran through fewer than 3 outputs (%d); run longer"
                 % np.count_nonzero(run))
    with h5py.File(a.h5, "r") as f:
        booked = f["damage_dissipation"][:]
        relaxed = f["relaxation_dissipation"][:] if "relaxation_dissipation" in f else np.zeros_like(booked)
    if a.quasi_static and len(booked) < len(t):
        booked, relaxed = np.concatenate(([0.0], booked)), np.concatenate(([0.0], relaxed))
    out = {
        "G": float(np.polyfit(area[run], D[run], 1)[0]),
        "G_total": float(D[-1] / area[-1]),
        "G_secant": float(np.polyfit(area[run], D_secant[run], 1)[0]),
        "peak_force": float(force.max()),
        "opening_at_peak": float(opening[np.argmax(force)]),
        "crack_length_end": float(a.a0 + area[-1] / a.B),
        "outputs_fitted": int(np.count_nonzero(run)),
        "kinetic_share_end": float(Kc[-1] / max(W[-1], 1e-300)),
        "G_bonds": float(np.polyfit(area[run], booked[rows][run], 1)[0]),
    }
    if a.quasi_static:
        out["G_relaxation"] = float(np.polyfit(area[run], relaxed[rows][run], 1)[0])
    if a.csv:
        np.savetxt(a.csv, np.column_stack((et, Dl, F, area, D)), delimiter=",",
                   header="time_s,opening_m,force_N,crack_area_m2,dissipated_J", comments="")
    if a.json:
        print(json.dumps(out))
    else:
        for k, v in out.items():
            print("%-18s %.6g" % (k, v))


if __name__ == "__main__":
    main()
