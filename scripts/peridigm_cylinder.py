#!/usr/bin/python3
"""Peridigm's fragmenting cylinder as a Peridigm discretization: an Exodus II file of SPHERE
elements (one node each, attributes 'radius' and 'volume'), the same points in Peridigm's text
format, the same cells as HEX8 elements, and the numbers a test checks them against.

    /usr/bin/python3 scripts/peridigm_cylinder.py OUT_PREFIX [--wall N] [--perturb A]

The tube of Peridigm's example: inner radius 0.020 m, outer 0.025 m, length 0.100 m along z.
It is cut into N cells through the wall, N_theta around and N_z along (cells of about equal
edge, h = (r_o - r_i) / N, N_theta = round(2 pi r_mean / h), N_z = round(L / h)); each cell is an
annular sector, its point at the sector's centroid and its volume the sector's volume
    V = (dtheta / 2) (r2^2 - r1^2) dz,
whose sum over the tube is exactly pi (r_o^2 - r_i^2) L. The centroid of an annular sector of
half-angle a lies at the radius
    r_c = (2 / 3) (r2^3 - r1^3) / (r2^2 - r1^2) * sin(a) / a
(the centroid of a circular sector, 2 r sin(a) / (3 a), weighted by the two sectors' areas).
Positions may be perturbed by up to A h per component (a fixed linear congruential stream; 0 by
default) to break the symmetry, as Peridigm's example does.

The HEX8 file holds the same cells with straight edges: the nodes at (r_i, theta_j, z_k) on the
cells' corners (not perturbed), each cell a prism over the trapezoid of its four corners in a
cross-section, of volume (sin(dtheta) / 2) (r2^2 - r1^2) dz, the tube's
(N_theta / 2) sin(dtheta) (r_o^2 - r_i^2) L. Its node sets are of nodes: 'bottom' (z = 0),
'top' (z = L), 'inner_wall' (r = r_i), 'all'; Peridigm maps a node set onto the points of every
element on its nodes, which are the cells of the SPHERE file's sets of the same names.

Blocks: 'lower' (id 1, z < L/2) and 'upper' (id 2). Node sets: 'bottom' (the first layer of
cells), 'top' (the last layer), 'inner_wall' (the innermost ring of cells), 'all'. The files:
OUT_PREFIX.g (Exodus, written with netCDF4 in the Exodus II layout), OUT_PREFIX.txt (x y z
block_id volume), OUT_PREFIX_hex.g (the HEX8 cells), OUT_PREFIX.json (counts, the volume sums,
the set sizes and set volumes, each summed here from the cells' own formulas).
"""
import argparse
import json
import math

import netCDF4
import numpy as np

R_IN, R_OUT, LENGTH = 0.020, 0.025, 0.100


