# Shared by the mpi_*.sh tests (sourced, not run): mpirun as root and oversubscribed, and a
# python3 that has netCDF4.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Ranks that wait yield the core: ctest -j2 runs two multi-rank tests on 2 cores, and busy-waiting
# ranks took the core from the rank they waited for (mpi_verify and mpi_digests side by side:
# 265 and 184 s busy-waiting, 195 and 150 s yielding).
export OMPI_MCA_mpi_yield_when_idle=1
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
# run NP ARGS...: mpirun on NP ranks, output to stdout
run() { local np=$1; shift; mpirun --oversubscribe -np "$np" "$@"; }
# digest_of TEXT: the "state digest: X" value
digest_of() { echo "$1" | sed -n 's/^state digest: //p'; }
# crash_in TEXT: 0 when TEXT shows a crash (a segmentation fault, a core dump, a double free, a
# process ended by a signal other than the SIGTERM with which MPI_Abort ends the other ranks of a
# run that stopped on an error)
crash_in() {
  echo "$1" | grep -qiE "segmentation|core dumped|double free" && return 0
  echo "$1" | grep -iE "signal [0-9]+|Signal:" | grep -qvE "signal 15\b|Terminated"
}
# digests_agree LABEL D1 D2 D3: the state digests of one deck on 1, 2 and 3 ranks are one (printed;
# status 1 and a FAIL line when not)
digests_agree() {
  local label=$1
  shift
  echo "$label: digests on 1, 2, 3 ranks: $*"
  [ $# = 3 ] && [ "$1" = "$2" ] && [ "$1" = "$3" ] || { echo "FAIL: $label: the digests differ"; return 1; }
}
# static_digests EXE DECK: DECK.yaml of this folder under the quasi-static solver cut to 2 load
# steps at tolerance 1e-4, on 1, 2 and 3 ranks (each run in DECK<np>/): the same state digest
# (status 1 and FAIL lines when not)
static_digests() {
  local exe=$1 deck=$2 digests="" np o st=0
  for np in 1 2 3; do
    mkdir -p "$deck$np"
    o=$(cd "$deck$np" && run $np "$exe" --quiet --set solver.load_steps=2 --set solver.tolerance=1e-4 "../$deck.yaml" 2>&1) ||
      { echo "FAIL: $deck on $np ranks: $o"; st=1; }
    digests="$digests $(digest_of "$o")"
  done
  digests_agree "$deck" $digests || st=1
  return $st
}
