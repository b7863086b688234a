#!/usr/bin/env bash
# The module layers hold (docs/architecture.md §1):
#  - every module's public header compiles in the modules that link it and fails to compile
#    (#error) in every other module: the layering is enforced, not only drawn; the allowed
#    modules are read from the build's PF_DEPS_<module> lists in CMakeLists.txt;
#  - a file of module M includes only M's own headers and the public headers of the modules
#    M links (no other module's private *_impl.h); include/perifem.h, the public C API, only
#    in sim/, which implements it;
#  - the driver calls bodies only through the body interface: no file of sim/ but the kinds'
#    own (sim/body_<kind>.c) names a PD, FE or coupled body function;
#  - sim/ calls bodies and interactions alike (docs/architecture.md §4b): no file of sim/ tests
#    an optional op for NULL outside the dispatchers (sim/body.c, sim/interaction.c), none
#    branches on a kind's or a material's name outside the registries (sim/*_kinds.c), and no
#    files of sim/ call each other in a loop (scripts/file_cycles.py on the build's objects).
# usage: layers.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 fail=0
rm -rf "$scratch" && mkdir -p "$scratch"
top=$(cd .. && pwd)
cc=$(command -v mpicc || echo cc)
modules=$(sed -n 's/^set(PF_MODULES \(.*\))$/\1/p' "$top/CMakeLists.txt")
[ -n "$modules" ] || { echo "FAIL: no PF_MODULES list in CMakeLists.txt"; exit 1; }
deps_of() { sed -n "s/^set(PF_DEPS_$1\(.*\))\$/\1/p" "$top/CMakeLists.txt"; }
header_of() { if [ "$1" = core ]; then echo core/core.h; else echo "$1/$1.h"; fi; }
upper() { echo "$1" | tr a-z A-Z; }

# 1. public headers under each module's definitions
for m in $modules; do
  allowed="$m $(deps_of "$m")"
  defs=""
  for a in $allowed; do defs="$defs -DPF_USES_$(upper "$a")"; done
  for n in $modules; do
    echo "#include \"$(header_of "$n")\"" > "$scratch/t.c"
    if "$cc" -fsyntax-only -std=c17 -I"$top" -I/usr/include/hdf5/openmpi $defs "$scratch/t.c" 2> "$scratch/err"; then ok=1; else ok=0; fi
    if [[ " $allowed " == *" $n "* ]]; then
      [ $ok = 1 ] || { echo "FAIL: $(header_of "$n") does not compile in $m/, which links it:"; head -5 "$scratch/err"; fail=1; }
    else
      [ $ok = 0 ] || { echo "FAIL: $(header_of "$n") compiles in $m/, which does not link $n/"; fail=1; }
      [ $ok = 0 ] && ! grep -q "is included by a module below" "$scratch/err" &&
        { echo "FAIL: $(header_of "$n") in $m/ fails, but not with the layering message:"; head -5 "$scratch/err"; fail=1; }
    fi
  done
done

# 2. includes of each module's files
for m in $modules; do
  allowed="$m $(deps_of "$m")"
  for f in "$top/$m"/*.c "$top/$m"/*.h; do
    [ -e "$f" ] || continue
    while read -r inc; do
      dir=${inc%%/*}
      if [ "$dir" = "$m" ]; then continue; fi
      # the public C API (include/perifem.h) is sim/'s outer face: sim/ alone implements it
      if [ "$inc" = include/perifem.h ]; then
        [ "$m" = sim ] || { echo "FAIL: ${f#$top/} includes $inc: only sim/ implements the public API"; fail=1; }
        continue
      fi
      if [[ " $allowed " != *" $dir "* ]]; then echo "FAIL: ${f#$top/} includes $inc: $m/ does not link $dir/"; fail=1
      elif [ "$inc" != "$(header_of "$dir")" ] && [ "$inc" != core/tensor.h ]; then
        echo "FAIL: ${f#$top/} includes $inc, a header private to $dir/"; fail=1
      fi
    done < <(sed -n 's/^#include "\([a-z]*\/[a-z_0-9]*\.h\)".*/\1/p' "$f")
  done
done

# 3. the driver and the body kinds
for f in "$top"/sim/*.c "$top"/sim/*.h; do
  case $(basename "$f") in body_*.c) continue ;; esac
  if grep -nE "pf_(pd|fem|coupled)_body_[a-z_]+\(" "$f" | grep -v "^[0-9]*: *\(/\*\|\*\)" > "$scratch/calls"; then
    calls=$(grep -vE "pf_sim_(body|fem_body)\b|^[0-9]+:pf_(pd|fem)_body \*pf_sim" "$scratch/calls")
    [ -z "$calls" ] || { echo "FAIL: ${f#$top/} calls a body kind's own function (use the body ops):"; echo "$calls" | head -5; fail=1; }
  fi
done

# 4. bodies and interactions through their ops, sim/ without circles
nulls=$(grep -nE "ops->[a-z_]+ *(\?|&&|\)|!=|==)|!\s*[a-z>.-]*ops->[a-z_]+" "$top"/sim/*.c | grep -v "/sim/body.c:\|/sim/interaction.c:\|_kinds.c:")
[ -z "$nulls" ] || { echo "FAIL: an optional op tested for NULL outside its dispatcher:"; echo "$nulls" | head -5; fail=1; }
kinds=$(grep -nE 'strcmp\([^)]*(kind|type|model|label)|"(pmb|lps|elastic_plastic|peridynamic|finite_element|particles)"' \
        "$top"/sim/*.c | grep -v "_kinds.c:\|/sim/body_[a-z]*.c:")
[ -z "$kinds" ] || { echo "FAIL: a branch on a kind's or a material's name in sim/:"; echo "$kinds" | head -5; fail=1; }
build=$(cd "${3:-../build/tests}/.." && pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
"$PY" "$top/scripts/file_cycles.py" "$build" sim --check > "$scratch/cycles" ||
  { echo "FAIL: files of sim/ call each other in a loop:"; cat "$scratch/cycles"; fail=1; }
exit $fail
