#!/usr/bin/env bash
# The fragmenting cylinder (inputs/fragmenting_cylinder.yaml, the example Peridigm, CabanaPD and
# Peridynamics.jl ship) in directed bond evaluations per second, on 1 and on 2 MPI ranks.
#
#   bash bench/run_fragmenting.sh [path/to/perifem]       # default: build/perifem
#
# The deck as it is (PMB steel tube, 1 mm cells, horizon 4.17462 mm, critical stretch 0.02),
# run to FRAG_FINAL_TIME (default the deck's 2.5e-4 s, about 1,180 steps; a shorter time gives
# a quick check, but fewer broken bonds than the whole run), with its Exodus output at the
# first and last steps only (output.interval 0; history rows every 25 steps as the deck).
# Reports, per rank count, from perifem's summary: directed bonds, steps, time-loop seconds,
# wall seconds (with output), bond evaluations per second (directed bonds x steps / time loop)
# and the final damage fraction. The table goes to stdout and bench/results/fragmenting.txt.
#
# Then, when LAMMPS is installed (`LMP`, default `lmp`; FRAG_LAMMPS=0 skips it), the same model in
# both codes, side by side: LAMMPS's peri/pmb on perifem's own points and initial velocities
# (bench/frag_lammps.py writes them from the first frame of the perifem run), the same
# micromodulus, horizon, constant critical stretch and step, for the same number of steps; and
# perifem's deck with the cylinder's self-contact added (radius 0.9 h, bonded points excluded),
# since LAMMPS's peri pair styles always compute a short-range contact force. Both use the
# neighbour/search skin FRAG_SKIN (default 5e-4 m: the cylinder moves 40 um a step).
#
# Environment: FRAG_FINAL_TIME (s; e.g. 2e-6 for a 10-step check), FRAG_RANKS (default "1 2"),
#   FRAG_REPEAT (runs of each case, the fastest counts; default 1), FRAG_KEEP=1 keeps the work
#   directory, FRAG_LAMMPS, FRAG_SKIN, LMP.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
final=${FRAG_FINAL_TIME:-2.5e-4}
ranks=${FRAG_RANKS:-1 2}
repeat=${FRAG_REPEAT:-1}
deck=$root/inputs/fragmenting_cylinder.yaml

die() { echo "run_fragmenting.sh: error: $*" >&2; exit 1; }
[[ -x $perifem ]] || die "perifem binary '$perifem' not found (build it, or pass its path)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
launch() { local np=$1; shift; if [[ $np == 1 ]]; then "$@"; else mpirun --oversubscribe -np "$np" "$@"; fi; }

