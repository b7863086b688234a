"""perifem.basis (the statistics of a campaign) against published values and Monte Carlo:
  1. the normal tolerance factors k_B, k_A against CMH-17-1G's table (Vol. 1, Ch. 8, the one-sided
     tolerance factors; printed to 3 decimals, transcribed in cmstatr's test suite) within 0.002,
     and against the values Natrella's tables give for n = 10, 20, 30 within 0.0005; against
     scipy's noncentral t quantile (Boost) within 1e-6 when scipy is there;
  2. CMH-17-1G's closed-form k approximations within 0.25 % of k for n >= 15;
  3. the B- and A-basis values STAT-17 (the handbook's program) gives for an 18-value sample,
     normal, lognormal and Weibull (quoted in cmstatr's test suite);
  4. the Weibull maximum-likelihood fit: the likelihood's gradient is 0 at the fit, and a large
     sample gives back the shape and scale it was drawn with;
  5. Monte Carlo: of 2000 samples (fixed seed) of a normal population (n = 10) and of a Weibull
     population (n = 15), the fraction whose B-basis value lies below the population's 10th
     percentile, and whose A-basis value below its 1st percentile, is 95 % +- 1.5 % (three
     binomial standard deviations: sqrt(0.95 0.05 / 2000) = 0.49 %).
usage: python3 test_basis.py   (PYTHONPATH holds the package)"""
import math
import sys

import numpy as np

from perifem import basis

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


# 1. CMH-17-1G's k_B and k_A (n: k_B, k_A)
CMH17 = {2: (20.581, 37.094), 3: (6.157, 10.553), 4: (4.163, 7.042), 5: (3.408, 5.741), 6: (3.007, 5.062),
         8: (2.583, 4.354), 10: (2.355, 3.981), 15: (2.069, 3.520), 20: (1.927, 3.295), 25: (1.839, 3.158),
         30: (1.778, 3.064), 40: (1.698, 2.941), 50: (1.646, 2.862), 75: (1.570, 2.748), 100: (1.527, 2.684)}
NATRELLA = {10: (2.355, 3.981), 20: (1.926, 3.295), 30: (1.777, 3.064)}
k = {n: (basis.k_factor(n, basis.B_BASIS), basis.k_factor(n, basis.A_BASIS)) for n in CMH17}
worst = max(max(abs(k[n][0] - t[0]), abs(k[n][1] - t[1])) for n, t in CMH17.items())
check(worst <= 0.002, "k_B, k_A of n = 2 ... 100 within 0.002 of CMH-17-1G's table (largest difference %.4f)" % worst)
worst = max(max(abs(k[n][0] - t[0]), abs(k[n][1] - t[1])) for n, t in NATRELLA.items())
check(worst <= 0.0005, "k_B, k_A of n = 10, 20, 30 within 0.0005 of Natrella's (largest difference %.5f)" % worst)
try:
    import warnings
    from scipy.stats import nct, norm
    warnings.simplefilter("ignore", RuntimeWarning)  # scipy's nct.ppf warns of precision at small n
except ImportError:
    print("skip  scipy's noncentral t (scipy is not installed)")
else:
    worst = 0.0
    for n in (2, 3, 5, 10, 20, 50, 137):
        for p, j in ((0.90, 0), (0.99, 1)):
            exact = nct.ppf(0.95, n - 1, norm.ppf(p) * math.sqrt(n)) / math.sqrt(n)
            worst = max(worst, abs((k[n][j] if n in k else basis.k_factor(n, p)) - exact))
    check(worst < 1e-6, "k_B, k_A equal to scipy's noncentral t quantile within 1e-6 (largest %.2g)" % worst)

# 2. the closed forms
worst = max(max(abs(basis.k_factor_approx(n, basis.B_BASIS) / k[n][0] - 1),
                abs(basis.k_factor_approx(n, basis.A_BASIS) / k[n][1] - 1)) for n in k if n >= 15)
check(worst < 0.0025,
      "CMH-17-1G's closed-form k_B, k_A within 0.25 %% of k for n >= 15 (largest %.3f %%)" % (100 * worst))

# 3. STAT-17's basis values of one sample
SAMPLE = [137.4438, 139.5395, 150.89, 141.4474, 141.8203, 151.8821, 143.9245, 132.9732, 136.6419, 138.1723,
          148.7668, 143.283, 143.5429, 141.7023, 137.4732, 152.338, 144.1589, 128.5218]
s = basis.summary(SAMPLE)
for key, published, tol in (("normal_B", 129.287, 0.0005), ("normal_A", 120.336, 0.0005),
                            ("lognormal_B", 129.664, 0.0005), ("lognormal_A", 121.710, 0.0005),
                            ("weibull_B", 125.441, 0.00001), ("weibull_A", 109.150, 0.00001)):
    check(abs(s[key] / published - 1) <= tol, "%s of the 18-value sample %.4f, STAT-17 %.3f (relative tolerance %g)"
          % (key, s[key], published, tol))

# 4. the Weibull fit
a, b = basis.weibull_fit(SAMPLE)
x = np.array(SAMPLE)
d_shape = x.size / a + np.sum(np.log(x / b)) - np.sum((x / b) ** a * np.log(x / b))
d_scale = (a / b) * (np.sum((x / b) ** a) - x.size)
check(abs(d_shape) < 1e-6 * x.size and abs(d_scale * b) < 1e-6 * x.size,
      "the log-likelihood's gradient at the fit (%.2g, %.2g) is 0" % (d_shape, d_scale * b))
rng = np.random.default_rng(2024)
a, b = basis.weibull_fit(100.0 * rng.weibull(20.0, 20000))
check(abs(a / 20 - 1) < 0.02 and abs(b / 100 - 1) < 0.002,
      "20,000 draws of Weibull(shape 20, scale 100) fit as shape %.3f, scale %.3f" % (a, b))

# 5. Monte Carlo coverage
rng = np.random.default_rng(12345)
n, mu, sigma = 10, 100.0, 5.0
x = rng.normal(mu, sigma, (2000, n))
kb, ka = k[n]
m, sd = x.mean(axis=1), x.std(axis=1, ddof=1)
for name, kk, p in (("B", kb, 0.10), ("A", ka, 0.01)):
    cover = float(np.mean(m - kk * sd < mu + sigma * basis.normal_quantile(p)))
    check(abs(cover - 0.95) <= 0.015,
          "normal, n = %d: %s-basis below the population's %g %% point in %.2f %% of 2000 samples"
          % (n, name, 100 * p, 100 * cover))
n, shape, scale = 15, 20.0, 100.0
fits = [basis.weibull_fit(scale * rng.weibull(shape, n)) for _ in range(2000)]
for name, p in (("B", 0.90), ("A", 0.99)):
    truth = scale * (-math.log(p)) ** (1 / shape)
    cover = float(np.mean([basis.weibull_basis_of_fit(a, b, n, p) < truth for a, b in fits]))
    check(abs(cover - 0.95) <= 0.015,
          "Weibull, n = %d: %s-basis below the population's %g %% point in %.2f %% of 2000 samples"
          % (n, name, 100 * (1 - p), 100 * cover))

# degenerate samples
s = basis.summary([3.0, 3.0, 3.0])
check(s["std"] == 0 and s["cov"] == 0 and s["normal_B"] == 3 and abs(s["lognormal_B"] - 3) < 1e-12
      and s["weibull_B"] == 3,
      "equal values: std 0, CoV 0, every basis value the value")
sys.exit(1 if failures else 0)
