#!/usr/bin/env bash
# What the Exodus file holds and how (output.fields, precision, compression). The shipped
# wave_in_bar.yaml cut to 1 us, written every 5 steps four ways, read back with netCDF4:
#  - default: every variable in double precision (the reference);
#  - precision: single: the same variables stored as float32, each value the reference's rounded
#    to single precision (relative difference <= 2^-24), the file at most 0.55 of the reference's;
#  - compression: 4: a netCDF-4 file, every value bitwise the reference's, the file smaller;
#  - fields: [displacement, damage]: exactly displacement_x/y/z and damage, bitwise the
#    reference's values;
# the run's digest is the same in all four (output does not touch the state); on 2 ranks the
# single-precision, compressed file holds the same values as on 1 rank. An unknown field name,
# a precision other than double or single and a level above 9 are refused naming the key.
# usage: output_format.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd .. && pwd)/inputs/wave_in_bar.yaml
scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
sed 's/final_time: 5.0e-6/final_time: 1.0e-6/; s/interval: 50/interval: 5/' "$src" > bar.yaml
grep -q "interval: 5$" bar.yaml || { echo "FAIL: the shipped deck changed; the sed edit no longer applies"; exit 1; }
declare -A digest
for v in ref single zip fields par; do
  case $v in
    ref) set -- ;; single) set -- --set output.precision=single ;; zip) set -- --set output.compression=4 ;;
    fields) set -- --set "output.fields=[displacement, damage]" ;;
    par) set -- --set output.precision=single --set output.compression=4 ;;
  esac
  np=1; [ $v = par ] && np=2
  digest[$v]=$(digest_of "$(run $np "$exe" --quiet bar.yaml --output-dir $v "$@" 2>&1)")
  [ -n "${digest[$v]}" ] && [ "${digest[$v]}" = "${digest[ref]}" ] ||
    { echo "FAIL $v: digest '${digest[$v]}', the reference run gives '${digest[ref]}'"; fail=1; }
done
"$PY" - <<'EOF' || fail=1
import os, sys
import numpy as np, netCDF4
def nodal(path):
    d = netCDF4.Dataset(path)
    names = [b"".join(r).decode().rstrip("\0") for r in d.variables["name_nod_var"][:]]
    vals = {n: np.asarray(d.variables["vals_nod_var%d" % (k + 1)][:]) for k, n in enumerate(names)}
    return d, names, vals
fail = []
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok: fail.append(what)
ref, rn, rv = nodal("ref/bar.e")
size = {v: os.path.getsize("%s/bar.e" % v) for v in ("ref", "single", "zip", "fields", "par")}
print("sizes (bytes):", size)
s, sn, sv = nodal("single/bar.e")
check(sn == rn and all(sv[n].dtype == np.float32 for n in sn), "single: the same variables, float32")
err = max(float(np.max(np.abs(sv[n].astype(np.float64) - rv[n]) / np.maximum(np.abs(rv[n]), 1e-300))) for n in rn)
check(err <= 2.0 ** -24, "single: values rounded to single precision (largest relative difference %.3g)" % err)
check(size["single"] <= 0.55 * size["ref"], "single: %.3f of the reference's size" % (size["single"] / size["ref"]))
z, zn, zv = nodal("zip/bar.e")
check(z.data_model.startswith("NETCDF4") and zn == rn and all(np.array_equal(zv[n], rv[n]) for n in rn),
      "compression: netCDF-4, every value bitwise the reference's")
check(size["zip"] < size["ref"], "compression: %.3f of the reference's size" % (size["zip"] / size["ref"]))
f, fn, fv = nodal("fields/bar.e")
check(fn == ["displacement_x", "displacement_y", "displacement_z", "damage"], "fields: %s" % fn)
check(all(np.array_equal(fv[n], rv[n]) for n in fn), "fields: values bitwise the reference's")
p, pn, pv = nodal("par/bar.e")
check(pn == sn and all(np.array_equal(pv[n], sv[n]) for n in pn), "2 ranks, single and compressed: the 1-rank single values")
sys.exit(1 if fail else 0)
EOF
refuse() { # WHAT EXPECTED ARGS...
  local what=$1 want=$2 err st
  shift 2
  err=$("$exe" --quiet bar.yaml --output-dir bad "$@" 2>&1 >/dev/null); st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$want" <<<"$err"; then echo "FAIL $what: exit $st: $err"; fail=1
  else echo "ok   $what: $err"; fi
}
refuse "unknown field" "key 'fields': no output field 'stres' in this deck (known: displacement, velocity, force" \
  --set "output.fields=[stres]"
refuse "bad precision" "key 'precision': double or single (got 'half')" --set output.precision=half
refuse "bad level" "key 'compression': 0 to 9 (got 10)" --set output.compression=10
exit $fail
