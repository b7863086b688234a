"""What the critical-energy law can dissipate on a cubic lattice, as a share of G0.

    /usr/bin/python3 scripts/dcb_lattice_share.py [--partial-volumes] [--calibration family]
        [--layers 6 9 12 0] [--horizons 2.01 3.015 4.01 5.01]

The law fails a bond once it holds w_c = 4 G0 / (pi delta^4) per V_i V_j, whatever its length
(docs/theory/bond_failure.md section 3); G0 = pi w_c delta^4 / 4 is the continuum's count of the
bonds that cross a unit area of a plane, each bond of length xi in the direction n counted
|xi . n| / A times (section 4.1). On the cell-centred lattice of spacing dx with the crack plane
halfway between two layers, an offset (i, j, k) with j > 0 crosses the plane j times per dx^2,
so the broken bonds per unit area, over the continuum's, are

    S = sum_{offsets, j > 0} j beta(i, j, k) n_z(k) / (pi m^4 / 4),    m = delta / dx,

beta = 1 within the horizon (or, with partial volumes, the share of the neighbour's cell inside
it, by the code's rule: docs/theory/pd.md), and n_z(k) the share of the layers through the
thickness whose neighbour k layers away is still in the body (layers = 0: an unbounded
lattice). The critical energy then gives G = S G0 (plus what the failing step overshoots and
the bonds that fail off the plane; docs/examples/dcb.md). Counted here from the lattice alone,
independently of the code.

With --calibration family (docs/theory/bond_failure.md section 7) a bond of direction n between
a point of layer a and one of layer b has w_c,ij = w_c / s_ij, with
s_ij = (mu_a(n) + mu_b(n)) / 2 / (pi m^4 / 3) and mu_a(n) = sum_offsets beta (o . n)^2 / |o| over
the offsets o whose neighbour is in the body, so each crossing bond counts 1 / s_ij instead of 1.
"""
import argparse
import math

import numpy as np


def cell_share(i, j, k, m, sub=16):
    """The share of the unit cell centred at (i, j, k) inside the sphere of radius m: 1 with all
    eight corners inside, 0 with none, else the share of sub^3 sub-cell midpoints inside."""
    corners = [(i + a, j + b, k + c) for a in (-.5, .5) for b in (-.5, .5) for c in (-.5, .5)]
    inside = [x * x + y * y + z * z <= m * m for x, y, z in corners]
    if all(inside):
        return 1.0
    if not any(inside):
        return 0.0
    s = (np.arange(sub) + 0.5) / sub - 0.5
    sx, sy, sz = np.meshgrid(i + s, j + s, k + s, indexing="ij")
    return float(np.count_nonzero(sx * sx + sy * sy + sz * sz <= m * m)) / sub ** 3


def family(m, partial_volumes):
    """The offsets (i, j, k) of a family with their volume shares beta."""
    r = int(m) + (1 if partial_volumes else 0)
    out = []
    for i in range(-r, r + 1):
        for j in range(-r, r + 1):
            for k in range(-r, r + 1):
                if (i, j, k) == (0, 0, 0):
                    continue
                beta = cell_share(i, j, k, m) if partial_volumes else float(i * i + j * j + k * k <= m * m)
                if beta > 0.0:
                    out.append(((i, j, k), beta))
    return out


def moment(fam, n, keep):
    """mu(n) in spacings: sum beta (o . n)^2 / |o| over the offsets o that keep() accepts."""
    return sum(b * (o[0] * n[0] + o[1] * n[1] + o[2] * n[2]) ** 2 / math.sqrt(o[0] ** 2 + o[1] ** 2 + o[2] ** 2)
               for o, b in fam if keep(o))


def crossing_share(m, layers, partial_volumes=False, calibration="continuum"):
    """S above for the horizon m spacings on `layers` layers (0: unbounded)."""
    fam = family(m, partial_volumes)
    zs = [None] if layers == 0 else list(range(layers))
    inside = (lambda kz, k: True) if layers == 0 else (lambda kz, k: 0 <= kz + k < layers)
    norm = math.pi * m ** 4 / 3
    total = 0.0
    for kz in zs:
        for o, beta in fam:
            if o[1] <= 0 or not inside(kz, o[2]):
                continue
            weight = 1.0
            if calibration == "family":
                length = math.sqrt(o[0] ** 2 + o[1] ** 2 + o[2] ** 2)
                n = [c / length for c in o]
                mu_a = moment(fam, n, lambda q: inside(kz, q[2]))
                mu_b = moment(fam, n, lambda q: inside(None if kz is None else kz + o[2], q[2]))
                weight = norm / (0.5 * (mu_a + mu_b))
            total += o[1] * beta * weight
    return total / len(zs) / (math.pi * m ** 4 / 4)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--partial-volumes", action="store_true")
    ap.add_argument("--calibration", choices=["continuum", "family"], default="continuum")
    ap.add_argument("--layers", type=int, nargs="+", default=[6, 9, 12, 24, 0])
    ap.add_argument("--horizons", type=float, nargs="+", default=[2.01, 3.015, 4.01, 5.01])
    a = ap.parse_args()
    print("layers " + " ".join("%8.3f" % m for m in a.horizons))
    for n in a.layers:
        print("%6s " % (n if n else "inf") +
              " ".join("%8.3f" % crossing_share(m, n, a.partial_volumes, a.calibration) for m in a.horizons))


if __name__ == "__main__":
    main()
