#!/usr/bin/env python3
"""Plots and checks of the two bi-material examples against their closed forms.

  bimaterial_plot.py wave RUN.e [--out PNG] [--check]   (a run of inputs/bimaterial_wave.yaml)
  bimaterial_plot.py bar RUN.e [--out PNG] [--check]    (a run of inputs/bimaterial_bar.yaml)

wave: the axial velocity along the bar (the mean over each cross-section of the nodal
velocity_x) before the pulse meets the first interface, after it has crossed it and after it has
crossed the second, over the closed-form amplitudes drawn as horizontal lines. (The velocity, not
the stress: a coupled body writes the nodal stress of its peridynamic nodes only.) For a one-dimensional wave
meeting an interface from material a into b (Graff 1975, Wave Motion in Elastic Solids, §1.4):
    R_ab = (Z_b - Z_a) / (Z_a + Z_b),   T_ab = 2 Z_b / (Z_a + Z_b),   Z = rho c,
c the P-wave speed sqrt((K + 4G/3) / rho) (the bar's lateral motion is held). In a pulse moving
along +x the stress is sigma = -Z v, along -x sigma = +Z v, so with the incident velocity V the
reflected velocity is -R_ab V and the transmitted one T_ab (Z_a / Z_b) V. It prints the ratios
measured from the momenta of the bar's three parts (a pulse's momentum is its stress amplitude
times its duration and area; durations do not change across an interface) and from the velocity
peaks, the transmitted energy share 4 Z_a Z_b / (Z_a + Z_b)^2 from the kinetic
energies, and the energy and momentum balances of the run's history file (RUN.h5 beside RUN.e).

bar: the axial displacement at every node against the series springs,
    u(x) = F x / (E1 A) (x < L1),   u(x) = F L1 / (E1 A) + F (x - L1) / (E2 A) (x > L1),
and the nodal stress_xx against F / A (one stress in both halves: no ghost force at the interface).

--check: exit status 1 unless the wave's incident momentum, four momentum ratios and two energy
shares are within 1 % of the closed forms, its energy balance within 1e-3 and its momentum balance
within 1e-9 (the bar: the displacement within 1 % of u(L) at every node, the stress within 1e-6
of F / A); it also prints "measure KEY VALUE" lines (tests/regression/bimaterial_examples.sh).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402

# The decks' constants (inputs/bimaterial_wave.yaml, inputs/bimaterial_bar.yaml), SI units.
WAVE = dict(rho1=2700.0, K1=70.0e9, G1=42.0e9, rho2=7800.0, K2=160.0e9, G2=96.0e9,
            xi1=0.112, xi2=0.208, V=0.1, tau=8.784e-6, width=0.002)
BAR = dict(F=2.0e3, A=1.0e-4, L1=0.05, L2=0.05, E1=200.0e9, E2=70.0e9)
# When to look (from the closed-form speeds c1 = 6831 m/s, c2 = 6077 m/s): at 12 us the incident
# pulse lies in 22-82 mm; at 30 us the reflected one in 19-79 mm and the transmitted one in
# 141-195 mm; at 44 us the pulse transmitted through both in 228-289 mm and the one reflected at
# the second interface in 136-190 mm (it meets the first interface at 48 us).
TIMES = (12e-6, 30e-6, 44e-6)


def nodal(e, name, frame):
    names = ["".join(c.decode() for c in n if c).strip() for n in np.ma.filled(e["name_nod_var"][:], b"")]
    return np.array(e["vals_nod_var%d" % (names.index(name) + 1)][frame])


def lumped_masses(e, X, density_of):
    """Each hexahedron's mass (density at its centroid's x) shared equally by its eight nodes."""
    m = np.zeros(len(X[0]))
    for key in e.variables:
        if not key.startswith("connect"):
            continue
        conn = np.array(e[key][:]) - 1
        xs = [c[conn] for c in X]
        vol = np.prod([x.max(axis=1) - x.min(axis=1) for x in xs], axis=0)  # rectilinear bricks
        rho = density_of(xs[0].mean(axis=1))
        np.add.at(m, conn, np.repeat((rho * vol / conn.shape[1])[:, None], conn.shape[1], axis=1))
    return m


def stations(x, f):
    """The mean of f over each cross-section (the nodes of one x)."""
    xs, inv = np.unique(np.round(x, 9), return_inverse=True)
    return xs, np.bincount(inv, weights=f) / np.bincount(inv)


def wave(path, out, check):
    w = WAVE
    M1, M2 = w["K1"] + 4 * w["G1"] / 3, w["K2"] + 4 * w["G2"] / 3
    Z1, Z2 = np.sqrt(w["rho1"] * M1), np.sqrt(w["rho2"] * M2)
    R12, T12 = (Z2 - Z1) / (Z1 + Z2), 2 * Z2 / (Z1 + Z2)
    R21, T21 = (Z1 - Z2) / (Z1 + Z2), 2 * Z1 / (Z1 + Z2)
    TE = 4 * Z1 * Z2 / (Z1 + Z2) ** 2
    e = netCDF4.Dataset(path)
    X = [np.array(e[c][:]) for c in ("coordx", "coordy", "coordz")]
    x = X[0]
    t = np.array(e["time_whole"][:])
    frames = [int(np.argmin(np.abs(t - tt))) for tt in TIMES]
    m = lumped_masses(e, X, lambda xc: np.where((xc > w["xi1"]) & (xc < w["xi2"]), w["rho2"], w["rho1"]))
    part = np.where(x < w["xi1"] - 1e-9, 0, np.where(x < w["xi2"] + 1e-9, 1, 2))

    def sums(frame):
        v = nodal(e, "velocity_x", frame)
        return (np.bincount(part, weights=m * v, minlength=3), np.bincount(part, weights=0.5 * m * v * v, minlength=3))

    p0, _ = sums(frames[0])
    p1, k1 = sums(frames[1])
    p2, k2 = sums(frames[2])
    p = p1.sum()
    beyond = p2[1] + p2[2]
    impulse = Z1 * w["width"] ** 2 * w["V"] * w["tau"] / 2
    rows = [  # name, measured, closed form, key (--check prints "measure KEY relative error")
        ("incident momentum / piston impulse Z1 A V tau/2", p0.sum() / impulse, 1.0, "incident_momentum"),
        ("R12 (soft -> stiff, peridynamic) = -p1 / p", -p1[0] / p, R12, "reflection_pd"),
        ("T12 = (p2 + p3) / p", (p1[1] + p1[2]) / p, T12, "transmission_pd"),
        ("R21 (stiff -> soft, elements) = -p2 / (p2 + p3)", -p2[1] / beyond, R21, "reflection_fe"),
        ("T21 = p3 / (p2 + p3)", p2[2] / beyond, T21, "transmission_fe"),
        ("energy transmitted at 112 mm (kinetic share)", (k1[1] + k1[2]) / k1.sum(), TE, "energy_transmission_pd"),
        ("energy transmitted at 208 mm (kinetic share)", k2[2] / (k2[1] + k2[2]), TE, "energy_transmission_fe"),
    ]
    # the velocity peaks: mean velocity_x over each cross-section, its extreme in each zone
    prof = [stations(x, nodal(e, "velocity_x", f)) for f in frames]

    def peak(k, lo, hi):
        xs, v = prof[k]
        sel = (xs > lo) & (xs < hi)
        return v[sel][np.argmax(np.abs(v[sel]))]

    inc = peak(0, 0.005, w["xi1"])
    z = Z1 / Z2
    peaks = [
        ("incident peak / V", inc / w["V"], 1.0),
        ("reflected at 112 mm / incident: -R12", peak(1, 0.005, w["xi1"] - 0.01) / inc, -R12),
        ("transmitted at 112 mm / incident: T12 Z1/Z2", peak(1, w["xi1"] + 0.01, w["xi2"]) / inc, T12 * z),
        ("reflected at 208 mm / incident: -T12 R21 Z1/Z2", peak(2, w["xi1"] + 0.01, w["xi2"] - 0.01) / inc, -T12 * R21 * z),
        ("through both / incident: T12 T21", peak(2, w["xi2"] + 0.01, 0.312) / inc, T12 * T21),
    ]
    print("Z1 = %.4g, Z2 = %.4g kg/(m^2 s), Z2/Z1 = %.4f" % (Z1, Z2, Z2 / Z1))
    print("frames at %s us" % ", ".join("%.2f" % (t[f] * 1e6) for f in frames))
    print("%-50s %9s %9s %8s" % ("from the momenta and kinetic energies", "measured", "closed", "error"))
    for name, got, want, _ in rows:
        print("%-50s %9.4f %9.4f %+7.2f %%" % (name, got, want, 100 * (got / want - 1)))
    print("%-50s %9s %9s %8s" % ("from the velocity peaks", "measured", "closed", "error"))
    for name, got, want in peaks:
        print("%-50s %9.4f %9.4f %+7.2f %%" % (name, got, want, 100 * (got / want - 1)))
    bad = [name for name, got, want, _ in rows if abs(got / want - 1) > 0.01]
    if check:
        for name, got, want, key in rows:
            print("measure %s_error %.6g" % (key, got / want - 1))
    h5 = os.path.splitext(path)[0] + ".h5"
    if os.path.exists(h5):
        import h5py

        h = h5py.File(h5, "r")
        # energy_error: E(t) - E(0) with the leapfrog-centred kinetic energy, all stored energies
        # and the work of the prescribed motions (docs/user_guide.md §3.4)
        ebal = h["energy_error"][-1] / h["external_work"][-1]
        mom = np.array(h["momentum_x"])
        imp = np.array(h["piston_impulse_x"]) + np.array(h["bc0_impulse_x"])
        mbal = np.abs(mom - imp).max() / np.abs(mom).max()
        print("energy balance: (kinetic + stored - work) / work at the end = %.2e" % ebal)
        print("momentum balance: max |momentum_x - impulse of the constraints| / max |momentum_x| = %.2e" % mbal)
        if check:
            print("measure energy_balance %.6g" % ebal)
            print("measure momentum_balance %.6g" % mbal)
        if abs(ebal) > 1e-3:
            bad.append("the energy balance")
        if mbal > 1e-9:
            bad.append("the momentum balance")
    elif check:
        bad.append("no history file " + h5)

    fig, axes = plt.subplots(3, 1, figsize=(10, 7.5), sharex=True)
    z = Z1 / Z2
    lines = [  # (label, value, x from, x to) per frame, in units of the piston's velocity V
        [("incident: 1", 1.0, 0, w["xi1"])],
        [("reflected: $-R_{12}$ = %.4f" % -R12, -R12, 0, w["xi1"]),
         ("transmitted: $T_{12}Z_1/Z_2$ = %.4f" % (T12 * z), T12 * z, w["xi1"], w["xi2"])],
        [("reflected at 208 mm: $-T_{12}R_{21}Z_1/Z_2$ = %.4f" % (-T12 * R21 * z), -T12 * R21 * z, w["xi1"], w["xi2"]),
         ("through both: $T_{12}T_{21}$ = %.4f" % (T12 * T21), T12 * T21, w["xi2"], 0.312)],
    ]
    for ax, (xs, v), f, ls in zip(axes, prof, frames, lines):
        ax.axvspan(w["xi1"] * 1e3, w["xi2"] * 1e3, color="0.9", lw=0)
        ax.axvspan(0.144e3, 0.160e3, color="0.8", lw=0)
        ax.plot(xs * 1e3, v / w["V"], "k-", lw=1.2, label="perifem, mean over the section")
        for k, (lab, val, a, b) in enumerate(ls):
            ax.hlines(val, a * 1e3, b * 1e3, colors="C%d" % (k + 1), linestyles="--", lw=1.2, label=lab)
        ax.axhline(0, color="0.5", lw=0.5)
        ax.set_ylabel(r"$v_x / V$")
        ax.set_title("t = %.1f µs" % (t[f] * 1e6), fontsize=10, loc="left")
        ax.legend(fontsize=8, loc="upper left" if ax is axes[-1] else "upper right")
        ax.set_ylim(-0.7, 1.4)
    axes[0].text(114, -0.6, "stiff (steel-like), 112-208 mm; darker: the overlap (PD to its left, elements to its right)", fontsize=8)
    axes[-1].set_xlabel("x (mm)")
    fig.suptitle("A pulse across two interfaces: the velocity over the piston velocity V, closed forms dashed", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("wrote", out)
    return bad


def bar(path, out, check):
    b = BAR
    e = netCDF4.Dataset(path)
    x = np.array(e["coordx"][:])
    ux, sxx = nodal(e, "displacement_x", -1), nodal(e, "stress_xx", -1)
    F, A, L1, E1, E2 = b["F"], b["A"], b["L1"], b["E1"], b["E2"]
    u_cf = np.where(x < L1, F * x / (E1 * A), F * L1 / (E1 * A) + F * (x - L1) / (E2 * A))
    uL = F * (L1 / (E1 * A) + b["L2"] / (E2 * A))
    err = np.abs(ux - u_cf).max() / uL
    end = ux[x > L1 + b["L2"] - 1e-9].mean()
    dev = np.abs(sxx / (F / A) - 1).max()
    iface = np.abs(sxx[np.abs(x - L1) < 1e-9] / (F / A) - 1).max()
    xs, um = stations(x, ux)
    s1 = np.polyfit(xs[xs < L1 + 1e-9], um[xs < L1 + 1e-9], 1)[0]
    s2 = np.polyfit(xs[xs > L1 - 1e-9], um[xs > L1 - 1e-9], 1)[0]
    print("u(L) = %.6e m, series springs F (L1/(E1 A) + L2/(E2 A)) = %.6e m (%+.4f %%)" % (end, uL, 100 * (end / uL - 1)))
    print("max |u - u_closed| over every node / u(L) = %.2e" % err)
    print("strain of the steel half %.6e, F/(E1 A) %.6e (%+.4f %%); of the aluminium half %.6e, F/(E2 A) %.6e (%+.4f %%)"
          % (s1, F / (E1 * A), 100 * (s1 * E1 * A / F - 1), s2, F / (E2 * A), 100 * (s2 * E2 * A / F - 1)))
    print("max |sigma_xx A / F - 1| over every node = %.2e (the interface's nodes: %.2e)" % (dev, iface))
    if check:
        print("measure end_displacement_error %.6g" % (end / uL - 1))
        print("measure displacement_error %.6g" % err)
        print("measure stress_deviation %.6g" % dev)

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, gridspec_kw=dict(height_ratios=(2, 1)))
    xx = np.linspace(0, L1 + b["L2"], 201)
    a1.plot(xx * 1e3, np.where(xx < L1, F * xx / (E1 * A), F * L1 / (E1 * A) + F * (xx - L1) / (E2 * A)) * 1e6,
            "C1-", lw=1.2, label="series springs, closed form")
    a1.plot(xs * 1e3, um * 1e6, "ko", ms=4, label="perifem (quasi-static), nodes")
    a1.axvspan(L1 * 1e3, (L1 + b["L2"]) * 1e3, color="0.9", lw=0)
    a1.set_ylabel(r"$u_x$ (µm)")
    a1.legend(fontsize=9, loc="upper left")
    a1.text(52, 0.3, "aluminium (E = 70 GPa)", fontsize=9)
    a1.text(2, 0.3 + F * L1 / (E1 * A) * 1e6, "steel (E = 200 GPa)", fontsize=9)
    xs2, sm = stations(x, sxx)
    a2.plot(xs2 * 1e3, (sm / (F / A) - 1) * 1e9, "ko", ms=4, label=r"perifem: $\sigma_{xx}A/F - 1$, mean over the section")
    a2.axhline(0, color="C1", lw=1.2, label=r"closed form $\sigma_{xx} = F/A$")
    a2.axvspan(L1 * 1e3, (L1 + b["L2"]) * 1e3, color="0.9", lw=0)
    a2.set_ylabel(r"$(\sigma_{xx}A/F - 1)\times 10^{9}$")
    a2.set_xlabel("x (mm)")
    a2.legend(fontsize=8, loc="lower right")
    fig.suptitle("A bi-material bar under an end force of 2 kN, solved statically", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("wrote", out)
    bad = []
    if err > 0.01:
        bad.append("the displacement field is off the series-spring closed form")
    if dev > 1e-6:
        bad.append("the stress is not F/A at every node (a jump at the interface?)")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=("wave", "bar"))
    ap.add_argument("exodus", help="the run's Exodus file")
    ap.add_argument("--out", help="PNG to write (default: bimaterial_<case>.png beside the Exodus file)")
    ap.add_argument("--check", action="store_true", help="exit 1 unless within the closed forms' tolerances")
    a = ap.parse_args()
    out = a.out or os.path.join(os.path.dirname(a.exodus) or ".", "bimaterial_%s.png" % a.case)
    bad = (wave if a.case == "wave" else bar)(a.exodus, out, a.check)
    for b in bad:
        print("FAIL:", b)
    if a.check:
        print("check: %s" % ("FAIL" if bad else "ok"))
        sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
