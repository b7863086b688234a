"""The plot of docs/examples/wave_variable_horizon.md: kinetic energy per 1 mm slab along the bar
at the start and after 24 us, for inputs/wave_variable_horizon.yaml with a constant horizon,
with the taper in the standard form, and with the taper in the corrected form.
Run from a folder holding the three runs' Exodus files const.e, standard.e, corrected.e:
  /usr/bin/python3 wave_variable_horizon_plot.py OUT.png"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import netCDF4
import numpy as np


def slabs(path, step):
    d = netCDF4.Dataset(path)
    names = [str(netCDF4.chartostring(n)) for n in d.variables["name_nod_var"][:]]
    x = d.variables["coordx"][:]
    v = d.variables["vals_nod_var%d" % (names.index("velocity_x") + 1)][step]
    k = np.round(x * 1e3).astype(int)
    e = np.bincount(k, weights=0.5 * 7800 * 1e-9 * v**2)  # rho V v^2 / 2 per point, J
    return np.arange(len(e)), e, d.variables["time_whole"][step]


fig, ax = plt.subplots(figsize=(8, 4))
x, e0, _ = slabs("const.e", 0)
ax.semilogy(x, e0 / e0.sum(), color="0.7", label="start (t = 0)")
for name, style in (("const", "k-"), ("standard", "r-"), ("corrected", "b--")):
    x, e, t = slabs(name + ".e", -1)
    left = e[x < 95].sum() / e0.sum()
    label = {"const": "constant horizon", "standard": "taper, standard form",
             "corrected": "taper, corrected form"}[name]
    ax.semilogy(x, e / e0.sum(), style, label="%s: %.2f %% left of 95 mm" % (label, 100 * left))
ax.axvspan(100, 120, color="y", alpha=0.3, label="horizon 3.01 -> 1.01 mm")
ax.set_ylim(1e-7, 1)
ax.set_xlabel("x (mm)")
ax.set_ylabel("kinetic energy per mm / initial")
ax.set_title("pulse after %.0f us" % (t * 1e6))
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=110)