def cells(wall, perturb):
    h = (R_OUT - R_IN) / wall
    n_theta = int(round(2 * math.pi * 0.5 * (R_IN + R_OUT) / h))
    n_z = int(round(LENGTH / h))
    dtheta, dz = 2 * math.pi / n_theta, LENGTH / n_z
    a = dtheta / 2
    seed = 12345
    pts = []
    for k in range(n_z):
        for j in range(n_theta):
            for i in range(wall):
                r1, r2 = R_IN + i * h, R_IN + (i + 1) * h
                rc = 2.0 / 3.0 * (r2 ** 3 - r1 ** 3) / (r2 ** 2 - r1 ** 2) * math.sin(a) / a
                theta = (j + 0.5) * dtheta
                xyz = [rc * math.cos(theta), rc * math.sin(theta), (k + 0.5) * dz]
                for c in range(3):
                    seed = (1103515245 * seed + 12345) % 2 ** 31
                    xyz[c] += perturb * h * (2 * seed / 2 ** 31 - 1)
                vol = a * (r2 ** 2 - r1 ** 2) * dz
                pts.append(dict(x=xyz, vol=vol, block=1 if k < n_z // 2 else 2, i=i, k=k))
    return pts, (wall, n_theta, n_z), h


def char_array(names, n):
    out = np.zeros((len(names), n), dtype="S1")
    for r, s in enumerate(names):
        for c, ch in enumerate(s.encode()[: n - 1]):
            out[r, c] = bytes([ch])
    return out


def write_exodus(path, title, xyz, blocks, sets):
    """The Exodus II netCDF layout (Schoof & Yarberry, SAND92-2137; 'large model' coordinates).
    xyz: [nodes][3]; blocks: (id, name, type, conn [elements][nodes] 1-based, attributes
    [elements][radius, volume] or None); sets: {name: [nodes, 0-based]}."""
    len_name = 33
    ds = netCDF4.Dataset(path, "w", format="NETCDF3_64BIT_OFFSET")
    ds.api_version = np.float32(8.03)
    ds.version = np.float32(2.0)
    ds.floating_point_word_size = np.int32(8)
    ds.file_size = np.int32(1)
    ds.maximum_name_length = np.int32(32)
    ds.int64_status = np.int32(0)
    ds.title = title
    for name, size in [("len_string", 33), ("len_line", 81), ("four", 4), ("len_name", len_name),
                       ("time_step", None), ("num_dim", 3), ("num_nodes", len(xyz)),
                       ("num_elem", sum(len(b[3]) for b in blocks)),
                       ("num_el_blk", len(blocks)), ("num_node_sets", len(sets))]:
        ds.createDimension(name, size)
    ds.createVariable("time_whole", "f8", ("time_step",))
    for c, axis in enumerate("xyz"):
        ds.createVariable("coord" + axis, "f8", ("num_nodes",))[:] = [x[c] for x in xyz]
    ds.createVariable("coor_names", "S1", ("num_dim", "len_name"))[:] = char_array(["x", "y", "z"], len_name)
    ds.createVariable("eb_status", "i4", ("num_el_blk",))[:] = [1] * len(blocks)
    prop = ds.createVariable("eb_prop1", "i4", ("num_el_blk",))
    prop.setncattr("name", "ID")
    prop[:] = [b[0] for b in blocks]
    ds.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))[:] = char_array([b[1] for b in blocks], len_name)
    for e, (_, _, kind, members, attrib) in enumerate(blocks, start=1):
        ds.createDimension("num_el_in_blk%d" % e, len(members))
        ds.createDimension("num_nod_per_el%d" % e, len(members[0]))
        conn = ds.createVariable("connect%d" % e, "i4", ("num_el_in_blk%d" % e, "num_nod_per_el%d" % e))
        conn.elem_type = kind
        conn[:] = np.array(members, dtype=np.int32)
        if attrib is None:
            continue
        ds.createDimension("num_att_in_blk%d" % e, 2)
        attr = ds.createVariable("attrib%d" % e, "f8", ("num_el_in_blk%d" % e, "num_att_in_blk%d" % e))
        attr[:] = attrib
        ds.createVariable("attrib_name%d" % e, "S1", ("num_att_in_blk%d" % e, "len_name"))[:] = \
            char_array(["radius", "volume"], len_name)
    ds.createVariable("ns_status", "i4", ("num_node_sets",))[:] = [1] * len(sets)
    prop = ds.createVariable("ns_prop1", "i4", ("num_node_sets",))
    prop.setncattr("name", "ID")
    prop[:] = list(range(1, len(sets) + 1))
    ds.createVariable("ns_names", "S1", ("num_node_sets", "len_name"))[:] = char_array(list(sets), len_name)
    for s, (name, members) in enumerate(sets.items(), start=1):
        ds.createDimension("num_nod_ns%d" % s, len(members))
        ds.createVariable("node_ns%d" % s, "i4", ("num_nod_ns%d" % s,))[:] = np.array(members, dtype=np.int32) + 1
    ds.close()


def write_spheres(path, pts, sets):
    """One SPHERE element a point, its node numbered as the point."""
    blocks = []
    for bid, name in [(1, "lower"), (2, "upper")]:
        members = [q for q, p in enumerate(pts) if p["block"] == bid]
        blocks.append((bid, name, "SPHERE", [[q + 1] for q in members],
                       [[(3 * pts[q]["vol"] / (4 * math.pi)) ** (1 / 3), pts[q]["vol"]] for q in members]))
    write_exodus(path, "Peridigm fragmenting cylinder, SPHERE elements", [p["x"] for p in pts], blocks, sets)


