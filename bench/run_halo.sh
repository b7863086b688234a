#!/usr/bin/env bash
# Halo traffic per step and rank, measured against the geometric model, and the weak-scaling
# estimate built on it (docs/parallel.md, section 7).
#
#   bash bench/run_halo.sh [path/to/perifem]      # default: build/perifem
#
# 1. Traffic. A PD box of 40 x 40 x 40 points (0.5 mm lattice, horizon 3.0002 spacings: PMB,
#    LPS, and PMB with a self-contact pair) runs on each rank count of HALO_RANKS (oversubscribed:
#    the counts do not depend on the cores) with bench/mpi_tally.c preloaded, for 10 and for 30
#    steps. The difference of the two runs is the time loop's traffic: per step and rank, messages
#    sent, bytes sent and MPI_Allreduce calls (largest and mean over the ranks). The model
#    (bench/halo_model.py split) counts each rank's ghosts on the same box cut by recursive
#    bisection with uniform weights; a step's exchanges send 3 doubles a ghost in 1 message a
#    neighbour rank (PMB: the displacements) or 5 in 3 (LPS: the displacements, the dilatation,
#    its moment).
# 2. Measured where the cores allow it, PMB, HALO_STEPS steps, time loop: the box on 1 rank, and
#    twice the box (80 x 40 x 40) on 2 ranks x 1 thread and on 1 rank x 2 threads (weak-scaling
#    efficiency, and the better split of this machine's 2 cores).
# 3. The estimate to 1,000 ranks (bench/halo_model.py weak): a rank a cube of n points (each of
#    HALO_POINTS) with neighbours on every side; step time = compute (the 1-rank run's time per
#    point-step) + halo (neighbours x alpha + bytes / beta) + reduction (2 alpha log2 P);
#    alpha and beta are the network's latency and bandwidth, HALO_ALPHA (s, default 2e-6) and
#    HALO_BETA (bytes per s, default 1e10): assumed, not measured here.
#
# Environment: HALO_RANKS (default "2 3 4 8 16"), HALO_STEPS (default 100), HALO_REPEAT (timed
# runs of each case, the fastest counts; default 2), HALO_POINTS (default "100000 10000"), HALO_ALPHA, HALO_BETA, HALO_KEEP=1 keeps the work directory. The
# tables go to stdout and to bench/results/halo.txt.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
ranks=${HALO_RANKS:-2 3 4 8 16}
steps=${HALO_STEPS:-100}
npts=${HALO_POINTS:-100000 10000}
repeat=${HALO_REPEAT:-2}
alpha=${HALO_ALPHA:-2e-6}
beta=${HALO_BETA:-1e10}

die() { echo "run_halo.sh: error: $*" >&2; exit 1; }
[[ -x $perifem ]] || die "perifem binary '$perifem' not found or not executable (build it, or pass its path)"
command -v mpicc >/dev/null || die "mpicc not found (Debian: apt-get install -y libopenmpi-dev)"
py=$(command -v python3 || true)
[[ -n $py ]] || die "python3 not found"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1

