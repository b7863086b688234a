"""A parameter sweep through the Python package: the glass disk struck by a rigid sphere
(inputs/disk_impact_rigid.yaml; Silling & Askari 2005) for several critical stretches s00 of the
Silling-Askari damage law, each run in this process with the value given as an override (no deck
edited, no process started). For each s00 it reports the damage fraction, the energy the broken
bonds released, and the largest force on the sphere, read from the history as the run goes.

  /usr/bin/python3 python/examples/disk_sweep.py [--deck inputs/disk_impact_rigid.yaml]
      [--s00 2.5e-4 5e-4 1e-3 2e-3] [--radius 0.037] [--final-time 1e-4] [--every 10]
      [--out sweep.csv]
  mpirun -np 2 /usr/bin/python3 python/examples/disk_sweep.py ...   (every rank runs the sweep;
      with mpi4py installed it gives the communicator)

--radius and --final-time shrink the problem (a smaller disk, a shorter run) for a quick look. Writes
no Exodus or history file; the table goes to standard output (rank 0) and to --out as CSV."""
import argparse
import csv
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, ".."))  # the package beside this folder, if not installed
try:
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
except ImportError:
    comm = None
import perifem  # noqa: E402


def one_run(deck, s00, radius=None, final_time=None, every=10):
    """Run the deck with critical stretch s00: (damage fraction, damage dissipated J, largest
    |force| on the sphere N)."""
    overrides = {"bodies.disk.damage.s00": s00}
    if radius:
        overrides["bodies.disk.geometry.radius"] = radius
    if final_time:
        overrides["time.final_time"] = final_time
    with perifem.Simulation(deck, overrides=overrides, output=False, quiet=True, comm=comm) as sim:
        force = 0.0
        while not sim.finished:
            sim.step(every)
            force = max(force, abs(sim.history()["sphere_force_z"]))
        h = sim.history()
        return h["damage_fraction"], h["damage_dissipation"], force


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--deck", default=os.path.join(here, "..", "..", "inputs", "disk_impact_rigid.yaml"))
    ap.add_argument("--s00", type=float, nargs="+", default=[2.5e-4, 5e-4, 1e-3, 2e-3])
    ap.add_argument("--radius", type=float, help="the disk's radius, m (the deck's: 0.037)")
    ap.add_argument("--final-time", type=float, help="s (the deck's: 1e-4 s, 1000 steps of 1e-7 s)")
    ap.add_argument("--every", type=int, default=10, help="steps between reads of the history")
    ap.add_argument("--out", help="write the table as CSV")
    a = ap.parse_args()
    rank = comm.Get_rank() if comm else 0
    rows = []
    for s00 in a.s00:
        damage, released, force = one_run(a.deck, s00, a.radius, a.final_time, a.every)
        rows.append((s00, damage, released, force))
        if rank == 0:
            print("s00 %-9.3g damage fraction %-10.4g released %-10.4g J  peak force %.4g N" % rows[-1], flush=True)
    if a.out and rank == 0:
        with open(a.out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["s00", "damage_fraction", "damage_dissipation_J", "peak_sphere_force_N"])
            w.writerows(rows)


if __name__ == "__main__":
    main()
