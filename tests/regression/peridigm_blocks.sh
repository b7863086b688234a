#!/usr/bin/env bash
# Several materials in one PD body by the blocks of a Peridigm discretization (material_regions
# entries with `block:`, docs/theory/interfaces.md §1a), and the Peridigm translator's merge of
# the blocks that share a model, a horizon and a damage model into one body (docs/peridigm.md).
# The discretization is written here by python: a bar of 61 x 3 x 3 points (h = 1 mm, volume h^3),
# block 1 for x < x_I = 29.5 mm, block 2 beyond, in Peridigm's columns (x y z block_id volume).
# Block 1 is the body's material (PMB, K1 = 50 GPa), block 2 takes a material three times as
# stiff (K2 = 150 GPa) by its block id. Checks:
#  - the static pull (quasi-static solver; lateral motion held, a horizon-thick layer at each end
#    following the series-spring field u = eps1 x (x < x_I), eps1 x_I + eps2 (x - x_I) beyond,
#    eps2 = eps1 K1 / K2, as verification/test_bimaterial_static): every point's u_x within 1 % of
#    the pulled end's closed-form displacement, each part's strain between layers a horizon from
#    the interface and the grips within 1 % of eps1 and eps2, their ratio within 1e-3 of K2 / K1
#    (the band of test_bimaterial_static; the interface zone's share is stated there);
#  - the same deck with the stiff part given by a region (a box x > x_I) runs to the same state
#    digest, and the block deck's digest is the same on 1, 2 and 3 ranks;
#  - the translator makes one body with a material_regions entry per block of a two-block Peridigm
#    deck (two materials, one horizon and one damage model), two bodies (and says why on stderr)
#    when the horizons differ, and perifem --check takes both translations;
#  - an entry that gives both block and region, and a block the discretization does not hold, are
#    refused (exit 2) naming the key (and tests/data/bad/133-135 for the file and line).
# usage: peridigm_blocks.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
scratch=$2 fail=0
root=$(cd .. && pwd)
tr=$root/scripts/peridigm_to_perifem.py
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
"$PY" - <<'EOF'
h, n = 1e-3, 61
with open("bar.txt", "w") as f:
    f.write("# x y z block_id volume (m, m^3)\n")
    for i in range(n):
        for j in range(3):
            for k in range(3):
                f.write("%.17g %.17g %.17g %d %.17g\n" % (i * h, j * h, k * h, 1 if i < 30 else 2, h ** 3))
EOF
deck() { # STIFF_PART (the material_regions entry's selector)
  cat <<DECK
materials:
  soft: {model: pmb, density: 2700, bulk_modulus: 50.0e9}
  stiff: {model: pmb, density: 7800, bulk_modulus: 150.0e9}
bodies:
  - name: bar
    material: soft
    horizon: 3.015e-3
    material_regions: [{material: stiff, $1}]
    geometry: {shape: points_file, file: bar.txt, columns: peridigm}
boundary_conditions:
  - {name: lateral, displacement: [free, "0", "0"]}
  - {name: held, region: {shape: box, lo: [-1, -1, -1], hi: [3.015e-3, 1, 1]}, displacement: ["1e-3 * x * t", "0", "0"]}
  - {name: pulled, region: {shape: box, lo: [56.985e-3, -1, -1], hi: [1, 1, 1]},
     displacement: ["(1e-3 * 29.5e-3 + 1e-3 / 3 * (x - 29.5e-3)) * t", "0", "0"]}
solver: {type: quasi_static, method: newton_krylov, load_steps: 1, tolerance: 1.0e-10, max_iterations: 200000}
time: {final_time: 1}
output: {interval: 0}
DECK
}
deck "block: 2" > blocks.yaml
deck "region: {shape: box, lo: [29.5e-3, -1, -1], hi: [1, 1, 1]}" > regions.yaml

