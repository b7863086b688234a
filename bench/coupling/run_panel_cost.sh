#!/usr/bin/env bash
# The projectile-on-panel problem (inputs/panel_impact.yaml, 530 m/s) as shipped -- peridynamics
# within r < 16 mm of the impact axis, blended into the elements over 16-20 mm -- against the same
# panel all peridynamic (every node a correspondence point of horizon 2.01 mm, no element
# evaluated): time loop, steps, directed bonds, peak resident memory of one rank, where the
# sphere stops, and the energy balance. Both on 2 MPI ranks, one after the other, to FINAL_TIME
# (default the deck's 120 us: about 4 + 4.5 minutes on 2 cores), with the panel PANEL_LENGTH long
# along the extrusion (default the mesh's 80e-3 m; 240e-3: about 7 + 13 minutes).
# docs/examples/panel_impact.md quotes the results.
# usage: [PANEL_LENGTH=240e-3] bash bench/coupling/run_panel_cost.sh [PERIFEM]   (from the repository root)
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
perifem=$(realpath "${1:-$root/build/perifem}")
final=${FINAL_TIME:-120.0e-6}
work=$(mktemp -d /tmp/perifem_panel_cost.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
length=${PANEL_LENGTH:-80e-3}
sed -E "s/^W = 60e-3; L = 80e-3;/W = 60e-3; L = $length;/" "$root/meshes/panel_sandwich.geo" > "$work/panel_sandwich.geo"
grep -q "L = $length;" "$work/panel_sandwich.geo" || { echo "meshes/panel_sandwich.geo no longer sets W and L on one line: update this script" >&2; exit 1; }
sed -E "s#file: \.\./meshes/panel_sandwich.geo#file: $work/panel_sandwich.geo#; s#file: \.\./meshes/#file: $root/meshes/#; s/final_time: 120.0e-6/final_time: $final/; s/interval: 200/interval: 100000/" \
  "$root/inputs/panel_impact.yaml" > "$work/coupled.yaml"
sed -E 's/horizon: "2.01e-3 - 1e-3 \* \(sqrt\(x\^2 \+ y\^2\) > 0.0225\)"/horizon: 2.01e-3/; s/blending: "1 - min\(max\(\(sqrt\(x\^2 \+ y\^2\) - 0.016\) \/ 0.004, 0\), 1\)"/blending: "1"/' \
  "$work/coupled.yaml" > "$work/all_pd.yaml"
cmp -s "$work/coupled.yaml" "$work/all_pd.yaml" && { echo "the deck's horizon and blending lines changed: update this script" >&2; exit 1; }
cd "$work"
for deck in coupled all_pd; do # (one python per run: its children's peak memory is that run's)
"$py" - "$perifem" "$deck" <<'PY'
import h5py, numpy as np, re, resource, subprocess, sys
deck = sys.argv[2]
log = subprocess.run(["mpirun", "-np", "2", sys.argv[1], "--progress", "plain", deck + ".yaml"],
                     capture_output=True, text=True).stdout
rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
m = re.search(r"perifem: (\d+) steps of .* \(time loop ([0-9.]+) s\)", log)
if not m:
    sys.exit("%s: the run failed:\n%s" % (deck, log[-2000:]))
bonds = re.search(r"directed bonds (\d+)", log).group(1)
h = h5py.File(deck + ".h5", "r")
t, vz, zc = h["time"][:], h["sphere_velocity_z"][:], h["sphere_position_z"][:]
i = int(np.argmax(vz >= 0))
stop = ("the sphere stopped at %.1f us, centre at %.1f mm" % (t[i] * 1e6, zc[i] * 1e3)) if (vz >= 0).any() \
    else "the sphere still moving at %.1f m/s" % -vz[-1]
balance = re.search(r"energy balance error (\S+) J \(relative (\S+);", log)
print("%-8s time loop %7.1f s, %d steps, directed bonds %s, peak memory of one rank %.0f MB; %s; "
      "energy balance %s J (%s of the largest energy)"
      % (deck, float(m.group(2)), int(m.group(1)), bonds, rss / 1024, stop, balance.group(1), balance.group(2)))
PY
done
