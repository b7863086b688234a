"""Residual velocity against impact velocity for the projectile-on-panel problem (Tupek et al.
2013, sec. 3.2; docs/examples/panel_impact.md), with the ballistic limit from a
Recht-Ipson fit v_r = a (v_i^p - v_bl^p)^(1/p).

  /usr/bin/python3 scripts/panel_sweep.py [--deck inputs/panel_impact.yaml] [--ranks 2]
      [--perifem build/perifem] [--out panel_sweep] [--velocities 370 530 740 900] [--plot]
      [--face-thickness 3e-3] [--bottom=-21e-3] [--label "coarse sandwich"]
  /usr/bin/python3 scripts/panel_sweep.py --report RUN.h5     (the outcome of one finished run)

The defaults describe the sandwich (meshes/panel_sandwich.geo); for the monolithic plate
(inputs/panel_plate.yaml, meshes/panel_plate.geo) give --face-thickness 8.5e-3 --bottom=-8.5e-3
(its top face is the whole plate).

For each impact velocity it runs the deck as it is, with the sphere's initial velocity given on
the command line (--set bodies.sphere.initial_velocity=[0, 0, -V]) and the outputs in
OUT/v<velocity>/ (mpirun on --ranks ranks when more than one), and reads the run's history: the sphere's mass-averaged velocity and centre of mass (columns
sphere_velocity_z, sphere_position_z). Outcomes, from the sphere's path alone:
  top face perforated   the whole sphere got below the top face (z_c + R < -tf) at some time;
  panel perforated      at the end the whole sphere is below the panel (z_c + R < z_bottom),
                        moving down; its residual velocity is then -v_z, else 0.
It prints one line per velocity and the fit, writes OUT/sweep.csv, and with --plot the figures
of the docs page (OUT/panel_residual.png, OUT/panel_velocity.png). Re-running reuses finished
runs (delete OUT/v<velocity> to redo one). A run that fails (the instability guard) is left out
of the table and the fit, and the script then exits with status 1 after the others."""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np

R = 0.5 * 13.97e-3          # sphere radius (0.55 in), m
TF, Z_BOTTOM = 3e-3, -21e-3  # defaults: face-sheet thickness, the bottom surface (panel_sandwich.geo)


def run(deck, v, folder, ranks, perifem):
    """Run the deck at impact velocity v with its outputs in folder (unless done before); True when
    the run finished."""
    if os.path.exists(os.path.join(folder, "done")):
        return True
    os.makedirs(folder, exist_ok=True)
    cmd = [perifem, "--quiet", os.path.abspath(deck), "--output-dir", folder,
           "--set", "bodies.sphere.initial_velocity=[0, 0, %r]" % -float(v),
           "--set", "output.file=panel.e", "--set", "output.history_file=panel.h5"]
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if subprocess.run(cmd, env=env).returncode != 0:
        return False
    open(os.path.join(folder, "done"), "w").close()
    return True


def outcome(folder, tf=TF, z_bottom=Z_BOTTOM, history=None):
    """Time, sphere z velocity and centre; top-face and panel perforation; residual velocity
    (of the run in folder, or of the history file given)."""
    import h5py
    with h5py.File(history or os.path.join(folder, "panel.h5"), "r") as h:
        t, vz, zc = h["time"][:], h["sphere_velocity_z"][:], h["sphere_position_z"][:]
    top = bool(np.any(zc + R < -tf))
    through = bool(zc[-1] + R < z_bottom and vz[-1] < 0)
    return t, vz, zc, top, through, (-vz[-1] if through else 0.0)


def recht_ipson(vi, vr):
    """Fit v_r = a (v_i^p - v_bl^p)^(1/p) (0 below v_bl) by least squares over all points, a in
    (0, 1], p in [1.5, 3], v_bl between the fastest stopped and the slowest perforating shot."""
    from scipy.optimize import least_squares
    vi, vr = np.asarray(vi, float), np.asarray(vr, float)
    lo = max([v for v, r in zip(vi, vr) if r == 0], default=0.0)
    hi = min([v for v, r in zip(vi, vr) if r > 0], default=vi.max())

    def model(q, v):
        a, p, vbl = q
        return a * np.maximum(v**p - vbl**p, 0.0) ** (1.0 / p)

    best = None
    for p0 in (2.0, 2.5):
        for f in (0.25, 0.5, 0.75):
            q0 = [0.8, p0, lo + f * (hi - lo)]
            r = least_squares(lambda q: model(q, vi) - vr, q0, bounds=([0.05, 1.5, lo], [1.0, 3.0, max(hi, lo + 1)]))
            if best is None or r.cost < best.cost:
                best = r
    return best.x, model


