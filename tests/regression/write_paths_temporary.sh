#!/usr/bin/env bash
# The checkpoint is written as <restart.file>.tmp and renamed: an output named like that
# temporary file (output.file or output.history_file c.h5.tmp beside restart.file c.h5, also
# spelt ./c.h5.tmp) is refused (exit 2, the output's key named, "the temporary file of the
# checkpoint"), nothing written; the same deck with another name runs.
# usage: write_paths_temporary.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
pd_deck "output: {file: c.h5.tmp}
restart: {file: c.h5, interval: 1}" > exodus.yaml && refused exodus.yaml file "temporary file of the checkpoint"
pd_deck "output: {history_file: ./c.h5.tmp}
restart: {file: c.h5, interval: 1}" > history.yaml && refused history.yaml history_file "temporary file of the checkpoint"
pd_deck "output: {file: c.e}
restart: {file: c.h5, interval: 1}" > valid.yaml
"$exe" --quiet valid.yaml > /dev/null 2>&1 && [ -s c.e ] && [ -s c.h5 ] && [ ! -e c.h5.tmp ] ||
  { echo "FAIL: the valid deck did not write c.e and c.h5"; fail=1; }
exit $fail
