#!/usr/bin/env bash
# ParaView itself (pvbatch, Debian packages paraview and python3-paraview; not installed by
# scripts/setup.sh, hence label slow) opens the joined Exodus file of a 1-rank run and the
# spread set of a 3-rank run of the bar, and finds the same points with the same displacement;
# and the file of a mixed run (a PD plate and an FE bar) shows a SPHERE and a HEX8 block.
# ParaView's default reader (OpenDataFile, the IOSS reader in ParaView 5.10 on), opening the
# spread set as a user does, loads every point: the list <file> by a bare name from its folder
# and by its full path, and a piece by its full path; the count wanted is the sum of the
# pieces' num_nodes read with netCDF4 (and equal to the joined 1-rank file's).
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
want=$("$PY" -c "import netCDF4, sys; n = [netCDF4.Dataset(f).dimensions['num_nodes'].size for f in sys.argv[1:]]; \
print(sum(n[1:]) if sum(n[1:]) == n[0] else -1)" "$scratch/np1/bar.e" "$scratch"/np3/bar.e.3.[0-9])
[ "$want" -gt 0 ] || { echo "the spread pieces do not hold the joined file's points"; exit 1; }
scripts=$(cd ../scripts && pwd)
(cd "$scratch/np3" && env -i PATH=/usr/bin:/bin HOME="$scratch" pvbatch "$scripts/paraview_points.py" "$want" \
  bar.e "$scratch/np3/bar.e" "$scratch/np3/bar.e.3.1") || exit 1
cp data/mixed_pd_fe.yaml "$scratch/mixed.yaml"
run 2 "$exe" --quiet --output-dir "$scratch" "$scratch/mixed.yaml" > /dev/null || exit 1
env -i PATH=/usr/bin:/bin HOME="$scratch" pvbatch ../scripts/paraview_blocks.py "$scratch/mixed.e"
