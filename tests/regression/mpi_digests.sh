#!/usr/bin/env bash
# Every shipped deck, at a reduced size, plus variants (LPS with METIS, re-partitioning at every
# output step, spread output, more ranks than points), runs on 1, 2 and 3 ranks and ends with
# bitwise the same state digest. The spread Exodus files of a 3-rank run hold every point once,
# with the same displacement as the joined file of the 1-rank run.
# The variants that repeat a deck of this list with one change (re-partitioning at every output
# step, spread output, the indenter written as a rigid surface, the consistent form of the
# variable-horizon block) do not run on 2 ranks: their deck runs on 2 ranks too, and 3 ranks
# re-partition, spread and split wherever 2 do (dcb_family, cylinder_contact and tube_ep, the
# re-partitioned decks with no plain twin, still run on 2). Neither do taylor_impact,
# disk_impact_rigid, sphere_on_block and coupled_bar, whose 2-rank runs mpi_restart.sh compares
# with their 1-rank runs. The variants whose change is only how the run is split, written or held
# (all but the consistent form) run on 3 ranks alone, against their plain deck's 1-rank digest:
# on 1 rank they are that deck's run, so a 1-rank run of their own repeated it.
# usage: mpi_digests.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

# name: sed script applied to the shipped deck (reduced size and length)
declare -A reduce=(
  [disk_impact_rigid]='s/radius: 0.037/radius: 0.012/; s/^(\s*)final_time:.*/\1steps: 150/'
  [fragmenting_cylinder]='s/height: 0.100/height: 0.024/; s/^(\s*)final_time:.*/\1steps: 40/; s/interval: 250/interval: 10/'
  [wave_in_bar]='s/^(\s*)final_time:.*/\1steps: 60/'
  [wave_variable_horizon]='s/^(\s*)final_time:.*/\1steps: 20/'
  [wave_pd_to_fe]='s/^(\s*)final_time:.*/\1steps: 20/'
  [taylor_impact]='s/^(\s*)final_time:.*/\1steps: 120/; s#\.\./meshes/#'"$OLDPWD"'/../meshes/#'
  # quasi-static with interface bonds failing: 8 x 8 points, horizon 2.015 h, 3 load steps, the
  # second past the debond onset (two damage passes)
  [single_fibre]='s/^(\s*)n: 16 /\1n: 8 /; s/^(\s*)m: 3.015 /\1m: 2.015 /; s/^(\s*)layers: 8 /\1layers: 6 /;
                  s/^(\s*)e2: 1.4e-3/\1e2: 8.0e-4/; s/^(\s*)strain: 3.0e-3/\1strain: 8.2e-4/;
                  s/^(\s*)fine: 36/\1fine: 1/; s/^(\s*)coarse: 8/\1coarse: 1/'
  # the other quasi-static decks of several materials in one body, as shipped (a few seconds)
  [fibre_rve]='' [laminate]='' [bimaterial_bar]=''
)
for name in "${!reduce[@]}"; do sed -E "${reduce[$name]}" "$OLDPWD/../inputs/$name.yaml" > "$name.yaml"; done
# variants of the reduced cylinder
sed -E 's/model: pmb/model: lps/' fragmenting_cylinder.yaml > cylinder_lps_metis.yaml
printf 'parallel:\n  decomposition: metis\n' >> cylinder_lps_metis.yaml
cp fragmenting_cylinder.yaml cylinder_rebalance.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> cylinder_rebalance.yaml
sed -E 's/^output:/output:\n  layout: spread/' wave_in_bar.yaml > wave_spread.yaml
# the foundation's indenter written as a rigid surface of the contact section (which keeps the
# deck's self-contact pair): the same run
sed -E 's/^indenters:/contact:\n  rigid_surfaces:/; /^contact:$/d' disk_impact_rigid.yaml > disk_rigid_surface.yaml
# FE <-> PD contact with friction and PD self-contact (tests/data/sphere_on_block.yaml); PD
# self-contact between every pair of neighbours of the cylinder (all points, radius above the
# spacing: active from the first step) with re-partitioning at every output step
sed -E 's#\.\./\.\./meshes/#'"$OLDPWD"'/../meshes/#' "$OLDPWD/data/sphere_on_block.yaml" > sphere_on_block.yaml
# the sphere deleting the elements it crushes (29 of 575): the contact's search, done ahead of the
# bodies' forces on 2 and 3 ranks, done again when a deletion in those forces changed the surface
sed -E 's/^(    initial_velocity: \["20")/    erosion: {min_volume_ratio: 0.995}\n\1/' sphere_on_block.yaml > sphere_on_block_erosion.yaml
grep -q "erosion:" sphere_on_block_erosion.yaml || { echo "sphere_on_block_erosion: the deck was not made"; fail=1; }
# the same sphere on block re-partitioned at every output step: the rest lengths of the bonds
# broken in the crushed zone travel with their rows (the self-contact of the fragments uses them)
cp sphere_on_block.yaml sphere_on_block_rebalance.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> sphere_on_block_rebalance.yaml
# (partitioned by METIS: RCB halves the symmetric cylinder exactly, and its work, contact
# candidates included, then never exceeds the mean)
cp fragmenting_cylinder.yaml cylinder_contact.yaml
printf 'contact:\n  pairs:\n    - {bodies: [cylinder, cylinder], radius: 0.0012, all_points: true, friction: 0.1}\nparallel:\n  rebalance_threshold: 1.0\n  decomposition: metis\n' >> cylinder_contact.yaml
cat > two_points.yaml <<'DECK'
materials: {m: {model: pmb, density: 1000, bulk_modulus: 1.0e9}}
bodies:
  - {name: pair, material: m, horizon: 0.0015, initial_velocity: ["x > 0 ? 1 : 0", "0", "0"],
     geometry: {shape: box, lo: [0, 0, 0], hi: [0.001, 0, 0], spacing: 0.001}}
