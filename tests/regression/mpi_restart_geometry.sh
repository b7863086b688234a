#!/usr/bin/env bash
# A restart whose deck makes another geometry than the checkpoint's is refused (exit status 2),
# the message naming the body, the file it is made from and what differs; the unchanged deck
# restarts to the uninterrupted digest. The deck's text alone cannot tell: a mesh or point file
# may change under the same name.
#  1. The Taylor bar (inputs/taylor_impact.yaml on the 0.8 mm mesh, 8 steps, a checkpoint at step
#     5, written on 2 ranks) with its mesh file copied to bar.geo, restarted on 1 rank:
#     - bar.geo unchanged: the uninterrupted run's digest;
#     - bar.geo 32.5 mm long instead of 32.4 (the same 5040 nodes and 4305 elements, other
#       coordinates): "body 'bar': its mesh file 'bar.geo' gives the same 5040 nodes ... but other
#       node coordinates";
#     - bar.geo 30.4 mm long (4680 nodes, 3990 elements), and the deck's element_size 0.7 mm:
#       refused naming the counts of both;
#     - the deck's mesh translated by 1 um: other node coordinates.
#  2. A PMB block read from a point file (x y z volume block, 4 x 4 x 4 points), written on 1 rank,
#     restarted on 2: one coordinate of the file moved by 1 um, or a point dropped: refused naming
#     the point file.
#  3. A checkpoint without the format attribute (as perifem wrote them before it recorded the
#     geometry), of an older format (4: the run's books as fixed scalars, before the ledger) or of
#     a newer one: refused naming the formats. One missing one of the ledger's records is refused
#     naming the attribute.
# usage: mpi_restart_geometry.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
# refused DECK CHECKPOINT NP LABEL PATTERN...: the restart exits with status 2 and its message has
# every pattern
refused() {
  local deck=$1 ck=$2 np=$3 label=$4 out status
  shift 4
  out=$(run $np "$exe" --quiet --restart $ck $deck 2>&1)
  status=$?
  [ $status -eq 2 ] || { echo "$label: exit $status, expected 2: $out" | head -5; fail=1; return; }
  for p in "$@"; do
    echo "$out" | grep -q -- "$p" || { echo "$label: the message has no '$p': $(echo "$out" | grep error)"; fail=1; }
  done
}

# 1. the FE mesh
cp "$OLDPWD/../meshes/taylor_bar.geo" bar.geo
sed -E 's/^(\s*)final_time:.*/\1steps: 8/; s#\.\./meshes/taylor_bar.geo#bar.geo#; s/element_size: 0.6e-3/element_size: 0.8e-3/' \
  "$OLDPWD/../inputs/taylor_impact.yaml" > bar.yaml
printf 'restart:\n  file: ck.h5\n  interval: 5\n' >> bar.yaml
grep -q "file: bar.geo" bar.yaml && grep -q "element_size: 0.8e-3" bar.yaml || { echo "the Taylor deck was not made"; fail=1; }
ref=$(digest_of "$(run 2 "$exe" --quiet bar.yaml 2>&1)")
d=$(digest_of "$(run 1 "$exe" --quiet --restart ck.h5 bar.yaml 2>&1)")
[ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "unchanged mesh: restart digest '$d', uninterrupted '$ref'"; fail=1; }
sed -i 's/^L = 32.4e-3;/L = 32.5e-3;/' bar.geo
grep -q "^L = 32.5e-3;" bar.geo || { echo "bar.geo was not changed"; fail=1; }
refused bar.yaml ck.h5 1 "mesh 0.1 mm longer" "body 'bar'" "mesh file 'bar.geo'" "gives the same 5040 nodes and 4305 elements" \
  "other node coordinates" "ck.h5"
sed -i 's/^L = 32.5e-3;/L = 30.4e-3;/' bar.geo
refused bar.yaml ck.h5 1 "mesh 2 mm shorter" "body 'bar'" "mesh file 'bar.geo' gives 4680 nodes and 3990 elements" \
  "written with 5040 nodes and 4305 elements"
