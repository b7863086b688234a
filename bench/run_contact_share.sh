#!/usr/bin/env bash
# The contact share of a step on the 87k-point bench cylinder (bench/README.md): the LAMMPS
# examples/peri target x3 (axis y, r = 15 mm, y in [-15, 0] mm, 0.5 mm lattice, 87,451 points,
# the point file of gen_bench.py), hit by an ELASTIC FE steel sphere (R = 5 mm, meshes/sphere.geo
# at element size 1 mm, -100 m/s) through an FE <-> PD contact pair, plus a short-range
# self-contact pair on the cylinder, for 150 steps of the stable step (the FE sphere sets it).
#
#   bash bench/run_contact_share.sh [path/to/perifem]      # default: build/perifem
#
# For each PD model (PMB with Silling-Askari damage, LPS with critical stretch: the materials of
# bench/run_bench.sh) it runs the deck twice, with and without its `contact:` section (without
# it the sphere flies through the cylinder untouched; the bodies, steps and output are the same),
# and reports the contact share of the time loop two ways:
#   summary:    the seconds perifem's summary line "contact: N search rebuilds, S s (P % of the
#               time loop)" gives (pf_contact_stats: search, ghosts, pair forces), over the loop;
#   difference: (loop with contact - loop without) / loop with contact.
# The table goes to stdout and to bench/results/contact_share.txt; progress to stderr.
#
# Environment: SHARE_STEPS (default 150), SHARE_MODELS (default "pmb lps"),
#   SHARE_ELEMENT (sphere element size in m, default 1e-3), SHARE_REPEAT (runs of each deck,
#   the fastest counts; default 1), SHARE_JITTER (gen_bench.py --jitter: each coordinate of each
#   point moved by up to this fraction of the spacing; default 0, the regular lattice; the table
#   then goes to bench/results/contact_share_jitter.txt), SHARE_SPLIT=1 also runs each pair
#   alone (the FE <-> PD pair only, the self-contact only) to split the contact seconds,
#   SHARE_KEEP=1 keeps the work directory.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
perifem=${1:-$root/build/perifem}
steps=${SHARE_STEPS:-150}
models=${SHARE_MODELS:-pmb lps}
esize=${SHARE_ELEMENT:-1e-3}
repeat=${SHARE_REPEAT:-1}
jitter=${SHARE_JITTER:-0}

die() { echo "run_contact_share.sh: error: $*" >&2; exit 1; }

[[ -x $perifem ]] || die "perifem binary '$perifem' not found or not executable (build it, or pass its path as the first argument)"
perifem=$(cd "$(dirname "$perifem")" && pwd)/$(basename "$perifem")
py=$(command -v python3 || true)
[[ -n $py ]] || die "python3 not found"

load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
work=$(mktemp -d /tmp/perifem_contact_share.XXXXXX)
cleanup() { if [[ ${SHARE_KEEP:-0} == 1 ]]; then echo "work directory kept: $work" >&2; else rm -rf "$work"; fi; }
trap cleanup EXIT

# --- inputs: gen_bench.py's point file and decks, the rigid indenter replaced ----------------
echo "== generating the bench cylinder in $work" >&2
"$py" "$here/gen_bench.py" generate "$work" --steps "$steps" --jitter "$jitter" >"$work/gen.log" || { cat "$work/gen.log" >&2; die "gen_bench.py failed"; }
npoints=$(sed -n 's/^points //p' "$work/gen.log")

for m in $models; do
  [[ -f $work/$m.yaml ]] || die "unknown model '$m' (gen_bench.py writes pmb and lps)"
  "$py" - "$work/$m.yaml" "$root/meshes/sphere.geo" "$esize" "$steps" "$work/${m}_contact.yaml" "$work/${m}_nocontact.yaml" <<'EOF'
import sys
src, geo, esize, steps, with_c, without_c = sys.argv[1:]
s = open(src).read()
head, rest = s.split("indenters:", 1)
# the steel sphere of inputs/disk_impact_elastic.yaml: K = 160 GPa, G = 78.3 GPa, rho = 7700
head = head.replace("materials:\n", "materials:\n  steel:\n    model: elastic\n    density: 7700\n"
                    "    youngs_modulus: 201.956e9\n    poissons_ratio: 0.28963\n", 1)