load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
work=$(mktemp -d /tmp/perifem_frag.XXXXXX)
cleanup() { if [[ ${FRAG_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT

grab() { # sed expression, log, what
  local v
  v=$(sed -n "$1" "$2" | head -1)
  [[ -n $v ]] || die "could not find '$3' in $2; last lines:"$'\n'"$(tail -20 "$2")"
  echo "$v"
}

declare -A loop wall bonds steps rate damage
for np in $ranks; do
  for rep in $(seq "$repeat"); do
    echo "== perifem fragmenting cylinder to t = $final s on $np rank(s), run $rep of $repeat" >&2
    log=$work/frag$np.log
    launch "$np" "$perifem" --progress plain --output-dir "$work/out$np" --set "time.final_time=$final" \
      --set output.interval=0 "$deck" >"$log" 2>&1 || { tail -30 "$log" >&2; die "perifem failed on $np rank(s)"; }
    grep -E '^perifem:|directed bonds|damage fraction' "$log" >&2 || true
    t=$(grab 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$log" "time loop")
    if [[ -z ${loop[$np]:-} ]] || awk -v a="$t" -v b="${loop[$np]}" 'BEGIN { exit !(a < b) }'; then
      loop[$np]=$t
      wall[$np]=$(grab 's/^perifem: .* in \([0-9.eE+-]*\) s (time loop.*/\1/p' "$log" "in W s")
      steps[$np]=$(grab 's/^perifem: \([0-9]*\) steps of.*/\1/p' "$log" "N steps")
      bonds[$np]=$(grab 's/.*directed bonds \([0-9]*\) .*/\1/p' "$log" "directed bonds")
      rate[$np]=$(grab 's/.*bond evaluations per second \([0-9.eE+-]*\).*/\1/p' "$log" "bond evaluations per second")
      damage[$np]=$(grab 's/.*final damage fraction \([0-9.eE+-]*\).*/\1/p' "$log" "final damage fraction")
    fi
  done
done

# The same model in both codes (see the header).
lmp=${LMP:-lmp}
skin=${FRAG_SKIN:-5e-4}
declare -A cloop lloop lbonds ldamage cdamage
if [[ ${FRAG_LAMMPS:-1} != 0 ]] && command -v "$lmp" >/dev/null; then
  first=${ranks%% *}
  exo=$work/out$first/fragmenting_cylinder.e
  dt=$(grab 's/^perifem: [0-9]* steps of \([0-9.eE+-]*\) s.*/\1/p' "$work/frag$first.log" "step")
  /usr/bin/python3 "$here/frag_lammps.py" "$exo" "$work" "$dt" "${steps[$first]}" "$skin" >&2
  for np in $ranks; do
    for rep in $(seq "$repeat"); do
      echo "== same model, $np rank(s), run $rep of $repeat: perifem with self-contact, then LAMMPS" >&2
      log=$work/fragc$np.log
      launch "$np" "$perifem" --progress plain --output-dir "$work/outc$np" --set "time.final_time=$final" \
        --set output.interval=0 --set "contact={skin: $skin, pairs: [{bodies: [cylinder, cylinder]}]}" "$deck" \
        >"$log" 2>&1 || { tail -30 "$log" >&2; die "perifem with contact failed on $np rank(s)"; }
      t=$(grab 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$log" "time loop")
      if [[ -z ${cloop[$np]:-} ]] || awk -v a="$t" -v b="${cloop[$np]}" 'BEGIN { exit !(a < b) }'; then cloop[$np]=$t; fi
      llog=$work/lammps$np.log
      (cd "$work" && launch "$np" "$lmp" -in in.frag -log "$llog" >/dev/null 2>&1) || { tail -30 "$llog" >&2; die "LAMMPS failed on $np rank(s)"; }
      t=$(grab 's/^Loop time of \([0-9.eE+-]*\) on.*/\1/p' "$llog" "Loop time")
      if [[ -z ${lloop[$np]:-} ]] || awk -v a="$t" -v b="${lloop[$np]}" 'BEGIN { exit !(a < b) }'; then lloop[$np]=$t; fi
      lbonds[$np]=$(grab 's/.*total # of bonds = \([0-9]*\).*/\1/p' "$llog" "total # of bonds")
      ldamage[$np]=$(awk '/^ *Step/ { h = 1; next } h && NF == 3 { d = $3 } /^Loop time/ { h = 0 } END { print d }' "$llog")
      cdamage[$np]=$(grab 's/.*final damage fraction \([0-9.eE+-]*\).*/\1/p' "$log" "final damage fraction")
    done
  done
fi

cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo 2>/dev/null | head -1)
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
mkdir -p "$here/results"
{
  echo "perifem fragmenting cylinder (inputs/fragmenting_cylinder.yaml) to t = $final s, output at the first and last steps"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine:  ${cpu:-unknown CPU}, nproc $(nproc), load average at start $load_start"
  echo "perifem:  $("$perifem" --version 2>/dev/null | head -1), checkout at $commit; fastest of $repeat run(s)"
  echo
  printf '%5s %12s %7s %14s %10s %16s %12s\n' ranks "dir. bonds" steps "time loop [s]" "wall [s]" "bond ev./s" "damage"
  for np in $ranks; do
    printf '%5s %12s %7s %14s %10s %16s %12s\n' "$np" "${bonds[$np]}" "${steps[$np]}" "${loop[$np]}" "${wall[$np]}" "${rate[$np]}" "${damage[$np]}"
  done
  echo
  echo "bond ev./s: directed bonds x steps / time-loop seconds (perifem's summary); wall: the run from the"
  echo "first forces to the output files closed (set-up excluded)."
  if [[ ${#lloop[@]} -gt 0 ]]; then
    echo
    echo "the same model side by side ($lmp: $("$lmp" -h 2>/dev/null | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' | head -1)):"
    echo "LAMMPS peri/pmb on perifem's points and velocities, perifem with the cylinder's self-contact, skin $skin m"
    printf '%5s %12s %12s %14s %14s %16s %16s %10s\n' ranks "pf bonds" "LMP bonds" "perifem [s]" "LAMMPS [s]" "perifem ev./s" "LAMMPS ev./s" "pf/LAMMPS"
    for np in $ranks; do
      awk -v np="$np" -v b="${bonds[$np]}" -v lb="${lbonds[$np]}" -v s="${steps[$np]}" -v p="${cloop[$np]}" -v l="${lloop[$np]}" \
        'BEGIN { printf "%5s %12s %12s %14s %14s %16.4g %16.4g %10.2f\n", np, b, lb, p, l, b * s / p, lb * s / l, l / p }'
    done
    echo "times: perifem 'time loop', LAMMPS 'Loop time'; the same steps and step size; fastest of $repeat."
    for np in $ranks; do
      echo "damage at the end, $np rank(s): perifem (damaged volume share) ${cdamage[$np]}, LAMMPS (mean damage/atom) ${ldamage[$np]}"
    done
  fi
} | tee "$here/results/fragmenting.txt"
