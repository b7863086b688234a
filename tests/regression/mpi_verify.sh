#!/usr/bin/env bash
# Every verification test passes on 1 and 3 ranks, and the state digests it prints (with
# PF_TEST_DIGESTS set) are the same on both rank counts. test_taylor (40 s per run) is left
# to 1 rank here: its deck, cut to 120 steps, runs on 1, 2 and 3 ranks in mpi_digests.sh; so are
# test_taylor_correspondence, test_damage_correspondence and test_correspondence_compression
# (20-30 s each), whose materials run on 1, 2 and 3 ranks there (taylor_corr, damage_bar); and
# test_kalthoff_winkler (label slow, minutes), a PMB deck like those of mpi_digests; and
# test_coupling_wave (label slow), whose coupled deck runs there as coupled_bar; and
# test_partial_stress (a dozen bars), whose forms run there as horizon_corr and horizon_lps; and
# test_hertz (80 s on one rank, the longest), whose parts - an FE sphere on a PMB block through
# FE <-> PD contact - run on 1, 2 and 3 ranks there as sphere_on_block (kept under the default
# run's 10 minutes on 2 cores); and test_coupling_chain (a pulse over 200 us), whose forms - the
# consistent transition and the energy overlap with its corrected kinks, the defaults - run on 1,
# 2 and 3 ranks there as wave_pd_to_fe and coupled_bar; and test_fibre_rve (it runs CalculiX,
# and four quasi-static cells), whose bodies - LPS and hexahedra with material_regions, solved
# by newton_krylov - run on 1 and 3 ranks here as test_bimaterial_static and on 1, 2 and 3 ranks
# in fe_material_regions.sh; and test_coupling_patch (16 s on 3 ranks), whose coupled bodies -
# the consistent transition, the energy overlap and the blending - run on 1, 2 and 3 ranks in
# mpi_digests.sh as coupled_bar and wave_pd_to_fe (the partial stress as horizon_corr); and
# test_critical_energy (25 s of separations), whose laws run on 1, 2 and 3 ranks there - the
# critical energy with family calibration as dcb_family, the critical stretch in the cylinders,
# an interface's own law between two PD materials as interface_pmb and interface_lps; and
# test_laminate (fourteen quasi-static runs; about 2 minutes on 3 ranks of 2 cores, 24 s for its
# FE runs alone): hexahedra with material_regions run on 1, 2 and 3 ranks in
# fe_material_regions.sh, orthotropic hexahedra under newton_krylov in static_orthotropic.sh; its
# own fourteen digests on 3 ranks equal the 1-rank ones, as run by hand (docs/theory/laminate.md); and
# test_bimaterial_static_correspondence (four quasi-static bars), whose several correspondence
# materials in one body run on 1, 2 and 3 ranks there as taylor_corr_regions; and
# test_single_fibre (it runs CalculiX, and reads the interface bonds' stretches from one
# rank's points): its deck, inputs/single_fibre.yaml - PMB with material_regions under
# newton_krylov, interface bonds failing in damage passes - runs reduced on 1, 2 and 3 ranks in
# mpi_digests.sh as single_fibre, and LPS with material_regions on 1 and 3 ranks here as
# test_bimaterial_static.
# The tests this script runs do so on 1 and 3 ranks, not on 2: 3 ranks already split every
# body the 2-rank run splits, and the same physics runs on 1, 2 and 3 ranks with equal digests in
# mpi_digests.sh (PD contact: cylinder_contact, sphere_on_block; FE: taylor_impact, mixed,
# coupled_bar; elastic_plastic: tube_ep; PMB waves: wave_in_bar, the deck of test_wave) and
# coupled_contact.sh (FE surface <-> FE nodes). A multi-rank run of these many-step tests costs
# far more than its 1-rank run (test_contact_pair: 0.8 s of CPU on 1 rank, 32 s on 2 ranks of a
# loaded machine, the ranks waiting for each other at every step).
# The 1-rank digests come from the test's own ctest run when it left them in
# TESTS_BINARY_DIR/digests/<test>.txt after its binary was built (PF_TEST_DIGEST_FILE; ctest runs
# those tests before this one); else this script runs the test on 1 rank too.
# usage: mpi_verify.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
bindir=$3 fail=0
source common/mpi_env.sh
export PF_TEST_DIGESTS=1
for src in verification/test_*.c; do
  name=$(basename "$src" .c)
  grep -qx "$name" common/mpi_verify_skip.txt && continue # (the tests named above; CMake reads it too)
  ref="" ranks="1 3" saved=$bindir/digests/$name.txt
  # the 1-rank digests of this build's own run of the test (ctest runs it before this script)
  if [ -s "$saved" ] && [ "$saved" -nt "$bindir/$name" ]; then ref=$(grep "^state digest" "$saved") ranks=${ranks#1 }; fi
  for np in $ranks; do
    out=$(run $np "$bindir/$name" 2>&1) || { echo "$name on $np ranks failed: $out"; fail=1; continue; }
    d=$(echo "$out" | grep "^state digest")
    [ -n "$d" ] || { echo "$name on $np ranks printed no digest"; fail=1; continue; }
    [ -n "$ref" ] || ref=$d
    [ "$d" = "$ref" ] || { echo "$name: digests on $np ranks"; echo "$d"; echo "differ from 1 rank"; echo "$ref"; fail=1; }
  done
done
exit $fail
