"""The Python package at its boundary, on tests/library/free_body.yaml (a free block):
  - a checkpoint into a folder that does not exist, or one HDF5 cannot create (/proc), raises
    PerifemError and fails that call only: the run goes on, the next checkpoint is written, and
    perifem.finalize() succeeds (before, after /proc: the interpreter ended with status 1 after
    the run, "a file could not be closed");
usage: python3 test_python_api.py DECK   (the package importable: PYTHONPATH, PERIFEM_LIBRARY)"""
import os
import sys

import perifem

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

perifem.finalize()  # raises PerifemError when MPI cannot end (before: after the failed checkpoint)
print("python api: %d failures" % len(failures))
sys.exit(1 if failures else 0)
