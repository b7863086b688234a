#!/usr/bin/env bash
# The Python package's boundary (tests/library/test_python_api.py, on tests/library/free_body.yaml):
# TypeErrors for arguments of the wrong type (step(2.7), a string of overrides as one override),
# a failed checkpoint that fails its call only (the interpreter then ends with status 0), and a
# field view read after close(). The package from the source tree, the build's library.
# usage: python_api.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" && cp "$tests/library/free_body.yaml" .
PYTHONPATH="$tests/../python" PERIFEM_LIBRARY="$build/libperifem.so.0" "$PY" "$tests/library/test_python_api.py" free_body.yaml
status=$?
[ $status -eq 0 ] || echo "FAIL: test_python_api.py exited $status"
exit $status
