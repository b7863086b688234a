#!/usr/bin/env bash
# Peridigm's Exodus discretization (SPHERE and HEX8 elements, geometry: {shape: exodus}) and node /
# side sets as regions. The discretization is written here by scripts/peridigm_cylinder.py:
# Peridigm's fragmenting cylinder (r 20-25 mm, 100 mm long) cut into 2 x 57 x 40 annular-sector
# cells in two blocks with four node sets, as SPHERE elements and as HEX8 elements on the cells'
# corners, its volumes and counts summed by the script from the cells' own formulas (not by
# perifem). Checked:
#  - the points read (--check) equal the cells written, per block taken by name and by id;
#  - the kinetic energy at t = 0 of a uniform 10 m/s is 1/2 rho v^2 pi (r_o^2 - r_i^2) L, to
#    1e-12: every volume attribute is read, and the cells tile the tube exactly;
#  - a boundary condition on each node set selects as many points as the script put in it
#    (and on a Pamgen brick, a node set and a side set select the (ny+1)(nz+1) nodes of a face);
#  - the fragmenting cylinder with a node-set condition runs to one state digest on 1, 2 and 3
#    ranks, equal to that of the same points given as Peridigm's text format with the same
#    condition as a box; the Pamgen brick with its node set and side set conditions gives the
#    digest of the same conditions as boxes;
#  - the HEX8 file: its node sets (of nodes: z = 0, z = L, r = r_i, all) select the cells of the
#    SPHERE file's sets (Peridigm: a node brings in every element on it); the kinetic energy at
#    t = 0 is 1/2 rho v^2 (N_theta / 2) sin(dtheta) (r_o^2 - r_i^2) L (the cells' trapezoidal
#    prisms), to 1e-12; a node-set condition runs to one digest on 1, 2 and 3 ranks;
#  - a missing volume attribute, a non-positive volume, a block of one-node HEX8 elements, an
#    unknown block and an unknown set name are refused naming the file and the key.
# usage: peridigm_exodus.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0 tests=$(pwd)
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
"$PY" "$tests/../scripts/peridigm_cylinder.py" cyl --wall 2 --perturb 0.001 || { echo "FAIL: the generator"; exit 1; }
val() { "$PY" -c "import json, sys; e = json.load(open('cyl.json')); print(eval(sys.argv[1]))" "$1"; }
ok() { echo "ok   $*"; }
bad() { echo "FAIL $*"; fail=1; }

deck() { # GEOMETRY REGION [STEPS]
  cat <<DECK
materials: {steel: {model: pmb, density: 7800, bulk_modulus: 130.0e9}}
bodies:
  - name: cylinder
    material: steel
    geometry: $1
    horizon: 0.0105
    damage: {law: critical_stretch, critical_stretch: 0.02}
    initial_velocity:
      - "(200 - 50 * (z / 0.05 - 1)^2) * x / sqrt(x^2 + y^2)"
      - "(200 - 50 * (z / 0.05 - 1)^2) * y / sqrt(x^2 + y^2)"
      - "100 * (z / 0.05 - 1)"
boundary_conditions:
  - {region: $2, velocity: ["free", "free", "-50"]}
time: {steps: ${3:-20}}
output: {interval: 10}
DECK
}
digests_are() { # WHAT REF WHO DECK RANKS...: the deck's digest on each number of ranks is REF (WHO's)
  local what=$1 ref=$2 who=$3 d=$4 np got
  shift 4
  for np in "$@"; do
    got=$(digest_of "$(run $np "$exe" --quiet $d.yaml --output-dir o_${d}_$np 2>&1)")
    [ -n "$ref" ] && [ "$got" = "$ref" ] && ok "$what on $np rank(s): digest $ref, as $who" ||
      bad "$what on $np rank(s): digest '$got', $who gives '$ref'"
  done
}
points_of() { "$exe" --check "$1" 2>&1 | sed -n 's/.*deck is valid (\([0-9]*\) points.*/\1/p'; }
bc_points() { "$exe" --check "$1" 2>&1 | sed -n "s/^boundary condition 'bc0' .*: \([0-9]*\) points$/\1/p"; }

