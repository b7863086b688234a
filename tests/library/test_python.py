"""The Python package on tests/library/free_body.yaml (a free PMB block, no boundary condition):
  - stepped in parts, the history's momentum keeps its initial value (internal forces come in
    equal and opposite pairs) and equals sum m v of the fields (this rank's, summed over ranks);
  - the history file the run wrote (HDF5) ends with the row the library gives;
  - with a uniform velocity given as an override (a dict) on the deck's text, u = v t everywhere;
  - a field view shares the library's memory (no copy) and equals the copy;
  - bad input raises PerifemError with the deck's name and line; a checkpoint over the deck is
    refused (the deck unchanged); a communicator that is not MPI_COMM_WORLD's ranks (COMM_SELF
    on 2 ranks) is refused.
Prints "state digest: X" (rank 0), which the calling test compares with perifem's.
usage: python3 test_python.py DECK [--mpi]   (under mpirun with --mpi: mpi4py gives the comm)"""
import os
import sys

import numpy as np

mpi = "--mpi" in sys.argv
if mpi:
    from mpi4py import MPI
    comm = MPI.COMM_WORLD.Dup()
    rank, size = comm.Get_rank(), comm.Get_size()
else:
    comm, rank, size = None, 0, 1
import perifem  # noqa: E402  (after mpi4py, which starts MPI)

deck = sys.argv[1]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL (rank %d): %s" % (rank, what), file=sys.stderr)


def allsum(x):
    return comm.allreduce(x) if mpi else x


# 1. momentum, stepped in parts
out = "out_py%d" % size
with perifem.Simulation(deck, output_dir=out, quiet=True, comm=comm) as sim:
    check(sim.bodies == ["block"], "bodies %s" % sim.bodies)
    check(sim.points_global("block") == 7 * 6 * 9, "points %d" % sim.points_global("block"))
    sim.step(0)
    h0 = sim.history()
    m, v = sim.field("block", "mass"), sim.field("block", "velocity")
    scale = allsum(float(np.sum(m * np.linalg.norm(v, axis=1))))
    for n in (3, 11, 6):
        sim.step(n)
    check(sim.step_count == 20 and not sim.finished, "step %d after 20" % sim.step_count)
    sim.run()
    check(sim.finished and sim.step_count == 60, "finished at %d" % sim.step_count)
    h = sim.history()
    m, v = sim.field("block", "mass"), sim.field("block", "velocity")
    p = [allsum(float(np.sum(m * v[:, c]))) for c in range(3)]
    for c, axis in enumerate("xyz"):
        key = "momentum_" + axis
        check(abs(h[key] - h0[key]) <= 1e-12 * scale, "%s %.17g, initially %.17g" % (key, h[key], h0[key]))
        check(abs(h[key] - p[c]) <= 1e-12 * scale, "%s: history %.17g, fields %.17g" % (key, h[key], p[c]))
    ids = allsum(int(sim.ids("block").sum()))
    n = 7 * 6 * 9
    check(ids == n * (n - 1) // 2, "global ids are 0 .. %d once each (sum %d)" % (n - 1, ids))
    view, copy = sim.field_view("block", "displacement"), sim.field("block", "displacement")
    check(np.array_equal(view, copy) and not view.flags.writeable and not np.shares_memory(view, copy),
          "field_view equals field(), read-only")
    check(np.shares_memory(view, sim.field_view("block", "displacement")), "field_view is the library's memory")
    del view  # (a view keeps the simulation, its output files and their locks, after close())
    digest = sim.digest()
    names = sim.history_names
if rank == 0:
    import h5py
    with h5py.File(os.path.join(out, os.path.splitext(os.path.basename(deck))[0] + ".h5"), "r") as f:
        last = {k: f[k][-1] for k in names if k in f}
    check(len(last) == len(names), "the history file has the columns %s" % sorted(set(names) - set(last)))
    check(all(last[k] == h[k] for k in last), "the history file's last row is the library's")
    print("state digest: %s" % digest, flush=True)

# 2. a rigid translation: the deck as text, the velocity as an override
text = open(deck).read()
with perifem.Simulation(text=text, name="text_deck.yaml", output=False, quiet=True, comm=comm,
                        overrides={"bodies.block.initial_velocity": [10, -5, 2], "time.steps": 30}) as sim:
    sim.run()
    u, t = sim.field("block", "displacement"), sim.time
    worst = comm.allreduce(float(np.abs(u - np.array([10.0, -5.0, 2.0]) * t).max()), op=MPI.MAX) if mpi else \
        float(np.abs(u - np.array([10.0, -5.0, 2.0]) * t).max())
    check(worst <= 1e-9 * 10 * t, "rigid translation: |u - v t| up to %g m" % worst)

# 3. errors
try:
    perifem.Simulation(text="bodies: [\n  - name: x\n    : : :\n", name="broken.yaml", quiet=True, comm=comm)
    check(False, "a broken deck was accepted")
except perifem.PerifemError as e:
    check(e.code == 2 and "broken.yaml:" in str(e), "a YAML error: %d %s" % (e.code, e))
before = open(deck, "rb").read()
with perifem.Simulation(deck, output_dir=out, quiet=True, comm=comm) as sim:
    sim.step(1)
    try:
        sim.checkpoint(deck)
        check(False, "a checkpoint over the deck was written")
    except perifem.PerifemError as e:
        check(e.code == 2 and "would overwrite the deck" in str(e), "a checkpoint over the deck: %d %s" % (e.code, e))
check(open(deck, "rb").read() == before, "the deck is unchanged")
if mpi and size > 1:
    try:
        perifem.Simulation(deck, output=False, quiet=True, comm=MPI.COMM_SELF)
        check(False, "COMM_SELF on %d ranks was accepted" % size)
    except perifem.PerifemError as e:
        check(e.code == 2 and "MPI_COMM_WORLD" in str(e), "a communicator not congruent: %s" % e)

sys.exit(1 if failures else 0)
