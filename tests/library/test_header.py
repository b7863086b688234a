"""The Python package's ctypes declarations against include/perifem.h: every function the header
declares is declared in perifem/_library.py (and nothing else), with the same number of
arguments, and each argument's and result's ctypes type is the one the C type needs; the fields
of perifem.Options are those of struct perifem_options, in order, with the same types. A header
change the Python side misses fails here (ctypes would otherwise pass wrong arguments silently).
usage: python3 test_header.py include/perifem.h   (the package importable: PYTHONPATH, PERIFEM_LIBRARY)"""
import ctypes
import re
import sys
from ctypes import POINTER, c_char_p, c_double, c_int, c_int64, c_long, c_uint64, c_void_p

from perifem import _library

header = open(sys.argv[1]).read()
text = re.sub(r"/\*.*?\*/", " ", header, flags=re.S)  # comments out
text = re.sub(r"^\s*#.*$", " ", text, flags=re.M)  # preprocessor lines out

Options = _library.Options
# The ctypes types a C type may be given as (a pointer to an array may be passed as c_void_p).
ALLOWED = {
    "void": [None],
    "int": [c_int],
    "long": [c_long],
    "double": [c_double],
    "int64_t": [c_int64],
    "const char *": [c_char_p],
    "const char *const *": [POINTER(c_char_p)],
    "int *": [POINTER(c_int)],
    "double *": [POINTER(c_double), c_void_p],
    "int64_t *": [POINTER(c_int64), c_void_p],
    "uint64_t *": [POINTER(c_uint64)],
    "const double **": [POINTER(POINTER(c_double))],
    "perifem_sim *": [c_void_p],
    "const perifem_sim *": [c_void_p],
    "perifem_sim **": [POINTER(c_void_p)],
    "const perifem_options *": [POINTER(Options)],
}


def normal(ctype):
    """'const char*' -> 'const char *' (one spelling per type)."""
    t = re.sub(r"\s*\*\s*", " *", ctype.strip())
    t = re.sub(r"\*\s+\*", "**", re.sub(r"\s+", " ", t))
    return t.replace("* const", "*const")


def split_decl(decl):
    """'const char *name' -> ('const char *', 'name')."""
    m = re.match(r"^(.*?)(\w+)\s*$", decl.strip(), flags=re.S)
    return normal(m.group(1)), m.group(2)


failures = []


def fail(what):
    failures.append(what)
    print("FAIL: " + what, file=sys.stderr)


def same(ctype, given, where):
    allowed = ALLOWED.get(ctype)
    if allowed is None:
        fail("%s: the C type '%s' has no ctypes mapping in this test (add it)" % (where, ctype))
    elif not any(given is a or (a is not None and given == a) for a in allowed):
        fail("%s: C type '%s' is declared as %s in Python (expected %s)" %
             (where, ctype, getattr(given, "__name__", given), " or ".join(getattr(a, "__name__", str(a)) for a in allowed)))


# the functions
functions = {}
for m in re.finditer(r"([A-Za-z_][\w\s\*]*?\bperifem_\w+)\s*\(([^;{]*?)\)\s*;", text, flags=re.S):
    ret, name = split_decl(m.group(1))
    args = m.group(2).strip()
    params = [] if args in ("", "void") else [split_decl(a)[0] for a in args.split(",")]
    functions[name] = (ret, params)
declared = _library._PROTOTYPES
for name in sorted(set(functions) - set(declared)):
    fail("%s is in perifem.h but not declared in perifem/_library.py" % name)
for name in sorted(set(declared) - set(functions)):
    fail("%s is declared in perifem/_library.py but not in perifem.h" % name)
for name in sorted(set(functions) & set(declared)):
    ret, params = functions[name]
    pres, pargs = declared[name]
    same(ret, pres, "%s's result" % name)
    if len(params) != len(pargs):
        fail("%s takes %d arguments in perifem.h, %d in Python" % (name, len(params), len(pargs)))
        continue
    for k, (c, p) in enumerate(zip(params, pargs)):
        same(c, p, "%s's argument %d" % (name, k + 1))
    f = getattr(_library.lib, name)
    if f.restype is not pres or f.argtypes != pargs:
        fail("%s: the library's function was not given the declared prototype" % name)

# the options struct
body = re.search(r"typedef struct perifem_options\s*\{(.*?)\}\s*perifem_options\s*;", text, flags=re.S).group(1)
fields = [split_decl(d) for d in body.split(";") if d.strip()]
given = Options._fields_
if [n for _, n in fields] != [n for n, _ in given]:
    fail("perifem_options' fields %s; Options' %s" % ([n for _, n in fields], [n for n, _ in given]))
else:
    for (c, n), (_, p) in zip(fields, given):
        same(c, p, "perifem_options.%s" % n)

if not failures:
    print("perifem.h and the Python declarations agree: %d functions, %d option fields" % (len(functions), len(fields)))
sys.exit(1 if failures else 0)
