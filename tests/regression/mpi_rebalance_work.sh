#!/usr/bin/env bash
# Re-partitioning weighs what the ranks do (docs/parallel.md §5): a point's work is its bonds + 1
# plus its contact candidates, the partition balances those weights, and the check that decides
# to re-partition measures the same ones.
#  1. Two PMB blocks of 10 x 6 x 6 points (spacing h = 1 mm, horizon 1.5 h) side by side along x,
#     3 h apart, moving together at 10 m/s; the left one in contact with itself between every
#     pair of points (all_points, r_c = 0.9 h, skin 0.2 h: the six lattice neighbours within
#     1.1 h are its candidates, none closer than r_c, so no force acts). RCB gives each block a
#     rank of its own on 2 ranks; at the first output step the left rank holds the contact's
#     work too. The work imbalance logged must be the one counted here on the lattice,
#     independently of the code: (N + B + C) / ((2 N + 2 B + C) / 2), N points, B bonds
#     (offsets within 1.5 h) and C candidates (offsets within 1.1 h) of a block, to 5e-4 (the
#     log's 3 decimals; the bodies' forces and the contact are two phases, and here the left
#     rank is the largest in both, so the sum of the phases' maxima is this count's maximum);
#     the new partition must balance both phases by the same weights (at most 1.02: a cut
#     across both blocks; a cut that balances only their sum, between the blocks, logs 1.216
#     and re-partitions at every output step); and the next output steps, whose work is the
#     same, must not re-partition again. With RCB and with METIS; the state digest equals the
#     run without re-partitioning.
#  2. tests/data/mixed_pd_fe.yaml (a PD plate and an FE bar, nothing breaks) with a threshold of
#     1.02 on 2 and 3 ranks: at most one re-partition, and every logged "now" at most 1.02. When
#     the check counted an FE node as 1 and the partition weighed it by its row, the partition
#     could not reach the check's balance and ran again at every output step ("work imbalance
#     1.048 > 1.020; now 1.048" at steps 20, 40, 60 and 80 on 2 ranks; the expanding tube: 38
#     re-partitions in 828 steps, "now 1.098" after each).
# usage: mpi_rebalance_work.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
source common/mpi_env.sh
here=$(pwd)
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
cat > blocks.yaml <<'DECK'
materials: {glass: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}
bodies:
  - {name: left, material: glass, horizon: 0.0015, initial_velocity: ["10", "0", "0"],
     geometry: {shape: box, lo: [0, 0, 0], hi: [0.009, 0.005, 0.005], spacing: 0.001}}
  - {name: right, material: glass, horizon: 0.0015, initial_velocity: ["10", "0", "0"],
     geometry: {shape: box, lo: [0.012, 0, 0], hi: [0.021, 0.005, 0.005], spacing: 0.001}}
contact:
  skin: 0.0002
  pairs:
    - {bodies: [left, left], radius: 0.0009, all_points: true}
time: {steps: 60}
output: {interval: 20}
parallel: {rebalance_threshold: 1.05}
DECK
expected=$($PY - <<'PY'
import itertools
pts = [(i, j, k) for i in range(10) for j in range(6) for k in range(6)]
inside = set(pts)
def count(r2):
    return sum(1 for p in pts for o in itertools.product((-1, 0, 1), repeat=3)
               if 0 < o[0]**2 + o[1]**2 + o[2]**2 <= r2 and (p[0] + o[0], p[1] + o[1], p[2] + o[2]) in inside)
n, b, c = len(pts), count(1.5**2), count(1.1**2)
print('%.6f %d %d %d' % ((n + b + c) / ((2 * n + 2 * b + c) / 2), n, b, c))
PY
)
read -r want n b c <<< "$expected"
echo "lattice count: N = $n points, B = $b bonds, C = $c candidates a block; expected imbalance $want"
ref=$("$exe" --output-dir np1 --set parallel.rebalance_threshold=0 blocks.yaml 2>&1) || { echo "blocks on 1 rank failed: $ref"; fail=1; }
ref=$(digest_of "$ref")
for method in rcb metis; do
  out=$(run 2 "$exe" --output-dir $method --set parallel.decomposition=$method blocks.yaml 2>&1) ||
    { echo "blocks ($method) on 2 ranks failed: $out"; fail=1; continue; }
  lines=$(echo "$out" | grep "re-partitioned")
  echo "$method: $lines"
  [ "$(echo "$lines" | grep -c .)" = 1 ] || { echo "FAIL: $method: expected one re-partition, at step 20"; fail=1; }
  read -r got now <<< "$(echo "$lines" | sed -n 's/^step 20: re-partitioned (work imbalance \([0-9.]*\) > 1.050); now \([0-9.]*\)$/\1 \2/p')"
  [ -n "${got:-}" ] || { echo "FAIL: $method: no re-partition at step 20"; fail=1; continue; }
  $PY -c "import sys; sys.exit(not (abs($got - $want) <= 5e-4 and $now <= 1.02))" ||
    { echo "FAIL: $method: imbalance $got (expected $want), now $now (at most 1.02)"; fail=1; }
  d=$(digest_of "$out")
  [ "$d" = "$ref" ] || { echo "FAIL: $method: digest $d, without re-partitioning $ref"; fail=1; }
done
for np in 2 3; do
  out=$(run $np "$exe" --output-dir mixed$np --set parallel.rebalance_threshold=1.02 "$here/data/mixed_pd_fe.yaml" 2>&1) ||
    { echo "mixed_pd_fe on $np ranks failed: $out"; fail=1; continue; }
  count=$(echo "$out" | grep -c "re-partitioned")
  echo "mixed_pd_fe, $np ranks: $count re-partitions"
  [ "$count" -le 1 ] || { echo "FAIL: mixed_pd_fe on $np ranks: $count re-partitions (the work does not change)"; fail=1; }
  for now in $(echo "$out" | sed -n 's/.*re-partitioned.*; now \([0-9.]*\)$/\1/p'); do
    $PY -c "import sys; sys.exit(not $now <= 1.02)" || { echo "FAIL: mixed_pd_fe on $np ranks: now $now > 1.02"; fail=1; }
  done
done
[ $fail = 0 ] && echo "PASS"
exit $fail