def write_hexes(path, shape):
    """The cells as HEX8 elements (Exodus node order: the inner-to-outer, counter-clockwise
    quadrilateral at z_k, then the same at z_k+1), in the points' order; returns the volume."""
    wall, n_theta, n_z = shape
    h, dtheta, dz = (R_OUT - R_IN) / wall, 2 * math.pi / n_theta, LENGTH / n_z
    def node(i, j, k):  # 1-based
        return 1 + i + (wall + 1) * (j % n_theta + n_theta * k)
    xyz = [[(R_IN + i * h) * math.cos(j * dtheta), (R_IN + i * h) * math.sin(j * dtheta), k * dz]
           for k in range(n_z + 1) for j in range(n_theta) for i in range(wall + 1)]
    conn = {1: [], 2: []}
    for k in range(n_z):
        for j in range(n_theta):
            for i in range(wall):
                quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
                conn[1 if k < n_z // 2 else 2].append([node(a, b, k + c) for c in (0, 1) for a, b in quad])
    nodes = [(i, k) for k in range(n_z + 1) for j in range(n_theta) for i in range(wall + 1)]
    sets = {
        "bottom": [q for q, (i, k) in enumerate(nodes) if k == 0],
        "top": [q for q, (i, k) in enumerate(nodes) if k == n_z],
        "inner_wall": [q for q, (i, k) in enumerate(nodes) if i == 0],
        "all": list(range(len(nodes))),
    }
    write_exodus(path, "Peridigm fragmenting cylinder, HEX8 elements", xyz,
                 [(1, "lower", "HEX8", conn[1], None), (2, "upper", "HEX8", conn[2], None)], sets)
    return n_theta / 2 * math.sin(dtheta) * (R_OUT ** 2 - R_IN ** 2) * LENGTH


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prefix")
    ap.add_argument("--wall", type=int, default=5, help="cells through the wall (Peridigm's example: 5)")
    ap.add_argument("--perturb", type=float, default=0.0, help="perturbation amplitude, a fraction of h")
    args = ap.parse_args()
    pts, (wall, n_theta, n_z), h = cells(args.wall, args.perturb)
    # The file stores the points block after block (elements are numbered so); give them in
    # that order everywhere, so the Exodus and the text discretization list the same sequence.
    pts.sort(key=lambda p: p["block"])
    sets = {
        "bottom": [q for q, p in enumerate(pts) if p["k"] == 0],
        "top": [q for q, p in enumerate(pts) if p["k"] == n_z - 1],
        "inner_wall": [q for q, p in enumerate(pts) if p["i"] == 0],
        "all": list(range(len(pts))),
    }
    write_spheres(args.prefix + ".g", pts, sets)
    hex_volume = write_hexes(args.prefix + "_hex.g", (wall, n_theta, n_z))
    with open(args.prefix + ".txt", "w") as f:
        f.write("# x y z block_id volume (m, m^3): Peridigm's fragmenting cylinder, %d x %d x %d cells\n"
                % (wall, n_theta, n_z))
        for p in pts:
            f.write("%.17g %.17g %.17g %d %.17g\n" % (p["x"][0], p["x"][1], p["x"][2], p["block"], p["vol"]))
    expect = {
        "cells": [wall, n_theta, n_z], "spacing": h, "points": len(pts),
        "volume": math.fsum(p["vol"] for p in pts),
        "volume_exact": math.pi * (R_OUT ** 2 - R_IN ** 2) * LENGTH,
        "hex_volume_exact": hex_volume,
        "blocks": {str(b): sum(p["block"] == b for p in pts) for b in (1, 2)},
        "block_volume": {str(b): math.fsum(p["vol"] for p in pts if p["block"] == b) for b in (1, 2)},
        "sets": {name: len(m) for name, m in sets.items()},
        "set_volume": {name: math.fsum(pts[q]["vol"] for q in m) for name, m in sets.items()},
    }
    with open(args.prefix + ".json", "w") as f:
        json.dump(expect, f, indent=1)


if __name__ == "__main__":
    main()
