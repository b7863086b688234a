#!/usr/bin/env bash
# Checkpoint/restart (HDF5, MPI-IO). The reference is the uninterrupted run's state digest.
#  1. Killed (SIGKILL of every rank) after a checkpoint, restarted on the same rank count
#     (1 and 2) and on another (2 -> 3, 3 -> 1): the final digest equals the reference.
#  2. SIGTERM to every rank (as a batch system sends it): the run writes a checkpoint, says so, exits 0 without a digest; the restart ends
#     with the reference digest.
#  3. Atomicity: checkpoints at every step, killed at random moments (often mid-write): the
#     checkpoint left behind always restarts to the reference digest.
#  4. A deck whose physics differs (density) is refused naming the part; an output-only change
#     (interval) is accepted (every restart here uses a deck with other output settings).
#  5. Finite elements (the Taylor bar, cut to 120 steps: J2 history, viscous hourglass,
#     adaptive step, rigid wall): a run with a checkpoint at step 80 on 2 ranks, restarted on
#     3 and on 1, ends with the uninterrupted 1-rank run's digest, and so does the 2-rank run
#     itself; the same with element erosion (elements deleted before and after the checkpoint).
#  6. PD materials with history, the coupled bar, two materials in a coupled body, contact, and a
#     rigid indenter (1 -> 1, 1 -> 3, 2 -> 2, 2 -> 1): restarts, and the 2-rank runs that write
#     their checkpoints, end with the uninterrupted 1-rank run's digest (these 2-rank runs are
#     the decks' 2-rank runs:
#     mpi_digests.sh runs taylor_impact, disk_impact_rigid, sphere_on_block, coupled_bar and
#     coupled_bimaterial on 1 and 3 ranks only). The uninterrupted 1-rank digests of the Taylor
#     bar, the tube, the Johnson-Cook bar, the sphere on the block, the coupled bar and the coupled
#     body of two materials are those of mpi_digests.sh's runs of the same decks when it left
#     them.
# usage: mpi_restart.sh PERIFEM SCRATCH [TESTS_BINARY_DIR]   (from the tests/ folder)
set -u
exe=$1 scratch=$2 bindir=${3:-} fail=0
source common/mpi_env.sh
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
tag=rs$$ # names this test's processes for pkill
sed -E 's/^(\s*)final_time:.*/\1steps: 240/' "$OLDPWD/../inputs/wave_in_bar.yaml" > $tag.yaml
printf 'restart:\n  file: ck.h5\n  interval: 40\n' >> $tag.yaml
sed -E 's/interval: 50/interval: 120/; s/interval: 40/interval: 0/' $tag.yaml > ${tag}_out.yaml
ref=$(digest_of "$(run 1 "$exe" --quiet $tag.yaml 2>&1)")
[ -n "$ref" ] || { echo "no reference digest"; exit 1; }

# (The waits for the first checkpoint allow 2 minutes: under a loaded ctest -j the start of the
# ranks can take tens of seconds, and a signal sent before it would test nothing.)
# kill every rank of this test's run once ck.h5 exists (after the first checkpoint)
kill_after_checkpoint() {
  local np=$1
  rm -f ck.h5 ck.h5.tmp
  run $np "$exe" --quiet $tag.yaml > /dev/null 2>&1 &
  local pid=$!
  for _ in $(seq 1 2400); do [ -f ck.h5 ] && break; sleep 0.05; done
  pkill -9 -f "perifem --quiet $tag.yaml"
  wait $pid 2>/dev/null
  [ -f ck.h5 ] || { echo "run on $np ranks: no checkpoint appeared"; fail=1; }
}
restart_digest() { digest_of "$(run $1 "$exe" --quiet --restart ck.h5 ${tag}_out.yaml 2>&1)"; }

