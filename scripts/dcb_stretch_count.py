"""What the LPS critical-stretch law can dissipate on a cubic lattice when a plane opens, as a
share of G0: the opening count of the critical stretch (docs/examples/dcb.md).

    /usr/bin/python3 scripts/dcb_stretch_count.py [--form closed|willberg] [--layers 6 0]
        [--horizons 2.01 3.015 4.01 5.01] [--K 1.75e9] [--G 0.808e9] [--no-dilatation]

The two halves of a cell-centred lattice of spacing dx (the plane y = 0 halfway between two
layers, the lattice unbounded in x, `layers` thick in z, 0 for unbounded) are pulled apart by a
jump Delta of the displacement in y. A bond of reference vector xi that crosses the plane then
has the extension e = Delta |xi_y| / |xi| (to first order) and the stretch e / |xi|, and every
other bond none. Each point holds the LPS energy (Silling et al. 2007, eq. 92)

    W_i = K theta_i^2 / 2 + (15 G / (2 m_i)) sum_j (e_ij - theta_i |xi_ij| / 3)^2 V_j,
    theta_i = (3 / m_i) sum_j |xi_ij| e_ij V_j,    m_i = sum_j |xi_ij|^2 V_j (omega = 1),

over its unbroken bonds, m_i over its family as built (fewer bonds near the faces z = 0 and B).
The energy per unit area of the plane is E = k(B) Delta^2 / 2, k depending only on the set B of
broken bonds; a crossing bond breaks once its stretch passes s0, i.e. at the opening
Delta_b = s0 |xi|^2 / |xi_y|. The energy the opening dissipates is the area under the
traction-separation curve, G = sum over the intervals between breaks of k (Delta_{n+1}^2 -
Delta_n^2) / 2. Printed is G / G0 for s0 from G0 by

    closed:   s0 = sqrt(8 G0 / (15 K delta))   (perifem's closed form, exact for nu = 1/4 with
              no dilatation and a whole family; docs/theory/bond_failure.md section 2)
    willberg: s_c = sqrt(G0 / ([3 G + (3/4)^4 (K - 5 G / 3)] delta))   (the DLR slides)

With --no-dilatation the theta terms are left out (the closed form's assumption): then, for
nu = 1/4 (K = 5 G / 3) and the whole continuum family, G = G0 exactly. Counted from the lattice
alone, independently of the code. The opening is not the crack tip's field: bonds beside the
plane also break in a run, so a run dissipates more than this count (docs/examples/dcb.md).
"""
import argparse
import math

import numpy as np


def s0_of(form, G0, K, G, delta):
    if form == "closed":
        return math.sqrt(8 * G0 / (15 * K * delta))
    return math.sqrt(G0 / ((3 * G + 0.31640625 * (K - 5 * G / 3)) * delta))


def offsets(m):
    """The offsets (i, j, k) of a family of radius m spacings (no partial volumes)."""
    r = int(m)
    g = np.arange(-r, r + 1)
    o = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    d2 = (o * o).sum(axis=1)
    return o[(d2 > 0) & (d2 <= m * m)].astype(float)


def opening_share(m, layers, s0, K, G, G0, dx=1.0, dilatation=True):
    """G / G0 dissipated by opening the plane, for horizon m dx (see the head of the file)."""
    o = offsets(m)
    xi = o * dx
    ln = np.linalg.norm(xi, axis=1)
    V = dx ** 3
    zs = range(layers) if layers else [None]
    rows = []  # per point above the plane: (in-body mask, m_i, e per unit Delta, Delta_b)
    for ly in range(int(m) + 1):
        for lz in zs:
            inb = np.ones(len(o), bool) if lz is None else (lz + o[:, 2] >= 0) & (lz + o[:, 2] < layers)
            cross = inb & (o[:, 1] <= -(ly + 1))
            c = np.where(cross, np.abs(xi[:, 1]) / ln, 0.0)
            rows.append((inb, np.sum(ln[inb] ** 2) * V, c, np.where(cross, s0 * ln / np.where(cross, c, 1.0), np.inf)))
    per_column = 2 * dx / (layers if layers else 1)  # two halves, points per unit area of the plane

    def stiffness(opening):
        k = 0.0
        for inb, mi, c, db in rows:
            alive = inb & (db > opening)
            ca = np.where(alive, c, 0.0)
            th = (3 / mi) * np.sum(ln * ca) * V if dilatation else 0.0
            ed = np.where(alive, ca - th * ln / 3, 0.0)
            k += 0.5 * K * th ** 2 + 15 * G / (2 * mi) * np.sum(ed ** 2) * V
        return 2 * per_column * k  # E = k Delta^2 / 2

    breaks = np.unique(np.concatenate([db[np.isfinite(db)] for _, _, _, db in rows]))
    dissipated, previous = 0.0, 0.0
    for b in breaks:
        dissipated += stiffness(0.5 * (b + previous)) * (b * b - previous * previous) / 2
        previous = b
    return dissipated / G0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--form", choices=["closed", "willberg"], default="closed")
    ap.add_argument("--layers", type=int, nargs="+", default=[6, 0])
    ap.add_argument("--horizons", type=float, nargs="+", default=[2.01, 3.015, 4.01, 5.01])
    ap.add_argument("--K", type=float, default=1.75e9)
    ap.add_argument("--G", type=float, default=0.808e9)
    ap.add_argument("--G0", type=float, default=12.0)
    ap.add_argument("--dx", type=float, default=0.5e-3)
    ap.add_argument("--no-dilatation", action="store_true")
    a = ap.parse_args()
    print("horizon/dx  " + "  ".join("layers %-3s" % (n if n else "inf") for n in a.layers))
    for m in a.horizons:
        s0 = s0_of(a.form, a.G0, a.K, a.G, m * a.dx)
        shares = [opening_share(m, n, s0, a.K, a.G, a.G0, a.dx, not a.no_dilatation) for n in a.layers]
        print("%-10g  " % m + "  ".join("%-10.3f" % s for s in shares))


if __name__ == "__main__":
    main()
