# Shared by the restart tests over decks (sourced after mpi_env.sh, from the scratch folder; SRC
# the tests/ folder): a deck cut short with a checkpoint in the middle, the uninterrupted 1-rank
# run, and restarts on other rank counts compared with it - the state digest and every history
# row the restarted run writes (its first one, at the checkpoint's step, included).
#
# restart_decks IN NAME STEPS CK HI: NAME.yaml (IN cut to STEPS steps, Exodus output at the first
# and last step only, a history row every HI steps, a checkpoint ck_NAME.h5 at step CK: CK < STEPS
# < 2 CK, so that it is the only one) and NAME_ref.yaml (the same without checkpoints).
restart_decks() {
  local in=$1 name=$2 steps=$3 ck=$4 hi=$5
  sed -E "s/^(\s*)final_time:.*/\1steps: $steps/; s#\.\./meshes/#$SRC/../meshes/#;
          s/^  interval: [0-9]+/  interval: 0/; s/^  history_interval: [0-9]+/  history_interval: $hi/;
          /^\s*(file|history_file): \S+\.(e|h5)\s*$/d" "$in" > $name.yaml
  grep -q "history_interval" $name.yaml || { echo "$name: the deck has no output.history_interval"; return 1; }
  cp $name.yaml ${name}_ref.yaml
  printf 'restart:\n  file: ck_%s.h5\n  interval: %d\n' $name $ck >> $name.yaml
}

# history_diff REF RESTARTED EXACT: every row of RESTARTED against REF's row of the same step.
# EXACT 1: every column, bitwise. Else (another rank count, whose sums over the points add in
# another order) the energy bookkeeping (columns in J: energies, works, dissipations, the balance
# error), the forces (N) and the damage fraction, each to 1e-9 of the largest magnitude in REF's
# columns of its units; the sums of momentum, mean positions and velocities over the points are
# round-off where they vanish (a pulse's momentum) and left to the state digest. Prints the
# differences; status 1 if any.
history_diff() {
  $PY - "$@" <<'PY'
import sys, h5py, numpy as np
ref, rs, exact = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), sys.argv[3] == "1"
bad = [] if set(ref.keys()) == set(rs.keys()) else ["columns differ: %s" % sorted(set(ref.keys()) ^ set(rs.keys()))]
unit = {c: ref[c].attrs.get("units", b"") for c in ref.keys()}
unit = {c: u.decode() if isinstance(u, bytes) else str(u) for c, u in unit.items()}
compared = [c for c in ref.keys() if exact or unit[c] in ("J", "N") or c in ("step", "time", "damage_fraction")]
scale = {}
for c in ref.keys():
    scale[unit[c]] = max(scale.get(unit[c], 0.0), float(np.max(np.abs(ref[c][:]))))
row = {int(s): k for k, s in enumerate(ref["step"][:])}
for k, s in enumerate(rs["step"][:]):
    if int(s) not in row:
        bad.append("step %d: no row in the uninterrupted run's history" % s)
        continue
    for c in compared:
        if c not in rs: continue
        a, b = ref[c][row[int(s)]], rs[c][k]
        tol = 0 if exact else 1e-9 * scale[unit[c]]
        if not (a == b or abs(a - b) <= tol):
            bad.append("step %d: %s %r, uninterrupted %r" % (s, c, b, a))
print("\n".join(bad[:8]) + ("\n(%d more)" % (len(bad) - 8) if len(bad) > 8 else ""), end="")
sys.exit(1 if bad else 0)
PY
}