sphere = f"""  - name: sphere
    type: finite_element
    material: steel
    mesh:
      file: {geo}
      element_size: {esize}
      translate: [0, 0.0052, 0]   # lowest point 0.2 mm above the top face y = 0
    element: reduced
    initial_velocity: ["0", "-100", "0"]
"""
tail = f"""time:
  steps: {steps}

output:
  interval: 0
  history_interval: 10
"""
contact = """contact:
  pairs:
    - bodies: [sphere, target]     # FE <-> PD, method surface, radius h/2, k = K h
    - bodies: [target, target]     # PD self-contact, short range (0.9 h, bonded points excluded)
"""
open(with_c, "w").write(head + sphere + "\n" + contact + "\n" + tail)
open(without_c, "w").write(head + sphere + "\n" + tail)
# each pair alone (SHARE_SPLIT=1)
for name, drop in (("feonly", "[target, target]"), ("selfonly", "[sphere, target]")):
    only = "\n".join(l for l in contact.split("\n") if drop not in l)
    open(with_c.replace("_contact.yaml", "_" + name + ".yaml"), "w").write(head + sphere + "\n" + only + "\n" + tail)
EOF
done

# --- runs ------------------------------------------------------------------------------------
grab() {
  local v
  v=$(sed -n "$1" "$2" | head -1)
  [[ -n $v ]] || die "could not find '$3' in $2; last lines:"$'\n'"$(tail -20 "$2")"
  echo "$v"
}
# a python with h5py (for the history), if any
hpy=
for c in "$py" /usr/bin/python3; do
  if "$c" -c "import h5py" 2>/dev/null; then hpy=$c; break; fi
done
# largest |value| of a history column, or "-" (no h5py, or no such column)
hist_peak() {
  [[ -n $hpy ]] || { echo "-"; return; }
  "$hpy" - "$1" "$2" 2>/dev/null <<'EOF' || echo "-"
import sys, h5py
f = h5py.File(sys.argv[1], "r")
print("%.4g" % max(abs(x) for x in f[sys.argv[2]][:]))
EOF
}

declare -A loop csec cpct creb dtv dmg fy
for m in $models; do
  cases="contact nocontact"
  [[ ${SHARE_SPLIT:-0} != 1 ]] || cases="$cases feonly selfonly"
  for c in $cases; do
    k=$m,$c
    for ((r = 1; r <= repeat; r++)); do
      echo "== perifem $m, $c (run $r of $repeat)" >&2
      out=$work/out_${m}_$c
      mkdir -p "$out"
      log=$work/${m}_${c}_$r.log
      "$perifem" --output-dir "$out" "$work/${m}_$c.yaml" >"$log" 2>&1 \
        || { tail -30 "$log" >&2; die "perifem failed on ${m}_$c.yaml (log above)"; }
      grep -E '^perifem:|contact:|damage' "$log" >&2 || true
      l=$(grab 's/.*(time loop \([0-9.eE+-]*\) s[,)].*/\1/p' "$log" "time loop")
      if [[ -z ${loop[$k]:-} ]] || awk -v a="$l" -v b="${loop[$k]}" 'BEGIN { exit !(a < b) }'; then
        loop[$k]=$l
        dtv[$k]=$(grab 's/^perifem: [0-9]* steps of \([0-9.eE+-]*\) s.*/\1/p' "$log" "steps of")
        dmg[$k]=$(grab 's/.*final damage fraction \([0-9.eE+-]*\),.*/\1/p' "$log" "final damage fraction")
        if [[ $c != nocontact ]]; then
          creb[$k]=$(grab 's/.*contact: \([0-9]*\) search rebuilds.*/\1/p' "$log" "contact: N search rebuilds")
          csec[$k]=$(grab 's/.*search rebuilds, \([0-9.eE+-]*\) s (.*/\1/p' "$log" "contact seconds")
          cpct[$k]=$(grab 's/.*s (\([0-9.eE+-]*\) % of the time loop).*/\1/p' "$log" "% of the time loop")
          [[ $c == selfonly ]] || fy[$k]=$(hist_peak "$out/${m}_$c.h5" sphere_target_force_y)
        fi
      fi
    done
  done
done

