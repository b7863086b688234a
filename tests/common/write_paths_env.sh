# Shared by the write_paths_*.sh tests (sourced, not run): a scratch folder holding a 16-point PD
# deck's point file, the deck (pd_deck), and the check of a refused run (refused).
# The sourcing script is called as SCRIPT PERIFEM SCRATCH (from the tests/ folder).
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 tests=$(pwd) fail=0
source "$tests/common/mpi_env.sh"
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
for x in 0 1 2 3; do for y in 0 1; do for z in 0 1; do
  echo "$(echo "$x*0.001" | bc -l) $(echo "$y*0.001" | bc -l) $(echo "$z*0.001" | bc -l) 1e-9 1"
done; done; done > pts.txt
# pd_deck LINES: the deck (3 steps unless LINES set time:), with LINES (output:, restart: ...)
pd_deck() {
  printf '%s\n' "materials: {m: {model: pmb, density: 1000, bulk_modulus: 1.0e9}}" "bodies:" \
    "  - {name: b, material: m, horizon: 0.0021, geometry: {shape: points_file, file: pts.txt}}"
  case "$1" in *time:*) ;; *) echo "time: {steps: 3}" ;; esac
  printf '%s\n' "$1"
}
# refused DECK KEY TEXT [ARGS...]: exit status 2 (no crash, no hang), an error naming key KEY
# and saying TEXT, and no file made or changed in the scratch folder
refused() {
  local deck=$1 key=$2 text=$3 before after out rc
  shift 3
  before=$(find . -type d -printf '%p\n' -o -printf '%p %s %T@ %y\n' | sort)
  out=$(timeout 60 "$exe" --quiet "$@" "$deck" 2>&1); rc=$?
  after=$(find . -type d -printf '%p\n' -o -printf '%p %s %T@ %y\n' | sort)
  [ $rc = 2 ] || { echo "FAIL $deck $*: exit status $rc, expected 2: $out"; fail=1; }
  echo "$out" | grep -q "key '$key'.*$text" || { echo "FAIL $deck $*: no key '$key' and '$text' in: $out"; fail=1; }
  [ "$before" = "$after" ] || { echo "FAIL $deck $*: files made or changed:"; diff <(echo "$before") <(echo "$after"); fail=1; }
}
