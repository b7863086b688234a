#!/usr/bin/env python3
"""The halo of a peridynamic body on a simple cubic lattice, counted from geometry alone.

A rank's ghosts are the points of other ranks within the horizon of one of its own points
(docs/parallel.md, section 1). For a box of lattice points split into boxes, a point outside a
rank's box at lattice offsets (dx, dy, dz) from it (0 inside the box's range on that axis) is a
ghost when dx^2 + dy^2 + dz^2 <= m^2, m the horizon in spacings. The per-step traffic of a rank
is then, for each exchange of the step, its ghost count times the exchanged doubles, in one
message per rank that owns some of its ghosts.

  halo_model.py split NX NY NZ M P      ghosts and neighbour ranks of each of P ranks of an
                                        NX x NY x NZ box, cut as recursive coordinate bisection
                                        with uniform weights cuts it (longest side first, parts
                                        in proportion to the ranks on each side)
  halo_model.py weak N M                a rank's ghosts and messages when it is a cube of N
                                        points inside a large body (every face, edge and corner
                                        shared)
"""
import math
import sys


def bisect(lo, hi, p):
    """Recursive coordinate bisection of the lattice box [lo, hi) into p boxes."""
    if p == 1:
        return [(lo, hi)]
    size = [hi[k] - lo[k] for k in range(3)]
    axis = max(range(3), key=lambda k: (size[k], -k))
    left = p // 2
    cut = lo[axis] + round(size[axis] * left / p)
    hi_left, lo_right = list(hi), list(lo)
    hi_left[axis] = lo_right[axis] = cut
    return bisect(lo, tuple(hi_left), left) + bisect(tuple(lo_right), hi, p - left)


def axis_offset(x, lo, hi):
    """Lattice distance along one axis from x to the range [lo, hi)."""
    return lo - x if x < lo else (x - hi + 1 if x >= hi else 0)


def halo(boxes, whole, m):
    """Per box: (points, ghosts, neighbour ranks) for a horizon of m spacings."""
    r = int(math.floor(m))
    owner = {}
    rows = []
    for q, (lo, hi) in enumerate(boxes):
        for x in range(lo[0], hi[0]):
            for y in range(lo[1], hi[1]):
                for z in range(lo[2], hi[2]):
                    owner[(x, y, z)] = q
    for q, (lo, hi) in enumerate(boxes):
        ghosts, ranks = 0, set()
        for x in range(max(whole[0][0], lo[0] - r), min(whole[1][0], hi[0] + r)):
            dx = axis_offset(x, lo[0], hi[0])
            for y in range(max(whole[0][1], lo[1] - r), min(whole[1][1], hi[1] + r)):
                dy = axis_offset(y, lo[1], hi[1])
                for z in range(max(whole[0][2], lo[2] - r), min(whole[1][2], hi[2] + r)):
                    dz = axis_offset(z, lo[2], hi[2])
                    d2 = dx * dx + dy * dy + dz * dz
                    if 0 < d2 <= m * m:
                        ghosts += 1
                        ranks.add(owner[(x, y, z)])
        n = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
        rows.append((n, ghosts, len(ranks)))
    return rows


def weak(n, m):
    """A cube of n points with neighbours on every side: its ghosts and messages."""
    side = round(n ** (1.0 / 3.0))
    r = int(math.floor(m))
    ghosts, messages = 0, 0
    offsets = range(0, r + 1)
    for dx in offsets:
        for dy in offsets:
            for dz in offsets:
                d2 = dx * dx + dy * dy + dz * dz
                if d2 == 0 or d2 > m * m:
                    continue
                count = 1
                for d in (dx, dy, dz):
                    count *= side if d == 0 else 2
                ghosts += count
    for sx in (-1, 0, 1):
        for sy in (-1, 0, 1):
            for sz in (-1, 0, 1):
                d2 = sx * sx + sy * sy + sz * sz
                messages += 1 if 0 < d2 <= m * m else 0
    return side ** 3, ghosts, messages


def main(argv):
    if len(argv) == 7 and argv[1] == "split":
        nx, ny, nz, m, p = int(argv[2]), int(argv[3]), int(argv[4]), float(argv[5]), int(argv[6])
        whole = ((0, 0, 0), (nx, ny, nz))
        for q, (n, ghosts, ranks) in enumerate(halo(bisect(*whole, p), whole, m)):
            print(f"rank {q} points {n} ghosts {ghosts} neighbours {ranks}")
        return 0
    if len(argv) == 4 and argv[1] == "weak":
        n, ghosts, messages = weak(int(argv[2]), float(argv[3]))
        print(f"points {n} ghosts {ghosts} neighbours {messages}")
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
