#!/usr/bin/env bash
# python/examples/campaign_disk.py, a virtual-allowables campaign of the glass disk struck by a
# rigid sphere on a 4 mm disk (150 steps), then tests/library/test_campaign.py on the same deck:
# zero scatter gives bit-identical replicas (one digest, CoV 0); a seed reproduces its replicas,
# whatever the number of replicas; a wider scatter of the critical stretch s00 gives a wider
# scatter of the damage fraction, which falls as s00 rises (Silling-Askari: a bond breaks past
# s0 = s00 - alpha s_min); a lattice perturbation with a seed of its own per replica.
# usage: python_campaign.sh PERIFEM SCRATCH TESTS_BINARY_DIR   (from the tests/ folder)
set -u
scratch=$2 build=$(cd "$3/.." && pwd) tests=$(pwd)
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
export PERIFEM_LIBRARY="$build/libperifem.so.0"
out=$("$PY" "$tests/../python/examples/campaign_disk.py" --deck "$tests/../inputs/disk_impact_rigid.yaml" \
      --replicas 6 --seed 3 --radius 0.004 --final-time 1.5e-5 --workers 2 --out example.csv 2>&1) \
  || { echo "$out"; echo "FAIL: campaign_disk.py"; exit 1; }
echo "$out"
PYTHONPATH="$tests/../python" "$PY" "$tests/library/test_campaign.py" "$tests/../inputs/disk_impact_rigid.yaml" example.csv
status=$?
[ $status -eq 0 ] || echo "FAIL: test_campaign.py exited $status"
exit $status
