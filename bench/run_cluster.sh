#!/usr/bin/env bash
# The cluster-cluster collision (inputs/cluster_collision.yaml, Ruestes et al. 2012, sec. 4.2)
# timed beside LAMMPS on the same model, on 1 and 2 ranks.
#
#   bash bench/run_cluster.sh [path/to/perifem]       # default: build/perifem
#
# perifem runs the deck as shipped (two PMB clusters of 33,401 grains, Silling-Askari damage,
# short-range contact between and within the clusters, skin 7 um) with Exodus output at the
# first and last steps. LAMMPS runs peri/pmb on perifem's own points and initial velocities
# (bench/frag_lammps.py --model cluster reads them from the first frame): the same micromodulus,
# horizon, s00, alpha, step and number of steps, the same skin; its contact is its own (pair
# peri: radius min(0.9 |x0_i - x0_j|, 1.35 h) between every two points), perifem's the deck's
# (1.35 h between the clusters; within each, 0.9 of the reference distance, bonded points left
# out until their bond breaks). Prints each code's time loop and their ratio, and the damage at
# the end, into bench/results/cluster.txt.
#
# Environment: CLUSTER_RANKS (default "1 2"), CLUSTER_REPEAT (runs of each case, the fastest
#   counts; default 1), CLUSTER_KEEP=1 keeps the work directory, LMP.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
ranks=${CLUSTER_RANKS:-1 2}
repeat=${CLUSTER_REPEAT:-1}
lmp=${LMP:-lmp}
deck=$root/inputs/cluster_collision.yaml
skin=7e-6

die() { echo "run_cluster.sh: error: $*" >&2; exit 1; }
[[ -x $perifem ]] || die "perifem binary '$perifem' not found (build it, or pass its path)"
command -v "$lmp" >/dev/null || die "LAMMPS ('$lmp') not found (apt-get install -y lammps)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
launch() { local np=$1; shift; if [[ $np == 1 ]]; then "$@"; else mpirun --oversubscribe -np "$np" "$@"; fi; }
value() { sed -n "$1" "$2" | head -1; }
faster() { [[ -z $2 ]] || awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

work=$(mktemp -d /tmp/perifem_cluster.XXXXXX)
cleanup() { if [[ ${CLUSTER_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT

declare -A pf lm pdmg ldmg
for np in $ranks; do
  for rep in $(seq "$repeat"); do
    echo "== $np rank(s), run $rep of $repeat: perifem, then LAMMPS" >&2
    log=$work/pf$np.log
    launch "$np" "$perifem" --progress plain --output-dir "$work/out$np" --set output.interval=0 "$deck" >"$log" 2>&1 ||
      { tail -30 "$log" >&2; die "perifem failed on $np rank(s)"; }
    t=$(value 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$log")
    [[ -n $t ]] || die "no time loop in $log"
    if faster "$t" "${pf[$np]:-}" || [[ -z ${pf[$np]:-} ]]; then pf[$np]=$t; fi
    pdmg[$np]=$(value 's/.*final damage fraction \([0-9.eE+-]*\).*/\1/p' "$log")
    if [[ ! -f $work/in.frag ]]; then
      dt=$(value 's/^perifem: [0-9]* steps of \([0-9.eE+-]*\) s.*/\1/p' "$log")
      steps=$(value 's/^perifem: \([0-9]*\) steps of.*/\1/p' "$log")
      /usr/bin/python3 "$here/frag_lammps.py" --model cluster "$work/out$np/cluster_collision.e" "$work" "$dt" "$steps" "$skin" >&2
    fi
    llog=$work/lammps$np.log
    (cd "$work" && launch "$np" "$lmp" -in in.frag -log "$llog" >/dev/null 2>&1) || { tail -30 "$llog" >&2; die "LAMMPS failed on $np rank(s)"; }
    t=$(value 's/^Loop time of \([0-9.eE+-]*\) on.*/\1/p' "$llog")
    if faster "$t" "${lm[$np]:-}" || [[ -z ${lm[$np]:-} ]]; then lm[$np]=$t; fi
    ldmg[$np]=$(awk '/^ *Step/ { h = 1; next } h && NF == 3 { d = $3 } /^Loop time/ { h = 0 } END { print d }' "$llog")
  done
done

mkdir -p "$here/results"
{
  echo "cluster-cluster collision (inputs/cluster_collision.yaml) to 0.4 ms, perifem beside LAMMPS peri/pmb"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "perifem:  $("$perifem" --version 2>/dev/null | head -1), checkout $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown); fastest of $repeat"
  printf '%5s %14s %14s %10s %16s %16s\n' ranks "perifem [s]" "LAMMPS [s]" "LAMMPS/pf" "pf damage" "LAMMPS damage"
  for np in $ranks; do
    awk -v np="$np" -v p="${pf[$np]}" -v l="${lm[$np]}" -v a="${pdmg[$np]}" -v b="${ldmg[$np]}" \
      'BEGIN { printf "%5s %14s %14s %10.2f %16s %16s\n", np, p, l, l / p, a, b }'
  done
  echo "times: perifem 'time loop', LAMMPS 'Loop time'; damage: perifem's broken-bond share, LAMMPS's mean damage/atom"
} | tee "$here/results/cluster.txt"
