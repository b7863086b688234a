#!/usr/bin/env bash
# perifem vs LAMMPS (PERI package) on the same particles, on 1 and on 2 MPI ranks.
#
#   bash bench/run_bench.sh [path/to/perifem]
#
# Generates the LAMMPS examples/peri target scaled by 3 (cylinder r = 15 mm, 15 mm long,
# 0.5 mm simple cubic lattice, ~87k points) as a perifem point file and a LAMMPS data file,
# runs PMB and LPS (influence function 1/|xi|, the one of LAMMPS's peri/lps) for 150 steps of
# 1e-7 s with a rigid sphere indenter in both codes, and perifem alone with the omega = 1 LPS, and
# prints directed bond evaluations per second (directed bonds x steps / time-loop seconds) and
# the parallel efficiency of each code, rate on 2 ranks / (2 x rate on 1 rank).
# The table also goes to bench/results/latest.txt. See bench/README.md.
#
# Environment: LMP=/path/to/lmp (default: first of lmp, lmp_serial, lmp_stable on PATH),
#   LMP_SKIN=neighbour skin in m (default 0.0001), BENCH_STEPS (default 150),
#   BENCH_KEEP=1 keeps the work directory, BENCH_RANKS (default "1 2"), BENCH_REPEAT (runs of
#   each case, the fastest counts; default 2).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
steps=${BENCH_STEPS:-150}
skin=${LMP_SKIN:-0.0001}
horizon=0.0015001

die() { echo "run_bench.sh: error: $*" >&2; exit 1; }

# --- tools -----------------------------------------------------------------------------------
[[ -x $perifem ]] || die "perifem binary '$perifem' not found or not executable (build it: cd build && cmake .. && make -j2, or pass its path as the first argument)"
perifem=$(cd "$(dirname "$perifem")" && pwd)/$(basename "$perifem")

lmp=${LMP:-}
if [[ -z $lmp ]]; then
  for c in lmp lmp_serial lmp_stable; do
    if command -v "$c" >/dev/null 2>&1; then lmp=$(command -v "$c"); break; fi
  done
fi
[[ -n $lmp ]] || die "LAMMPS not found: none of lmp, lmp_serial, lmp_stable is on PATH. Install it (Debian: apt-get install -y lammps) or set LMP=/path/to/lmp."
command -v "$lmp" >/dev/null 2>&1 || die "LMP='$lmp' is not an executable"
lmp_help=$("$lmp" -h 2>&1 || true)
for style in peri/pmb peri/lps; do
  grep -qw -- "$style" <<<"$lmp_help" || die "$lmp has no pair style $style (LAMMPS must be built with the PERI package)"
