"""Statistics of a sample for material allowables: mean, standard deviation, coefficient of
variation, and the B-basis (90 % of the population above it, with 95 % confidence) and A-basis
(99 %, 95 %) values as one-sided lower tolerance limits, for the normal and for the two-parameter
Weibull distribution, as the Composite Materials Handbook CMH-17-1G (Vol. 1, Ch. 8, §8.3.4 and
§8.3.5) defines them. numpy and the standard library only (docs/library.md, "Campaigns").

Normal:  basis = mean - k s (lognormal: the same of ln x, back-transformed),  k = t'_{conf}(n - 1, z_p sqrt(n)) / sqrt(n), the quantile of the
         noncentral t distribution, computed here by quadrature and bisection (Owen 1968;
         Natrella 1963, Table A-7).
Weibull: maximum-likelihood shape a and scale b; basis = q exp(-V / (a sqrt(n))),
         q = b (-ln p)^(1/a), V from CMH-17-1G's approximations (eq. 8.3.5.2(b), (c))."""
import math

import numpy as np

B_BASIS = 0.90  # the fraction of the population above the B-basis value
A_BASIS = 0.99
CONFIDENCE = 0.95


def normal_cdf(x):
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def normal_quantile(p):
    """z with normal_cdf(z) = p, 0 < p < 1 (Newton from a bracketing bisection)."""
    if not 0.0 < p < 1.0:
        raise ValueError("a probability in (0, 1), not %r" % (p,))
    lo, hi = -40.0, 40.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if normal_cdf(mid) < p:
            lo = mid
        else:
            hi = mid
    z = 0.5 * (lo + hi)
    for _ in range(3):
        z -= (normal_cdf(z) - p) / (math.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi))
    return z


def _scaled_chi_grid(nu, points=4001):
    """Nodes s and Simpson weights w (density included) for s = sqrt(chi2_nu / nu): sum(w f(s))
    approximates E f(s)."""
    upper = 1.0 + 12.0 / math.sqrt(2.0 * nu) + 2.0
    s = np.linspace(0.0, upper, points)
    h = s[1] - s[0]
    simpson = np.ones(points)
    simpson[1:-1:2], simpson[2:-1:2] = 4.0, 2.0
    log_density = np.full(points, -np.inf)
    pos = s > 0
    log_density[pos] = (math.log(2.0) + 0.5 * nu * math.log(0.5 * nu) - math.lgamma(0.5 * nu)
                        + (nu - 1.0) * np.log(s[pos]) - 0.5 * nu * s[pos] ** 2)
    if nu == 1:
        log_density[0] = math.log(2.0) + 0.5 * math.log(0.5) - math.lgamma(0.5)
    return s, simpson * h / 3.0 * np.exp(log_density)


def _expected_phi(t, delta, s, w):
    """sum(w Phi(t s - delta)): P(T <= t) over the grid of _scaled_chi_grid."""
    x = (t * s - delta) / math.sqrt(2.0)
    return float(np.sum(w * 0.5 * np.array([math.erfc(-v) for v in x])))


def noncentral_t_cdf(t, nu, delta):
    """P(T <= t) for T = (Z + delta) / sqrt(chi2_nu / nu), Z standard normal: the expectation
    over s = sqrt(chi2_nu / nu) of Phi(t s - delta)."""
    return _expected_phi(t, delta, *_scaled_chi_grid(nu))


def noncentral_t_quantile(q, nu, delta):
    """t with noncentral_t_cdf(t, nu, delta) = q (bisection, 1e-10 relative)."""
    s, w = _scaled_chi_grid(nu)

    def cdf(t):
        return _expected_phi(t, delta, s, w)

    lo, hi = delta - 10.0, delta + 10.0
    while cdf(lo) > q:
        lo -= 2.0 * (hi - lo)
    while cdf(hi) < q:
        hi += 2.0 * (hi - lo)
    while hi - lo > 1e-10 * max(1.0, abs(hi)):
        mid = 0.5 * (lo + hi)
        if cdf(mid) < q:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def k_factor(n, p=B_BASIS, conf=CONFIDENCE):
    """The one-sided normal tolerance factor: mean - k s of a sample of n lies below the
    population's 100 (1 - p) % percentile with probability conf (p of the population above)."""
    if n < 2:
        raise ValueError("a tolerance factor needs n >= 2, not %r" % (n,))
    return noncentral_t_quantile(conf, n - 1, normal_quantile(p) * math.sqrt(n)) / math.sqrt(n)


def k_factor_approx(n, p=B_BASIS):
    """CMH-17-1G's closed forms of k (eq. 8.3.5.1(c), (d)), B- (p = 0.90) or A-basis (0.99)."""
    if p == B_BASIS:
        return 1.282 + math.exp(0.958 - 0.520 * math.log(n) + 3.19 / n)
    if p == A_BASIS:
        return 2.326 + math.exp(1.34 - 0.522 * math.log(n) + 3.87 / n)
    raise ValueError("the approximation is for p = 0.90 or 0.99, not %r" % (p,))