time: {steps: 20}
DECK

# Willberg's double cantilever beam on a 1 mm lattice, opened at 1 m/s until bonds fail, with the
# critical energy calibrated to each bond's families (the moment tensors are a ghosted field,
# recomputed after each re-partition), re-partitioned at output steps
sed -E 's/^(\s*)dx: 0.5e-3/\1dx: 1.0e-3/; s/^(\s*)v: 0.05 /\1v: 1.0 /; s/final_time: 600e-6/final_time: 80e-6/;
        s/interval: 100/interval: 25/; s/^(\s*)law: critical_energy/\1law: critical_energy\n\1calibration: family/' \
  "$OLDPWD/../inputs/dcb.yaml" > dcb_family.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> dcb_family.yaml

# a peridynamic plate beside a finite-element bar hitting a wall (tests/data/mixed_pd_fe.yaml)
cp "$OLDPWD/data/mixed_pd_fe.yaml" mixed.yaml

cp mixed.yaml mixed_rebalance.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> mixed_rebalance.yaml

# PD materials with history, re-partitioned at output steps when imbalanced: the elastic-plastic tube
# (tests/data/expanding_tube_ep.yaml: yields and breaks bonds; its per-bond plastic extensions
# travel with the bond rows), correspondence J2 (the Taylor bar, reduced) and the modified
# Johnson-Cook bar whose damage correspondence breaks bonds (d1 = 0), pulled at 400 m/s instead of
# 40: bonds break from step 10, 19 % of them by step 60 (at 40 m/s from step 160, 12.5 % by step
# 200), across the re-partitions at steps 20 and 40
cp "$OLDPWD/data/expanding_tube_ep.yaml" tube_ep.yaml
sed -E 's/final_time: 80.0e-6, safety_factor: 0.8/steps: 60/; s/interval: 100, history_interval: 10/interval: 20, history_interval: 10/' \
  "$OLDPWD/data/taylor_correspondence.yaml" > taylor_corr.yaml
