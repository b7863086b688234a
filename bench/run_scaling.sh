#!/usr/bin/env bash
# Time per bond-step at three problem sizes (issue 9): the bench cylinder of run_bench.sh (axis y,
# radius = height, 0.5 mm lattice, horizon 3 spacings, PMB with Silling-Askari damage, the rigid
# sphere indenter and the self-contact pair) at radius 7.5, 15 and 30 mm: about 10k, 87k and
# 700k points. Each runs SCALING_STEPS fixed steps on one rank; the table gives the time-loop
# nanoseconds per directed bond and step, their spread (largest / smallest; flat within 20 %
# is the target) and the set-up time (whole run less the time loop) in steps' worth.
#
#   bash bench/run_scaling.sh [path/to/perifem]      # default: build/perifem
#
# Environment: SCALING_STEPS (default 40), SCALING_RADII (m, default "0.0075 0.015 0.03"),
#   SCALING_KEEP=1 keeps the work directory. The table goes to stdout and to
#   bench/results/scaling.txt.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
steps=${SCALING_STEPS:-40}
radii=${SCALING_RADII:-0.0075 0.015 0.03}

die() { echo "run_scaling.sh: error: $*" >&2; exit 1; }
[[ -x $perifem ]] || die "perifem binary '$perifem' not found or not executable (build it, or pass its path)"
perifem=$(cd "$(dirname "$perifem")" && pwd)/$(basename "$perifem")

work=$(mktemp -d /tmp/perifem_scaling.XXXXXX)
cleanup() { if [[ ${SCALING_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT

grab() {
  local v
  v=$(sed -n "$1" "$2" | head -1)
  [[ -n $v ]] || die "could not find '$3' in $2; last lines:"$'\n'"$(tail -20 "$2")"
  echo "$v"
}

rows=()
for R in $radii; do
  deck=$work/cyl_$R.yaml
  cat >"$deck" <<EOF
# bench/run_scaling.sh: the bench cylinder of radius $R m
materials:
  glass: {model: pmb, density: 2200, bulk_modulus: 1.49e10}
bodies:
  - name: target
    material: glass
    geometry: {shape: cylinder, axis: y, center: [0, -$R, 0], radius: $R, height: $R, spacing: 0.0005}
    horizon: 0.0015001
    damage: {law: silling_askari, s00: 0.0005, alpha: 0.25}
indenters:
  - {name: sphere, shape: sphere, center: [0, 0.0051, 0], radius: 0.005, velocity: ["0", "-100", "0"], stiffness: 1e17}
contact:
  skin: 0.0001
  pairs:
    - bodies: [target, target]
time: {steps: $steps, dt: 1e-7}
output: {interval: 0, history_interval: 100000}
EOF
  echo "== radius $R m" >&2
  "$perifem" --progress plain --output-dir "$work/out_$R" "$deck" >"$work/log_$R" 2>&1 \
    || { tail -20 "$work/log_$R" >&2; die "perifem failed on radius $R"; }
  grep -E '^perifem:|points' "$work/log_$R" >&2
  wall=$(grab 's/.* in \([0-9.]*\) s (time loop.*/\1/p' "$work/log_$R" "in X s")
  loop=$(grab 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$work/log_$R" "time loop")
  npts=$(grab 's/.*points \([0-9]*\), directed.*/\1/p' "$work/log_$R" "points")
  nb=$(grab 's/.*directed bonds \([0-9]*\) .*/\1/p' "$work/log_$R" "directed bonds")
  rows+=("$R $npts $nb $wall $loop")
done

{
  echo "perifem time per bond-step against problem size (bench/run_scaling.sh), one rank"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine:  $(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -1), nproc $(nproc)"
  echo "perifem:  $("$perifem" --version | head -1), $perifem"
  echo "problem:  cylinder axis y, radius = height = R, h = 0.5 mm, horizon 0.0015001 m, PMB (Silling-Askari),"
  echo "          rigid sphere indenter, self-contact (skin 1e-4 m), $steps steps of 1e-7 s"
  echo
  printf '%-8s %9s %12s %10s %10s %14s %16s\n' "R [m]" points "dir. bonds" "loop [s]" "setup [s]" "ns/bond-step" "setup [steps]"
  for r in "${rows[@]}"; do
    read -r R npts nb wall loop <<<"$r"
    awk -v R="$R" -v p="$npts" -v b="$nb" -v w="$wall" -v l="$loop" -v s="$steps" 'BEGIN {
      printf "%-8s %9d %12d %10.2f %10.2f %14.3f %16.1f\n", R, p, b, l, w - l, 1e9 * l / (b * s), (w - l) / (l / s) }'
  done
  printf '%s\n' "${rows[@]}" | awk -v s="$steps" '{ v = $5 / ($3 * s); if (NR == 1 || v < lo) lo = v; if (NR == 1 || v > hi) hi = v }
    END { printf "\nspread of ns/bond-step, largest / smallest: %.3f (target: within 1.20)\n", hi / lo }'
  echo "setup: the run's seconds less the time loop (reading the deck, lattice, partition, neighbour"
  echo "  search, families, first output), in steps of this run's mean step (target: below 10)."
} | tee "$work/table.txt"
mkdir -p "$here/results"
cp "$work/table.txt" "$here/results/scaling.txt"