def weibull_v(n, p=B_BASIS):
    """CMH-17-1G's approximations of V for the Weibull basis value (eq. 8.3.5.2(b), (c))."""
    if p == B_BASIS:
        return 3.803 + math.exp(1.79 - 0.516 * math.log(n) + 5.1 / (n - 1))
    if p == A_BASIS:
        return 6.649 + math.exp(2.55 - 0.526 * math.log(n) + 4.76 / n)
    raise ValueError("the approximation is for p = 0.90 or 0.99, not %r" % (p,))


def weibull_fit(x):
    """Maximum-likelihood (shape, scale) of a two-parameter Weibull sample (positive values):
    the shape a solves sum(x^a ln x) / sum(x^a) - 1/a - mean(ln x) = 0 (increasing in a;
    bisection), the scale is mean(x^a)^(1/a). Values all equal: shape inf, scale the value."""
    x = np.asarray(x, dtype=float)
    if x.size < 2 or np.any(x <= 0) or not np.all(np.isfinite(x)):
        raise ValueError("a Weibull fit needs 2 or more positive finite values")
    y = np.log(x / np.exp(np.mean(np.log(x))))  # ln of x over its geometric mean: mean(y) = 0
    if np.ptp(y) == 0:
        return math.inf, float(x[0])

    def g(a):
        e = np.exp(a * (y - y.max()))
        return float(np.sum(e * y) / np.sum(e)) - 1.0 / a

    sd = float(np.std(y, ddof=1))
    lo = hi = 1.28 / sd  # the usual start: shape ~ pi / (sqrt(6) sd(ln x))
    while g(lo) > 0:
        lo *= 0.5
    while g(hi) < 0:
        hi *= 2.0
    while hi - lo > 1e-12 * hi:
        mid = 0.5 * (lo + hi)
        if g(mid) < 0:
            lo = mid
        else:
            hi = mid
    a = 0.5 * (lo + hi)
    # scale = mean(x^a)^(1/a) = gm exp(max y) mean(exp(a (y - max y)))^(1/a), gm the geometric mean
    gm = math.exp(float(np.mean(np.log(x))))
    return a, gm * math.exp(float(y.max())) * float(np.mean(np.exp(a * (y - y.max())))) ** (1.0 / a)


def normal_basis(x, p=B_BASIS, conf=CONFIDENCE):
    x = np.asarray(x, dtype=float)
    return float(np.mean(x) - k_factor(x.size, p, conf) * np.std(x, ddof=1))


def lognormal_basis(x, p=B_BASIS, conf=CONFIDENCE):
    """The normal basis value of ln x, back-transformed (positive values)."""
    return math.exp(normal_basis(np.log(np.asarray(x, dtype=float)), p, conf))


def weibull_basis_of_fit(shape, scale, n, p=B_BASIS):
    """CMH-17-1G's Weibull basis value of a sample of n values whose ML fit is (shape, scale)."""
    if math.isinf(shape):
        return scale
    q = scale * (-math.log(p)) ** (1.0 / shape)
    return q * math.exp(-weibull_v(n, p) / (shape * math.sqrt(n)))


def weibull_basis(x, p=B_BASIS):
    """CMH-17-1G's Weibull basis value (95 % confidence; p = 0.90 or 0.99)."""
    x = np.asarray(x, dtype=float)
    return weibull_basis_of_fit(*weibull_fit(x), x.size, p)


def summary(x):
    """{n, mean, std, cov, normal_B, normal_A, lognormal_B, lognormal_A, weibull_shape,
    weibull_scale, weibull_B, weibull_A} of a sample (std with n - 1; cov = std / |mean|, nan at
    mean 0; lognormal and Weibull entries nan unless every value is positive)."""
    x = np.asarray(x, dtype=float)
    n = x.size
    mean = float(np.mean(x)) if n else math.nan
    std = float(np.std(x, ddof=1)) if n > 1 else math.nan
    out = {"n": n, "mean": mean, "std": std, "cov": std / abs(mean) if mean else math.nan}
    out.update(dict.fromkeys(("normal_B", "normal_A", "lognormal_B", "lognormal_A", "weibull_shape", "weibull_scale",
                              "weibull_B", "weibull_A"), math.nan))
    if n < 2:
        return out
    out["normal_B"] = mean - k_factor(n, B_BASIS) * std
    out["normal_A"] = mean - k_factor(n, A_BASIS) * std
    if np.all(x > 0):
        out["lognormal_B"], out["lognormal_A"] = lognormal_basis(x, B_BASIS), lognormal_basis(x, A_BASIS)
        out["weibull_shape"], out["weibull_scale"] = weibull_fit(x)
        out["weibull_B"] = weibull_basis(x, B_BASIS)
        out["weibull_A"] = weibull_basis(x, A_BASIS)
    return out