# --- table -----------------------------------------------------------------------------------
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo 2>/dev/null | head -1)
src_desc="binary outside this checkout, commit unknown"
if [[ $perifem == "$root"/* ]] && commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null); then
  src_desc="checkout at $commit"
  [[ -z $(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null) ]] || src_desc="$src_desc + uncommitted changes"
fi
pf_version=$("$perifem" --version 2>/dev/null | head -1 || echo perifem)
nel=$(sed -n 's/.*elements \([0-9]*\), element cycles.*/\1/p' "$work/${models%% *}_contact_1.log" | head -1)

mkdir -p "$here/results"
table=$work/table.txt
{
  echo "perifem contact share of a step: bench cylinder hit by an FE sphere, 1 MPI rank"
  echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine:  ${cpu:-unknown CPU}, nproc $(nproc), load average at start $load_start"
  echo "perifem:  $pf_version, $perifem ($src_desc)"
  echo "problem:  bench/gen_bench.py cylinder (axis y, r = 15 mm, y in [-15, 0] mm, h = 0.5 mm, $npoints points,"
  [[ $jitter == 0 ]] || echo "          each coordinate moved by a uniform offset in [-$jitter h, $jitter h] (gen_bench.py --jitter $jitter),"
  echo "          horizon 0.0015001 m) hit by an elastic FE steel sphere (R = 5 mm, ${nel:-?} hexahedra of"
  echo "          ~$esize m, lowest point 0.2 mm above the top face, -100 m/s), $steps steps of the stable step;"
  echo "          contact: pair sphere <-> target (surface method, radius h/2, k = K h) and the"
  echo "          target's short-range self-contact (radius 0.9 h, bonded points excluded); default skin"
  echo "command:  SHARE_JITTER=$jitter SHARE_SPLIT=${SHARE_SPLIT:-0} bash bench/run_contact_share.sh ${1:-build/perifem}   (SHARE_REPEAT=$repeat: fastest of $repeat run(s))"
  echo
  printf '%-5s %10s %10s %11s %10s %9s %10s %11s %9s %9s\n' model "dt [s]" "loop [s]" "no-cont [s]" "contact[s]" rebuilds "share sum." "share diff." "damage" "F_y [N]"
  for m in $models; do
    awk -v m="${m^^}" -v dt="${dtv[$m,contact]}" -v lw="${loop[$m,contact]}" -v lo="${loop[$m,nocontact]}" \
        -v cs="${csec[$m,contact]}" -v rb="${creb[$m,contact]}" -v pc="${cpct[$m,contact]}" \
        -v d="${dmg[$m,contact]}" -v f="${fy[$m,contact]}" 'BEGIN {
      printf "%-5s %10.4g %10.2f %11.2f %10.2f %9d %9.1f%% %10.1f%% %9.3g %9s\n", m, dt, lw, lo, cs, rb, pc, 100 * (lw - lo) / lw, d, f }'
  done
  if [[ ${SHARE_SPLIT:-0} == 1 ]]; then
    echo
    echo "each pair alone (the contact: section with one pair; its own default skin):"
    for m in $models; do
      for c in feonly selfonly; do
        awk -v m="${m^^}" -v c="$c" -v lw="${loop[$m,$c]}" -v cs="${csec[$m,$c]}" -v rb="${creb[$m,$c]}" -v pc="${cpct[$m,$c]}" \
            -v d="${dmg[$m,$c]}" 'BEGIN {
          what = c == "feonly" ? "FE <-> PD pair only" : "self-contact only";
          printf "  %-5s %-20s loop %7.2f s, contact %6.2f s (%4.1f %%), %d rebuilds, damage %.3g\n", m, what, lw, cs, pc, rb, d }'
      done
    done
  fi
  echo
  echo "loop: perifem's 'time loop' seconds with the contact: section; no-cont: the same deck without it."
  echo "contact, share sum.: the summary's contact seconds and its '% of the time loop' (pf_contact_stats)."
  echo "share diff.: (loop - no-cont) / loop. damage: final damage fraction with contact. F_y: the"
  echo "  largest |sphere_target_force_y| in the history (a row every 10 steps; the force on the sphere, N)."
  echo "  The difference also holds the physics the contact changes (broken bonds are skipped: with"
  echo "  much damage it underestimates the share); the summary's seconds are the direct measure."
  echo "requirement: contact <= 25 % of a step."
} >"$table"

cat "$table"
saved=$here/results/contact_share.txt
[[ $jitter == 0 ]] || saved=$here/results/contact_share_jitter.txt
cp "$table" "$saved"
echo "(saved to $saved)" >&2
