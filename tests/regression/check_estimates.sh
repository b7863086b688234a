#!/usr/bin/env bash
# `perifem --check` estimates the run time (from a few timed steps) and the Exodus file's size
# (in the deck's precision and compression) within a factor 2 of the run's CPU time (user + sys)
# and file, on three shipped decks shortened with --set: the PMB bar in single precision with
# compression 1 (the old estimate, 8 bytes a value uncompressed, was 10 times the file), the
# coupled wave_pd_to_fe to 12 us, and disk_impact_elastic to 10 us (an FE sphere in contact with
# an LPS disk from the first steps; the old estimate left contact out and was half the run).
# --check writes nothing: the output folder it would use is not made, and a file already there
# is left as it was. On 2 ranks the calibration is collective (the report comes, exit 0).
# usage: check_estimates.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0
here=$(pwd)
source "$here/common/mpi_env.sh"
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
bad() { echo "FAIL: $*"; fail=1; }
within2() { awk -v a="$1" -v b="$2" 'BEGIN {exit !(a > 0 && b > 0 && a <= 2 * b && b <= 2 * a)}'; }
# the report's run time in seconds, and its Exodus size in bytes
seconds() {
  sed -n 's/^  run time: about \([0-9.e+]*\) \(s\|min\|h\) on.*/\1 \2/p' "$1" |
    awk '{f["s"]=1; f["min"]=60; f["h"]=3600; print $1 * f[$2]}'
}
bytes() {
  sed -n 's/^  output: Exodus \([0-9.e+]*\) \([KMG]*B\) (.*/\1 \2/p' "$1" |
    awk '{f["B"]=1; f["KB"]=1e3; f["MB"]=1e6; f["GB"]=1e9; print $1 * f[$2]}'
}

# estimate NAME DECK SETS...: --check, then the run (its CPU time and Exodus file)
estimate() {
  local name=$1 deck=$here/../inputs/$2 stem=${2%.yaml}
  shift 2
  "$exe" --check "$deck" "$@" --output-dir "out_$name" > "$name.check" 2>&1 || bad "$name: --check exited $?"
  [ -e "out_$name" ] && bad "$name: --check made the output folder"
  local TIMEFORMAT='%3U %3S' cpu
  cpu=$({ time "$exe" --quiet --output-dir "out_$name" "$deck" "$@" > "$name.run" 2>&1; } 2>&1 | awk '{print $1 + $2}')
  [ -s "out_$name/$stem.e" ] || bad "$name: the run wrote no Exodus file: $(tail -3 "$name.run")"
  local est size real
  est=$(seconds "$name.check") size=$(bytes "$name.check") real=$(stat -c %s "out_$name/$stem.e" 2>/dev/null)
  echo "$name: run time estimated ${est:-?} s, run ${cpu} s CPU; Exodus estimated ${size:-?} bytes, written ${real:-?}"
  within2 "${est:-0}" "$cpu" || bad "$name: run time estimate ${est:-none} s against ${cpu} s: $(grep 'run time' "$name.check")"
  within2 "${size:-0}" "${real:-0}" || bad "$name: Exodus estimate ${size:-none} bytes against ${real:-0}"
}

estimate bar wave_in_bar.yaml --set output.precision=single --set output.compression=1
estimate coupled wave_pd_to_fe.yaml --set time.final_time=12e-6
estimate contact disk_impact_elastic.yaml --set time.final_time=10e-6

# an output file already there is left as it was; no lock file
mkdir -p kept && echo old > kept/wave_in_bar.e
"$exe" --check --output-dir kept "$here/../inputs/wave_in_bar.yaml" > kept.check 2>&1 || bad "--check into kept exited $?"
[ "$(cat kept/wave_in_bar.e)" = old ] && [ "$(ls kept)" = wave_in_bar.e ] || bad "--check touched kept/: $(ls kept)"

run 2 "$exe" --check "$here/../inputs/wave_in_bar.yaml" --output-dir out2 > two.check 2>&1 || bad "2 ranks: --check exited $?"
grep -q "^  run time: about .* on 2 rank(s)" two.check || bad "2 ranks: no run time line: $(tail -2 two.check)"
[ -e out2 ] && bad "2 ranks: --check made the output folder"
exit $fail