work=$(mktemp -d /tmp/perifem_halo.XXXXXX)
cleanup() { if [[ ${HALO_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT
mpicc -O2 -shared -fPIC -o "$work/libmpi_tally.so" "$here/mpi_tally.c" || die "could not build bench/mpi_tally.c"

# deck NAME MODEL NX [SECTION]: a box of NX x 40 x 40 points, with SECTION appended
deck() {
  local extra=""
  [[ $2 == lps ]] && extra=", shear_modulus: 1.0e10"
  cat >"$work/$1.yaml" <<EOF
# bench/run_halo.sh: a $3 x 40 x 40 box, $2
materials:
  m: {model: $2, density: 2200, bulk_modulus: 1.49e10$extra}
bodies:
  - name: box
    material: m
    geometry: {shape: box, lo: [0, 0, 0], hi: [$(awk -v n="$3" 'BEGIN { print (n - 1) * 0.0005 }'), 0.0195, 0.0195], spacing: 0.0005}
    horizon: 0.0015001
    initial_velocity: ["x > 0.01 ? 1 : 0", "0", "0"]
time: {steps: 10, dt: 1e-7}
output: {interval: 0, history_interval: 100000}
${4:-}
EOF
}
deck pmb pmb 40
deck lps lps 40
deck pmb_twice pmb 80
deck contact pmb 40 "contact: {skin: 0.0001, pairs: [{bodies: [box, box]}]}"

# tally NAME NP STEPS: the per-rank lines of mpi_tally
tally() {
  local f=$work/tally_$1_$2_$3.txt
  rm -f "$f"
  MPI_TALLY_FILE=$f mpirun --oversubscribe -np "$2" -x LD_PRELOAD="$work/libmpi_tally.so" -x MPI_TALLY_FILE \
    "$perifem" --set time.steps="$3" --output-dir "$work/out_$1_$2_$3" "$work/$1.yaml" >"$work/log_$1_$2_$3" 2>&1 \
    || { tail -20 "$work/log_$1_$2_$3" >&2; die "perifem failed: $1 on $2 ranks"; }
  [[ $(wc -l <"$f") == "$2" ]] || die "mpi_tally wrote $(wc -l <"$f") lines for $2 ranks (is LD_PRELOAD honoured?)"
  sort -k2,2n "$f"
}

loop_time() { sed -n 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$1" | head -1; }

# traffic NAME NP: the time loop's traffic per step (30-step run less 10-step run, / 20) as
# "bytes_max bytes_mean messages_max allreduce_max" over the ranks
traffic() {
  paste <(tally "$1" "$2" 10) <(tally "$1" "$2" 30) | awk '
    { s = ($14 - $4) / 20; by = ($16 - $6) / 20; ar = ($18 - $8) / 20
      if (s > smax) smax = s; if (by > bmax) bmax = by; bsum += by; if (ar > armax) armax = ar }
    END { printf "%.0f %.0f %.1f %.1f\n", bmax, bsum / NR, smax, armax }'
}

# model NP DOUBLES EXCHANGES: "bytes_mean messages_max" of halo_model.py's split of the box
model() {
  "$py" "$here/halo_model.py" split 40 40 40 3.0002 "$1" | awk -v nc="$2" -v ne="$3" '
    { g += $6; if ($8 > nb) nb = $8 } END { printf "%.0f %d\n", g * nc * 8 / NR, nb * ne }'
}

# timed NP THREADS DECK: the time loop's seconds of HALO_STEPS steps, the fastest of HALO_REPEAT
# runs. --bind-to none: Open MPI binds each of 1 or 2 ranks to one core by default, which puts
# all threads of a rank on that core.
timed() {
  local log=$work/timed_$1_$2_$3.log best="" t
  for _ in $(seq "$repeat"); do
    OMP_NUM_THREADS=$2 mpirun --oversubscribe --bind-to none -np "$1" -x OMP_NUM_THREADS "$perifem" --set time.steps="$steps" \
      --output-dir "$work/timed_$1_$2_$3" "$work/$3.yaml" >"$log" 2>&1 || die "perifem failed: $3 on $1 x $2"
    t=$(loop_time "$log")
    [[ -n $t ]] || die "no 'time loop' in $log"
    best=$(awk -v a="$t" -v b="$best" 'BEGIN { print (b == "" || a < b) ? a : b }')
  done
  echo "$best"
}

{
  echo "perifem halo traffic per step and rank against the geometric model (bench/run_halo.sh)"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine:  $(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -1), nproc $(nproc)"
  echo "perifem:  $("$perifem" --version | head -1)"
  echo "problem:  box of 40 x 40 x 40 points, h = 0.5 mm, horizon 3.0002 h; 30 steps less 10"
  echo
  printf '%-5s %5s %12s %12s %12s %7s %9s %9s %9s\n' model ranks "bytes max" "bytes mean" "model mean" ratio "msgs max" "model" allreduce
  for np in $ranks; do
    for spec in "pmb 3 1" "lps 5 3" "contact - -"; do
      read -r name nc ne <<<"$spec"
      read -r bmax bmean smax armax <<<"$(traffic "$name" "$np")"
      mb=- mm=- ratio=-
      if [[ $nc != - ]]; then
        read -r mb mm <<<"$(model "$np" "$nc" "$ne")"
        ratio=$(awk -v a="$bmean" -v b="$mb" 'BEGIN { printf "%.4f", a / b }')
      fi
      printf '%-5s %5d %12s %12s %12s %7s %9s %9s %9s\n' "${name/contact/pmb+c}" "$np" "$bmax" "$bmean" "$mb" "$ratio" "$smax" "$mm" "$armax"
    done
  done
  echo
  echo "bytes, msgs: sent per step by a rank (the largest and the mean over the ranks); model: the ghosts"
  echo "  of bench/halo_model.py split 40 40 40 3.0002 P x doubles x 8, and neighbour ranks x exchanges"
  echo "  (PMB: 1 exchange, 3 doubles: the displacements; LPS: 3 exchanges, 5 doubles: the displacements,"
  echo "  the dilatation, its moment); allreduce: calls per step. pmb+c: the PMB box with a self-contact"
  echo "  pair (skin 0.1 mm), measured only: the contact's view exchanges depend on the motion."
  echo
  t1=$(timed 1 1 pmb) t2=$(timed 2 1 pmb_twice) t3=$(timed 1 2 pmb_twice)
  echo "measured here, PMB, $steps steps, time loop (the fastest of $repeat runs): 1 rank, 64,000 points: $t1 s; 128,000 points on"
  echo "  2 ranks x 1 thread: $t2 s, on 1 rank x 2 threads: $t3 s"
  awk -v a="$t1" -v b="$t2" -v c="$t3" -v s="$steps" 'BEGIN {
    printf "  weak-scaling efficiency 1 -> 2 ranks %.3f; threads / ranks %.3f; %.1f ns a point-step\n", a / b, c / b, 1e9 * a / (s * 64000) }'
  echo
  cpp=$(awk -v a="$t1" -v s="$steps" 'BEGIN { print a / (s * 64000) }')
  echo "estimate, PMB, each rank a cube of n points inside the body: step = compute + halo + reduction;"
  echo "  compute $cpp s a point-step (measured above); alpha $alpha s, beta $beta B/s (assumed);"
  echo "  halo = neighbours x alpha + ghosts x 24 B / beta; reduction = 2 alpha log2 P (1 a step)"
  printf '%9s %7s %9s %11s %12s %12s %12s %11s\n' n ghosts neighbours ranks "compute [s]" "halo [s]" "reduce [s]" efficiency
  for n in $npts; do
    read -r _ nc _ g _ nb <<<"$("$py" "$here/halo_model.py" weak "$n" 3.0002)"
    for P in 8 64 216 512 1000; do
      awk -v P="$P" -v n="$nc" -v g="$g" -v nb="$nb" -v c="$cpp" -v al="$alpha" -v be="$beta" 'BEGIN {
        tc = n * c; th = nb * al + g * 3 * 8 / be; tr = 2 * al * log(P) / log(2)
        printf "%9d %7d %9d %11d %12.3e %12.3e %12.3e %11.4f\n", n, g, nb, P, tc, th, tr, tc / (tc + th + tr) }'
    done
  done
} | tee "$work/table.txt"
mkdir -p "$here/results"
cp "$work/table.txt" "$here/results/halo.txt"
