#!/usr/bin/env bash
# The command line's options (issue 48):
#  1. every option taking a value takes it as --opt VALUE and as --opt=VALUE (--output-dir,
#     --set, --progress, --restart), before or after the deck, and "--" ends the options;
#  2. an unknown option, a shortened one or one a few letters off, exits 2 with the nearest known
#     option ("did you mean --output-dir?") and the usage on stderr; an option without a value
#     takes none (--check=yes); a missing or empty value is named;
#  3. the --set examples --help gives are keys of the deck it names: --check takes them (exit 0,
#     no warning) and a key that is none is refused (exit 2).
# usage: cli_options.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd .. && pwd)/inputs/wave_in_bar.yaml
scratch=$2 fail=0
here=$(pwd)
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
sed 's/final_time: 5.0e-6/final_time: 2.0e-8/' "$src" > bar.yaml
grep -q 'final_time: 2.0e-8' bar.yaml || { echo "FAIL: the shipped deck changed; the sed edit no longer applies"; exit 1; }

ran() { # WHAT DIR ARGS...: the run passes and writes bar.e into DIR
  local what=$1 dir=$2 out
  shift 2
  out=$("$exe" "$@" 2>&1)
  if [ $? -ne 0 ] || [ ! -s "$dir/bar.e" ]; then echo "FAIL $what: no $dir/bar.e: $(head -1 <<<"$out")"; fail=1
  else echo "ok   $what"; fi
}
ran "--output-dir DIR" o1 --quiet --output-dir o1 bar.yaml
ran "--output-dir=DIR" o2 --quiet --output-dir=o2 bar.yaml
ran "the deck first, then --output-dir=DIR" o3 bar.yaml --quiet --output-dir=o3
ran "--set=KEY=VALUE, --progress=plain" o4 --output-dir=o4 --set=time.final_time=1e-8 --progress=plain bar.yaml
ran "--progress plain, -- before the deck" o5 --output-dir o5 --progress plain -- bar.yaml
out=$("$exe" --check bar.yaml --set=time.final_time=5e-8 2>&1)
grep -q "steps to 5e-08 s" <<<"$out" && echo "ok   --set=KEY=VALUE applied" ||
  { echo "FAIL: --set=time.final_time=5e-8 not applied: $(head -1 <<<"$out")"; fail=1; }

refuse() { # WHAT EXPECTED-TEXT USAGE(0/1) ARGS...: exit 2, the text on stderr, the usage there or not
  local what=$1 want=$2 usage=$3 err st
  shift 3
  err=$("$exe" "$@" 2>&1 >/dev/null)
  st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$want" <<<"$err"; then
    echo "FAIL $what: exit $st, stderr lacks '$want': $(head -1 <<<"$err")"; fail=1
  elif [ "$usage" = 1 ] && ! grep -q '^usage: perifem' <<<"$err"; then
    echo "FAIL $what: no usage on stderr: $err"; fail=1
  else echo "ok   $what: $(head -1 <<<"$err")"; fi
}
refuse "--ouput-dir" "unknown option '--ouput-dir' (did you mean --output-dir?)" 1 --ouput-dir o bar.yaml
refuse "--output_dir=o" "unknown option '--output_dir=o' (did you mean --output-dir?)" 1 --output_dir=o bar.yaml
refuse "--chek" "unknown option '--chek' (did you mean --check?)" 1 --chek bar.yaml
refuse "-check" "unknown option '-check' (did you mean --check?)" 1 -check bar.yaml
refuse "--out (shortened)" "unknown option '--out' (did you mean --output-dir?)" 1 --out o bar.yaml
refuse "--nonsense" "unknown option '--nonsense'" 1 --nonsense bar.yaml
refuse "--check=yes" "--check takes no value (got '--check=yes')" 0 --check=yes bar.yaml
refuse "--set with no value" "--set needs KEY.PATH=VALUE" 0 bar.yaml --set
refuse "--output-dir= (empty)" "--output-dir needs a directory" 0 --output-dir= bar.yaml
refuse "--restart with no value" "--restart needs a checkpoint file" 0 bar.yaml --restart
refuse "--progress=sometimes" "--progress needs auto, plain or line (got 'sometimes')" 0 --progress=sometimes bar.yaml
refuse "two decks" "more than one deck given ('bar.yaml' and 'other.yaml')" 0 bar.yaml -- other.yaml
refuse "--restart=FILE reads FILE" "checkpoint no_such.ckpt" 0 --restart=no_such.ckpt bar.yaml

# ---- 3. --help's --set examples, on the deck it names ----
help=$("$exe" --help)
example=$(grep -o 'inputs/[a-z_]*\.yaml' <<<"$help" | head -1)
sets=$(grep -o -- '--set [a-z_.]*=[^ ]*' <<<"$help" | grep -v KEY)
if [ -z "$example" ] || [ "$(wc -l <<<"$sets")" -lt 2 ]; then
  echo "FAIL: --help names no example deck and two --set examples: $example / $sets"; fail=1
else
  args=()
  while read -r opt kv; do args+=("$opt" "$kv"); done <<<"$sets"
  out=$("$exe" --check "$here/../$example" "${args[@]}" 2>&1)
  st=$?
  if [ $st -ne 0 ] || grep -qi "warning\|error" <<<"$out"; then
    echo "FAIL: --help's examples ${args[*]} on $example: exit $st: $(grep -i 'warning\|error' <<<"$out" | head -2)"; fail=1
  else echo "ok   --help's examples ${args[*]} on $example"; fi
  out=$("$exe" --check "$here/../$example" --set bodies.sphere.velocity=[0,0,-900] 2>&1)
  [ $? -eq 2 ] || { echo "FAIL: the old example bodies.sphere.velocity was taken: $(head -2 <<<"$out")"; fail=1; }
fi
exit $fail
