#!/usr/bin/env bash
# ParaView itself (pvbatch, Debian packages paraview and python3-paraview; not installed by
# scripts/setup.sh, hence label slow) opens the joined Exodus file of a 1-rank run and the
# spread set of a 3-rank run of the bar, and finds the same points with the same displacement;
# and the file of a mixed run (a PD plate and an FE bar) shows a SPHERE and a HEX8 block.
# usage: slow_paraview_output.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2
source common/mpi_env.sh
command -v pvbatch > /dev/null || { echo "pvbatch not found: apt-get install paraview python3-paraview"; exit 1; }
rm -rf "$scratch" && mkdir -p "$scratch/np1" "$scratch/np3"
sed -E 's/^(\s*)final_time:.*/\1steps: 60/; s/^output:/output:\n  layout: spread/' ../inputs/wave_in_bar.yaml > "$scratch/bar.yaml"
run 1 "$exe" --quiet --output-dir "$scratch/np1" "$scratch/bar.yaml" > /dev/null || exit 1
run 3 "$exe" --quiet --output-dir "$scratch/np3" "$scratch/bar.yaml" > /dev/null || exit 1
# pvbatch embeds its own Python: keep a user's Python environment out of it
env -i PATH=/usr/bin:/bin HOME="$scratch" pvbatch ../scripts/paraview_read.py "$scratch/np1/bar.e" "$scratch/np3/bar.e.3.0" || exit 1
cp data/mixed_pd_fe.yaml "$scratch/mixed.yaml"
run 2 "$exe" --quiet --output-dir "$scratch" "$scratch/mixed.yaml" > /dev/null || exit 1
env -i PATH=/usr/bin:/bin HOME="$scratch" pvbatch ../scripts/paraview_blocks.py "$scratch/mixed.e"