cp "$OLDPWD/../meshes/taylor_bar.geo" bar.geo
sed 's/element_size: 0.8e-3/element_size: 0.7e-3/' bar.yaml > bar_h.yaml
refused bar_h.yaml ck.h5 1 "element size 0.7 mm" "body 'bar'" "mesh file 'bar.geo' gives [0-9]* nodes" \
  "written with 5040 nodes and 4305 elements"
sed -E 's/^(\s*)element_size: 0.8e-3/\1element_size: 0.8e-3\n\1translate: [0, 0, 1.0e-6]/' bar.yaml > bar_t.yaml
refused bar_t.yaml ck.h5 1 "mesh translated" "body 'bar'" "other node coordinates"

# 2. a point file
awk 'BEGIN { for (i = 0; i < 4; i++) for (j = 0; j < 4; j++) for (k = 0; k < 4; k++)
             printf "%.4e %.4e %.4e 1.0e-9 1\n", 1e-3 * i, 1e-3 * j, 1e-3 * k }' > pts.txt
cat > pts.yaml <<'DECK'
materials:
  glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}
bodies:
  - name: block
    material: glass
    geometry: {shape: points_file, file: pts.txt}
    horizon: 0.0030001
    initial_velocity: ["x < 0.0005 ? 10 : 0", "0", "0"]
time: {steps: 8}
output: {interval: 0, history_interval: 4}
restart: {file: ckp.h5, interval: 5}
DECK
ref=$(digest_of "$(run 1 "$exe" --quiet pts.yaml 2>&1)")
d=$(digest_of "$(run 2 "$exe" --quiet --restart ckp.h5 pts.yaml 2>&1)")
[ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "unchanged point file: restart digest '$d', uninterrupted '$ref'"; fail=1; }
cp pts.txt pts_orig.txt
awk 'NR == 10 { $1 = $1 + 1e-6 } { print }' pts_orig.txt > pts.txt
cmp -s pts.txt pts_orig.txt && { echo "pts.txt was not changed"; fail=1; }
refused pts.yaml ckp.h5 2 "point moved" "body 'block'" "point file 'pts.txt' gives the same 64 points" "other point positions"
sed '64d' pts_orig.txt > pts.txt
refused pts.yaml ckp.h5 2 "point dropped" "body 'block'" "point file 'pts.txt' gives 63 points and 0 elements" \
  "written with 64 points and 0 elements"
cp pts_orig.txt pts.txt

# 3. the format
for f in 0 4 6; do
  cp ckp.h5 ckp$f.h5
  "$PY" -c "
import h5py, sys
with h5py.File('ckp$f.h5', 'r+') as h:
    if $f: h.attrs.modify('format', $f)
    else: del h.attrs['format']
" || { echo "h5py could not edit the checkpoint"; fail=1; }
done
refused pts.yaml ckp0.h5 1 "no format attribute" "ckp0.h5 is of format 1, this perifem reads formats 5 to 5 only" "older perifem"
refused pts.yaml ckp4.h5 1 "format 4" "ckp4.h5 is of format 4" "older perifem"
refused pts.yaml ckp6.h5 1 "format 6" "ckp6.h5 is of format 6" "newer perifem"
# a checkpoint without one of the ledger's records (the books of the run) is refused naming it
"$PY" -c "
import h5py, shutil
shutil.copy('ckp.h5', 'ckp_books.h5')
with h5py.File('ckp_books.h5', 'r+') as h:
    books = [a for a in h.attrs if a.startswith('ledger:')]
    assert 'ledger:block_external_work' in books and 'ledger:initial_energy' in books, books
    del h.attrs['ledger:block_external_work']
" || { echo "h5py could not edit the checkpoint"; fail=1; }
refused pts.yaml ckp_books.h5 1 "a record of the books missing" "ckp_books.h5 has no attribute 'ledger:block_external_work'"
exit $fail