sed -E 's/final_time: 4.5e-5/steps: 60/; s/d1: 0.1,/d1: 0.0,/; s/interval: 100/interval: 20/; s/"(-?)40 \* min/"\1400 * min/' \
  "$OLDPWD/data/damage_bar.yaml" > damage_bar.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' | tee -a taylor_corr.yaml >> damage_bar.yaml
# several correspondence materials in one body (docs/theory/interfaces.md §3a): the reduced Taylor
# bar, its upper half a harder J2 (its own density, moduli and yield), with the stiffness hourglass
# control (each point's micromodulus from its own material), re-partitioned as taylor_corr
sed -E 's/^  copper: \{/  hard: {model: j2, density: 8960, youngs_modulus: 130.0e9, poissons_ratio: 0.34, yield_stress: 800.0e6}\n  copper: {/;
        s/hourglass: \{type: none\}/hourglass: {type: stiffness, coefficient: 0.05}\n    material_regions: [{material: hard, region: {shape: box, lo: [-1, -1, 0.016], hi: [1, 1, 1]}}]/' \
  taylor_corr.yaml > taylor_corr_regions.yaml

# a variable horizon (tests/data/variable_horizon_block.yaml): one-sided bonds and the partial-stress
# form, correspondence and LPS (whose partial stress is a ghosted field)
cp "$OLDPWD/data/variable_horizon_block.yaml" horizon_corr.yaml
sed -E 's/\{model: neo_hookean, density: 7800, youngs_modulus: 200.0e9, poissons_ratio: 0.0\}/{model: lps, density: 7800, bulk_modulus: 66.7e9, shear_modulus: 100.0e9}/; /hourglass:/d' \
  horizon_corr.yaml > horizon_lps.yaml
# the consistent form (its multipliers, solved on every rank from the gathered transition, are a
# ghosted point field that migrates), re-partitioned at output steps
sed -E 's/formulation: auto/formulation: consistent/' horizon_corr.yaml > horizon_consistent.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> horizon_consistent.yaml

# the PD -> transition -> overlap -> FE chain on one mesh (tests/data/coupled_bar.yaml), also
# re-partitioned at output steps (the PD bonds, broken ones included, travel with the node rows)
cp "$OLDPWD/data/coupled_bar.yaml" coupled_bar.yaml
cp coupled_bar.yaml coupled_rebalance.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> coupled_rebalance.yaml
# (the consistent form is the default: coupled_bar runs it; a separate variant would repeat it)
# two materials in one coupled body (inputs/bimaterial_wave.yaml, the deck of
# test_coupled_bimaterial_wave, cut to 20 us: the pulse reaches the interface in the peridynamic
# part), also re-partitioned at output steps (each node's material is found again from its
# elements, its mass must match the one that travelled with it)
sed -E 's/^(\s*)final_time:.*/\1final_time: 20.0e-6/; s/^(\s*)time_interval:.*/\1interval: 50/' \
  "$OLDPWD/../inputs/bimaterial_wave.yaml" > coupled_bimaterial.yaml
cp coupled_bimaterial.yaml coupled_bimaterial_rebalance.yaml
printf 'parallel:\n  rebalance_threshold: 1.0\n' >> coupled_bimaterial_rebalance.yaml

# two materials in one PD body (material_regions), pulled apart across their interface until the
# interface's own law breaks its bonds: PMB with the series micromodulus and the critical stretch,
# LPS (each end its own material's state) with the critical energy
cat > interface_pmb.yaml <<'DECK'
materials:
  soft: {model: pmb, density: 2000, bulk_modulus: 2.0e9}
  hard: {model: pmb, density: 2700, bulk_modulus: 8.0e9}
bodies:
  - name: bar
    material: soft
    material_regions: [{material: hard, region: {shape: box, lo: [0.0125, -1, -1], hi: [1, 1, 1]}}]
    interface: {damage: {law: critical_stretch, critical_stretch: 0.004}}
    damage: {law: critical_stretch, critical_stretch: 0.05}
    geometry: {shape: box, lo: [0, 0, 0], hi: [0.024, 0.006, 0.006], spacing: 0.001}
    horizon: 0.003015
