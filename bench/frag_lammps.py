#!/usr/bin/python3
"""LAMMPS inputs for the fragmenting cylinder, from perifem's own particles.

    frag_lammps.py EXODUS WORKDIR DT STEPS [SKIN]

EXODUS is a perifem output of inputs/fragmenting_cylinder.yaml whose first frame is the
initial state (run_fragmenting.sh runs the deck with output at its first and last steps). The
script writes into WORKDIR:
  frag.data  LAMMPS data file (atom_style peri: id type volume density x y z), the points in
             perifem's order, at the frame's positions, with their initial velocities (the
             deck's radial and axial profiles, as perifem evaluated them) in a Velocities section;
  in.frag    the LAMMPS input: pair_style peri/pmb with c = 18 K / (pi delta^4), the deck's
             horizon and damage (the cylinder: critical stretch, alpha = 0, s0 constant; the
             clusters: Silling-Askari s00 and alpha), fix nve, the step DT, STEPS steps,
             neighbour skin SKIN (default 1e-4 m), `lattice sc` of the deck's spacing (LAMMPS's
             contact radius 1.35 of it between points never bonded); thermo prints the kinetic
             energy and the mean of damage/atom at the first and last steps.
The point volume is the deck's: h^3 for the cylinder (a cell-centred cubic lattice: every point
stands for one cell; perifem's summary of the same run prints the body's mass, which the caller
can compare with density x points x h^3), a grain's 1.44e-15 m^3 for the clusters. Requires
netCDF4 (python3-netcdf4).
"""
import math
import sys

import netCDF4

# the decks' constants: inputs/fragmenting_cylinder.yaml and inputs/cluster_collision.yaml
MODELS = {
    "cylinder": {"density": 7800.0, "bulk": 130.0e9, "horizon": 0.00417462, "spacing": 0.001,
                 "volume": 0.001 ** 3, "s00": 0.02, "alpha": 0.0, "title": "fragmenting cylinder"},
    "cluster": {"density": 2000.0, "bulk": 61461.88067, "horizon": 4.2e-5, "spacing": 1.4e-5,
                "volume": 1.44e-15, "s00": 0.0023, "alpha": 0.25, "title": "cluster collision"},
}


def nodal(ds, name, frame=0):
    names = ["".join(c.decode() for c in row if c).strip() for row in ds.variables["name_nod_var"][:]]
    return ds.variables[f"vals_nod_var{names.index(name) + 1}"][frame, :]


def main(argv):
    model = MODELS["cylinder"]
    if len(argv) > 2 and argv[1] == "--model":
        if argv[2] not in MODELS:
            sys.exit(f"frag_lammps.py: unknown model '{argv[2]}' (known: {', '.join(MODELS)})")
        model, argv = MODELS[argv[2]], argv[:1] + argv[3:]
    if len(argv) not in (5, 6):
        sys.exit(__doc__)
    exo, work, dt, steps = argv[1], argv[2], float(argv[3]), int(argv[4])
    skin = float(argv[5]) if len(argv) == 6 else 1e-4
    ds = netCDF4.Dataset(exo)
    x = [ds.variables[f"coord{c}"][:] + nodal(ds, f"displacement_{c}") for c in "xyz"]
    v = [nodal(ds, f"velocity_{c}") for c in "xyz"]
    n = len(x[0])
    vol, density, horizon = model["volume"], model["density"], model["horizon"]
    pad = 2 * horizon
    with open(f"{work}/frag.data", "w") as f:
        f.write(f"{model['title']}: perifem's points (bench/frag_lammps.py)\n\n")
        f.write(f"{n} atoms\n1 atom types\n\n")
        for c in range(3):
            f.write(f"{min(x[c]) - pad:.10g} {max(x[c]) + pad:.10g} {'xyz'[c]}lo {'xyz'[c]}hi\n")
        f.write("\nAtoms # peri\n\n")
        for i in range(n):
            f.write(f"{i + 1} 1 {vol:.10g} {density:g} {x[0][i]!r} {x[1][i]!r} {x[2][i]!r}\n")
        f.write("\nVelocities\n\n")
        for i in range(n):
            f.write(f"{i + 1} {v[0][i]!r} {v[1][i]!r} {v[2][i]!r}\n")
    c = 18.0 * model["bulk"] / (math.pi * horizon ** 4)
    with open(f"{work}/in.frag", "w") as f:
        f.write(f"""# {model['title']} (perifem's deck) in LAMMPS's PERI package
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
neighbor        {skin:g} bin
lattice         sc {model['spacing']:g}
read_data       frag.data
pair_style      peri/pmb
pair_coeff      * * {c:.6e} {horizon} {model['s00']} {model['alpha']}
fix             1 all nve
# mean damage over the atoms (1 - intact share of each family's volume), printed at the end
compute         dmg all damage/atom
compute         dmean all reduce ave c_dmg
thermo_style    custom step ke c_dmean
thermo          {max(steps, 1)}
timestep        {dt!r}
run             {steps}
""")
    print(f"{n} atoms, c = {c:.6e}, dt = {dt!r}, {steps} steps")


if __name__ == "__main__":
    main(sys.argv)
