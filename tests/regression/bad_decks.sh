#!/usr/bin/env bash
# Malformed decks must be refused cleanly: exit status 2, an error naming file:line:column
# (when the deck says so) and containing the expected text, no crash, nothing written.
#
#   bash tests/regression/bad_decks.sh PERIFEM SCRATCH_DIR [TESTS_BINARY_DIR (unused)]
#
# Each tests/data/bad/*.yaml starts with
#   # expect-line: LINE:COL   (or -: the error need not name a deck position)
#   # expect: TEXT            (a substring the error message must contain)
# Prints one line per failure and nothing when all pass; exits 1 on any failure.
set -u

if [ $# -lt 2 ]; then
  echo "usage: bash $0 PERIFEM SCRATCH_DIR" >&2
  exit 2
fi
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
decks=$here/data/bad
valid_deck=$here/../inputs/disk_impact_rigid.yaml
[ -x "$exe" ] || { echo "bad_decks: '$exe' is not an executable"; exit 1; }
mkdir -p -- "$scratch" && scratch=$(cd "$scratch" && pwd) || exit 1
# Remove only what an earlier run of this script made there.
rm -rf -- "$scratch/logs" "$scratch/cli_"* "$scratch/deck_"*
mkdir -p -- "$scratch/logs" || exit 1

# Keep a runaway deck (e.g. an alias bomb) from taking the machine's memory: a 2 GB address
# space limit, or for a sanitizer build (which reserves huge address ranges) an RSS limit.
# In a sanitizer build, the leaks of the MPI stack, gmsh and Pamgen are suppressed (reached
# through libmpi/libopen-pal only with the slow unwinder), so that any leak left is perifem's.
if grep -aq __asan_init "$exe" 2>/dev/null; then
  printf 'leak:%s\n' libmpi.so libopen-pal.so libopen-rte.so libhwloc.so libevent libpmix.so \
    libucs libucp libfabric libgmsh.so libtrilinos_pamgen.so >"$scratch/logs/lsan.supp"
  export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}hard_rss_limit_mb=2048"
  export LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}suppressions=$scratch/logs/lsan.supp:fast_unwind_on_malloc=0:print_suppressions=0"
  memlimit=unlimited
  limit=90 # the sanitizers make e.g. the alias-bomb deck's expansion several times slower
else
  memlimit=2097152
  limit=20
fi
crash_re='Segmentation|Abort|abort\(\)|core dumped|Bus error|Floating point exception|Illegal instruction|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error:|stack smashing|double free|free\(\): |malloc\(\): '
src_root=$(cd "$here/.." && pwd)

failures=0
problems=""
# problem WHAT: note one thing wrong with the current case; report CASE: print them on one line.
problem() { problems="${problems:+$problems; }$1"; }
report() { # case name
  local text=""
  [ -n "$problems" ] || return 0
  [ -s "$err" ] && text=$(head -c 600 "$err" | tr '\n' '|' | sed 's/|$//; s/|/ | /g')
  echo "FAIL $1: $problems -- stderr: ${text:-(empty)}"
  failures=$((failures + 1))
  problems=""
}

# run NAME DIR ARGS...: perifem with cwd DIR (made if need be), a 20 s timeout (90 s in a sanitizer build), memory limit;
# sets $status and leaves stdout/stderr in $scratch/logs/NAME.{out,err}.
run() {
  local name=$1 dir=$2
  shift 2
  mkdir -p "$dir"
  out=$scratch/logs/$name.out
  err=$scratch/logs/$name.err
  (ulimit -v "$memlimit" 2>/dev/null; cd "$dir" && exec timeout -k 5 "$limit" "$exe" "$@") >"$out" 2>"$err"
  status=$?
}