for pair in "1 1" "2 2" "2 3" "3 1"; do
  set -- $pair
  kill_after_checkpoint $1
  d=$(restart_digest $2)
  [ "$d" = "$ref" ] || { echo "killed on $1 ranks, restarted on $2: digest '$d', uninterrupted $ref"; fail=1; }
done

# SIGTERM to every rank: checkpoint, message, clean exit, then restart. The signal goes as soon
# as the first checkpoint (step 40 of 240) exists, so that the run is surely still going.
rm -f ck.h5
out=$(run 2 "$exe" $tag.yaml 2>&1 & pid=$!
      for _ in $(seq 1 12000); do [ -f ck.h5 ] && break; sleep 0.01; done
      pkill -TERM -f "^$exe $tag.yaml"; wait $pid; echo "exit $?")
echo "$out" | grep -q "stopped at step .* continue with --restart" || { echo "SIGTERM: no stop message: $out"; fail=1; }
echo "$out" | grep -q "^exit 0" || { echo "SIGTERM: exit status not 0: $out"; fail=1; }
echo "$out" | grep -q "state digest" && { echo "SIGTERM: printed a digest for an unfinished run"; fail=1; }
d=$(restart_digest 2)
[ "$d" = "$ref" ] || { echo "after SIGTERM: digest '$d', uninterrupted $ref"; fail=1; }

# atomicity: a checkpoint every step, killed at random moments
sed -E 's/interval: 40/interval: 1/' $tag.yaml > ${tag}_every.yaml
for k in 1 2; do
  rm -f ck.h5 ck.h5.tmp
  run 2 "$exe" --quiet ${tag}_every.yaml > /dev/null 2>&1 &
  pid=$!
  for _ in $(seq 1 6000); do [ -f ck.h5 ] && break; sleep 0.02; done
  sleep "0.$((RANDOM % 9 + 1))"
  pkill -9 -f "perifem --quiet ${tag}_every.yaml"
  wait $pid 2>/dev/null
  d=$(restart_digest 1)
  [ "$d" = "$ref" ] || { echo "atomicity, kill $k: restart digest '$d', uninterrupted $ref"; fail=1; }
done

