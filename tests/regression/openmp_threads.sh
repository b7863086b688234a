#!/usr/bin/env bash
# OpenMP threads give the bits of one thread (issue 9: "results still bitwise identical to 1
# thread"): decks exercising every threaded loop -- the PMB and LPS bond loops with bonds
# breaking, the elastic-plastic passes, the PD short-range contact, FE <-> PD contact with its node shares, the integrator,
# the correspondence passes with damage, the hexahedra and a coupled body --
# run without threads (the reference: perifem_plain beside a threaded perifem, or perifem itself
# when built with PERIFEM_OPENMP=OFF) and with 2 and 3 threads (perifem, or perifem_omp beside
# an unthreaded one), and 2 MPI ranks of 2 threads each: every run must end with the same state
# digest. (The 2 x 2 hybrid runs skip the plain cylinder, whose PMB bond loop runs hybrid in
# cylinder_contact, and the elastic-plastic cylinder, whose passes run on 2 and 3 threads here
# and on 2 and 3 ranks in mpi_digests.sh as tube_ep.)
# Waiting threads sleep (OMP_WAIT_POLICY=passive) instead of spinning: libgomp's spin on 2
# threads per process took 3-5 times the CPU of the plain run from the other tests of ctest -j2
# (sphere_on_block: 4.0 s of CPU spinning, 1.0 s passive, 0.7 s without threads; same digest).
# usage: openmp_threads.sh PERIFEM SCRATCH   (from the tests/ folder); exit 77 (skipped) when
# no threaded build exists.
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
dir=$(cd "$(dirname "$exe")" && pwd)
threaded() { "$1" --version | grep -q "^  OpenMP"; }
if threaded "$exe"; then
  omp=$exe plain=$dir/perifem_plain
  [ -x "$plain" ] || { echo "no perifem_plain (PERIFEM_OPENMP_CHECK=OFF): the threads are checked against 1 thread only"; plain=$exe; }
elif [ -x "$dir/perifem_omp" ]; then plain=$exe omp=$dir/perifem_omp
else echo "no threaded build (perifem_omp, or PERIFEM_OPENMP=ON with a compiler that has OpenMP): skipped"; exit 77
fi
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

# the reduced fragmenting cylinder (PMB, critical stretch), its LPS variant, and PD self-contact
# between every pair of neighbours (active from the first step); the FE sphere on a PMB block
# (FE <-> PD surface contact with friction, and the block's self-contact)
sed -E 's/height: 0.100/height: 0.024/; s/^(\s*)final_time:.*/\1steps: 40/; s/interval: 250/interval: 10/' \
  "$OLDPWD/../inputs/fragmenting_cylinder.yaml" > cylinder.yaml
sed -E 's/model: pmb/model: lps/' cylinder.yaml > cylinder_lps.yaml
# the same cylinder in the elastic-plastic solid (pd/material_elastic_plastic.c: both passes
# threaded, the failed bonds' energy booked after them in point order); it yields and breaks bonds
sed -E 's/model: pmb/model: elastic_plastic\n    yield_stress: 5.0e8\n    hardening_modulus: 1.0e9/' cylinder.yaml > cylinder_ep.yaml
cp cylinder.yaml cylinder_contact.yaml
printf 'contact:\n  pairs:\n    - {bodies: [cylinder, cylinder], radius: 0.0012, all_points: true, friction: 0.1}\n' >> cylinder_contact.yaml
sed -E 's#\.\./\.\./meshes/#'"$OLDPWD"'/../meshes/#' "$OLDPWD/data/sphere_on_block.yaml" > sphere_on_block.yaml
# the modified Johnson-Cook bar whose damage correspondence breaks bonds (the correspondence
# passes and the model batched over blocks of points), pulled at 400 m/s instead of 40 so that
# 60 steps break 19 % of its bonds; the FE sphere on an FE block with coupled peridynamics (the
# hexahedra's chunks, the node gather, the blended forces) and contact, 60 steps
sed -E 's/final_time: 4.5e-5/steps: 60/; s/d1: 0.1,/d1: 0.0,/; s/interval: 100/interval: 20/; s/"(-?)40 \* min/"\1400 * min/' \
  "$OLDPWD/data/damage_bar.yaml" > damage_bar.yaml
sed -E 's#\.\./\.\./meshes/#'"$OLDPWD"'/../meshes/#; s/steps: 150/steps: 60/' "$OLDPWD/data/sphere_on_coupled_block.yaml" > coupled_block.yaml

export OMP_WAIT_POLICY=passive
for deck in cylinder cylinder_lps cylinder_ep cylinder_contact sphere_on_block damage_bar coupled_block; do
  out=$(OMP_NUM_THREADS=1 "$plain" --output-dir plain "$deck.yaml" 2>&1) || { echo "$deck: exit $?: $out"; fail=1; continue; }
  ref=$(digest_of "$out")
  [ -n "$ref" ] || { echo "$deck: no digest"; fail=1; continue; }
  for t in 2 3; do  # (1 thread: every other test runs the threaded build on one thread)
    out=$(OMP_NUM_THREADS=$t "$omp" --output-dir "t$t" "$deck.yaml" 2>&1) || { echo "$deck, $t threads: exit $?: $out"; fail=1; continue; }
    d=$(digest_of "$out")
    [ "$d" = "$ref" ] || { echo "$deck: digest on $t threads '$d' differs from '$ref' without threads"; fail=1; }
    # the run must have used them (gmsh's initialisation once set OpenMP's count back to 1)
    grep -q "threads per rank $t\b" <<<"$out" || { echo "$deck: asked for $t threads, the summary says: $(grep -o 'threads per rank [0-9]*' <<<"$out")"; fail=1; }
  done
  case $deck in cylinder | cylinder_ep) echo "$deck: $ref"; continue ;; esac # (hybrid: above)
  out=$(OMP_NUM_THREADS=2 run 2 -x OMP_NUM_THREADS -x OMP_WAIT_POLICY "$omp" --output-dir hybrid "$deck.yaml" 2>&1) ||
    { echo "$deck, 2 ranks x 2 threads: exit $?: $out"; fail=1; continue; }
  d=$(digest_of "$out")
  [ "$d" = "$ref" ] || { echo "$deck: digest on 2 ranks x 2 threads '$d' differs from '$ref'"; fail=1; }
  echo "$deck: $ref"
done
exit $fail
