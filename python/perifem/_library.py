"""Loading libperifem.so.0 and declaring its functions (include/perifem.h) for ctypes."""
import ctypes
import os

from ctypes import POINTER, c_char_p, c_double, c_int, c_int64, c_long, c_uint64, c_void_p

PERIFEM_OK, PERIFEM_ERR_RUN, PERIFEM_ERR_INPUT, PERIFEM_ERR_MEMORY, PERIFEM_ERR_LIB = range(5)


class Options(ctypes.Structure):
    """struct perifem_options (include/perifem.h), field for field."""
    _fields_ = [("overrides", POINTER(c_char_p)), ("noverrides", c_int), ("output_dir", c_char_p),
                ("no_output", c_int), ("restart_from", c_char_p), ("quiet", c_int), ("strict", c_int),
                ("progress", c_int), ("silent_errors", c_int), ("catch_signals", c_int), ("use_comm", c_int),
                ("comm", c_int), ("command_line", c_char_p)]


# The CMake install prefix's default (cmake --install, scripts/setup.sh).
_DEFAULT_PREFIX_LIBRARY = "/usr/local/lib/libperifem.so.0"


def _pkg_config_library():
    """libperifem.so.0 in the libdir of `pkg-config perifem` (PKG_CONFIG_PATH), or None."""
    import shutil
    import subprocess
    exe = shutil.which("pkg-config")
    if not exe:
        return None
    try:
        out = subprocess.run([exe, "--variable=libdir", "perifem"], capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    libdir = out.stdout.strip()
    return os.path.join(libdir, "libperifem.so.0") if out.returncode == 0 and libdir else None


def _candidates():
    """Where to look for the library, first to last (docs/library.md):
      1. $PERIFEM_LIBRARY, when set (then the only place);
      2. the path recorded when the package was installed (_library_path.py: written by
         cmake --install, or by pip from pkg-config or $PERIFEM_LIBRARY at that time);
      3. the libdir of `pkg-config perifem`;
      4. the dynamic loader's search path (LD_LIBRARY_PATH, ldconfig's cache);
      5. the CMake install prefix's default, /usr/local/lib."""
    if os.environ.get("PERIFEM_LIBRARY"):
        yield "$PERIFEM_LIBRARY", os.environ["PERIFEM_LIBRARY"]
        return
    try:
        from ._library_path import LIBRARY  # written at install time
        yield "the path recorded at install time", LIBRARY
    except ImportError:
        pass
    found = _pkg_config_library()
    if found:
        yield "pkg-config perifem", found
    yield "the dynamic loader's path", "libperifem.so.0"
    yield "the default install prefix", _DEFAULT_PREFIX_LIBRARY


def _load():
    errors = []
    for where, path in _candidates():
        try:
            # RTLD_GLOBAL: Open MPI's plug-ins look up MPI's own symbols in the global namespace
            return ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
        except OSError as e:
            errors.append("%s: %s" % (where, e))
    raise ImportError("perifem: cannot load libperifem.so.0; looked at, in order:\n  " + "\n  ".join(errors) +
                      "\nset PERIFEM_LIBRARY to its path, or PKG_CONFIG_PATH to the folder of perifem.pc")


lib = _load()

_SIM = c_void_p
_PROTOTYPES = {
    "perifem_version": (c_char_p, []),
    "perifem_version_numbers": (None, [POINTER(c_int), POINTER(c_int), POINTER(c_int)]),
    "perifem_last_error": (c_char_p, []),
    "perifem_create": (c_int, [c_char_p, POINTER(Options), POINTER(_SIM)]),
    "perifem_create_from_string": (c_int, [c_char_p, c_char_p, POINTER(Options), POINTER(_SIM)]),
    "perifem_destroy": (c_int, [POINTER(_SIM)]),
    "perifem_finalize": (c_int, []),
    "perifem_step": (c_int, [_SIM, c_long]),
    "perifem_run": (c_int, [_SIM]),
    "perifem_finished": (c_int, [_SIM]),
    "perifem_time": (c_double, [_SIM]),
    "perifem_step_count": (c_long, [_SIM]),
    "perifem_dt": (c_double, [_SIM]),
    "perifem_total_steps": (c_long, [_SIM]),
    "perifem_catch_signals": (c_int, [c_int]),
    "perifem_signal_caught": (c_int, []),
    "perifem_print_check": (c_int, [_SIM]),
    "perifem_body_count": (c_int, [_SIM]),
    "perifem_body_name": (c_char_p, [_SIM, c_int]),
    "perifem_body_index": (c_int, [_SIM, c_char_p]),
    "perifem_body_points": (c_long, [_SIM, c_int]),
    "perifem_body_points_global": (c_int64, [_SIM, c_int]),
    "perifem_body_ids": (c_int, [_SIM, c_int, c_void_p]),
    "perifem_field_count": (c_int, [_SIM]),
    "perifem_field_name": (c_char_p, [_SIM, c_int]),
    "perifem_field_components": (c_int, [_SIM, c_char_p]),
    "perifem_field_read": (c_int, [_SIM, c_int, c_char_p, c_void_p, c_long]),
    "perifem_field_view": (c_int, [_SIM, c_int, c_char_p, POINTER(POINTER(c_double)), POINTER(c_int)]),
    "perifem_history_count": (c_int, [_SIM]),
    "perifem_history_name": (c_char_p, [_SIM, c_int]),
    "perifem_history_unit": (c_char_p, [_SIM, c_int]),
    "perifem_history_row": (c_int, [_SIM, c_void_p, c_int]),
    "perifem_history_value": (c_int, [_SIM, c_char_p, POINTER(c_double)]),
    "perifem_checkpoint": (c_int, [_SIM, c_char_p]),
    "perifem_digest": (c_int, [_SIM, POINTER(c_uint64)]),
}
for _name, (_res, _args) in _PROTOTYPES.items():
    _f = getattr(lib, _name)
    _f.restype, _f.argtypes = _res, _args