# a physics change is refused, naming the part
sed -E 's/density: 2200/density: 2300/' ${tag}_out.yaml > ${tag}_bad.yaml
out=$(run 1 "$exe" --restart ck.h5 ${tag}_bad.yaml 2>&1)
status=$?
[ $status -eq 2 ] || { echo "changed density: exit $status, expected 2"; fail=1; }
echo "$out" | grep -q "'materials' differs from the deck the checkpoint" || { echo "changed density: message: $out"; fail=1; }
# finite elements
# (the deck of mpi_digests' taylor_impact: 120 steps)
sed -E 's/^(\s*)final_time:.*/\1steps: 120/; s#\.\./meshes/#'"$OLDPWD"'/../meshes/#' "$OLDPWD/../inputs/taylor_impact.yaml" > fe$tag.yaml
printf 'restart:\n  file: ckfe.h5\n  interval: 80\n' >> fe$tag.yaml
# saved_digest NAME SOURCE: the 1-rank digest mpi_digests.sh left for its deck NAME in this
# ctest run (TESTS_BINARY_DIR/work_mpi_digests/one_rank.txt; ctest runs mpi_digests first:
# DEPENDS in tests/CMakeLists.txt), when that file is newer than this perifem and than SOURCE,
# the deck both scripts copy unchanged or cut the same way (this script adds only its restart
# section, which changes no bit: the 2-rank runs that write checkpoints end with the uninterrupted
# run's digest; mpi_digests' output intervals and re-partitioning change none either: its 3-rank
# runs end with the 1-rank digest)
saved_digest() {
  local saved=$bindir/work_mpi_digests/one_rank.txt
  [ -n "$bindir" ] && [ -s "$saved" ] && [ "$saved" -nt "$exe" ] && [ "$saved" -nt "$2" ] &&
    sed -n "s/^$1: //p" "$saved" | head -1
}
# check_restart DECK CHECKPOINT LABEL [NAME SOURCE]: the uninterrupted 1-rank digest (mpi_digests'
# run of the same deck, NAME, when saved_digest has it; else a run here); the 2-rank run that
# writes the checkpoints must end with it, and so must its restarts on 3 and on 1 ranks
check_restart() {
  local ref="" d out
  [ $# -ge 5 ] && ref=$(saved_digest "$4" "$5")
  [ -n "$ref" ] && echo "$3: the uninterrupted 1-rank digest of mpi_digests' $4: $ref" ||
    ref=$(digest_of "$(run 1 "$exe" --quiet $1 2>&1)")
  rm -f $2
  out=$(run 2 "$exe" --quiet $1 2>&1) || { echo "$3: run with checkpoints failed: $out"; fail=1; }
  d=$(digest_of "$out")
  [ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "$3: on 2 ranks: digest '$d', on 1 rank '$ref'"; fail=1; }
  for np in 3 1; do
    d=$(digest_of "$(run $np "$exe" --quiet --restart $2 $1 2>&1)")
    [ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "$3: restarted on $np ranks: digest '$d', uninterrupted '$ref'"; fail=1; }
  done
}
check_restart fe$tag.yaml ckfe.h5 FE taylor_impact "$OLDPWD/../inputs/taylor_impact.yaml"
# the same with element erosion at an eqps of 0.3 (72 of the 10,206 elements deleted by step 40,
# 430 by the checkpoint at step 80, 515 by step 120): the deleted elements travel with the
# checkpoint
sed -E 's/^(\s*)element: reduced/\1element: reduced\n\1erosion: {plastic_strain: 0.3}/; s/ckfe.h5/ckfer.h5/' fe$tag.yaml > fer$tag.yaml
grep -q "erosion:" fer$tag.yaml || { echo "FE erosion: the deck was not made"; fail=1; }
check_restart fer$tag.yaml ckfer.h5 "FE erosion"
# PD materials with history: the elastic-plastic tube (tests/data/expanding_tube_ep.yaml,
# yielding from the first steps; per-bond plastic extensions in /bonds/state) and the modified
# Johnson-Cook bar (tests/data/damage_bar.yaml; stress, history and the last step's damage
# record as point fields; pulled at 400 m/s instead of 40, so that bonds break from step 10, in
# steps 10-30 before the checkpoint at step 40 and in steps 42 and 51 after it: 60 steps instead
# of 360 at 40 m/s, whose bonds broke from step 160): a 2-rank run with checkpoints, restarted on
# 3 and on 1, ends with the uninterrupted 1-rank run's digest
cp "$OLDPWD/data/expanding_tube_ep.yaml" ep$tag.yaml
sed -E 's/final_time: 4.5e-5/steps: 60/; s/d1: 0.1,/d1: 0.0,/; s/"(-?)40 \* min/"\1400 * min/' "$OLDPWD/data/damage_bar.yaml" > jc$tag.yaml
grep -q '"400 \* min' jc$tag.yaml || { echo "jc: the deck was not made"; fail=1; }
# and the coupled PD/FE bar (tests/data/coupled_bar.yaml: PD bonds with damage on FE nodes, J2
# elements, blending), checkpointed at step 50 of 60, in the consistent form (the default), whose
# multipliers, solved at t = 0 from the gathered transition, come back from the checkpoint instead
# of being solved again
# (cc: the same in the corrected form, whose ghost-correction vectors, set at t = 0 from the
# neighbours' shape tensors, must survive the restart unchanged after bonds broke nearby; a
# statics form, which an explicit run takes only with allow_in_dynamics)
cp "$OLDPWD/data/coupled_bar.yaml" cb$tag.yaml
sed -E 's/^(\s*)damage: \{law/\1formulation: corrected\n\1allow_in_dynamics: true\n\1damage: {law/' cb$tag.yaml > cc$tag.yaml
# and contact with an FE body that is not the first body (tests/data/sphere_on_block.yaml: PD
# block, then the FE ball, FE <-> PD and PD self-contact pairs; its node ids start after the
# block's, which the restart must number the same way), checkpointed at step 100 of 150
sed -E 's#\.\./\.\./meshes/#'"$OLDPWD"'/../meshes/#' "$OLDPWD/data/sphere_on_block.yaml" > sb$tag.yaml
# and two materials in one coupled body (inputs/bimaterial_wave.yaml cut to 20 us as
# mpi_digests cuts it: each node's material, found from its elements at set-up, must give the
# masses the checkpoint holds), checkpointed at step 200
sed -E 's/^(\s*)final_time:.*/\1final_time: 20.0e-6/; s/^(\s*)time_interval:.*/\1interval: 50/' \
  "$OLDPWD/../inputs/bimaterial_wave.yaml" > bm$tag.yaml
# (ep, jc, sb, cb and bm are mpi_digests' tube_ep, damage_bar, sphere_on_block, coupled_bar and coupled_bimaterial with a
# restart section; its damage_bar writes output every 20 steps and is re-partitioned there)
declare -A twin=([ep]="tube_ep $OLDPWD/data/expanding_tube_ep.yaml" [jc]="damage_bar $OLDPWD/data/damage_bar.yaml"
                 [sb]="sphere_on_block $OLDPWD/data/sphere_on_block.yaml" [cb]="coupled_bar $OLDPWD/data/coupled_bar.yaml"
                 [bm]="coupled_bimaterial $OLDPWD/../inputs/bimaterial_wave.yaml")
for m in ep jc cb cc sb bm; do
  printf 'restart:\n  file: ck%s.h5\n  interval: %d\n' $m $(case $m in ep) echo 60 ;; jc) echo 40 ;; sb) echo 100 ;; bm) echo 200 ;; *) echo 25 ;; esac) >> $m$tag.yaml
  check_restart $m$tag.yaml ck$m.h5 $m ${twin[$m]:-}