# counts: the whole file, and each block by name and by id
n=$(val 'e["points"]') n1=$(val 'e["blocks"]["1"]') n2=$(val 'e["blocks"]["2"]')
deck "{shape: exodus, file: cyl.g}" "{shape: node_set, set: bottom}" > all.yaml
deck "{shape: exodus, file: cyl.g, blocks: [upper]}" "{shape: node_set, set: top}" > upper.yaml
deck "{shape: exodus, file: cyl.g, blocks: ['1']}" "{shape: node_set, set: bottom}" > lower.yaml
for c in "all $n" "upper $n2" "lower $n1"; do
  set -- $c
  got=$(points_of $1.yaml)
  [ "$got" = "$2" ] && ok "$1: $got points" || bad "$1: '$got' points, the file has $2"
done
# node sets: as many points as the script put in them
for s in bottom top inner_wall all; do
  deck "{shape: exodus, file: cyl.g}" "{shape: node_set, set: $s}" > set_$s.yaml
  got=$(bc_points set_$s.yaml) want=$(val "e['sets']['$s']")
  [ "$got" = "$want" ] && ok "node set $s selects $got points" || bad "node set $s selects '$got' points, the file's set has $want"
done
# with the upper block alone, the top layer (all in it) is still whole
got=$(bc_points upper.yaml)
[ "$got" = "$(val 'e["sets"]["top"]')" ] && ok "upper block: node set top selects $got points" || bad "upper block: top selects '$got'"

# volumes: the kinetic energy of a uniform 10 m/s at t = 0
ke_is() { # FILE VOLUME FORMULA
  cat > ke_$1.yaml <<DECK
materials: {steel: {model: pmb, density: 7800, bulk_modulus: 130.0e9}}
bodies:
  - {name: cylinder, material: steel, geometry: {shape: exodus, file: $1}, horizon: 0.0105,
     initial_velocity: ["10", "0", "0"]}
time: {steps: 1}
output: {interval: 1, history_interval: 1}
DECK
  "$exe" --quiet ke_$1.yaml --output-dir o_ke_$1 > /dev/null 2>&1 || bad "ke $1: the run failed"
  "$PY" - o_ke_$1/ke_$1.h5 "$2" "$1" "$3" <<'EOF' || fail=1
import sys, h5py
ke = h5py.File(sys.argv[1], "r")["kinetic_energy"][0]
want = 0.5 * 7800 * float(sys.argv[2]) * 10.0 ** 2
ok = abs(ke - want) <= 1e-12 * want
print("%s %s: kinetic energy at t = 0: %.17g J, 1/2 rho v^2 %s = %.17g J" % ("ok  " if ok else "FAIL", sys.argv[3], ke, sys.argv[4], want))
sys.exit(0 if ok else 1)
EOF
}
ke_is cyl.g "$(val 'e["volume_exact"]')" "pi (r_o^2 - r_i^2) L"

# digests: 1, 2, 3 ranks; the text discretization with the condition as a box (the first layer)
dz=$(val 'e["spacing"]')
deck "{shape: points_file, file: cyl.txt, columns: peridigm}" "{shape: box, lo: [-1, -1, -1], hi: [1, 1, $dz]}" > text.yaml
ref=$(digest_of "$(run 1 "$exe" --quiet text.yaml --output-dir o_text 2>&1)")
digests_are "exodus + node set" "$ref" "the text format with a box" all 1 2 3

# the HEX8 file: node sets of nodes select the SPHERE file's cells; volumes; digests on 1, 2, 3 ranks
for s in bottom top inner_wall all; do
  deck "{shape: exodus, file: cyl_hex.g}" "{shape: node_set, set: $s}" 10 > hex_$s.yaml
  got=$(bc_points hex_$s.yaml) want=$(val "e['sets']['$s']")
  [ "$got" = "$want" ] && ok "HEX8 node set $s selects $got points" || bad "HEX8 node set $s selects '$got' points, the SPHERE file's set has $want"
done
ke_is cyl_hex.g "$(val 'e["hex_volume_exact"]')" "(N_theta / 2) sin(dtheta) (r_o^2 - r_i^2) L"
ref=$(digest_of "$(run 1 "$exe" --quiet hex_bottom.yaml --output-dir o_hex1 2>&1)")
digests_are "HEX8 + node set" "$ref" "1 rank" hex_bottom 2 3

