#!/usr/bin/env bash
# The Python package under mpirun on 2 ranks with mpi4py giving the communicator (a duplicate of
# MPI_COMM_WORLD): tests/library/test_python.py's checks (momentum from the history and from the
# fields summed over the ranks, u = v t, the history file's last row, COMM_SELF refused) and
# the state digest equal to perifem's on 2 ranks. Skipped (77) without mpi4py.
# usage: mpi_python_api.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
exe=$1 scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
source common/mpi_env.sh
"$PY" -c "import mpi4py" 2>/dev/null || { echo "SKIP: no mpi4py (apt-get install python3-mpi4py)"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
cp "$tests/library/free_body.yaml" .
cli=$(run 2 "$exe" --quiet --output-dir out_cli free_body.yaml 2>&1) || { echo "$cli"; echo "FAIL: perifem"; exit 1; }
want=$(digest_of "$cli")
got=$(run 2 -x PYTHONPATH="$tests/../python" -x PERIFEM_LIBRARY="$build/libperifem.so.0" \
      "$PY" "$tests/library/test_python.py" free_body.yaml --mpi 2>&1) ||
  { echo "$got"; echo "FAIL: the Python package on 2 ranks"; exit 1; }
[ "$(digest_of "$got")" = "$want" ] || { echo "$got"; echo "FAIL: digest on 2 ranks, perifem's $want"; exit 1; }
exit 0