# common checks after a run: timeout, crash text, files left in DIR.
check_run() { # dir
  local left
  if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then problem "timed out after $limit s (exit $status)"; fi
  if grep -Eq "$crash_re" "$out" "$err"; then problem "output looks like a crash"; fi
  local leak
  leak=$(awk -v root="$src_root/" '
    /^(Direct|Indirect) leak of/ { inleak = 1; next }
    /^$/ { inleak = 0 }
    inleak && (index($0, root) || / in pf_/) { sub(/^ *#[0-9]+ 0x[0-9a-f]+ /, ""); print; exit }' "$err")
  if [ -n "$leak" ]; then problem "memory leak through perifem code ($leak)"; fi
  left=$(cd "$1" && find . -mindepth 1 | sort | tr '\n' ' ' | sed 's/ $//')
  if [ -n "$left" ]; then problem "files left in the output directory: $left"; fi
}

shopt -s nullglob
list=("$decks"/*.yaml)
if [ ${#list[@]} -eq 0 ]; then
  err=/dev/null
  problem "no decks found"
  report "$decks"
fi
for deck in "${list[@]}"; do
  name=$(basename "$deck")
  where=$(sed -n '1s/^# expect-line: *//p' "$deck")
  expect=$(sed -n '2s/^# expect: *//p' "$deck")
  if [ -z "$where" ] || [ -z "$expect" ]; then
    err=/dev/null
    problem "the deck does not start with '# expect-line:' and '# expect:' lines"
    report "$name"
    continue
  fi
  dir=$scratch/deck_${name%.yaml}
  mkdir -p "$dir"
  run "${name%.yaml}" "$dir" --output-dir "$dir" "$deck"
  [ "$status" -eq 2 ] || problem "exit status $status, expected 2"
  grep -qF -- "$expect" "$err" || problem "stderr lacks '$expect'"
  if [ "$where" != - ] && ! grep -qF -- "$name:$where" "$err"; then
    problem "stderr does not name '$name:$where'"
  fi
  check_run "$dir"
  report "$name"
done

# The command line.
# cli_case LABEL STATUS STREAM TEXT ARGS...: run perifem with ARGS (@DIR@ stands for a fresh
# folder, also its cwd) and check the exit status, that STREAM (out or err) contains TEXT
# (!TEXT: does not contain it; -: no check), and the common checks.
cli_n=0
cli_case() {
  local label=$1 want=$2 stream=$3 text=$4
  shift 4
  cli_n=$((cli_n + 1))
  local dir=$scratch/cli_$cli_n
  run "cli_$cli_n" "$dir" "${@//@DIR@/$dir}"
  local file=$err
  [ "$stream" = out ] && file=$out
  [ "$status" -eq "$want" ] || problem "exit status $status, expected $want"
  case "$text" in
    -) ;;
    !*) ! grep -qF -- "${text#!}" "$file" || problem "$stream says '${text#!}'" ;;
    *) grep -qF -- "$text" "$file" || problem "$stream lacks '$text'" ;;
  esac
  check_run "$dir"
  report "$label"
}

cli_case "--check $(basename "$valid_deck")" 0 err - --check --output-dir @DIR@ "$valid_deck"
cli_case "--help" 0 out usage --help
cli_case "--version" 0 out "libyaml" --version
cli_case "--version (the private libraries)" 0 out "METIS" --version
cli_case "--progress sometimes" 2 err "--progress needs auto, plain or line" --progress sometimes "$valid_deck"
cli_case "--deck-keys" 0 out "## 1. \`(top level)\`" --deck-keys
cli_case "--nonsense" 2 err --nonsense --nonsense
cli_case "(no deck given)" 2 err -
cli_case "no_such_deck.yaml" 2 err "cannot open deck" --output-dir @DIR@ "$decks/no_such_deck.yaml"
cli_case "(a directory as the deck)" 2 err "$decks" --output-dir @DIR@ "$decks"
cli_case "--output-dir with no value" 2 err "!unknown option" "$decks/02_unknown_top_key.yaml" --output-dir
cli_case "--output-dir under a file" 2 err "cannot create the folder" --output-dir "$valid_deck/out" "$valid_deck"

[ "$failures" -eq 0 ] || exit 1
exit 0