done
lmp_version=$(sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' <<<"$lmp_help" | head -1)

py=$(command -v python3 || command -v /usr/bin/python3 || true)
[[ -n $py ]] || die "python3 not found"

# mpirun as root (containers, CI) needs these.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ranks=${BENCH_RANKS:-1 2}
repeat=${BENCH_REPEAT:-2} # runs of each case; the fastest counts (another job on the machine only slows a run)
# launch NP COMMAND...: the command itself on one rank, under mpirun otherwise
launch() { local np=$1; shift; if [[ $np == 1 ]]; then "$@"; else mpirun --oversubscribe -np "$np" "$@"; fi; }

load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
work=$(mktemp -d /tmp/perifem_bench.XXXXXX)
cleanup() { if [[ ${BENCH_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT

# --- inputs ----------------------------------------------------------------------------------
echo "== generating inputs in $work" >&2
"$py" "$here/gen_bench.py" generate "$work" --skin "$skin" --steps "$steps" >"$work/gen.log" \
  || { cat "$work/gen.log" >&2; die "input generation failed"; }
cat "$work/gen.log" >&2
npoints=$(sed -n 's/^points //p' "$work/gen.log")
pair_pmb=$(sed -n 's/^pmb: pair_coeff //p' "$work/gen.log")
pair_lps=$(sed -n 's/^lps: pair_coeff //p' "$work/gen.log")

echo "== counting directed bonds |xi| <= $horizon independently (python, grid hashing)" >&2
bonds_ref=$("$py" "$here/gen_bench.py" count "$work/points.txt" "$horizon")
echo "   $bonds_ref" >&2

# --- runs ------------------------------------------------------------------------------------
# field VALUE from a log: first match of a sed -n expression, or die
grab() {
  local v
  v=$(sed -n "$1" "$2" | head -1)
  [[ -n $v ]] || die "could not find '$3' in $2; last lines:"$'\n'"$(tail -20 "$2")"
  echo "$v"
}

# the table's name of a case
label() { case $1 in pmb) echo PMB ;; lps) echo "LPS 1/|xi|" ;; lps_w1) echo "LPS w=1 (pf only)" ;; *) echo "$1" ;; esac; }

# the smaller of two times (the first may be empty)
fastest() { if [[ -z $1 ]]; then echo "$2"; else awk -v a="$1" -v b="$2" 'BEGIN { print (b < a ? b : a) }'; fi; }

declare -A pf_loop pf_bonds pf_bytes pf_contact pf_rate lmp_loop lmp_bonds lmp_neigh lmp_builds lmp_danger lmp_update
models="pmb lps lps_w1" # lps_w1: perifem only (omega = 1; LAMMPS has no such LPS)
for np in $ranks; do
for m in $models; do
  k=$m,$np
  for rep in $(seq "$repeat"); do
  echo "== perifem $m ($np rank(s), run $rep of $repeat)" >&2
  mkdir -p "$work/out_$m$np"
  launch "$np" "$perifem" --output-dir "$work/out_$m$np" "$work/$m.yaml" >"$work/perifem_$m$np.log" 2>&1 \
    || { tail -30 "$work/perifem_$m$np.log" >&2; die "perifem failed on $m.yaml on $np ranks (log above)"; }
  grep -E '^perifem:|points|damage' "$work/perifem_$m$np.log" >&2 || true
  t=$(grab 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$work/perifem_$m$np.log" "time loop")
  pf_loop[$k]=$(fastest "${pf_loop[$k]:-}" "$t")
  done
  pf_bonds[$k]=$(grab 's/.*directed bonds \([0-9]*\) .*/\1/p' "$work/perifem_$m$np.log" "directed bonds")
  pf_bytes[$k]=$(grab 's/.*directed bonds [0-9]* (\([0-9.eE+-]*\) bytes each).*/\1/p' "$work/perifem_$m$np.log" "bytes each")
  pf_contact[$k]=$(grab 's/.*contact: .* search rebuilds, \([0-9.eE+-]*\) s (\([0-9.]*\) %.*/\1 s, \2 %/p' "$work/perifem_$m$np.log" "contact: N search rebuilds")
  pf_rate[$k]=$(grab 's/.*bond evaluations per second \([0-9.eE+-]*\).*/\1/p' "$work/perifem_$m$np.log" "bond evaluations per second")

  [[ -f $work/in.$m ]] || continue # perifem only

  for rep in $(seq "$repeat"); do
  echo "== LAMMPS $m ($np rank(s), run $rep of $repeat)" >&2
  (cd "$work" && launch "$np" "$lmp" -in "in.$m" -log "log.lammps.$m$np" -echo none -nocite >"lmp_$m$np.out" 2>&1) \
    || { tail -30 "$work/lmp_$m$np.out" >&2; die "LAMMPS failed on in.$m on $np ranks (output above)"; }
  grep -E 'Loop time|total # of bonds' "$work/lmp_$m$np.out" >&2 || true
  t=$(grab "s/^Loop time of \([0-9.eE+-]*\) on $np procs for $steps steps.*/\1/p" "$work/lmp_$m$np.out" "Loop time of X on $np procs for $steps steps")
  lmp_loop[$k]=$(fastest "${lmp_loop[$k]:-}" "$t")
  done
  lmp_bonds[$k]=$(grab 's/^ *total # of bonds = \([0-9]*\).*/\1/p' "$work/lmp_$m$np.out" "total # of bonds")
  lmp_neigh[$k]=$(grab 's/^Ave neighs\/atom = \([0-9.eE+-]*\).*/\1/p' "$work/lmp_$m$np.out" "Ave neighs/atom")
  lmp_builds[$k]=$(grab 's/^Neighbor list builds = \([0-9]*\).*/\1/p' "$work/lmp_$m$np.out" "Neighbor list builds")
  lmp_danger[$k]=$(grab 's/^Dangerous builds = \([0-9]*\).*/\1/p' "$work/lmp_$m$np.out" "Dangerous builds")
  lmp_update[$k]=$(grab 's/^ *update every \(.*\)$/\1/p' "$work/lmp_$m$np.out" "update every")
done
done

# --- memory bandwidth: the STREAM-like triad of bench/stream.c, one core --------------------------
triad=unknown
if command -v cc >/dev/null 2>&1 && cc -O3 -march=native -o "$work/stream" "$here/stream.c" 2>"$work/stream.log"; then
  echo "== memory bandwidth (bench/stream.c)" >&2
  triad=$("$work/stream" | sed -n 's/^triad GB\/s //p')
fi

# --- table -----------------------------------------------------------------------------------
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo 2>/dev/null | head -1)
# The repository's commit describes the binary only when the binary lives in this checkout.
src_desc="binary outside this checkout, commit unknown"
if [[ $perifem == "$root"/* ]] && commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null); then
  src_desc="checkout at $commit"
  if [[ -n $(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null) ]]; then
    src_desc="$src_desc + uncommitted changes"
  fi
fi
pf_version=$("$perifem" --version 2>/dev/null | head -1 || echo perifem)

ok=1
mkdir -p "$here/results"
table=$work/table.txt
{
  echo "perifem vs LAMMPS PERI: directed bond evaluations per second, on $(echo $ranks | sed 's/ / and /g') MPI rank(s)"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine:  ${cpu:-unknown CPU}, nproc $(nproc), load average at start $load_start"
  echo "perifem:  $pf_version, $perifem ($src_desc)"
  echo "LAMMPS:   ${lmp_version:-unknown version}, $lmp"
  echo "problem:  LAMMPS examples/peri target x3: cylinder r = 15 mm, y in [-15, 0] mm, h = 0.5 mm,"
  echo "          $npoints points, horizon $horizon m, rigid sphere r = 5 mm at 100 m/s (k = 1e17),"
  echo "          $steps steps of 1e-7 s; same points in the same order in both codes"
  echo "LAMMPS:   PMB pair_coeff $pair_pmb"
  echo "          LPS pair_coeff $pair_lps"
  echo
  printf '%-18s %5s %12s %12s %12s %14s %14s %10s\n' model ranks "dir. bonds" "perifem [s]" "LAMMPS [s]" "perifem ev/s" "LAMMPS ev/s" "pf/LAMMPS"
  for m in $models; do
    for np in $ranks; do
      k=$m,$np
      awk -v m="$(label "$m")" -v np="$np" -v b="${pf_bonds[$k]}" -v s="$steps" -v tp="${pf_loop[$k]}" -v tl="${lmp_loop[$k]:-}" 'BEGIN {
        rp = b * s / tp
        if (tl == "") { printf "%-18s %5d %12d %12.2f %12s %14.4g %14s %10s\n", m, np, b, tp, "-", rp, "-", "-"; exit }
        rl = b * s / tl;
        printf "%-18s %5d %12d %12.2f %12.2f %14.4g %14.4g %10.2f\n", m, np, b, tp, tl, rp, rl, rp / rl }'
    done
  done
  echo "LPS 1/|xi|: influence function omega = 1/|xi| in both codes (LAMMPS peri/lps's own); LPS w=1 (perifem"
  echo "  only): omega = 1, perifem's AVX-512 LPS kernels. bench/README.md lists what each code computes."
  if [[ " $ranks " == *" 1 "* && " $ranks " == *" 2 "* ]]; then
    echo
    echo "parallel efficiency, rate on 2 ranks / (2 x rate on 1 rank) = time on 1 / (2 x time on 2):"
    for m in $models; do
      [[ -n ${lmp_loop[$m,1]:-} ]] || { awk -v m="$(label "$m")" -v p1="${pf_loop[$m,1]}" -v p2="${pf_loop[$m,2]}" 'BEGIN {
        printf "  %s: perifem %.3f\n", m, p1 / (2 * p2) }'; continue; }
      awk -v m="$(label "$m")" -v p1="${pf_loop[$m,1]}" -v p2="${pf_loop[$m,2]}" -v l1="${lmp_loop[$m,1]}" -v l2="${lmp_loop[$m,2]}" 'BEGIN {
        printf "  %s: perifem %.3f, LAMMPS %.3f\n", m, p1 / (2 * p2), l1 / (2 * l2) }'
    done
  fi
  echo
  echo "directed bonds (|xi| <= $horizon): independent python count $bonds_ref"
  for m in $models; do
    for np in $ranks; do
      k=$m,$np
      status=match
      if [[ ${pf_bonds[$k]} != "$bonds_ref" || ${lmp_bonds[$k]:-$bonds_ref} != "$bonds_ref" ]]; then status=MISMATCH; ok=0; fi
      echo "  $(label "$m") on $np rank(s): perifem ${pf_bonds[$k]}, LAMMPS ${lmp_bonds[$k]:--} (fix PERI_NEIGH 'total # of bonds') -> $status"
    done
  done
  r1=${ranks%% *}
  echo "perifem's own summary rate on $r1 rank(s): PMB ${pf_rate[pmb,$r1]}, LPS 1/|xi| ${pf_rate[lps,$r1]}, LPS w=1 ${pf_rate[lps_w1,$r1]} bond evaluations/s"
  echo "perifem's bond memory: PMB ${pf_bytes[pmb,$r1]}, LPS ${pf_bytes[lps,$r1]} bytes per directed bond (plus a 64-byte"
  echo "  record per point, 0.6 bytes per bond here); one core's memory bandwidth (bench/stream.c triad): $triad GB/s"
  echo "times: perifem 'time loop' seconds; LAMMPS 'Loop time of X on N procs for $steps steps'; the fastest of $repeat run(s) each."
  echo "rates: directed bonds x steps / time (LAMMPS's bond count is the same number)."
  echo "contact on both sides: LAMMPS's peri/* pair styles compute a short-range contact force over"
  echo "  their neighbour list (horizon + skin, ${lmp_neigh[pmb,$r1]} / ${lmp_neigh[lps,$r1]} full neighbours per atom for PMB / LPS)"
  echo "  in the force call, neighbour skin $skin m: list builds PMB ${lmp_builds[pmb,$r1]}, LPS ${lmp_builds[lps,$r1]}"
  echo "  (dangerous ${lmp_danger[pmb,$r1]}, ${lmp_danger[lps,$r1]}; update every ${lmp_update[pmb,$r1]});"
  echo "  perifem's decks have the target's self-contact pair (radius 0.9 h, bonded points excluded,"
  echo "  search skin $skin m, the same),"
  echo "  its share of perifem's time loop on $r1 rank(s): PMB ${pf_contact[pmb,$r1]}, LPS 1/|xi| ${pf_contact[lps,$r1]}, LPS w=1 ${pf_contact[lps_w1,$r1]}."
} >"$table"

cat "$table"
cp "$table" "$here/results/latest.txt"
echo "(saved to $here/results/latest.txt)" >&2
[[ $ok == 1 ]] || die "directed bond counts differ (see the table)"
