#!/usr/bin/env bash
# The installed library as a user sees it: cmake --install into a scratch prefix; the library's
# SONAME is libperifem.so.0 and it exports the perifem_* functions only; a C program
# (tests/library/free_body.c) compiled with `cc $(pkg-config --cflags --libs perifem)` runs
# tests/library/free_body.yaml in parts (momentum conserved, u = v t under a uniform velocity, bad
# input as a status) and the installed Python package, found by the system python3 with no
# other path than its site folder, runs the same deck (tests/library/test_python.py); both print
# the state digest, which must be the installed perifem's on the same deck.
# usage: library_install.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
prefix=$scratch/prefix
fail() { echo "FAIL: $*"; exit 1; }
cmake --install "$build" --prefix "$prefix" > install.log 2>&1 || { cat install.log; fail "cmake --install"; }
for f in bin/perifem include/perifem.h lib/libperifem.so.0 lib/pkgconfig/perifem.pc; do
  [ -e "$prefix/$f" ] || fail "$f is not installed"
done
soname=$(readelf -d "$prefix/lib/libperifem.so.0" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
[ "$soname" = libperifem.so.0 ] || fail "SONAME '$soname', expected libperifem.so.0"
others=$(nm -D --defined-only "$prefix/lib/libperifem.so.0" | awk '$3 !~ /^perifem_/ && $2 != "A"' | head -5)
[ -z "$others" ] || fail "the library exports more than perifem_*: $others"

export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
[ "$(pkg-config --modversion perifem)" = "$("$prefix/bin/perifem" --version | sed -n '1s/^perifem //p')" ] ||
  fail "perifem.pc's version $(pkg-config --modversion perifem) is not the executable's"
cc -o free_body "$tests/library/free_body.c" $(pkg-config --cflags --libs perifem) -Wl,-rpath,"$prefix/lib" -lm \
  2> cc.log || { cat cc.log; fail "compiling free_body.c with pkg-config"; }
cp "$tests/library/free_body.yaml" .
cli=$("$prefix/bin/perifem" --quiet --output-dir out_cli free_body.yaml 2>&1) || { echo "$cli"; fail "perifem"; }
want=$(echo "$cli" | sed -n 's/^state digest: //p')
got=$(./free_body free_body.yaml 2>&1) || { echo "$got"; fail "free_body (C)"; }
[ "$(echo "$got" | sed -n 's/^state digest: //p')" = "$want" ] || fail "C program's digest: $got; perifem's: $want"

site=$(dirname "$(find "$prefix" -path '*/perifem/__init__.py' | head -1)")
[ -f "$site/_library_path.py" ] || fail "the Python package is not installed with its library path"
got=$(env -u PERIFEM_LIBRARY PYTHONPATH="$(dirname "$site")" "$PY" "$tests/library/test_python.py" free_body.yaml 2>&1) ||
  { echo "$got"; fail "the installed Python package"; }
[ "$(echo "$got" | sed -n 's/^state digest: //p')" = "$want" ] || fail "Python's digest: $got; perifem's: $want"
exit 0
