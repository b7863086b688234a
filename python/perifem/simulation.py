"""The Simulation class over the C API (include/perifem.h)."""
import atexit
import ctypes
import operator
import os
import signal
import weakref

import numpy as np

from ._library import Options, lib

_live = weakref.WeakSet()  # simulations not yet closed: closed at exit, before MPI ends
_pending = set()  # closed simulations whose memory field views still show: freed with the last view


class PerifemError(RuntimeError):
    """A call into perifem failed: code is the status (1 run failure, 2 bad input, 3 memory, 4 a
    library perifem calls), the message says what and where (deck file:line:column and key)."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def _check(status):
    if status != 0:
        raise PerifemError(status, lib.perifem_last_error().decode(errors="replace"))


def version():
    """The library's version, "MAJOR.MINOR.PATCH"."""
    return lib.perifem_version().decode()


def version_numbers():
    """(major, minor, patch) of the library."""
    v = [ctypes.c_int() for _ in range(3)]
    lib.perifem_version_numbers(*[ctypes.byref(x) for x in v])
    return tuple(x.value for x in v)


def finalize():
    """Close every open simulation and end MPI if perifem started it (also done at exit). Field
    views of closed simulations must be gone first (they show the library's memory)."""
    for sim in list(_live):
        sim.close()
    if _pending:
        raise PerifemError(2, "finalize: field views of %d closed simulation(s) are still referenced; delete them "
                              "first (they show memory that finalize would free)" % len(_pending))
    _check(lib.perifem_finalize())


def _at_exit():
    for handle in list(_pending):  # the interpreter is ending: no view will be read again
        handle.destroy()
    try:
        finalize()
    except PerifemError as e:  # a file could not be closed: MPI cannot end cleanly
        os.write(2, ("perifem: %s\n" % e).encode())
        os._exit(1)


atexit.register(_at_exit)


