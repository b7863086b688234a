"""The plots of docs/examples/wave_variable_horizon.md: kinetic energy per 1 mm slab along the bar
at the start and at the end of each run, and the energy each run reflected.
  /usr/bin/python3 wave_variable_horizon_plot.py OUT.png RUN.e:LABEL [RUN.e:LABEL ...] [--mesh]
The first run's first frame is drawn as the start. --mesh: the runs are of a hexahedral mesh
(inputs/wave_pd_to_fe.yaml), whose boundary nodes carry half a cell per face they lie on; without
it, of a lattice of points of one volume each (inputs/wave_variable_horizon.yaml).
Reflected energy (as tests/verification/test_coupling_wave.c measures it): per slab, the
mass-weighted cross-section means of u_x and v_x, eps = d<u>/dx, the left-going amplitude
w = (v + c eps) / 2 and its energy M w^2, summed over x < 95 mm, less the same at t = 0, over the
pulse's energy (twice its initial kinetic energy)."""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import netCDF4
import numpy as np

RHO, VOL, C = 7800.0, 1e-9, 5063.6965


def node_masses(X, mesh):
    m = np.full(len(X), RHO * VOL)
    if mesh:
        for a in range(3):
            edge = np.isclose(X[:, a], X[:, a].min()) | np.isclose(X[:, a], X[:, a].max())
            m[edge] *= 0.5
    return m


def slabs(path, step, mesh):
    """Slab positions (mm), kinetic energy, mass, mean u_x and mean v_x per 1 mm slab; time."""
    d = netCDF4.Dataset(path)
    names = [str(netCDF4.chartostring(n)) for n in d.variables["name_nod_var"][:]]
    X = np.array([d.variables[c][:] for c in ("coordx", "coordy", "coordz")]).T
    u = d.variables["vals_nod_var%d" % (names.index("displacement_x") + 1)][step]
    v = d.variables["vals_nod_var%d" % (names.index("velocity_x") + 1)][step]
    m = node_masses(X, mesh)
    k = np.round(X[:, 0] * 1e3).astype(int)
    ms = np.bincount(k, weights=m)
    return (np.arange(len(ms)), np.bincount(k, weights=0.5 * m * v**2), ms,
            np.bincount(k, weights=m * u) / ms, np.bincount(k, weights=m * v) / ms, d.variables["time_whole"][step])


def left_going(x, m, mu, mv):
    eps = np.zeros_like(mu)
    eps[1:-1] = (mu[2:] - mu[:-2]) / 2e-3
    w = 0.5 * (mv + C * eps)
    keep = (x > 0) & (x < len(x) - 1) & (x < 95)
    return (m * w * w)[keep].sum()


args = [a for a in sys.argv[2:] if a != "--mesh"]
mesh = "--mesh" in sys.argv[2:]
runs = [a.split(":", 1) for a in args]
fig, ax = plt.subplots(figsize=(8, 5))
x, e0, *_ = slabs(runs[0][0], 0, mesh)
ax.semilogy(x, e0 / e0.sum(), color="0.7", label="start (t = 0)")
for (path, label), style in zip(runs, ("k-", "r-", "b--", "g-.")):
    _, es, ms, us, vs, _ = slabs(path, 0, mesh)
    x, e, m, u, v, t = slabs(path, -1, mesh)
    refl = (left_going(x, m, u, v) - left_going(x, ms, us, vs)) / (2 * es.sum())
    ax.semilogy(x, e / es.sum(), style, label="%s: reflected %.3f %%" % (label, 100 * refl))
    print("%s: reflected %.4f %%, kinetic energy left of 95 mm %.3f %%" % (label, 100 * refl, 100 * e[x < 95].sum() / es.sum()))
if mesh:
    ax.axvspan(80, 100, color="y", alpha=0.3, label="horizon 3.01 -> 1.01 mm")
    ax.axvspan(100, 120, color="c", alpha=0.2, label="overlap: PD -> FE")
else:
    ax.axvspan(100, 120, color="y", alpha=0.3, label="horizon 3.01 -> 1.01 mm")
ax.set_ylim(1e-7, 1)
ax.set_xlabel("x (mm)")
ax.set_ylabel("kinetic energy per mm / initial")
ax.set_title("pulse after %.0f us" % (t * 1e6))
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2)
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=110)
