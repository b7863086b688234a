#!/usr/bin/env bash
# Paths of any length. The Exodus library (6.02) formats the path of a failed ex_create or ex_open
# into a 256-byte message and the process aborts (SIGABRT) from about 210 bytes (140 for a
# compressed file): longer paths reach it through a short alias, and a path the system cannot take
# (over 4000 bytes) is refused with the key and the limit.
#  1. a 300-byte Exodus output path in an existing folder, classic and compressed: the runs write
#     a netCDF and an HDF5 (netCDF-4) file;
#  2. a mistyped folder deep in a 300-byte path: refused before anything is written (exit 2, the
#     key, "No such file or directory"), no abort;
#  3. a damaged mesh file at a 300-byte path: an input error naming the file (exit 2), no abort;
#  4. a 5000-byte output.file, and the default names under a 5000-byte --output-dir: exit 2,
#     the key and "at most 4000";
#  5. the HDF5 files, opened through MPI-IO, at a 300-byte path: a checkpoint every step and the
#     history are written (Open MPI's lockedfile component aborted the process there, "buffer
#     overflow detected", until perifem left it out: core/comm.c).
# usage: write_paths_long.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
long=$scratch/$(printf 'd%.0s' $(seq 60))
long=$long/${long##*/}/${long##*/}/${long##*/}/${long##*/}
mkdir -p "$long" || exit 1
magic() { head -c 4 "$1" | od -An -c | tr -d ' '; }
# 1.
pd_deck "output: {file: $long/classic.e}" > classic.yaml
pd_deck "output: {file: $long/compressed.e, compression: 4}" > compressed.yaml
for deck in classic compressed; do
  out=$("$exe" --quiet $deck.yaml 2>&1) || { echo "$out"; echo "FAIL: $deck: exit status $?"; fail=1; }
done
[ ${#long} -gt 280 ] && [ "$(magic "$long/classic.e")" = "CDF002" ] && [ "$(magic "$long/compressed.e")" = "211HDF" ] ||
  { echo "FAIL: the Exodus files at ${#long}+ bytes: $(ls -l "$long")"; fail=1; }
# 2.
pd_deck "output: {file: ${long}x/out.e}" > typo.yaml && refused typo.yaml file "No such file or directory"
# 3.
echo "not an Exodus file" > "$long/bad.e"
printf '%s\n' "materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}" \
  "bodies: [{name: block, type: finite_element, material: steel, mesh: {file: $long/bad.e}}]" "time: {steps: 3}" > mesh.yaml
out=$(timeout 60 "$exe" --quiet mesh.yaml 2>&1); rc=$?
[ $rc = 2 ] && echo "$out" | grep -q "$long/bad.e: Exodus ex_open" ||
  { echo "$out" | tail -3; echo "FAIL: a damaged mesh at a ${#long}-byte path: exit status $rc"; fail=1; }
# 4.
huge=$scratch$(printf "/$(printf 'e%.0s' $(seq 200))%.0s" $(seq 25))
pd_deck "output: {file: $huge/out.e}" > huge.yaml && refused huge.yaml file "is 5[0-9]* bytes long; at most 4000"
pd_deck "" > plain.yaml && refused plain.yaml file "is 5[0-9]* bytes long; at most 4000" --output-dir "$huge"
# 5.
pd_deck "output: {history_file: $long/history.h5}
restart: {file: $long/ck.h5, interval: 1}" > hdf5.yaml
out=$(timeout 60 "$exe" --quiet hdf5.yaml 2>&1); rc=$?
[ $rc = 0 ] && [ "$(magic "$long/ck.h5")" = "211HDF" ] && [ "$(magic "$long/history.h5")" = "211HDF" ] ||
  { echo "$out" | tail -3; echo "FAIL: a checkpoint and a history at a ${#long}-byte path: exit status $rc"; fail=1; }
exit $fail
