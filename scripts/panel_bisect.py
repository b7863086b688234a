"""The ballistic limit of the projectile-on-panel problem (Tupek et al. 2013, sec. 3.2;
docs/examples/panel_impact.md) bracketed by bisection.

  /usr/bin/python3 scripts/panel_bisect.py --stop 530 --perforate 740 [--width 20]
      [--deck inputs/panel_impact.yaml] [--ranks 2] [--perifem build/perifem] [--out panel_bisect]
      [--set KEY=VALUE ...] [--cap 250e-6] [--face-thickness 3e-3] [--bottom=-21e-3]
  /usr/bin/python3 scripts/panel_bisect.py --report RUN.h5     (judge one run's history)

The ballistic limit is the lowest impact velocity at which the panel is perforated (Tupek et al.
2013, sec. 3.2). A shot perforates the panel when the whole sphere ends below the panel's bottom
surface, moving down (scripts/panel_sweep.py). The script first runs both ends of the bracket
[--stop, --perforate] and checks that the panel stops the sphere at the lower one and is
perforated at the upper one (else it exits with status 1). It then fires at the bracket's
midpoint and keeps the half whose ends differ in outcome, until the bracket is at most --width
wide (20 m/s: the limit is the midpoint +-10 m/s). Each shot prints its velocity, outcome,
residual velocity, the time the outcome was decided and its run time; OUT/bisect.csv lists them.

A shot is stopped as soon as its outcome is decided, from the sphere's history (its mass-averaged
velocity v_z and centre z_c, read while the run writes them):
  stopped     v_z >= 0: the sphere moves up. The panel's contact only pushes it back (up or
              sideways), so it cannot turn down again;
  perforated  the whole sphere below the bottom surface (z_c + R < z_bottom), moving down, and
              its velocity changed by less than 1 m/s over the last 5 us: nothing holds it any
              more; the residual velocity is -v_z.
A shot still undecided at --cap (simulated time, the run's final_time) is judged as
panel_sweep.py judges it at its end and flagged "undecided". The decision uses the history up to
the decision time only, so a run that went on longer is judged the same. --set passes overrides
to every run (another resolution: the panel's element_size and horizon). Re-running reuses
finished shots (OUT/v<velocity>/result.txt)."""
import argparse
import csv
import glob
import os
import signal
import subprocess
import sys
import time

import numpy as np

R = 0.5 * 13.97e-3           # sphere radius (0.55 in), m
TF, Z_BOTTOM = 3e-3, -21e-3  # top face thickness and bottom surface of meshes/panel_sandwich.geo
FREE_DV, FREE_DT = 1.0, 5e-6  # free flight: |delta v_z| below 1 m/s over 5 us


def history(path):
    """Time, sphere z velocity and centre from a history file (maybe still being written)."""
    import h5py
    with h5py.File(path, "r") as h:
        n = min(len(h["time"]), len(h["sphere_velocity_z"]), len(h["sphere_position_z"]))
        return h["time"][:n], h["sphere_velocity_z"][:n], h["sphere_position_z"][:n]


def judge(t, vz, zc, z_bottom=Z_BOTTOM, tf=TF, final=False):
    """(outcome, residual velocity, decision time, top face perforated) from the history so far;
    outcome None while undecided (unless final: the end-of-run rule of panel_sweep.py)."""
    for i in range(len(t)):
        top = bool(np.any(zc[:i + 1] + R < -tf))
        if vz[i] >= 0:
            return "stopped", 0.0, t[i], top
        if zc[i] + R < z_bottom and vz[i] < 0:
            j = np.searchsorted(t, t[i] - FREE_DT)
            if t[i] - t[0] >= FREE_DT and j < i and np.all(zc[j:i + 1] + R < z_bottom) \
                    and abs(vz[i] - vz[j]) < FREE_DV:
                return "perforated", -vz[i], t[i], top
    if not final or len(t) == 0:
        return None, 0.0, None, False
    top = bool(np.any(zc + R < -tf))
    through = bool(zc[-1] + R < z_bottom and vz[-1] < 0)
    return ("perforated" if through else "stopped") + " (undecided)", (-vz[-1] if through else 0.0), t[-1], top