# fragments_diff REF RESTARTED: the fragments of the last step (output.fragments' CSV rows of the
# last time) the same: bodies, fragment ids and point counts exactly, masses, centres and velocities
# to 1e-9 of each column's largest magnitude. Prints the differences; status 1 if any.
fragments_diff() {
  $PY - "$@" <<'PY'
import sys, csv
def last(path):
    rows = list(csv.DictReader(open(path)))
    t = rows[-1]["time"]
    return [r for r in rows if r["time"] == t]
a, b = last(sys.argv[1]), last(sys.argv[2])
bad = []
if [(r["body"], r["fragment"], r["points"]) for r in a] != [(r["body"], r["fragment"], r["points"]) for r in b]:
    bad.append("%d fragments, uninterrupted %d (or other ids or sizes)" % (len(b), len(a)))
else:
    for c in ["time", "mass", "x", "y", "z", "vx", "vy", "vz"]:
        scale = max(abs(float(r[c])) for r in a)
        for ra, rb in zip(a, b):
            if abs(float(ra[c]) - float(rb[c])) > 1e-9 * scale:
                bad.append("fragment %s: %s %s, uninterrupted %s" % (rb["fragment"], c, rb[c], ra[c]))
print("\n".join(bad[:8]), end="")
sys.exit(1 if bad else 0)
PY
}

# history_at H5 COLUMN STEP: the column's value at that step (empty when there is no such row).
history_at() {
  $PY - "$@" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
rows = [k for k, s in enumerate(f["step"][:]) if int(s) == int(sys.argv[3])]
if rows and sys.argv[2] in f: print(repr(float(f[sys.argv[2]][rows[0]])))
PY
}

# restart_case NAME CK COLUMN RUN...: the uninterrupted 1-rank run of NAME_ref.yaml must have
# COLUMN non-zero at step CK (something happened before the checkpoint: contact, damage); then for
# each RUN "W R...": NAME.yaml run on W ranks (writes the checkpoint at CK), restarted from it on
# each R ranks, must end with the uninterrupted digest and write the uninterrupted history rows
# (bitwise for 1 -> 1) from step CK on, and with output.fragments the same fragments at the last
# step. Sets fail=1 on a failure; adds the case's time to times.txt.
restart_case() {
  local name=$1 ck=$2 col=$3 t0 ref d v h msg w r all="" spec # (local: a caller's own variable is not touched)
  shift 3
  t0=$(date +%s)
  ref=$(digest_of "$(run 1 "$exe" --quiet ${name}_ref.yaml 2>&1)")
  [ -n "$ref" ] || { echo "$name: the uninterrupted run gave no digest"; fail=1; return; }
  v=$(history_at ${name}_ref.h5 $col $ck)
  [ -n "$v" ] && awk -v x="$v" 'BEGIN { exit !(x + 0 != 0) }' ||
    { echo "$name: $col is '$v' at the checkpoint's step $ck: nothing happened yet, the test would not fail"; fail=1; }
  for spec in "$@"; do
    set -- $spec
    w=$1
    shift
    rm -f ck_$name.h5
    run $w "$exe" --quiet $name.yaml > /dev/null 2>&1 || { echo "$name: the run with a checkpoint on $w ranks failed"; fail=1; continue; }
    for r in "$@"; do
      all="$all $w->$r"
      rm -f $name-restart*
      d=$(digest_of "$(run $r "$exe" --quiet --restart ck_$name.h5 $name.yaml 2>&1)")
      [ "$d" = "$ref" ] || { echo "$name: written on $w ranks, restarted on $r: digest '$d', uninterrupted '$ref'"; fail=1; }
      h=$name-restart$ck.h5
      [ -f $h ] || { echo "$name: $w -> $r: no history $h (the checkpoint was not at step $ck?)"; fail=1; continue; }
      msg=$(history_diff ${name}_ref.h5 $h $([ $w$r = 11 ] && echo 1 || echo 0)) ||
        { echo "$name: written on $w ranks, restarted on $r: the history differs:"; echo "$msg"; fail=1; }
      [ ! -f ${name}_ref.fragments.csv ] || msg=$(fragments_diff ${name}_ref.fragments.csv $name-restart$ck.fragments.csv) ||
        { echo "$name: written on $w ranks, restarted on $r: the last fragments differ:"; echo "$msg"; fail=1; }
    done
  done
  echo "$name:$all: $(($(date +%s) - t0)) s ($col at step $ck: $v)" >> times.txt
}