def plot(out, rows, fit, model, series, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    vi = np.array([r[0] for r in rows])
    vr = np.array([r[3] for r in rows])
    fig, ax = plt.subplots(figsize=(5.5, 4))
    v = np.linspace(0, 1.05 * vi.max(), 300)
    a, p, vbl = fit
    ax.plot(v, model(fit, v), "b-", label="Recht-Ipson: a = %.2f, p = %.2f, $v_{bl}$ = %.0f m/s" % (a, p, vbl))
    ax.plot(vi, vr, "ko", label="perifem (%s)" % label)
    ax.plot(v, v, ":", color="0.6", label="$v_r = v_i$")
    ax.set_xlabel("impact velocity (m/s)")
    ax.set_ylabel("residual velocity (m/s)")
    ax.set_xlim(0, v[-1])
    ax.set_ylim(0, v[-1])
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "panel_residual.png"), dpi=110)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for v0, (t, vz) in series:
        ax.plot(t * 1e6, -vz, label="%g m/s" % v0)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("time (us)")
    ax.set_ylabel("sphere velocity, downward (m/s)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "panel_velocity.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--deck", default="inputs/panel_impact.yaml")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--perifem", default=os.path.abspath("build/perifem"))
    ap.add_argument("--out", default="panel_sweep")
    ap.add_argument("--velocities", type=float, nargs="+", default=[370, 530, 740, 900])
    ap.add_argument("--plot", action="store_true")
    ap.add_argument("--face-thickness", type=float, default=TF, help="top face thickness, m")
    ap.add_argument("--bottom", type=float, default=Z_BOTTOM, help="z of the panel's bottom surface, m")
    ap.add_argument("--label", default="coarse sandwich", help="the points' legend in the plot")
    ap.add_argument("--report", metavar="RUN.h5", help="only print the outcome of a finished run's history")
    args = ap.parse_args()
    if args.report:
        t, vz, zc, top, through, vr = outcome(None, args.face_thickness, args.bottom, args.report)
        print("at %.1f us: top face %s, panel %s; residual velocity %.1f m/s" %
              (t[-1] * 1e6, "perforated" if top else "holds", "perforated" if through else "stops the sphere", vr))
        return
    perifem = os.path.abspath(args.perifem)
    rows, series, failed = [], [], []
    for v in args.velocities:
        folder = os.path.join(args.out, "v%g" % v)
        if not run(args.deck, v, folder, args.ranks, perifem):
            print("impact %5.0f m/s: the run failed (its message above; the last good state in %s): left out"
                  % (v, folder), flush=True)
            failed.append(v)
            continue
        t, vz, zc, top, through, vr = outcome(folder, args.face_thickness, args.bottom)
        rows.append((v, top, through, vr))
        series.append((v, (t, vz)))
        print("impact %5.0f m/s: top face %-13s panel %-13s residual %6.1f m/s" %
              (v, "perforated," if top else "holds,", "perforated," if through else "stops it,", vr), flush=True)
    with open(os.path.join(args.out, "sweep.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["impact_velocity", "top_face_perforated", "panel_perforated", "residual_velocity"])
        w.writerows(rows)
    fit = None
    if sum(r[3] > 0 for r in rows) >= 1 and sum(r[3] == 0 for r in rows) >= 1:
        fit, model = recht_ipson([r[0] for r in rows], [r[3] for r in rows])
        print("Recht-Ipson fit: a = %.3f, p = %.2f, ballistic limit v_bl = %.0f m/s" % tuple(fit))
    else:
        print("Recht-Ipson fit: needs at least one stopped and one perforating shot")
    if args.plot and fit is not None:
        plot(args.out, rows, fit, model, series, args.label)
    if failed:
        sys.exit("panel_sweep: the runs at %s m/s failed" % ", ".join("%g" % v for v in failed))


if __name__ == "__main__":
    main()
