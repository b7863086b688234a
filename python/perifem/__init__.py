"""perifem from Python: build a simulation from a deck (a file or YAML text, with overrides), run
it step by step, read its fields as numpy arrays and its history, checkpoint it. A thin layer
over the C library libperifem.so.0 (include/perifem.h) through ctypes; docs/library.md.

    import perifem
    with perifem.Simulation("inputs/disk_impact_rigid.yaml",
                            overrides={"bodies.disk.damage.s00": 4e-4}, output=False) as sim:
        sim.run()
        print(sim.history()["damage_fraction"])

Under mpirun every rank runs the same script; give an mpi4py communicator with comm= (it must
hold every rank of MPI_COMM_WORLD, in order). Fields are this rank's points of a body."""
from .simulation import PerifemError, Simulation, finalize, version, version_numbers

__all__ = ["Simulation", "PerifemError", "version", "version_numbers", "finalize"]
__version__ = version()
