#!/usr/bin/env bash
# The damaged checkpoints the checkpoint fuzz target found (tests/data/checkpoint_fuzz/*.bin, as
# libFuzzer wrote them: the first byte picks the deck of tests/fuzz/decks, in the order of
# tests/fuzz/fuzz_checkpoint.c, the rest is the file) are refused: a --restart from each exits
# with status 2 and a "perifem error" naming the file, with glibc's heap checks on
# (MALLOC_CHECK_=3), no signal. dense_fields_heap.bin: a damaged dense /fields group on which
# HDF5 1.10's lookup by index freed link messages it never decoded (abort, status 134).
# usage: checkpoint_fuzz_cases.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
decks=(pd fe coupled contact)
rm -rf "$scratch" && mkdir -p "$scratch"
for f in data/checkpoint_fuzz/*.bin; do
  name=$(basename "$f" .bin)
  deck=fuzz/decks/${decks[$(($(head -c 1 "$f" | od -An -tu1) % 4))]}.yaml
  tail -c +2 "$f" > "$scratch/$name.h5"
  out=$(MALLOC_CHECK_=3 timeout 60 "$exe" --quiet --output-dir "$scratch" --restart "$scratch/$name.h5" "$deck" 2>&1)
  status=$?
  if [ $status -ne 2 ] || ! echo "$out" | grep "perifem error" | grep -qF "$name.h5"; then
    echo "FAIL $name ($deck): exit $status, expected 2 and a message naming $name.h5:"
    echo "$out" | head -8
    fail=1
  fi
done
exit $fail
