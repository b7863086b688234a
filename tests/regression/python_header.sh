#!/usr/bin/env bash
# The Python package's ctypes prototypes and options struct against include/perifem.h
# (tests/library/test_header.py): names, argument counts and types, the struct's fields in order.
# usage: python_header.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
build=$(cd "$3/.." && pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
PYTHONPATH=../python PERIFEM_LIBRARY="$build/libperifem.so.0" "$PY" library/test_header.py ../include/perifem.h
