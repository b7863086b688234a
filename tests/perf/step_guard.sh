#!/usr/bin/env bash
# The whole-step guard: fails when a whole time step of a model family executes 10 % more
# instructions than recorded here, relative to a reference workload counted in the same process.
#
#   bash tests/perf/step_guard.sh path/to/step_guard WORKDIR     (ctest: perf/step_guard)
#
# For each deck of tests/perf/decks (PMB; LPS with omega = 1/|xi|; correspondence with the
# stiffness hourglass control; reduced hex8 finite elements, elastic and yielding under modified
# Johnson-Cook; FE <-> PD penalty contact with the
# PD block's self-contact; two PMB blocks in collision whose bonds break, the contact of
# fragments), step_guard builds the simulation, takes WARMUP steps, and valgrind's
# callgrind counts the instructions of STEPS whole steps (pf_sim_step: forces, damage, contact,
# integration, halo exchange, per-step records; no output files), then those of a fixed
# reference workload written in step_guard.c (4 velocity-Verlet steps of a plain bond-based PMB
# lattice, 1,000 points, 84,288 directed bonds, none failing, one bond at a time). The guarded
# number is
#   ratio = instructions of the steps / instructions of the reference.
#
# Why instructions and why a ratio. Instruction counts do not depend on the machine's load, nor
# on the CPU model but for glibc's CPU-dispatched string functions (under 1 % of a step; valgrind
# shows every CPU at most AVX2): repeated runs give the same count (spread 0, also beside a loaded machine,
# docs/verification.md), so a 10 % margin is all regression. They depend on the compiler and its
# flags; the reference, compiled by the same compiler with the same flags in the same build,
# moves with them, so the ratio follows the code rather than the toolchain. Valgrind does not
# execute AVX-512, so step_guard links a third build of the modules for x86-64-v3 (AVX2 and
# FMA, the batched bond loops' AVX2 form); the AVX-512 kernels are timed by
# unit/test_bond_loop_speed. Only one rank: the busy-polling of MPI waits would make the counts
# depend on timing (so the halo exchange is the 1-rank one, next to nothing). What counts cannot
# see: cache misses and memory traffic.
#
# The recorded ratios (BASELINE below) were measured with Debian 12's GCC 12.2 and valgrind
# 3.19 on the build of the commit that added this guard; the test fails when a ratio exceeds
# 1.10 x its baseline and notes one below 0.90 x (a faster step: lower the baseline then, so
# that the guard keeps its 10 %). A change that makes a step legitimately more expensive (a new
# feature in the step) updates its baseline in the same commit, saying why.
# Exit 77 (skip) when valgrind is missing or the CPU has no AVX2.
set -euo pipefail

exe=${1:?usage: step_guard.sh path/to/step_guard WORKDIR}
work=${2:?usage: step_guard.sh path/to/step_guard WORKDIR}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
limit=1.10

# family deck warm-up steps, counted steps, baseline ratio
BASELINE=(
  "pmb             pmb.yaml                  2 10 11.7864"
  "lps_inv_dist    lps_inverse_distance.yaml 2 10 24.2414"
  "correspondence  correspondence.yaml       2 10 11.3331"
  "hex8            hex8.yaml                 2 10 8.3074"
  "hex8_mjc        hex8_mjc.yaml             2 10 6.2420"
  "contact         contact.yaml              2 10 5.1130"
  "fragments       fragments.yaml           12 10 5.5916"
)

command -v valgrind >/dev/null 2>&1 || { echo "step_guard: valgrind not found (apt-get install valgrind); skipped"; exit 77; }
grep -qw avx2 /proc/cpuinfo || { echo "step_guard: the CPU has no AVX2 (the guard's build is x86-64-v3); skipped"; exit 77; }
[[ -x $exe ]] || { echo "step_guard: $exe not found" >&2; exit 1; }
exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
export OMPI_MCA_ess_singleton_isolated=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# instructions in a callgrind dump (its summary or totals line)
instructions() { awk '/^(summary|totals):/ { print $2; exit }' "$1"; }

fail=0
printf '%-15s %7s %8s %8s %12s %12s %9s %9s %7s %5s\n' family points bonds elements "step Ir" "ref. Ir" ratio baseline change "s" 
for row in "${BASELINE[@]}"; do
  read -r family deck warm steps base <<<"$row"
  out=$work/$family
  t0=$SECONDS
  (cd "$here/decks" && valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$out.cg" \
     "$exe" "$deck" "$warm" "$steps") >"$out.log" 2>&1 \
    || { tail -20 "$out.log"; echo "step_guard: $family: the run failed (log above)"; fail=1; continue; }
  step=$(instructions "$out.cg.1" || true)
  ref=$(instructions "$out.cg.2" || true)
  if [[ -z $step || -z $ref ]]; then
    echo "step_guard: $family: no callgrind counts in $out.cg.1 / $out.cg.2"; fail=1; continue
  fi
  read -r points bonds elements < <(sed -n 's/^steps [0-9]* points \([0-9]*\) bonds \([0-9]*\) elements \([0-9]*\) .*/\1 \2 \3/p' "$out.log")
  verdict=$(awk -v s="$step" -v r="$ref" -v b="$base" -v lim="$limit" 'BEGIN {
    q = s / r
    if (b <= 0) { printf "%.4f - new", q; exit }
    c = q / b
    printf "%.4f %.4f %+.1f%% %s", q, b, 100 * (c - 1), (c > lim ? "FAIL" : (c < 2 - lim ? "faster" : "ok")) }')
  read -r ratio shown change status <<<"$verdict"
  printf '%-15s %7s %8s %8s %12s %12s %9s %9s %7s %5s\n' "$family" "$points" "$bonds" "$elements" "$step" "$ref" "$ratio" "$shown" "$change" $((SECONDS - t0))
  case $status in
    FAIL) echo "step_guard: $family: $ratio is more than $limit x the baseline $shown: a whole step costs ${change} more instructions"; fail=1 ;;
    faster) echo "step_guard: $family: $ratio is below the baseline $shown by more than 10 %: lower the baseline in tests/perf/step_guard.sh" ;;
    "") echo "step_guard: $family: no baseline recorded"; fail=1 ;;
  esac
done
exit $fail