done
# A rigid indenter (inputs/disk_impact_rigid.yaml, reduced: radius 12 mm, 60 steps, checkpoint at
# step 50): its position and reaction travel in the checkpoint's scalars, which must know the
# indenter when the restart reads them. The uninterrupted 1-rank run writes the checkpoint
# restarted on 1 and 3; a 2-rank run (ending with the same digest) writes the one restarted on 2
# and 1: each restart ends with the uninterrupted 1-rank run's digest.
sed -E 's/radius: 0.037/radius: 0.012/; s/^(\s*)final_time:.*/\1steps: 60/' "$OLDPWD/../inputs/disk_impact_rigid.yaml" > ri$tag.yaml
printf 'restart:\n  file: ckri.h5\n  interval: 25\n' >> ri$tag.yaml
for np in 1 2; do
  rm -f ckri.h5
  out=$(run $np "$exe" --quiet ri$tag.yaml 2>&1) || { echo "indenter: the run with checkpoints on $np ranks failed: $out"; fail=1; }
  d=$(digest_of "$out")
  [ $np -eq 1 ] && ref=$d
  [ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "indenter: on $np ranks: digest '$d', on 1 rank '$ref'"; fail=1; }
  mv ckri.h5 ckri$np.h5 2>/dev/null || { echo "indenter: no checkpoint written on $np ranks"; fail=1; }
done
for pair in "1 1" "1 3" "2 2" "2 1"; do
  set -- $pair
  d=$(digest_of "$(run $2 "$exe" --quiet --restart ckri$1.h5 ri$tag.yaml 2>&1)")
  [ -n "$ref" ] && [ "$d" = "$ref" ] || { echo "indenter: written on $1 ranks, restarted on $2: digest '$d', uninterrupted '$ref'"; fail=1; }
done
exit $fail
