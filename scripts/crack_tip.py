"""Crack-tip speed and branching of a mode-I crack grown from a notch along y = 0, measured from the
damage field of a perifem Exodus II file (inputs/glass_branching.yaml; docs/examples/glass_branching.md).

  /usr/bin/python3 scripts/crack_tip.py RUN.e [--notch-tip X] [--threshold D] [--json FILE]
        [--youngs E --poisson NU --density RHO] [--plot OUTDIR [--name NAME]]

The points are projected on the (x, y) plane (the plate's layers through the thickness fall on one
another). At each output a point is cracked when its damage exceeds the threshold (default 0.35).
  - Crack tip: the cracked point ahead of the notch tip (x > X) farthest from the notch tip
    (X, 0); its distance a(t) is the crack's extension along its path (the straight crack's
    length, then the longer branch's reach).
  - Tip speed: a(t) differentiated by a least-squares line through the outputs within +-2 us
    (5 to 9 outputs), so single-output jumps of one lattice spacing do not show as spikes.
  - Branching: a column of points (one lattice spacing wide in x, ahead of the notch) is split
    when its cracked points form two groups in y with more than two spacings between them and
    the rows next to y = 0 intact, i.e. two cracks, one above and one below the mid-line.
    The first branch is the smallest x of a split column at the last output, and its time the
    first output with a split column.
  - Rayleigh speed c_R of the material: the root of the Rayleigh equation
      (2 - k^2)^2 = 4 sqrt(1 - k^2 c_s^2 / c_p^2) sqrt(1 - k^2),  k = c_R / c_s,
    with c_s = sqrt(G / rho) and c_p = sqrt((K + 4G/3) / rho) (three dimensions, plane strain), or
    the plane-stress c_p = sqrt(E / (rho (1 - nu^2))) of a thin plate (Graff, Wave Motion in Elastic
    Solids, 1975, sec. 6.1); both are printed, the smaller is the bound.
With --plot OUTDIR: OUTDIR/NAME.png (damage at the last output) and OUTDIR/NAME_speed.png (tip
position and speed against time, c_R marked); NAME is glass_branching unless --name."""
import argparse
import json
import math
import sys

import numpy as np
from netCDF4 import Dataset


def exodus_damage(path):
    """(x, y, times, damage[time, point]) of an Exodus file written by perifem."""
    with Dataset(path) as nc:
        x = np.asarray(nc.variables["coordx"][:], dtype=float)
        y = np.asarray(nc.variables["coordy"][:], dtype=float)
        times = np.asarray(nc.variables["time_whole"][:], dtype=float)
        names = ["".join(c.decode() for c in row if c) .strip() for row in np.asarray(nc.variables["name_nod_var"][:])]
        if "damage" not in names:
            sys.exit("crack_tip.py: %s has no nodal variable 'damage' (it has %s)" % (path, ", ".join(names)))
        k = names.index("damage") + 1
        damage = np.asarray(nc.variables["vals_nod_var%d" % k][:], dtype=float)
    return x, y, times, damage


def rayleigh_ratio(cs_over_cp):
    """k = c_R / c_s from the Rayleigh equation, by bisection on (0, 1)."""
    r2 = cs_over_cp ** 2

    def f(k):
        k2 = k * k
        return (2 - k2) ** 2 - 4 * math.sqrt(1 - k2 * r2) * math.sqrt(1 - k2)

    lo, hi = 0.5, 0.999999  # f(lo) < 0 < f(hi) for 0 <= nu < 1/2 (f < 0 from k = 0 to the root)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def rayleigh_speeds(E, nu, rho):
    G = E / (2 * (1 + nu))
    K = E / (3 * (1 - 2 * nu))
    cs = math.sqrt(G / rho)
    cp3 = math.sqrt((K + 4 * G / 3) / rho)
    cp_ps = math.sqrt(E / (rho * (1 - nu * nu)))
    return {"c_s": cs, "c_p": cp3, "c_p_plane_stress": cp_ps,
            "c_R": rayleigh_ratio(cs / cp3) * cs, "c_R_plane_stress": rayleigh_ratio(cs / cp_ps) * cs}


