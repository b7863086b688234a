#!/usr/bin/env bash
# The Python package installed as Python packages are (docs/library.md, "Installing"): the
# library cmake --install'ed into a scratch prefix, a virtual environment that sees the system's
# numpy (python3 -m venv --system-site-packages), `pip install --no-build-isolation --no-index`
# of a copy of python/ with PKG_CONFIG_PATH naming the prefix's perifem.pc; then, with no
# PERIFEM_LIBRARY, PYTHONPATH, PKG_CONFIG_PATH or LD_LIBRARY_PATH, the environment's python
# imports perifem from the environment, loads the prefix's library (the path pip recorded), has
# the library's version, and runs tests/library/test_python.py on tests/library/free_body.yaml
# (a free block, 60 steps), whose state digest must be the installed perifem's. A library that
# cannot be loaded gives an ImportError listing where it looked. Skipped (77) without python3-venv.
# usage: python_venv.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
"$PY" -c "import venv, ensurepip" 2> /dev/null || { echo "SKIP: python3-venv is not installed (apt-get install python3-venv)"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
prefix=$scratch/prefix
fail() { echo "FAIL: $*"; exit 1; }
clean() { env -u PERIFEM_LIBRARY -u PYTHONPATH -u PKG_CONFIG_PATH -u LD_LIBRARY_PATH "$@"; }
cmake --install "$build" --prefix "$prefix" > install.log 2>&1 || { cat install.log; fail "cmake --install"; }
"$PY" -m venv --system-site-packages env > venv.log 2>&1 || { cat venv.log; fail "python3 -m venv"; }
cp -r "$tests/../python" src && rm -rf src/perifem/_library_path.py src/build src/*.egg-info
clean PKG_CONFIG_PATH="$prefix/lib/pkgconfig" env/bin/pip install --no-build-isolation --no-index ./src > pip.log 2>&1 ||
  { cat pip.log; fail "pip install"; }

where=$(cd / && clean "$scratch/env/bin/python" -c "import perifem, perifem._library as l; print(perifem.__file__); print(l.lib._name); print(perifem.version())" 2>&1) ||
  { echo "$where"; fail "import perifem in the environment"; }
echo "$where"
file=$(echo "$where" | sed -n 1p) loaded=$(echo "$where" | sed -n 2p) version=$(echo "$where" | sed -n 3p)
case "$file" in "$scratch"/env/lib/python3*/site-packages/perifem/__init__.py) ;; *) fail "perifem imported from $file, not the environment";; esac
[ "$(readlink -f "$loaded")" = "$(readlink -f "$prefix/lib/libperifem.so.0")" ] || fail "the library loaded is $loaded, not the prefix's"
pip_version=$(env/bin/pip show perifem 2> /dev/null | sed -n 's/^Version: //p')
[ "$pip_version" = "$version" ] || fail "pip's version of the package $pip_version, the library's $version"

cp "$tests/library/free_body.yaml" .
want=$("$prefix/bin/perifem" --quiet --output-dir out_cli free_body.yaml 2>&1 | sed -n 's/^state digest: //p')
got=$(clean env/bin/python "$tests/library/test_python.py" free_body.yaml 2>&1) || { echo "$got"; fail "test_python.py in the environment"; }
[ -n "$want" ] && [ "$(echo "$got" | sed -n 's/^state digest: //p')" = "$want" ] || fail "digest $got; perifem's $want"

err=$(clean PERIFEM_LIBRARY=/nonexistent/libperifem.so.0 env/bin/python -c "import perifem" 2>&1) && fail "a missing library was imported"
echo "$err" | grep -q "ImportError: perifem: cannot load libperifem.so.0; looked at, in order:" &&
  echo "$err" | grep -q "PERIFEM_LIBRARY: /nonexistent/libperifem.so.0" || { echo "$err"; fail "the ImportError does not say where it looked"; }
echo "venv: perifem $version from $file, library $loaded; digest $want"
exit 0
