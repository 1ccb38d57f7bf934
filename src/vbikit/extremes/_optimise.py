"""Maximum likelihood of scipy.stats' GEV and GPD from an analytic start (L-moments).

scipy's generic ``rv_continuous.fit`` starts Nelder–Mead from a moment guess in the data's own
units and stops at absolute tolerances (1e-4 on the parameters and on −log L), so a fit of GEV
maxima needed several restarts to be safe.  Here the likelihood is still scipy's
(``genextreme.nnlf`` / ``genpareto.nnlf``, nothing is re-derived), minimised by Nelder–Mead
(``scipy.optimize.minimize``) once, from

- the L-moment estimates (Hosking 1990, *J. R. Statist. Soc. B* 52, 105–124; the probability-
  weighted moments of Hosking, Wallis & Wood 1985, *Technometrics* 27, 251–261): for the GEV
  Hosking's k from τ₃ by his rational approximation (eq. 14 of Hosking, Wallis & Wood 1985:
  c = 2/(3 + τ₃) − ln 2/ln 3, k ≈ 7.8590 c + 2.9554 c²), then σ = λ₂ k / ((1 − 2⁻ᵏ) Γ(1 + k))
  and μ = λ₁ − σ (1 − Γ(1 + k))/k; for the GPD of excesses over a known threshold
  (Hosking & Wallis 1987, *Technometrics* 29, 339–349) k = λ₁/λ₂ − 2, σ = (1 + k) λ₁.
  Hosking's k is scipy's ``genextreme`` c and minus scipy's ``genpareto`` c;
- with the start's shape pulled inside the support the data need (analytic bounds: every value
  must have 1 + ξ (z − μ)/σ > 0), so the first likelihood is finite;
- in standardised units (data minus their mean, over their standard deviation; excesses over a
  threshold only divided), so that one tolerance serves maxima in newtons and in metres alike.

A run that does not converge, or ends on a non-finite likelihood, returns None: the caller then
falls back to scipy's ``fit`` from several starts.
"""
from __future__ import annotations

import numpy as np

#: Nelder–Mead tolerances in standardised units (parameters of order one): absolute on the
#: parameters and on −log L; tighter than scipy's ``fit`` (1e-4 on both in the data's units)
XATOL = 1e-6
FATOL = 1e-9
#: the same for a bootstrap's refit from the full sample's estimate, scipy's ``fit`` tolerances: a
#: resample's estimate scatters by its standard error (of order 1/√n ≥ 1e-2 here), not by these
REFIT_XATOL = 1e-4
REFIT_FATOL = 1e-6
#: evaluations allowed to one run (a regular fit takes 60–200; a likelihood unbounded at ξ < −1
#: runs on toward its end point, and the caller's fallback takes over)
MAXFEV = 1000
#: Hosking's k is kept in this range at the start (Γ(1 + k) needs k > −1; beyond it the GEV has
#: no mean and the L-moments no meaning)
K_RANGE = (-0.9, 2.0)


def sample_l_moments(data: np.ndarray) -> tuple[float, float, float]:
    """λ₁, λ₂, λ₃ of a sample from its unbiased probability-weighted moments b₀, b₁, b₂
    (Hosking 1990, eqs. 2.3 and 2.12 with the estimators of Landwehr et al. 1979)."""
    x = np.sort(data)
    n = x.size
    j = np.arange(n, dtype=float)
    b0 = float(x.mean())
    b1 = float(np.sum(j * x)) / (n * (n - 1))
    b2 = float(np.sum(j * (j - 1) * x)) / (n * (n - 1) * (n - 2))
    return b0, 2 * b1 - b0, 6 * b2 - 6 * b1 + b0


def _inside(k: float, loc: float, scale: float, z: np.ndarray) -> float:
    """Hosking's k (= scipy's genextreme c) pulled toward 0 until every value has
    1 − k (z − μ)/σ > 0 with a margin (k = 0, the Gumbel, has no bound)."""
    hi, lo = float(z.max()) - loc, loc - float(z.min())
    if k > 0 and hi > 0:
        k = min(k, 0.9 * scale / hi)
    if k < 0 and lo > 0:
        k = max(k, -0.9 * scale / lo)
    return k


def gev_start(z: np.ndarray, l1: float, l2: float, l3: float) -> np.ndarray:
    """(c, loc, scale) of scipy's ``genextreme`` from the L-moments (module note), inside the support."""
    from scipy.special import gamma

    t3 = l3 / l2
    cc = 2.0 / (3.0 + t3) - np.log(2.0) / np.log(3.0)
    k = float(np.clip(7.8590 * cc + 2.9554 * cc * cc, *K_RANGE))
    if abs(k) < 1e-6:  # the Gumbel limit: σ = λ₂/ln 2, μ = λ₁ − γ σ
        scale = l2 / np.log(2.0)
        loc = l1 - np.euler_gamma * scale
    else:
        g = float(gamma(1.0 + k))
        scale = l2 * k / ((1.0 - 2.0 ** (-k)) * g)
        loc = l1 - scale * (1.0 - g) / k
    return np.array([_inside(k, loc, scale, z), loc, scale])


def gpd_start(y: np.ndarray, l1: float, l2: float) -> np.ndarray:
    """(c, scale) of scipy's ``genpareto`` (loc 0) from the L-moments of the excesses (module note),
    with ξ = −k below 1 and above −σ/max(y) (the upper end point beyond the largest excess)."""
    k = float(np.clip(l1 / l2 - 2.0, -0.9, K_RANGE[1]))
    scale = (1.0 + k) * l1
    if k > 0:
        k = min(k, 0.9 * scale / float(y.max()))
    return np.array([-k, scale])


def minimise_nnlf(dist, data: np.ndarray, start: np.ndarray, fixed_loc: bool, xatol: float = XATOL,
                  fatol: float = FATOL) -> np.ndarray | None:
    """Minimise scipy's ``dist.nnlf`` over (c, loc, scale), or (c, scale) with loc 0 when
    ``fixed_loc``, by Nelder–Mead from ``start`` (same layout), in standardised units, to the
    tolerances ``xatol`` (parameters) and ``fatol`` (−log L).

    Returns the parameters in the data's units, or None when the run fails (not converged, or a
    non-finite likelihood at its end)."""
    from scipy.optimize import minimize

    l1 = 0.0 if fixed_loc else float(np.mean(data))
    s = float(np.std(data))
    if not (s > 0 and np.isfinite(s)):
        return None
    z = (data - l1) / s
    if fixed_loc:
        x0 = np.array([start[0], start[1] / s])

        def f(p: np.ndarray) -> float:
            return dist.nnlf((p[0], 0.0, p[1]), z)
    else:
        x0 = np.array([start[0], (start[1] - l1) / s, start[2] / s])

        def f(p: np.ndarray) -> float:
            return dist.nnlf((p[0], p[1], p[2]), z)
    if not np.isfinite(f(x0)):
        return None

    def finite(p: np.ndarray) -> float:  # −∞ (an infinite density at an end point) is no optimum
        v = f(p)
        return v if np.isfinite(v) else np.inf

    res = minimize(finite, x0, method="Nelder-Mead", options={"xatol": xatol, "fatol": fatol, "maxfev": MAXFEV})
    if not (res.success and np.isfinite(res.fun)):
        return None
    p = res.x
    if fixed_loc:
        return np.array([p[0], p[1] * s])
    return np.array([p[0], l1 + p[1] * s, p[2] * s])