def spacing(y):
    """The lattice spacing: the smallest gap between distinct y values."""
    u = np.unique(np.round(y, 12))
    return float(np.min(np.diff(u)))


def split_columns(x, y, cracked, h, x0, midline_intact):
    """x of the columns ahead of x0 whose cracked points form two groups or more in y (more than
    two spacings of intact points between them); midline_intact: only columns whose rows next to
    y = 0 are intact, with cracked points on both sides (the crack has become two)."""
    out = []
    sel = cracked & (x > x0)
    if not sel.any():
        return out
    cols = np.round((x[sel] - x0) / h).astype(int)
    ys = y[sel]
    for c in np.unique(cols):
        yc = np.unique(np.round(ys[cols == c], 9))
        if len(yc) < 2 or np.max(np.diff(yc)) <= 2.5 * h:
            continue
        if midline_intact and (np.any(np.abs(yc) < 1.5 * h) or yc[0] > 0 or yc[-1] < 0):
            continue
        out.append(x0 + c * h)
    return out


def tip_speed(times, a, half_window=2.0e-6):
    v = np.full(len(times), np.nan)
    for i, t in enumerate(times):
        w = np.abs(times - t) <= half_window * (1 + 1e-9)
        if w.sum() >= 3:
            v[i] = np.polyfit(times[w], a[w], 1)[0]
    return v


def analyse(path, x0, threshold, E, nu, rho):
    x, y, times, damage = exodus_damage(path)
    h = spacing(y)
    tip = np.zeros(len(times))
    tip_xy = np.zeros((len(times), 2))
    first = {False: None, True: None}  # first output with a side branch / with the crack split in two
    for i in range(len(times)):
        cracked = damage[i] > threshold
        ahead = cracked & (x > x0)
        if ahead.any():
            r = np.hypot(x[ahead] - x0, y[ahead])
            j = int(np.argmax(r))
            tip[i] = r[j]
            tip_xy[i] = (x[ahead][j], y[ahead][j])
        for mid in (False, True):
            if first[mid] is None and split_columns(x, y, cracked, h, x0, mid):
                first[mid] = float(times[i])
    v = tip_speed(times, tip)
    started = np.nonzero(tip > 2 * h)[0]
    t_start = float(times[started[0]]) if len(started) else None
    final = {mid: split_columns(x, y, damage[-1] > threshold, h, x0, mid) for mid in (False, True)}
    c = rayleigh_speeds(E, nu, rho)
    vmax = float(np.nanmax(v)) if np.isfinite(v).any() else 0.0
    first_split_time = first[False]
    out = {
        "file": path, "spacing": h, "threshold": threshold, "notch_tip": x0,
        "times": times.tolist(), "tip_distance": tip.tolist(), "tip_speed": [None if not np.isfinite(s) else float(s) for s in v],
        "tip_xy": tip_xy.tolist(), "initiation_time": t_start, "max_speed": vmax, "final_time": float(times[-1]),
        "branched": bool(final[False]), "branch_x": float(min(final[False])) if final[False] else None,
        "branch_time": first[False],
        "split": bool(final[True]), "split_x": float(min(final[True])) if final[True] else None,
        "split_time": first[True] if final[True] else None,
    }
    if first_split_time is not None and t_start is not None:
        before = (times >= t_start) & (times <= first_split_time) & np.isfinite(v)
        out["mean_speed_before_branching"] = float(np.polyfit(times[(times >= t_start) & (times <= first_split_time)],
                                                              tip[(times >= t_start) & (times <= first_split_time)], 1)[0]) \
            if ((times >= t_start) & (times <= first_split_time)).sum() >= 2 else None
        out["max_speed_before_branching"] = float(np.max(v[before])) if before.any() else None
    out.update(c)
    return out, (x, y, damage[-1], times)


