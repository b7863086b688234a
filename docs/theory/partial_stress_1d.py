"""The partial-stress operator on a 1-D lattice with a tapering horizon (docs/theory/coupling.md
§2.4): growth rates of its modes, and a pulse through the taper.

Linear elasticity with E = rho = h = 1. The nonlocal gradient (G u)_i = sum_j (u_j - u_i) xi / K_i
over j within delta_i, K_i = sum_j xi^2; the standard (weak) form is a = -G^T G u, the
partial-stress (strong) form a = G G u. A mode u ~ exp(i w t) with a = -w^2 u grows when w has an
imaginary part. Run: /usr/bin/python3 partial_stress_1d.py"""
import numpy as np


def gradient(x, delta):
    n = len(x)
    G = np.zeros((n, n))
    for i in range(n):
        js = [j for j in range(n) if j != i and abs(x[j] - x[i]) <= delta[i]]
        K = sum((x[j] - x[i]) ** 2 for j in js)
        for j in js:
            G[i, j] += (x[j] - x[i]) / K
            G[i, i] -= (x[j] - x[i]) / K
    return G


def taper(x, start, length):
    return 3.01 - 2.0 * np.clip((x - start) / length, 0, 1)


def growth(A):
    lam = np.linalg.eigvals(A[10:-10, 10:-10])  # away from the bar's ends
    w = np.sqrt(-lam.astype(complex))
    return np.max(np.abs(w.imag)), np.max(np.abs(w))


def pulse(x, delta, partial_stress, T=200.0, dt=0.3):
    """A right-going Gaussian pulse (s = 8 h, from x0 = 100 h), the partial-stress form at the
    points whose family is complete and the standard one at the bar's ends. Returns the energy
    left of x = 150 h at time T over the total, and the total over the initial energy."""
    G = gradient(x, delta)
    n = len(x)
    interior = (x >= 6) & (x <= n - 7)
    A = np.where(interior[:, None], G @ G, -(G.T @ G)) if partial_stress else -(G.T @ G)
    s, x0 = 8.0, 100.0
    u = 1e-3 * np.exp(-((x - x0) / s) ** 2)
    v = 2e-3 * (x - x0) / s**2 * np.exp(-((x - x0) / s) ** 2)  # v = -c du/dx, c = 1

    def energy():
        return 0.5 * v**2 + 0.5 * (G @ u) ** 2

    e0 = energy().sum()
    a, t = A @ u, 0.0
    while t < T:
        v += 0.5 * dt * a
        u += dt * v
        a = A @ u
        v += 0.5 * dt * a
        t += dt
    e = energy()
    return e[x < 150].sum() / e.sum(), e.sum() / e0


x = np.arange(200.0)
for length in (20, 60):
    G = gradient(x, taper(x, 80, length))
    g_ps, w_ps = growth(G @ G)
    g_st, _ = growth(-(G.T @ G))
    print("taper over %d spacings: partial stress: largest growth rate %.4f c/h (largest "
          "frequency %.3f c/h); standard: %.1e c/h" % (length, g_ps, w_ps, g_st))

x = np.arange(400.0)
for name, delta in (("constant 3.01 h", np.full(len(x), 3.01)),
                    ("3.01 h -> 1.01 h over 20 h", taper(x, 180, 20))):
    for ps in (False, True):
        left, gain = pulse(x, delta, ps)
        print("1-D pulse, %s, %s: energy left behind %.2e of the total; total / initial %.3f"
              % (name, "partial stress" if ps else "standard", left, gain))