def shoot(args, v):
    """Run the deck at impact velocity v until its outcome is decided; (outcome, residual,
    decision time, top face perforated, wall seconds)."""
    folder = os.path.join(args.out, "v%g" % v)
    done = os.path.join(folder, "result.txt")
    if os.path.exists(done):
        o, vr, td, top, wall = open(done).read().split(";")
        return o, float(vr), float(td), top == "True", float(wall)
    os.makedirs(folder, exist_ok=True)
    h5 = os.path.join(folder, "panel.h5")
    cmd = [os.path.abspath(args.perifem), "--quiet", os.path.abspath(args.deck), "--output-dir", folder,
           "--set", "bodies.sphere.initial_velocity=[0, 0, %r]" % -float(v),
           "--set", "output.file=panel.e", "--set", "output.history_file=panel.h5",
           "--set", "time.final_time=%r" % args.cap]
    for s in args.set:
        cmd += ["--set", s]
    if args.ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(args.ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               HDF5_USE_FILE_LOCKING="FALSE")
    os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"  # read the history while perifem writes it
    if os.path.exists(h5):
        os.remove(h5)
    wall0 = time.time()
    proc = subprocess.Popen(cmd, env=env)
    decided = None
    while proc.poll() is None:
        time.sleep(3)
        try:
            decided = judge(*history(h5), args.bottom, args.face_thickness)
        except (OSError, KeyError):
            continue  # not written yet
        if decided[0] is not None:
            proc.send_signal(signal.SIGTERM)  # perifem checkpoints and stops
            proc.wait()
            break
    wall = time.time() - wall0
    if decided is None or decided[0] is None:
        if proc.returncode != 0:
            sys.exit("panel_bisect: the run at %g m/s failed (exit %d; its message above, its state in %s)"
                     % (v, proc.returncode, folder))
        decided = judge(*history(h5), args.bottom, args.face_thickness, final=True)
    for f in glob.glob(os.path.join(folder, "*.restart.h5*")):
        os.remove(f)  # the checkpoint perifem writes when stopped
    o, vr, td, top = decided
    with open(done, "w") as f:
        f.write("%s;%.6g;%.6g;%s;%.1f" % (o, vr, td, top, wall))
    return o, vr, td, top, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--stop", type=float, help="an impact velocity at which the panel stops the sphere, m/s")
    ap.add_argument("--perforate", type=float, help="an impact velocity at which it is perforated, m/s")
    ap.add_argument("--width", type=float, default=20.0, help="the bracket's final width, m/s")
    ap.add_argument("--deck", default="inputs/panel_impact.yaml")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--perifem", default="build/perifem")
    ap.add_argument("--out", default="panel_bisect")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="an override for every run")
    ap.add_argument("--cap", type=float, default=250e-6, help="the runs' final_time, s")
    ap.add_argument("--face-thickness", type=float, default=TF, help="top face thickness, m")
    ap.add_argument("--bottom", type=float, default=Z_BOTTOM, help="z of the panel's bottom surface, m")
    ap.add_argument("--report", metavar="RUN.h5", help="only judge a run's history")
    args = ap.parse_args()
    if args.report:
        os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"
        o, vr, td, top = judge(*history(args.report), args.bottom, args.face_thickness, final=True)
        print("%s at %.1f us, top face %s, residual velocity %.1f m/s" %
              (o, td * 1e6, "perforated" if top else "holds", vr))
        return
    if args.stop is None or args.perforate is None or not args.stop < args.perforate:
        ap.error("give --stop V1 --perforate V2 with V1 < V2")
    os.makedirs(args.out, exist_ok=True)
    rows = []

    def fire(v):
        o, vr, td, top, wall = shoot(args, v)
        rows.append((v, o, vr, td, top, wall))
        print("impact %6.1f m/s: %-24s residual %6.1f m/s, decided at %5.1f us, top face %-10s run %4.0f s"
              % (v, o, vr, td * 1e6, "perforated" if top else "holds", wall), flush=True)
        with open(os.path.join(args.out, "bisect.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["impact_velocity", "outcome", "residual_velocity", "decided_at", "top_face_perforated",
                        "run_seconds"])
            w.writerows(rows)
        return o.startswith("perforated")

    lo, hi = args.stop, args.perforate
    ok_lo, ok_hi = not fire(lo), fire(hi)
    if not (ok_lo and ok_hi):
        sys.exit("panel_bisect: not a bracket: %g m/s %s, %g m/s %s" %
                 (lo, "stopped" if ok_lo else "perforated", hi, "perforated" if ok_hi else "stopped"))
    while hi - lo > args.width:
        mid = 0.5 * (lo + hi)
        if fire(mid):
            hi = mid
        else:
            lo = mid
    print("bracket [%g, %g] m/s: ballistic limit %.1f +- %.1f m/s" % (lo, hi, 0.5 * (lo + hi), 0.5 * (hi - lo)))


if __name__ == "__main__":
    main()
