"""The Python package at its boundary, on tests/library/free_body.yaml (a free block):
  - wrong argument types raise TypeError before anything runs: step(2.7), step("2"), step(True)
    (before: 2.7 took 2 steps), a field name or body of the wrong type, a number as a path,
    overrides neither a dict, a list of strings nor a string, a list holding a number; a single
    string "key.path=value" is one override (before: split into characters);
  - a checkpoint into a folder that does not exist, or one HDF5 cannot create (/proc), raises
    PerifemError and fails that call only: the run goes on, the next checkpoint is written, and
    perifem.finalize() succeeds (before, after /proc: the interpreter ended with status 1 after
    the run, "a file could not be closed");
  - check() (the --check report) times a few steps and spends the model: step() then raises
    PerifemError naming the calibration, and a new simulation of the deck runs;
  - a field view read after close() shows the values it showed before (before: SIGSEGV, on a
    block of 17 325 points whose arrays are unmapped when freed); the
    closed simulation refuses further calls; it is freed once the last view is gone.
usage: python3 test_python_api.py DECK   (the package importable: PYTHONPATH, PERIFEM_LIBRARY)"""
import gc
import os
import sys

import numpy as np

import perifem
from perifem import simulation

deck = sys.argv[1]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: %s" % what, file=sys.stderr)


def raises(exc, call, what, text=None):
    try:
        call()
    except exc as e:
        check(text is None or text in str(e), "%s: %s (expected it to mention %r)" % (what, e, text))
        return
    except Exception as e:  # noqa: BLE001
        check(False, "%s raised %s: %s, not %s" % (what, type(e).__name__, e, exc.__name__))
        return
    check(False, "%s raised nothing (expected %s)" % (what, exc.__name__))


def make(**kw):
    return perifem.Simulation(deck, output=False, quiet=True, **kw)


# 1. types
with make(overrides="time.steps=7") as sim:
    check(sim.total_steps == 7, "one string as one override: %d steps, expected 7" % sim.total_steps)
    raises(TypeError, lambda: sim.step(2.7), "step(2.7)", "an integer")
    raises(TypeError, lambda: sim.step("2"), "step('2')")
    raises(TypeError, lambda: sim.step(True), "step(True)")
    raises(ValueError, lambda: sim.step(-1), "step(-1)")
    check(sim.step_count == 0, "refused steps took %d steps" % sim.step_count)
    sim.step(np.int64(2))
    check(sim.step_count == 2, "step(np.int64(2)): %d steps" % sim.step_count)
    raises(TypeError, lambda: sim.field("block", 3), "field('block', 3)", "field's name")
    raises(TypeError, lambda: sim.field_view(0.0, "mass"), "field_view(0.0, 'mass')", "body")
    raises(perifem.PerifemError, lambda: sim.field(5, "mass"), "field(5, 'mass')", "no body 5")
    raises(TypeError, lambda: sim.checkpoint(3), "checkpoint(3)", "path")
    check(np.array_equal(sim.field(0, "mass"), sim.field("block", "mass")), "a body by index and by name")
# 2b. check() spends the model it times
with make(overrides="time.steps=20") as sim:
    sim.check()
    raises(perifem.PerifemError, lambda: sim.step(1), "step() after check()", "calibration steps")
with make(overrides="time.steps=20") as sim:
    sim.step(1)
    check(sim.step_count == 1, "a new simulation after check(): %d steps" % sim.step_count)
raises(TypeError, lambda: make(overrides=5), "overrides=5", "overrides")
raises(TypeError, lambda: make(overrides=["time.steps=3", 4]), "overrides=[..., 4]", "an override")
raises(TypeError, lambda: make(overrides={3: 1}), "overrides={3: 1}", "key")
raises(TypeError, lambda: perifem.Simulation(3), "Simulation(3)", "deck")
raises(TypeError, lambda: perifem.Simulation(text=b"x: 1"), "text=bytes", "text")
raises(TypeError, lambda: make(output_dir=3), "output_dir=3", "output_dir")
raises(TypeError, lambda: make(comm="world"), "comm='world'", "mpi4py")
raises(ValueError, lambda: make(progress="bar"), "progress='bar'", "progress")

# 2. a failed checkpoint fails that call only
with make() as sim:
    sim.step(3)
    raises(perifem.PerifemError, lambda: sim.checkpoint(os.path.join("no_such_folder", "c.h5")),
           "a checkpoint into a missing folder", "no_such_folder")
    raises(perifem.PerifemError, lambda: sim.checkpoint("/proc/perifem_checkpoint.h5"),
           "a checkpoint HDF5 cannot create", "/proc")
    sim.step(2)
    check(sim.step_count == 5, "steps after a failed checkpoint: %d" % sim.step_count)
    sim.checkpoint("after_failure.h5")
    check(os.path.getsize("after_failure.h5") > 0, "the checkpoint after the failed one is written")

# 3. a field view outlives close(); a block of 17 325 points, whose arrays (over 128 kB) the C
# library's malloc maps apart and unmaps when they are freed: reading them then was SIGSEGV
sim = make(overrides={"bodies.block.geometry.spacing": 0.25e-3, "bodies.block.horizon": 0.76e-3})
sim.step(4)
view, copy = sim.field_view("block", "displacement"), sim.field("block", "displacement")
mass = sim.field_view("block", "mass")
sim.close()
check(np.array_equal(view, copy) and float(np.abs(view).max()) > 0, "a view read after close() shows its values")
check(float(mass.sum()) > 0, "a scalar view read after close()")
raises(perifem.PerifemError, lambda: sim.step(1), "step() after close()", "closed")
raises(perifem.PerifemError, lambda: sim.field_view("block", "mass"), "field_view() after close()", "closed")
check(len(simulation._pending) == 1, "a closed simulation with views is kept (%d kept)" % len(simulation._pending))
del view
gc.collect()
check(len(simulation._pending) == 1, "kept while one view is left")
del mass
gc.collect()
check(len(simulation._pending) == 0, "freed with its last view (%d kept)" % len(simulation._pending))
tmp = make()
tmp.step(1)
orphan = tmp.field_view(0, "velocity")
del tmp  # a simulation dropped without close() while its view is used
gc.collect()
check(orphan.shape[1] == 3 and np.isfinite(orphan).all(), "a view of a dropped simulation")
del orphan
gc.collect()

perifem.finalize()  # raises PerifemError when MPI cannot end (before: after the failed checkpoint)
print("python api: %d failures" % len(failures))
sys.exit(1 if failures else 0)
