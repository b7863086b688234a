#!/usr/bin/env bash
# Per-bond fields across ranks: unit/test_bond_fields (a bond field the code does not know,
# migrated to other ranks, checkpointed and read back, a checkpoint without it refused) on 2
# and 3 ranks.
# usage: mpi_bond_fields.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
bindir=$3 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
for np in 2 3; do
  out=$(run $np "$bindir/test_bond_fields" "$scratch" 2>&1) || { echo "test_bond_fields on $np ranks failed:"; echo "$out"; fail=1; }
done
exit $fail
