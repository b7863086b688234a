#!/usr/bin/env bash
# A FIFO (named pipe) is no output: as output.file, output.history_file and restart.file it is
# refused (exit 2 within the time limit, not a run blocked on the pipe; the key named, "is a
# FIFO"), nothing written, the FIFO left a FIFO.
# usage: write_paths_fifo.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
mkfifo pipe || { echo "SKIP: no mkfifo"; exit 77; }
pd_deck "output: {file: pipe}" > exodus.yaml && refused exodus.yaml file "is a FIFO"
pd_deck "output: {history_file: pipe}" > history.yaml && refused history.yaml history_file "is a FIFO"
pd_deck "restart: {file: pipe, interval: 1}" > checkpoint.yaml && refused checkpoint.yaml file "is a FIFO"
[ -p pipe ] || { echo "FAIL: the FIFO was replaced"; fail=1; }
exit $fail