boundary_conditions:
  - {name: left, region: {shape: box, lo: [-1, -1, -1], hi: [0.0025, 1, 1]}, velocity: ["-20", "0", "0"]}
  - {name: right, region: {shape: box, lo: [0.0215, -1, -1], hi: [1, 1, 1]}, velocity: ["20", "0", "0"]}
time: {steps: 80}
output: {interval: 40}
DECK
sed -E 's/model: pmb, density: 2000, bulk_modulus: 2.0e9/model: lps, density: 2000, bulk_modulus: 2.0e9, shear_modulus: 1.2e9/;
        s/model: pmb, density: 2700, bulk_modulus: 8.0e9/model: lps, density: 2700, bulk_modulus: 8.0e9, shear_modulus: 4.8e9/;
        s/law: critical_stretch, critical_stretch: 0.004/law: critical_energy, energy_release_rate: 5.0/' interface_pmb.yaml > interface_lps.yaml

not_on_2=" cylinder_rebalance mixed_rebalance sphere_on_block_rebalance coupled_rebalance coupled_bimaterial_rebalance horizon_consistent wave_spread disk_rigid_surface "
# (and the decks whose uninterrupted 2-rank runs mpi_restart.sh compares with their 1-rank runs,
# as the runs that write its checkpoints: the Taylor bar (the same 120 steps), the indenter (60 steps),
# the sphere on the block, the coupled bar and the coupled body of two materials)
not_on_2+="taylor_impact disk_impact_rigid sphere_on_block coupled_bar coupled_bimaterial "
# The variants that change only how the run is split, written or held - re-partitioning at every
# output step, spread output, the indenter written as a rigid surface - are their plain deck's run
# on 1 rank: their 3-rank digest is compared with the plain deck's 1-rank digest (re-partitioning,
# spreading or the rigid surface must change no bit), without a 1-rank run of their own.
declare -A plain_of=([cylinder_rebalance]=fragmenting_cylinder [mixed_rebalance]=mixed
                     [sphere_on_block_rebalance]=sphere_on_block [coupled_rebalance]=coupled_bar
                     [coupled_bimaterial_rebalance]=coupled_bimaterial
                     [wave_spread]=wave_in_bar [disk_rigid_surface]=disk_impact_rigid)
declare -A one_rank=()
rebalanced="cylinder_rebalance mixed_rebalance sphere_on_block_rebalance cylinder_contact tube_ep coupled_rebalance coupled_bimaterial_rebalance horizon_consistent dcb_family" # (the other two split evenly on 2 ranks)
decks="disk_impact_rigid disk_rigid_surface fragmenting_cylinder single_fibre fibre_rve laminate bimaterial_bar wave_in_bar wave_variable_horizon wave_pd_to_fe cylinder_lps_metis cylinder_rebalance wave_spread two_points taylor_impact mixed mixed_rebalance sphere_on_block sphere_on_block_rebalance sphere_on_block_erosion cylinder_contact tube_ep taylor_corr taylor_corr_regions damage_bar horizon_corr horizon_lps horizon_consistent coupled_bar coupled_rebalance coupled_bimaterial coupled_bimaterial_rebalance dcb_family interface_pmb interface_lps"
# The 1-rank runs first, two at a time (one process each: both cores busy; each deck writes files
# of its own name), their output and status kept for the loop below.
mkdir -p np1
for deck in $decks; do
  [ -n "${plain_of[$deck]:-}" ] && continue
  { run 1 "$exe" --output-dir np1 "$deck.yaml" > "np1/$deck.out" 2>&1; echo $? > "np1/$deck.status"; } &
  while [ "$(jobs -rp | wc -l)" -ge 2 ]; do wait -n; done