# The static pull against the series springs.
out=$("$exe" --quiet blocks.yaml --output-dir o1 2>&1) || { echo "FAIL: blocks.yaml: $out"; exit 1; }
d1=$(digest_of "$out")
"$PY" - o1/blocks.e <<'EOF' || fail=1
import sys
import netCDF4
import numpy as np
e = netCDF4.Dataset(sys.argv[1])
names = [b"".join(n).decode().strip("\x00") for n in e["name_nod_var"][:]]
X = np.array(e["coordx"][:])
ux = np.array(e["vals_nod_var%d" % (names.index("displacement_x") + 1)][-1])
h, delta, xI, xend, e1c, K1, K2 = 1e-3, 3.015e-3, 29.5e-3, 60e-3, 1e-3, 50e9, 150e9
e2c = e1c * K1 / K2
cf = np.where(X < xI, e1c * X, e1c * xI + e2c * (X - xI))
uend = e1c * xI + e2c * (xend - xI)
worst = np.abs(ux - cf).max() / uend
layer = lambda x: ux[np.abs(X - x) < 0.5 * h].mean()
a1, b1 = h * np.ceil(2 * delta / h), h * np.floor((xI - delta) / h)
a2, b2 = h * np.ceil((xI + delta) / h), h * np.floor((xend - 2 * delta) / h)
s1, s2 = (layer(b1) - layer(a1)) / (b1 - a1), (layer(b2) - layer(a2)) / (b2 - a2)
ok = worst < 0.01 and abs(s1 / e1c - 1) < 0.01 and abs(s2 / e2c - 1) < 0.01 and abs(s1 / s2 / (K2 / K1) - 1) < 1e-3
print("%s static pull, blocks by id: largest |u - series springs| %.3g of u_end = %.6g m; strains %.5f and %.5f "
      "of eps1, eps2; ratio %.6f of K2/K1" % ("ok  " if ok else "FAIL", worst, uend, s1 / e1c, s2 / e2c,
                                              s1 / s2 / (K2 / K1)))
sys.exit(0 if ok else 1)
EOF

# The region deck's digest, and the block deck's on 2 and 3 ranks.
dr=$(digest_of "$(run 1 "$exe" --quiet regions.yaml --output-dir or 2>&1)")
[ -n "$d1" ] && [ "$dr" = "$d1" ] && echo "ok   blocks and regions: one digest $d1" ||
  { echo "FAIL: the block deck's digest '$d1', the region deck's '$dr'"; fail=1; }
d2=$(digest_of "$(run 2 "$exe" --quiet blocks.yaml --output-dir o2 2>&1)")
d3=$(digest_of "$(run 3 "$exe" --quiet blocks.yaml --output-dir o3 2>&1)")
digests_agree "blocks.yaml" "$d1" "$d2" "$d3" || fail=1

# An Exodus discretization's blocks by name and by id: Peridigm's fragmenting cylinder in SPHERE
# elements (scripts/peridigm_cylinder.py, one cell through the wall: 560 points; blocks 'lower',
# id 1, z < L/2, and 'upper', id 2), the upper block stiffer, under its expanding initial velocity:
# one digest with the block named, numbered, and as a region z > L/2, and from the same points'
# text file by id.
"$PY" "$root/scripts/peridigm_cylinder.py" cyl --wall 1 > /dev/null || { echo "FAIL: the generator"; fail=1; }
cylinder() { # GEOMETRY STIFF_PART
  cat <<DECK
materials: {soft: {model: pmb, density: 7800, bulk_modulus: 130.0e9}, stiff: {model: pmb, density: 7800, bulk_modulus: 390.0e9}}
bodies:
  - {name: cylinder, material: soft, geometry: $1, horizon: 0.0151, material_regions: [{material: stiff, $2}],
     initial_velocity: ["200 * x / sqrt(x^2 + y^2)", "200 * y / sqrt(x^2 + y^2)", "100 * (z / 0.05 - 1)"]}
time: {steps: 20}
output: {interval: 0}
DECK
}
exo="{shape: exodus, file: cyl.g}"
cylinder "$exo" "block: upper" > cyl_name.yaml
cylinder "$exo" "block: 2" > cyl_id.yaml
cylinder "$exo" "region: {shape: box, lo: [-1, -1, 0.05], hi: [1, 1, 1]}" > cyl_region.yaml
cylinder "{shape: points_file, file: cyl.txt, columns: peridigm}" "block: 2" > cyl_text.yaml
ref=$(digest_of "$("$exe" --quiet cyl_region.yaml --output-dir o_cyl_region 2>&1)")
for d in name id text; do
  got=$(digest_of "$("$exe" --quiet cyl_$d.yaml --output-dir o_cyl_$d 2>&1)")
  [ -n "$ref" ] && [ "$got" = "$ref" ] && echo "ok   Exodus cylinder, the upper block by $d: the region's digest $ref" ||
    { echo "FAIL: Exodus cylinder, the upper block by $d: digest '$got', by region '$ref'"; fail=1; }
