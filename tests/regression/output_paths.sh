#!/usr/bin/env bash
# No output overwrites an input or another output; the run is refused before anything is
# written (exit 2, an error naming the output's key), and every input is left byte for byte as
# it was. Files are compared through the file system, so each case also comes in a spelling
# that differs from the input's: ./name, a path through another folder, a symbolic link.
#  1. the Exodus output named like the deck (output.file: deck.yaml, ./deck.yaml);
#  2. a deck part.yaml whose FE body reads the mesh part.e, with the default output name;
#     the same mesh reached as ../run/part.e;
#  3. the history named like the deck's point file, through a symbolic link;
#  4. the history or the Exodus file named like the checkpoint (o.e against ./o.e);
#  5. the default history r.h5 of a deck r.yaml against its checkpoint r.h5; a restart from a
#     checkpoint rewrites that same checkpoint (allowed: it is read first, and written through a
#     temporary file), its other outputs get new names (<name>-restart<step>);
# and the valid decks around them run (exit 0).
# usage: output_paths.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0
rm -rf "$scratch" && mkdir -p "$scratch/run" && cd "$scratch/run" || exit 1
mesh=$(cd "$OLDPWD/data/mesh" && pwd)/two_hexes.msh

# a small PD deck: 4 x 2 x 2 points from a point file, 3 steps
for x in 0 1 2 3; do for y in 0 1; do for z in 0 1; do
  echo "$(echo "$x*0.001" | bc -l) $(echo "$y*0.001" | bc -l) $(echo "$z*0.001" | bc -l) 1e-9 1"
done; done; done > pts.txt
pd_deck() { # $1: extra output/restart lines
  cat <<DECK
materials: {m: {model: pmb, density: 1000, bulk_modulus: 1.0e9}}
bodies:
  - {name: b, material: m, horizon: 0.0021, geometry: {shape: points_file, file: pts.txt}}
time: {steps: 3}
$1
DECK
}
fe_deck() { # an FE body reading the mesh $1
  cat <<DECK
materials: {steel: {model: elastic, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.3}}
bodies:
  - {name: block, type: finite_element, material: steel, mesh: {file: $1}}
time: {steps: 3}
DECK
}
sums() { md5sum pts.txt part.e rr.h5 *.yaml sub/*.yaml 2>/dev/null; }
# refused DECK KEY [ARGS...]: exit 2, the key named, no new file, the inputs unchanged
refused() {
  local deck=$1 key=$2; shift 2
  local before after out rc
  before=$(sums; ls)
  out=$("$exe" "$@" "$deck" 2>&1); rc=$?
  after=$(sums; ls)
  [ $rc = 2 ] || { echo "$deck $*: exit $rc, expected 2: $out"; fail=1; }
  echo "$out" | grep -q "key '$key'.*would overwrite\|key '$key'.*same file" ||
    { echo "$deck $*: the error does not name key '$key' and the clash: $out"; fail=1; }
  [ "$before" = "$after" ] || { echo "$deck $*: files changed:"; diff <(echo "$before") <(echo "$after") | head; fail=1; }
}
runs() { "$@" > /dev/null 2>&1 || { echo "a valid run failed: $*"; fail=1; }; }

# 1. Exodus output named like the deck
pd_deck "output: {file: self.yaml}" > self.yaml && refused self.yaml file
pd_deck "output: {file: ./self2.yaml}" > self2.yaml && refused self2.yaml file

# 2. the default output <deck>.e against the mesh part.e (an Exodus mesh: an FE run's output),
#    and the same mesh named from a deck in another folder
fe_deck "$mesh" > gen.yaml && runs "$exe" --quiet gen.yaml && mv gen.e part.e && rm -f gen.h5
fe_deck part.e > part.yaml
refused part.yaml file
mkdir -p sub && fe_deck ../part.e > sub/other.yaml && printf 'output: {file: part.e}\n' >> sub/other.yaml
refused sub/other.yaml file

# 3. the history named like the point file, through a symbolic link
ln -sf pts.txt link.txt
pd_deck "output: {history_file: link.txt}" > hist.yaml && refused hist.yaml history_file

# 4. history and Exodus file the same file; Exodus against the checkpoint
pd_deck "output: {file: o.e, history_file: ./o.e}" > same.yaml && refused same.yaml history_file
pd_deck "output: {file: c.h5}
restart: {file: ./c.h5}" > ck.yaml && refused ck.yaml file

# 5. checkpoints
#    (and the default history r.h5 of a deck r.yaml is the same file as a checkpoint r.h5)
pd_deck "restart: {file: r.h5, interval: 1}" > r.yaml && refused r.yaml file
pd_deck "restart: {file: rr.h5, interval: 1}" > r.yaml && runs "$exe" --quiet r.yaml
[ -f rr.h5 ] || { echo "no checkpoint rr.h5 written"; fail=1; }
runs "$exe" --quiet --restart rr.h5 r.yaml
# valid: distinct names run
pd_deck "output: {file: ok.e, history_file: ok.h5}" > ok.yaml && runs "$exe" --quiet ok.yaml
exit $fail
