#!/usr/bin/env bash
# The statistics of a campaign (python/perifem/basis.py; tests/library/test_basis.py): the normal
# tolerance factors against CMH-17-1G's table, Natrella's values and (when scipy is there) the
# noncentral t quantile of scipy; the handbook's closed forms; the B- and A-basis values STAT-17
# gives for an 18-value sample (normal and Weibull); the Weibull fit; Monte Carlo coverage.
# usage: python_basis.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
PYTHONPATH="$tests/../python" PERIFEM_LIBRARY="$build/libperifem.so.0" "$PY" "$tests/library/test_basis.py"
status=$?
[ $status -eq 0 ] || echo "FAIL: test_basis.py exited $status"
exit $status