def plot(res, fields, outdir, name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x, y, d, times = fields
    fig, ax = plt.subplots(figsize=(8, 3.6))
    h = res["spacing"]  # the largest damage through the thickness, one pixel a lattice column
    i = np.round((x - x.min()) / h).astype(int)
    j = np.round((y - y.min()) / h).astype(int)
    img = np.zeros((j.max() + 1, i.max() + 1))
    np.maximum.at(img, (j, i), d)
    sc = ax.imshow(img, origin="lower", cmap="viridis", vmin=0, vmax=0.5, interpolation="nearest",
                   extent=(1e3 * (x.min() - h / 2), 1e3 * (x.max() + h / 2), 1e3 * (y.min() - h / 2),
                           1e3 * (y.max() + h / 2)))
    fig.colorbar(sc, ax=ax, label="damage")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_aspect("equal")
    ax.set_title("damage at %.1f us (h = %.3g mm)" % (1e6 * times[-1], 1e3 * res["spacing"]))
    fig.tight_layout()
    fig.savefig("%s/%s.png" % (outdir, name), dpi=120)
    plt.close(fig)
    t = np.array(res["times"]) * 1e6
    v = np.array([np.nan if s is None else s for s in res["tip_speed"]])
    fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax[0].plot(t, 1e3 * np.array(res["tip_distance"]), "k.-", ms=3)
    ax[0].set_ylabel("tip distance from notch (mm)")
    ax[1].plot(t, v, "b.-", ms=3, label="crack tip")
    ax[1].axhline(res["c_R"], color="r", ls="--", label="Rayleigh speed %.0f m/s" % res["c_R"])
    if res["branch_time"] is not None:
        for a in ax:
            a.axvline(1e6 * res["branch_time"], color="g", ls=":", label="first branch")
    ax[1].set_ylabel("tip speed (m/s)")
    ax[1].set_xlabel("time (us)")
    ax[1].set_ylim(0, 1.1 * res["c_R"])
    ax[1].legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig("%s/%s_speed.png" % (outdir, name), dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description="crack-tip speed and branching from a perifem damage field")
    ap.add_argument("exodus")
    ap.add_argument("--notch-tip", type=float, default=0.0, help="x of the notch tip (m), the notch along y = 0")
    ap.add_argument("--threshold", type=float, default=0.35)
    ap.add_argument("--youngs", type=float, default=72e9)
    ap.add_argument("--poisson", type=float, default=0.25)
    ap.add_argument("--density", type=float, default=2440.0)
    ap.add_argument("--json")
    ap.add_argument("--plot", help="OUTDIR: write the two pictures there")
    ap.add_argument("--name", default="glass_branching", help="file names of the pictures: NAME.png, NAME_speed.png")
    a = ap.parse_args()
    res, fields = analyse(a.exodus, a.notch_tip, a.threshold, a.youngs, a.poisson, a.density)
    print("lattice spacing %.4g mm, damage threshold %.2f" % (1e3 * res["spacing"], res["threshold"]))
    print("Rayleigh speed %.0f m/s (3-D), %.0f m/s (plane stress); c_s %.0f m/s"
          % (res["c_R"], res["c_R_plane_stress"], res["c_s"]))
    print("crack starts at %s us; max tip speed %.0f m/s = %.2f c_R (tip speed over +-2 us windows)"
          % ("%.2f" % (1e6 * res["initiation_time"]) if res["initiation_time"] is not None else "-",
             res["max_speed"], res["max_speed"] / res["c_R"]))
    if res["branched"]:
        print("branches: yes, first at x = %.1f mm, t = %.1f us" % (1e3 * res["branch_x"], 1e6 * res["branch_time"]))
        if res["split"]:
            print("the crack splits in two (the mid-line intact beyond) at x = %.1f mm, t = %.1f us"
                  % (1e3 * res["split_x"], 1e6 * res["split_time"]))
        if res.get("mean_speed_before_branching") is not None:
            print("mean tip speed from initiation to branching %.0f m/s" % res["mean_speed_before_branching"])
    else:
        print("branches: no")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)
    if a.plot:
        plot(res, fields, a.plot, a.name)


if __name__ == "__main__":
    main()