done
wait
for deck in $decks; do
  ref="" own=""
  ranks="1 2 3"
  [[ "$not_on_2" == *" $deck "* ]] && ranks="1 3"
  if [ -n "${plain_of[$deck]:-}" ]; then
    ranks=3 ref=${one_rank[${plain_of[$deck]}]:-}
    [ -n "$ref" ] || { echo "$deck: no 1-rank digest of ${plain_of[$deck]} to compare with"; fail=1; }
  fi
  for np in $ranks; do
    mkdir -p "np$np"
    if [ $np = 1 ]; then out=$(cat "np1/$deck.out"); st=$(cat "np1/$deck.status")
    else out=$(run $np "$exe" --output-dir "np$np" "$deck.yaml" 2>&1); st=$?; fi
    [ "$st" = 0 ] || { echo "$deck on $np ranks: exit $st: $out"; fail=1; continue; }
    d=$(digest_of "$out")
    [ -n "$d" ] || { echo "$deck on $np ranks: no digest"; fail=1; continue; }
    [ $np = 1 ] && one_rank[$deck]=$d && echo "$deck: $d" >> one_rank.txt # (mpi_restart.sh reads some)
    [ -n "$own" ] || own=$d
    [ -n "$ref" ] || ref=$d
    [ "$d" = "$ref" ] || { echo "$deck: digest on $np ranks $d differs from $ref on 1 rank${plain_of[$deck]:+ (${plain_of[$deck]})}"; fail=1; }
    if [[ " $rebalanced " == *" $deck "* ]] && [ $np -gt 1 ]; then
      echo "$out" | grep -q "re-partitioned" || { echo "$deck on $np ranks: no re-partition logged"; fail=1; }
    fi
  done
  echo "$deck: $own" >> digests.txt # (this deck's own digest: the 3-rank one for the variants)
done

# the eroding sphere deleted elements while in contact
grep -Eq "body 'ball': [1-9][0-9]* of [0-9]+ elements deleted" np1/sphere_on_block_erosion.out ||
  { echo "sphere_on_block_erosion: no element deleted"; fail=1; }
# the rigid surface of the contact section gives the foundation indenter's run, bit for bit
d1=$(grep '^disk_impact_rigid:' digests.txt | cut -d' ' -f2) d2=$(grep '^disk_rigid_surface:' digests.txt | cut -d' ' -f2)
[ -n "$d1" ] && [ "$d1" = "$d2" ] || { echo "disk_rigid_surface digest $d2 differs from disk_impact_rigid $d1"; fail=1; }
# the mixed deck's Exodus file holds a SPHERE block and a HEX8 block
ncdump -h np3/mixed.e | grep -q SPHERE && ncdump -h np3/mixed.e | grep -q HEX8 ||
  { echo "mixed.e: expected a SPHERE and a HEX8 block"; fail=1; }

# spread files (3 ranks) against the joined file (1 rank: wave_in_bar's run, the same deck joined)
$PY - np1/wave_in_bar.e np3/wave_spread.e.3.0 np3/wave_spread.e.3.1 np3/wave_spread.e.3.2 <<'PY' || fail=1
import sys, numpy as np, netCDF4
joined = netCDF4.Dataset(sys.argv[1])
names = [netCDF4.chartostring(n) for n in joined.variables["name_nod_var"][:]]
ux = names.index("displacement_x") + 1
ref = dict(zip(joined.variables["node_num_map"][:], joined.variables["vals_nod_var%d" % ux][-1, :]))
seen = {}
for path in sys.argv[2:]:
    d = netCDF4.Dataset(path)
    for gid, u in zip(d.variables["node_num_map"][:], d.variables["vals_nod_var%d" % ux][-1, :]):
        if gid in seen: sys.exit("point %d in two spread files" % gid)
        seen[gid] = u
if sorted(seen) != sorted(ref): sys.exit("spread files hold %d points, the joined file %d" % (len(seen), len(ref)))
bad = [g for g in ref if seen[g] != ref[g]]
if bad: sys.exit("%d points differ between spread and joined output, e.g. id %d" % (len(bad), bad[0]))
PY

exit $fail