done

# The translator: two blocks of one model, horizon and damage model make one body with an entry of
# material_regions per block; another horizon for block 2 makes two bodies, said on stderr.
peridigm() { # HORIZON_OF_BLOCK_2
  cat <<DECK
Peridigm:
  Discretization: {Type: "Text File", Input Mesh File: "bar.txt"}
  Materials:
    Soft Material: {Material Model: "Elastic", Density: 2700.0, Bulk Modulus: 50.0e9, Shear Modulus: 30.0e9}
    Stiff Material: {Material Model: "Elastic", Density: 7800.0, Bulk Modulus: 150.0e9, Shear Modulus: 90.0e9}
  Damage Models:
    Bar Damage: {Damage Model: "Critical Stretch", Critical Stretch: 0.01}
  Blocks:
    Soft Block: {Block Names: "block_1", Material: "Soft Material", Damage Model: "Bar Damage", Horizon: 3.015e-3}
    Stiff Block: {Block Names: "block_2", Material: "Stiff Material", Damage Model: "Bar Damage", Horizon: $1}
  Solver: {Initial Time: 0.0, Final Time: 1.0e-6, Verlet: {Safety Factor: 0.8}}
DECK
}
peridigm 3.015e-3 > peridigm_one.yaml
peridigm 2.5e-3 > peridigm_two.yaml
for d in one two; do
  "$PY" "$tr" peridigm_$d.yaml perifem_$d.yaml > /dev/null 2> translate_$d.txt ||
    { echo "FAIL: peridigm_$d.yaml not translated: $(cat translate_$d.txt)"; fail=1; }
  "$exe" --check perifem_$d.yaml > check_$d.txt 2>&1 || { echo "FAIL: perifem_$d.yaml: $(cat check_$d.txt)"; fail=1; }
done
"$PY" - perifem_one.yaml perifem_two.yaml <<'EOF' || fail=1
import sys
import yaml
one, two = (yaml.safe_load(open(f)) for f in sys.argv[1:])
b = one["bodies"]
ok = (len(b) == 1 and "block" not in b[0]["geometry"] and b[0]["material"] == "soft_material" and
      b[0].get("material_regions") == [{"block": 1, "material": "soft_material"},
                                       {"block": 2, "material": "stiff_material"}])
print("%s one horizon: %d body, material_regions %s" % ("ok  " if ok else "FAIL", len(b), b[0].get("material_regions")))
g = [x["geometry"].get("block") for x in two["bodies"]]
ok2 = g == [1, 2] and not any("material_regions" in x for x in two["bodies"])
print("%s two horizons: %d bodies of blocks %s" % ("ok  " if ok2 else "FAIL", len(g), g))
sys.exit(0 if ok and ok2 else 1)
EOF
grep -q "note: Blocks: block_1, block_2: one body 'soft_block'" translate_one.txt &&
  grep -q "note: Blocks block_1 (body 'soft_block'); block_2 (body 'stiff_block'): separate bodies" translate_two.txt &&
  grep -q "^# Blocks block_1 .*: separate bodies" perifem_two.yaml && echo "ok   the translator says how the blocks became bodies" ||
  { echo "FAIL: the translator's notes: $(cat translate_one.txt translate_two.txt)"; fail=1; }

# Refusals naming the key.
refuse() { # WHAT SELECTOR EXPECTED
  local err st
  deck "$2" > refuse.yaml
  err=$("$exe" --quiet --check refuse.yaml 2>&1 >/dev/null); st=$?
  if [ $st -ne 2 ] || ! grep -qF -- "$3" <<<"$err"; then echo "FAIL $1: exit $st: $err"; fail=1
  else echo "ok   $1: $err"; fi
}
refuse "block and region" "block: 2, region: {shape: box, lo: [0, 0, 0], hi: [1, 1, 1]}" \
  "refuse.yaml:8:49: key 'block': body 'bar': an entry of material_regions gives both of block and region"
refuse "unknown block" "block: 7" "key 'block': body 'bar': its geometry holds no block '7' (its blocks: 1, 2)"
exit $fail
