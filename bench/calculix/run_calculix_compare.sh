#!/usr/bin/env bash
# perifem vs CalculiX (explicit dynamics, C3D8R) on the same hexahedral mesh. See README.md.
#
#   bash bench/calculix/run_calculix_compare.sh [--quick] [--no-perf] [--work DIR] [PERIFEM]
#
# 1. Agreement: an elastic steel bar 20 x 2 x 2 mm (0.25 mm hexahedra; --quick: 0.5 mm), the
#    end x = 0 driven by a smooth displacement ramp to 10 m/s. perifem runs the deck written by
#    ccx_compare.py, the mesh of its Exodus output becomes a CalculiX deck with the same time
#    increment, and the axial displacement histories at three probe nodes are compared:
#    max_t |u_perifem - u_ccx| / max_t |u_ccx| <= 2 % at each (exit 1 otherwise).
# 2. Performance (unless --no-perf): the same bar with 0.1 mm hexahedra (200 x 20 x 20 = 80,000
#    elements), single-threaded, both codes; element-cycles per second = elements x steps /
#    time-loop seconds, and the ratio perifem / CalculiX. The table goes to stdout and to
#    bench/results/calculix.txt.
#
# Environment: CCX (default ccx), PY (default /usr/bin/python3: needs numpy, netCDF4, h5py),
#   PERF_NX PERF_NY PERF_NZ (default 200 20 20), PERF_DT (6.4e-9 s), PERF_STEPS (300),
#   PERF_REPEAT (3: best of), KEEP=1 keeps the work directory.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
quick=0 perf=1 work=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --no-perf) perf=0; shift ;;
    --work) work=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "${BASH_SOURCE[0]}"; exit 0 ;;
    -*) echo "run_calculix_compare.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
perifem=${1:-$root/build/perifem}
ccx=${CCX:-ccx}
py=${PY:-/usr/bin/python3}
tool="$py $here/ccx_compare.py"

die() { echo "run_calculix_compare.sh: error: $*" >&2; exit 1; }
[[ -x $perifem ]] || die "perifem binary '$perifem' not found (build it, or pass its path)"
perifem=$(cd "$(dirname "$perifem")" && pwd)/$(basename "$perifem")
command -v "$ccx" > /dev/null || die "CalculiX '$ccx' not found (Debian: apt-get install calculix-ccx; or set CCX)"
"$py" -c 'import numpy, netCDF4, h5py' 2> /dev/null || die "$py lacks numpy, netCDF4 or h5py (set PY)"

ncpu=$(nproc --all)
load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
# one thread everywhere: ccx reads OMP_NUM_THREADS, CCX_NPROC_STIFFNESS, CCX_NPROC_RESULTS and
# caps them by NUMBER_OF_CPUS; perifem is built without OpenMP by default
export OMP_NUM_THREADS=1 CCX_NPROC_STIFFNESS=1 CCX_NPROC_RESULTS=1 CCX_NPROC_EQUATION_SOLVER=1 NUMBER_OF_CPUS=1

