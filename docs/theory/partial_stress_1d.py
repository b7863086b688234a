"""Growth rates of the partial-stress operator on a 1-D lattice with a tapering horizon
(docs/theory/coupling.md §2.4). Linear elasticity with E = rho = h = 1: the nonlocal gradient
G (G u)_i = sum_j (u_j - u_i) xi / K_i over j within delta_i, K_i = sum_j xi^2; the standard
(weak) form is a = -G^T G u, the partial-stress (strong) form a = G G u. A mode u ~ exp(i w t)
with a = -w^2 u grows when w has an imaginary part. Run: /usr/bin/python3 partial_stress_1d.py"""
import numpy as np

N, x = 200, np.arange(200.0)


def gradient(taper):
    delta = 3.01 - 2.0 * np.clip((x - 80) / taper, 0, 1)
    G = np.zeros((N, N))
    for i in range(N):
        js = [j for j in range(N) if j != i and abs(x[j] - x[i]) <= delta[i]]
        K = sum((x[j] - x[i]) ** 2 for j in js)
        for j in js:
            G[i, j] += (x[j] - x[i]) / K
            G[i, i] -= (x[j] - x[i]) / K
    return G


def growth(A):
    lam = np.linalg.eigvals(A[10:-10, 10:-10])  # away from the bar's ends
    w = np.sqrt(-lam.astype(complex))
    return np.max(np.abs(w.imag)), np.max(np.abs(w))


for taper in (20, 60):
    G = gradient(taper)
    g_ps, w_ps = growth(G @ G)
    g_st, _ = growth(-(G.T @ G))
    print("taper over %d spacings: partial stress: largest growth rate %.4f c/h (largest "
          "frequency %.3f c/h); standard: %.1e c/h" % (taper, g_ps, w_ps, g_st))
