"""The plot of docs/examples/wave_variable_horizon.md: kinetic energy per 1 mm slab along the bar
at the start and after 24 us, for inputs/wave_variable_horizon.yaml with a constant horizon, and
with the taper in the standard and in the consistent form; and the energy each run reflected.
Run from a folder holding the runs' Exodus files const.e, standard.e, consistent.e:
  /usr/bin/python3 wave_variable_horizon_plot.py OUT.png
Reflected energy (as tests/verification/test_coupling_wave.c measures it): per slab, the
cross-section means of u_x and v_x, eps = d<u>/dx, the left-going amplitude w = (v + c eps) / 2 and
its energy M w^2, summed over x < 95 mm, less the same at t = 0, over the pulse's energy (twice
its initial kinetic energy)."""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import netCDF4
import numpy as np

RHO, VOL, C = 7800.0, 1e-9, 5063.6965


def slabs(path, step):
    """Slab positions (mm), kinetic energy, mass, mean u_x and mean v_x per 1 mm slab; time."""
    d = netCDF4.Dataset(path)
    names = [str(netCDF4.chartostring(n)) for n in d.variables["name_nod_var"][:]]
    x = d.variables["coordx"][:]
    u = d.variables["vals_nod_var%d" % (names.index("displacement_x") + 1)][step]
    v = d.variables["vals_nod_var%d" % (names.index("velocity_x") + 1)][step]
    k = np.round(x * 1e3).astype(int)
    m = np.bincount(k, weights=np.full(len(x), RHO * VOL))
    e = np.bincount(k, weights=0.5 * RHO * VOL * v**2)
    mu = np.bincount(k, weights=RHO * VOL * u) / m
    mv = np.bincount(k, weights=RHO * VOL * v) / m
    return np.arange(len(e)), e, m, mu, mv, d.variables["time_whole"][step]


def left_going(x, m, mu, mv):
    eps = np.zeros_like(mu)
    eps[1:-1] = (mu[2:] - mu[:-2]) / 2e-3
    w = 0.5 * (mv + C * eps)
    keep = (x > 0) & (x < len(x) - 1) & (x < 95)
    return (m * w * w)[keep].sum()


fig, ax = plt.subplots(figsize=(8, 4))
x, e0, m0, u0, v0, _ = slabs("const.e", 0)
ax.semilogy(x, e0 / e0.sum(), color="0.7", label="start (t = 0)")
for name, style in (("const", "k-"), ("standard", "r-"), ("consistent", "b--")):
    _, es, ms, us, vs, _ = slabs(name + ".e", 0)
    x, e, m, u, v, t = slabs(name + ".e", -1)
    refl = (left_going(x, m, u, v) - left_going(x, ms, us, vs)) / (2 * es.sum())
    label = {"const": "constant horizon", "standard": "taper, standard form",
             "consistent": "taper, consistent form"}[name]
    ax.semilogy(x, e / e0.sum(), style, label="%s: reflected %.3f %%" % (label, 100 * refl))
    print("%s: reflected %.4f %%, kinetic energy left of 95 mm %.3f %%" % (name, 100 * refl, 100 * e[x < 95].sum() / e0.sum()))
ax.axvspan(100, 120, color="y", alpha=0.3, label="horizon 3.01 -> 1.01 mm")
ax.set_ylim(1e-7, 1)
ax.set_xlabel("x (mm)")
ax.set_ylabel("kinetic energy per mm / initial")
ax.set_title("pulse after %.0f us" % (t * 1e6))
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=110)