def _yaml_value(value):
    """A Python value as the YAML text of a deck value: lists and tuples as [a, b, c], numbers by
    repr (exact), booleans as true/false, strings as they are (YAML parses them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_yaml_value(v) for v in value) + "]"
    if isinstance(value, (int, float, np.integer, np.floating)):
        return repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))
    return str(value)


def _type_error(what, expected, value):
    return TypeError("%s must be %s, not %s (%r)" % (what, expected, type(value).__name__, value))


def _override_list(overrides):
    """Overrides as "key.path=value" strings: from a mapping {key.path: value}, a list of strings,
    or one string (one override)."""
    if overrides is None:
        return []
    if isinstance(overrides, str):
        return [overrides]
    if isinstance(overrides, dict):
        for k in overrides:
            if not isinstance(k, str):
                raise _type_error("an override's key", "a str (\"key.path\")", k)
        return ["%s=%s" % (k, _yaml_value(v)) for k, v in overrides.items()]
    if isinstance(overrides, (list, tuple)):
        for item in overrides:
            if not isinstance(item, str):
                raise _type_error("an override", "a str (\"key.path=value\")", item)
        return list(overrides)
    raise _type_error("overrides", "a dict, a list of \"key.path=value\" strings or one such string", overrides)


def _path(value, what):
    """A file or folder argument as bytes for the library."""
    if isinstance(value, (str, bytes, os.PathLike)):
        return os.fsencode(value)
    raise _type_error(what, "a path (str or os.PathLike)", value)


def _name(value, what):
    if isinstance(value, str):
        return value.encode()
    raise _type_error(what, "a str", value)


def _integer(value, what):
    """An integer argument: int or numpy integer; a float (2.7), a bool or a string is refused."""
    if not isinstance(value, bool):
        try:
            return operator.index(value)
        except TypeError:
            pass
    raise _type_error(what, "an integer", value)


def _flag(value, what):
    if isinstance(value, (bool, int)):
        return int(bool(value))
    raise _type_error(what, "a bool", value)


class _Handle:
    """The library's simulation, freed once it is closed and no field view of its memory is left
    (a view keeps it alive: reading a view after close() reads memory still there)."""

    def __init__(self):
        self.ptr = ctypes.c_void_p()
        self.closed = False
        self.views = 0  # the _ViewMemory objects alive

    def view_gone(self):
        self.views -= 1
        if self.closed and not self.views:
            try:
                self.destroy()
            except PerifemError:
                pass

    def destroy(self):
        _pending.discard(self)
        if self.ptr:
            _check(lib.perifem_destroy(ctypes.byref(self.ptr)))


class _ViewMemory:
    """The memory a field view shows (numpy's base of the view), holding the simulation's handle."""

    def __init__(self, handle, address, count):
        self.handle = handle
        self.__array_interface__ = {"data": (address, True), "shape": (count,), "typestr": "<f8", "version": 3}
        handle.views += 1
        weakref.finalize(self, handle.view_gone)


class Simulation:
    """A perifem simulation built from a deck.

    Simulation(deck, overrides=None, text=None, name=None, output=True, output_dir=None,
               restart_from=None, quiet=False, strict=False, progress="auto", comm=None)

    deck      the deck file (or None with text=)
    text      the deck as YAML text; name= is the file it stands for (relative paths, output
              names, messages; default "deck.yaml")
    overrides {"bodies.sphere.initial_velocity": [0, 0, -900], ...}, ["key.path=value", ...] or
              one "key.path=value" string: as perifem's --set, applied after include: and
              before ${...} parameters
    output    False: write no Exodus, history or fragments file
    output_dir the outputs' folder (created when missing)
    restart_from a checkpoint to continue from
    quiet     print errors only; progress "auto" | "plain" | "line"
    strict    a run-health warning stops the run (PerifemError)
    comm      an mpi4py communicator (congruent to MPI_COMM_WORLD); None: MPI_COMM_WORLD

    Collective under MPI: create, step, run, digest, checkpoint, points_global, close."""

    def __init__(self, deck=None, overrides=None, text=None, name=None, output=True, output_dir=None,
                 restart_from=None, quiet=False, strict=False, progress="auto", comm=None):
        if (deck is None) == (text is None):
            raise ValueError("give a deck file or text=, not both")
        if text is not None and not isinstance(text, str):
            raise _type_error("text", "a str (the deck's YAML)", text)
        if progress not in ("auto", "plain", "line"):
            raise ValueError("progress must be \"auto\", \"plain\" or \"line\", not %r" % (progress,))
        if comm is not None and not hasattr(comm, "py2f"):
            raise _type_error("comm", "an mpi4py communicator", comm)
        self._handle = None
        handle = _Handle()
        sets = [s.encode() for s in _override_list(overrides)]
        self._sets = (ctypes.c_char_p * max(len(sets), 1))(*sets)
        opt = Options()
        opt.overrides = ctypes.cast(self._sets, ctypes.POINTER(ctypes.c_char_p))
        opt.noverrides = len(sets)
        opt.output_dir = _path(output_dir, "output_dir") if output_dir is not None else None
        opt.no_output = 1 - _flag(output, "output")
        opt.restart_from = _path(restart_from, "restart_from") if restart_from is not None else None
        opt.quiet, opt.strict = _flag(quiet, "quiet"), _flag(strict, "strict")
        opt.progress = {"auto": 0, "plain": 1, "line": 2}[progress]
        opt.catch_signals = 0  # Ctrl-C stays Python's
        opt.silent_errors = 1  # the exception carries the message
        if comm is not None:
            opt.use_comm, opt.comm = 1, comm.py2f()
        if text is not None:
            _check(lib.perifem_create_from_string(text.encode(), _path(name, "name") if name is not None else None,
                                                  ctypes.byref(opt), ctypes.byref(handle.ptr)))
        else:
            _check(lib.perifem_create(_path(deck, "deck"), ctypes.byref(opt), ctypes.byref(handle.ptr)))
        self._handle = handle
        _live.add(self)

    # ---- life ----
    def close(self):
        """Free the simulation (output files still open are closed). Collective. Field views still
        referenced keep its memory (and files) until the last of them is gone, or the exit: under
        MPI delete them before close(), so that every rank frees it at the same call."""
        handle = getattr(self, "_handle", None)
        if handle is None or handle.closed:
            return
        _live.discard(self)
        handle.closed = True
        if handle.views:
            _pending.add(handle)
        else:
            handle.destroy()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def _h(self):
        handle = getattr(self, "_handle", None)
        if handle is None or handle.closed:
            raise PerifemError(2, "the simulation is closed")
        return handle.ptr

    # ---- running ----
    def _advance(self, call, *args):
        """call(*args) with SIGINT and SIGTERM taken by the library as the command line takes them
        (the run checkpoints at the end of the current step and stops), then the signal handed
        to Python's handler: Ctrl-C raises KeyboardInterrupt as soon as the step is done."""
        _check(lib.perifem_catch_signals(1))
        try:
            status = call(*args)
            error = PerifemError(status, lib.perifem_last_error().decode(errors="replace")) if status else None
        finally:
            lib.perifem_catch_signals(0)
        caught = lib.perifem_signal_caught()
        if caught:
            signal.raise_signal(caught)  # Python's handler: KeyboardInterrupt for SIGINT
        if error:
            raise error

    def step(self, n=1):
        """Take n steps (an integer; n = 0: start the run: forces at t = 0, first output and history
        row), with output, history and checkpoints at the deck's intervals. Collective. Ctrl-C
        (SIGINT) stops the run at the end of the current step with a checkpoint, then raises
        KeyboardInterrupt; the run cannot go on (continue with restart_from=)."""
        n = _integer(n, "step(n): n")
        if n < 0:
            raise ValueError("step(n): n must be 0 or more, not %d" % n)
        self._advance(lib.perifem_step, self._h(), n)

    def run(self):
        """Run to the deck's final time. Collective. Ctrl-C as in step()."""
        self._advance(lib.perifem_run, self._h())

    def check(self):
        """Print the set-up report of perifem --check (rank 0). Collective. Before the run
        has begun it times a few steps, which spend the model: step() and run() then fail."""
        _check(lib.perifem_print_check(self._h()))

    @property
    def finished(self):
        return bool(lib.perifem_finished(self._h()))

    @property
    def time(self):
        """Simulated time, s."""
        return lib.perifem_time(self._h())

    @property
    def step_count(self):
        return lib.perifem_step_count(self._h())

    @property
    def dt(self):
        """The step, s."""
        return lib.perifem_dt(self._h())

    @property
    def total_steps(self):
        """Steps of the whole run (an estimate when the step follows the deformation)."""
        return lib.perifem_total_steps(self._h())

    # ---- bodies and fields ----
    @property
    def bodies(self):
        """The bodies' names, in deck order."""
        h = self._h()
        return [lib.perifem_body_name(h, b).decode() for b in range(lib.perifem_body_count(h))]

    def _body(self, body):
        if isinstance(body, str):
            b = lib.perifem_body_index(self._h(), body.encode())
            if b < 0:
                raise PerifemError(2, "no body '%s' (bodies: %s)" % (body, ", ".join(self.bodies)))
            return b
        b = _integer(body, "body (its index or name)")
        if not 0 <= b < lib.perifem_body_count(self._h()):
            raise PerifemError(2, "no body %d (bodies: %s, numbered from 0)" % (b, ", ".join(self.bodies)))
        return b

    def points(self, body):
        """The number of the body's points on this rank."""
        return lib.perifem_body_points(self._h(), self._body(body))

    def points_global(self, body):
        """The number of the body's points over all ranks. Collective."""
        return lib.perifem_body_points_global(self._h(), self._body(body))

    def ids(self, body):
        """Global ids (int64) of the body's points on this rank, in the order of the fields."""
        b = self._body(body)
        out = np.empty(max(self.points(b), 0), dtype=np.int64)
        _check(lib.perifem_body_ids(self._h(), b, out.ctypes.data_as(ctypes.c_void_p)))
        return out

    @property
    def fields(self):
        """The field names: reference_position, position, displacement, velocity, force, mass,
        volume and the registered ones (damage, ...)."""
        h = self._h()
        return [lib.perifem_field_name(h, k).decode() for k in range(lib.perifem_field_count(h))]

    def field(self, body, name):
        """A copy of field name of the body's points on this rank: shape (points, components) for
        vectors, (points,) for scalars."""
        b = self._body(body)
        ncomp = lib.perifem_field_components(self._h(), _name(name, "the field's name"))
        n = max(self.points(b), 0)
        out = np.empty(n * max(ncomp, 1))
        _check(lib.perifem_field_read(self._h(), b, _name(name, "the field's name"), out.ctypes.data_as(ctypes.c_void_p),
                                      out.size))
        return out.reshape(n, ncomp) if ncomp > 1 else out

    def field_view(self, body, name):
        """Field name of the body's points on this rank without a copy: a read-only numpy array
        over the library's memory, valid until the next step or run (a step may move the points
        between ranks). The view keeps that memory after close() (the simulation is freed once
        the last view is gone). Use field() to keep values."""
        b = self._body(body)
        data, ncomp = ctypes.POINTER(ctypes.c_double)(), ctypes.c_int()
        _check(lib.perifem_field_view(self._h(), b, _name(name, "the field's name"), ctypes.byref(data),
                                      ctypes.byref(ncomp)))
        n, c = max(self.points(b), 0), ncomp.value
        if n == 0:
            return np.empty((0, c) if c > 1 else 0)
        a = np.asarray(_ViewMemory(self._handle, ctypes.cast(data, ctypes.c_void_p).value, n * c))
        a.flags.writeable = False
        return a.reshape(n, c) if c > 1 else a

    # ---- history ----
    @property
    def history_names(self):
        """The history's columns (time, step, energies, momentum, ...), once the run has started."""
        h = self._h()
        return [lib.perifem_history_name(h, k).decode() for k in range(lib.perifem_history_count(h))]

    @property
    def history_units(self):
        h = self._h()
        return [lib.perifem_history_unit(h, k).decode() for k in range(lib.perifem_history_count(h))]

    def history_row(self):
        """The history's values at the current step (numpy array, history_names' order)."""
        n = lib.perifem_history_count(self._h())
        out = np.empty(n)
        _check(lib.perifem_history_row(self._h(), out.ctypes.data_as(ctypes.c_void_p), n))
        return out

    def history(self):
        """The history at the current step as {column: value} (the same on every rank)."""
        return dict(zip(self.history_names, self.history_row().tolist()))

    # ---- checkpoint and digest ----
    def checkpoint(self, path):
        """Write a checkpoint of the current state to path (restart_from= continues from it).
        A path the run may not write (the deck, another input or output, a device, a FIFO, an
        unwritable folder) raises PerifemError (code 2) and writes nothing. Collective."""
        _check(lib.perifem_checkpoint(self._h(), _path(path, "the checkpoint's path")))

    def digest(self):
        """The state digest as perifem prints it ("%016x"), independent of the number of ranks.
        Collective."""
        d = ctypes.c_uint64()
        _check(lib.perifem_digest(self._h(), ctypes.byref(d)))
        return "%016x" % d.value