if [[ -z $work ]]; then
  work=$(mktemp -d /tmp/perifem_ccx.XXXXXX)
  cleanup() { if [[ ${KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
  trap cleanup EXIT
else
  rm -rf "$work" && mkdir -p "$work"
fi
work=$(cd "$work" && pwd)

# run_perifem DIR NAME: runs NAME.yaml in DIR, log in NAME.log; checks it ran without a dt warning
run_perifem() {
  (cd "$1" && "$perifem" "$2.yaml" > "$2.log" 2>&1) || die "perifem failed on $1/$2.yaml:"$'\n'"$(tail -20 "$1/$2.log")"
  if grep -q "^warning: dt" "$1/$2.log"; then die "perifem: $(grep '^warning: dt' "$1/$2.log")"; fi
}
# run_ccx DIR NAME DT: runs NAME.inp in DIR, log in NAME.log; checks ccx took the increment DT
run_ccx() {
  (cd "$1" && "$ccx" -i "$2" > "$2.log" 2>&1) || true
  run_ccx_check "$@"
}
run_ccx_check() {
  grep -q "ERROR" "$1/$2.log" && die "ccx failed on $1/$2.inp:"$'\n'"$(grep -A3 ERROR "$1/$2.log" | head -20)"
  local sel
  sel=$(sed -n 's/.*SELECTED time increment[^:]*:[ ]*//p' "$1/$2.log" | head -1)
  [[ -n $sel ]] || die "no 'SELECTED time increment' in $1/$2.log"
  "$py" -c "import sys; s, d = float('$sel'), float('$3'); sys.exit(abs(s - d) > 1e-6 * d)" \
    || die "ccx chose the increment $sel s instead of $3 s: dt is above its Courant estimate ($(grep -o 'initial stable time increment:.*' "$1/$2.log"))"
}

# --- 1. agreement ----------------------------------------------------------------------------
if [[ $quick == 1 ]]; then nx=40 ny=4 nz=4 dt=3.2e-8 steps=500 every=5; else nx=80 ny=8 nz=8 dt=1.6e-8 steps=1000 every=5; fi
cmp=$work/compare && mkdir -p "$cmp"
echo "== agreement: bar $nx x $ny x $nz elements, dt $dt s, $steps steps, in $cmp" >&2
$tool deck "$cmp/bar.yaml" --nx $nx --ny $ny --nz $nz --dt $dt --steps $steps --interval $every
run_perifem "$cmp" bar
$tool inp "$cmp/bar.e" "$cmp/bar_ccx.inp" --dt $dt --steps $steps --print-every $every > "$cmp/inp.log"
run_ccx "$cmp" bar_ccx $dt
status=0
$tool compare "$cmp/bar.e" "$cmp/bar_ccx.dat" --tol 0.02 --table "$cmp/histories.txt" > "$cmp/compare.txt" || status=1
hg=$("$py" -c "
import h5py; f = h5py.File('$cmp/bar.h5', 'r')
print('%.3g' % (f['hourglass_energy'][-1] / f['fe_internal_energy'][-1]))")
agreement="agreement (bar $nx x $ny x $nz, h = $("$py" -c "print(20/$nx)") mm, dt = $dt s, $steps steps; ccx $(sed -n 's/.*Volumetric COURANT initial stable time increment:/Courant estimate /p' "$cmp/bar_ccx.log" | head -1) s):
$(cat "$cmp/compare.txt")
perifem hourglass energy / internal energy at the end: $hg"
if [[ $perf == 1 ]]; then echo "$agreement" >&2; else echo "$agreement"; exit $status; fi

# --- 2. performance --------------------------------------------------------------------------
# Each code runs the bar twice, with s0 and with s0 + psteps steps, under /usr/bin/time. Rates
# over the psteps steps in between (set-up, mesh reading and the first steps cancel):
#   wall: perifem's summary 'time loop' (output excluded) of the two runs; ccx prints no loop
#         time, so the wall time of its whole runs;
#   cpu:  user + system seconds of the whole runs, for both codes (less sensitive to the load
#         other processes put on the machine).
# Best of PERF_REPEAT rounds. The runs go one after the other.
pnx=${PERF_NX:-200} pny=${PERF_NY:-20} pnz=${PERF_NZ:-20} pdt=${PERF_DT:-6.4e-9}
psteps=${PERF_STEPS:-300} repeat=${PERF_REPEAT:-3} s0=20 s1=$(( ${PERF_STEPS:-300} + 20 ))
nel=$((pnx * pny * pnz))
prf=$work/perf && mkdir -p "$prf"
[[ -x /usr/bin/time ]] || die "/usr/bin/time not found (Debian package time)"
echo "== performance: bar $pnx x $pny x $pnz = $nel elements, dt $pdt s, $s0 and $s1 steps, best of $repeat, in $prf" >&2
for k in 0 1; do
  $tool deck "$prf/p$k.yaml" --nx $pnx --ny $pny --nz $pnz --dt $pdt --steps $([[ $k == 0 ]] && echo $s0 || echo $s1) --interval 0
done
# timed LOG CMD...: runs CMD > LOG 2>&1 and prints "wall-seconds cpu-seconds" (user + system)
timed() {
  local log=$1 t0 t1
  shift
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$work/time.out" "$@" > "$log" 2>&1 || true
  t1=$(date +%s.%N)
  "$py" -c "u, s = open('$work/time.out').read().split()[-2:]; print('%.4g %.4g' % ($t1 - $t0, float(u) + float(s)))"
}
# rate "T1 - T0": element-cycles per second over the psteps steps
rate() {
  "$py" -c "import sys; d = $1; sys.exit(1) if d <= 0 else print($nel * $psteps / d)" \
    || die "time difference $1 <= 0: the timing noise exceeds the run (raise PERF_STEPS)"
}
fmt() { "$py" -c "print('%.4g' % $1)"; }
declare -A best=([pw]=0 [pc]=0 [cw]=0 [cc]=0) sec=()
for r in $(seq 1 "$repeat"); do
  declare -A w=() c=()
  for k in 0 1; do
    read -r _ c[p$k] < <(timed "$prf/p$k.log" "$perifem" --output-dir "$prf" "$prf/p$k.yaml")
    grep -q "^state digest" "$prf/p$k.log" || die "perifem failed on $prf/p$k.yaml:"$'\n'"$(tail -20 "$prf/p$k.log")"
    if grep -q "^warning: dt" "$prf/p$k.log"; then die "perifem: $(grep '^warning: dt' "$prf/p$k.log")"; fi
    w[p$k]=$(sed -n 's/.*(time loop \([0-9.]*\) s[,)].*/\1/p' "$prf/p$k.log")
  done
  if [[ $r == 1 ]]; then
    $tool inp "$prf/p0.e" "$prf/c0.inp" --dt $pdt --steps $s0 --print-every 0 > /dev/null
    $tool inp "$prf/p0.e" "$prf/c1.inp" --dt $pdt --steps $s1 --print-every 0 > /dev/null
  fi
  for k in 0 1; do
    read -r w[c$k] c[c$k] < <(cd "$prf" && timed "c$k.log" "$ccx" -i c$k)
    run_ccx_check "$prf" c$k $pdt
  done
  pw=$(rate "${w[p1]} - ${w[p0]}") pc=$(rate "${c[p1]} - ${c[p0]}")
  cw=$(rate "${w[c1]} - ${w[c0]}") cc=$(rate "${c[c1]} - ${c[c0]}")
  echo "   round $r: perifem loop ${w[p0]} / ${w[p1]} s, cpu ${c[p0]} / ${c[p1]} s; ccx wall $(fmt ${w[c0]}) / $(fmt ${w[c1]}) s, cpu $(fmt ${c[c0]}) / $(fmt ${c[c1]}) s" >&2
  echo "            element-cycles/s: perifem wall $(fmt $pw) cpu $(fmt $pc); ccx wall $(fmt $cw) cpu $(fmt $cc)" >&2
  for m in pw pc cw cc; do
    if "$py" -c "import sys; sys.exit(not ${!m} > ${best[$m]})"; then
      best[$m]=${!m}
      case $m in
        pw) sec[pw]="${w[p1]} - ${w[p0]}" ;; pc) sec[pc]="${c[p1]} - ${c[p0]}" ;;
        cw) sec[cw]="$(fmt ${w[c1]}) - $(fmt ${w[c0]})" ;; cc) sec[cc]="$(fmt ${c[c1]}) - $(fmt ${c[c0]})" ;;
      esac
    fi
  done
done
rw=$("$py" -c "print('%.2f' % (${best[pw]} / ${best[cw]}))")
rc=$("$py" -c "print('%.2f' % (${best[pc]} / ${best[cc]}))")
verdict=$("$py" -c "print('meets' if ${best[pw]} / ${best[cw]} >= 5 else 'is BELOW')")
load_end=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
table="perifem vs CalculiX: explicit dynamics, 8-node hexahedra with one-point integration
command: bash bench/calculix/run_calculix_compare.sh${1:+ $1}   (from the repository root)
date: $(date -u '+%Y-%m-%d %H:%M UTC')
machine: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1), $ncpu CPUs, load average at start $load_start, at end $load_end
perifem: $("$perifem" --version 2>&1 | head -1) ($perifem; source $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' with uncommitted changes')); CalculiX: $("$ccx" -v 2>&1 | grep -o 'Version.*' | head -1) ($(command -v "$ccx"))
threads: 1 (OMP_NUM_THREADS=1 CCX_NPROC_STIFFNESS=1 CCX_NPROC_RESULTS=1 NUMBER_OF_CPUS=1; perifem: one MPI rank, no OpenMP)

$agreement

performance: bar 20 x 2 x 2 mm, $pnx x $pny x $pnz = $nel elements, $(( (pnx + 1) * (pny + 1) * (pnz + 1) )) nodes, dt = $pdt s;
  rates over the $psteps steps between a $s0-step and a $s1-step run of each code, best of $repeat rounds
  (wall: perifem's 'time loop', ccx's whole-run wall time; cpu: user + system time of the whole runs)
  code      element-cycles/s per core: wall        cpu    seconds for $psteps steps (wall; cpu)
  perifem   $(printf '%34s %10s' "$(fmt ${best[pw]})" "$(fmt ${best[pc]})")    ${sec[pw]}; ${sec[pc]}
  CalculiX  $(printf '%34s %10s' "$(fmt ${best[cw]})" "$(fmt ${best[cc]})")    ${sec[cw]}; ${sec[cc]}
  ratio perifem / CalculiX: wall $rw, cpu $rc: perifem $verdict the 5x target (wall)"
echo
echo "$table"
mkdir -p "$root/bench/results"
echo "$table" > "$root/bench/results/calculix.txt"
exit $status