# an FE body: a Pamgen brick of 3 x 4 x 5 elements over [0, 0.3] x [0, 0.2] x [0, 0.1] with a
# node set on x = 0 and a side set on x = 0.3, each (4 + 1)(5 + 1) = 30 nodes
brick() { # REGION_A REGION_B
  cat <<DECK
materials: {al: {model: elastic, density: 2700, youngs_modulus: 70.0e9, poissons_ratio: 0.3}}
bodies:
  - name: brick
    type: finite_element
    material: al
    mesh:
      pamgen: |
        mesh
          rectilinear
            nx = 3
            ny = 4
            nz = 5
            bx = 1
            by = 1
            bz = 1
            gmin = 0 0 0
            gmax = 0.3 0.2 0.1
          end
          set assign
            nodeset, ilo, 1
            sideset, ihi, 2
          end
        end
boundary_conditions:
  - {region: $1, velocity: ["0", "0", "0"]}
  - {region: $2, velocity: ["1", "0", "0"]}
time: {steps: 20}
output: {interval: 10}
DECK
}
brick "{shape: node_set, set: nodeset_1}" "{shape: side_set, set: sideset_2}" > brick_sets.yaml
brick "{shape: box, lo: [-1, -1, -1], hi: [0, 1, 1]}" "{shape: box, lo: [0.3, -1, -1], hi: [1, 1, 1]}" > brick_boxes.yaml
got=$("$exe" --check brick_sets.yaml 2>&1 | sed -n "s/^boundary condition 'bc[01]' .*: \([0-9]*\) points$/\1/p" | tr '\n' ' ')
[ "$got" = "30 30 " ] && ok "pamgen node set and side set: $got points" || bad "pamgen sets select '$got' points, want 30 and 30"
ref=$(digest_of "$(run 1 "$exe" --quiet brick_boxes.yaml --output-dir o_bb 2>&1)")
digests_are "pamgen sets" "$ref" "the same conditions as boxes" brick_sets 1 3

# refusals
refuse() { # WHAT DECK EXPECTED...
  local what=$1 d=$2 err st
  shift 2
  err=$("$exe" --quiet "$d" 2>&1 >/dev/null); st=$?
  for want in "$@"; do
    if [ $st -ne 2 ] || ! grep -qF -- "$want" <<<"$err"; then bad "$what: exit $st: $err (want '$want')"; return; fi
  done
  ok "$what: $err"
}
edit() { # OUT PYTHON (on the netCDF dataset f)
  cp cyl.g "$1" && "$PY" -c "import netCDF4, numpy as np; f = netCDF4.Dataset('$1', 'a'); $2; f.close()"
}
edit noattr.g "f['attrib_name2'][1] = netCDF4.stringtochar(np.array(['mass'], 'S33'))[0]"
deck "{shape: exodus, file: noattr.g}" "{shape: all}" > noattr.yaml
refuse "no volume attribute" noattr.yaml "key 'file'" "noattr.g: block 'upper' (id 2) has no volume attribute" "'radius', 'mass'"
edit negvol.g "a = f['attrib1'][:]; a[6, 1] = -1e-9; f['attrib1'][:] = a"
deck "{shape: exodus, file: negvol.g}" "{shape: all}" > negvol.yaml
refuse "negative volume" negvol.yaml "negvol.g: element 7 (block 'lower') has volume -1e-09"
edit hex.g "f['connect2'].elem_type = 'HEX8'"
deck "{shape: exodus, file: hex.g}" "{shape: all}" > hex.yaml
refuse "one-node HEX8" hex.yaml "hex.g: block 'upper' (id 2) holds HEX8 elements of 1 nodes; a Peridigm discretization is read from SPHERE (1 node), HEX8"
deck "{shape: exodus, file: hex.g, blocks: [lower]}" "{shape: node_set, set: bottom}" > hex_lower.yaml
got=$(points_of hex_lower.yaml)
[ "$got" = "$n1" ] && ok "a HEX8 block left out by blocks: $got points" || bad "hex.g with blocks: [lower]: '$got' points, want $n1"
deck "{shape: exodus, file: cyl.g, blocks: [middle]}" "{shape: all}" > noblock.yaml
refuse "unknown block" noblock.yaml "key 'blocks'" "has no block named or numbered 'middle' (its blocks: 'lower' (id 1), 'upper' (id 2))"
deck "{shape: exodus, file: cyl.g}" "{shape: node_set, set: tpo}" > noset.yaml
refuse "unknown node set" noset.yaml "key 'set'" "no body has a node set 'tpo' (the node sets: 'bottom' (body cylinder), 'top' (body cylinder)"
deck "{shape: exodus, file: cyl.g}" "{shape: side_set, set: top}" > noside.yaml
refuse "no side sets" noside.yaml "key 'set'" "no body has a side set 'top' (the side sets: none)"
exit $fail
