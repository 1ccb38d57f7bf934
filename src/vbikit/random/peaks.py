"""The largest value of a non-stationary Gaussian response during a crossing, from its mean and
standard-deviation histories (pure statistics: no models).

Up-crossing rate (Rice 1944, §3.3, extended to a time-varying mean and variance, e.g. Lutes &
Sarkani 2004, "Random Vibrations", §7.2): for Z(t) Gaussian with mean μ(t), standard deviation
σ(t), rate standard deviation σ̇(t) = σ_Ż and correlation ρ(t) of Z and Ż, the mean rate of
up-crossings of the level b is

    ν_b(t) = φ(η)/σ · [s φ(m/s) + m Φ(m/s)],   η = (b − μ)/σ,
    m = μ̇ + ρ σ_Ż η,   s = σ_Ż √(1 − ρ²)

(φ, Φ: standard normal density and distribution; m, s the mean and standard deviation of Ż
given Z = b).

Vanmarcke's correction (Vanmarcke 1975, J. Appl. Mech. 42:215–220) removes the crossings that
come in clumps in a narrow-band process: with the bandwidth q = √(1 − λ₁²/(λ₀λ₂)) of the
spectral moments λ₀ = σ², λ₂ = σ_Ż², λ₁ (non-stationary: λ₁(t) = Σ_k |z̃_k||ż̃_k| over the
pseudo-excitation lines, the form of Michaelov, Sarkani & Lutes 1999, Struct. Safety 21:245)
and δ_e = q^1.2, the rate is multiplied by

    [1 − exp(−√(π/2) δ_e η)] / [1 − exp(−η²/2)]   (η > 0; capped at 1, and 1 for η ≤ 0).

Poisson assumption: the corrected crossings are independent events.  Counting them from the
start would treat the mean's own passage through b (certain when b < max μ) as a random event
missed with probability e⁻¹; so they are counted from the time t*_b at which Z is most likely
above b (largest (μ − b)/σ) in both directions — up-crossings after t*, down-crossings before
it (the up-crossings of the time-reversed process: μ̇ → −μ̇, ρ → −ρ):

    F_P(b) = Φ((b − μ(t*))/σ(t*)) · exp(−∫_{t*}^{T} ν⁺_b dt − ∫_{t₀}^{t*} ν⁻_b dt).

Assumptions (where it fails): Gaussian response (linear system, Gaussian road); the Poisson
assumption is conservative (F_P too low, the peak too high) for low levels and narrow-band
responses without the correction.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.special import ndtr

_SQRT_2PI = np.sqrt(2.0 * np.pi)


def _pdf(x: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.exp(-0.5 * x * x) / _SQRT_2PI


@dataclass(frozen=True)
class PeakDistribution:
    """F_P(b) of the peak on the levels ``levels`` (increasing); ``mean``, ``std`` and quantiles by
    integrating it."""

    levels: NDArray[np.float64]
    cdf: NDArray[np.float64]

    @property
    def mean(self) -> float:
        b, f = self.levels, self.cdf
        return float(b[0] + np.trapezoid(1.0 - f, b))

    @property
    def std(self) -> float:
        b, f = self.levels, self.cdf
        second = b[0] ** 2 + np.trapezoid(2.0 * b * (1.0 - f), b)
        return float(np.sqrt(max(second - self.mean**2, 0.0)))

    def quantile(self, p: float) -> float:
        """The level b with F_P(b) = p (linear between levels)."""
        if not 0.0 < p < 1.0:
            raise ValueError(f"quantile: p must be in (0, 1), got {p!r}")
        f = np.maximum.accumulate(self.cdf)
        return float(np.interp(p, f, self.levels))


def upcrossing_rate(level: float, mean: NDArray[np.float64], mean_rate: NDArray[np.float64], std: NDArray[np.float64],
                    rate_std: NDArray[np.float64], corr: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rice's rate ν_b(t) [1/s] of up-crossings of ``level`` (module docstring); 0 where σ = 0.
    ``level`` a float, or (levels, 1) for (levels, n_t) rates of several levels at once."""
    ok = std > 0
    sd = np.where(ok, std, 1.0)
    eta = (level - mean) / sd
    rho = np.clip(corr, -1.0, 1.0)
    m = mean_rate + rho * rate_std * eta
    s = rate_std * np.sqrt(1.0 - rho * rho)
    pos = s > 0
    ss = np.where(pos, s, 1.0)
    cond = np.where(pos, ss * _pdf(m / ss) + m * ndtr(m / ss), np.maximum(m, 0.0))
    return np.where(ok, _pdf(eta) / sd * cond, 0.0)


def vanmarcke_factor(eta: NDArray[np.float64], bandwidth: NDArray[np.float64]) -> NDArray[np.float64]:
    """Vanmarcke's clumping factor (module docstring), in [0, 1]."""
    de = np.clip(bandwidth, 0.0, 1.0) ** 1.2
    e = np.maximum(eta, 1e-12)
    ratio = -np.expm1(-np.sqrt(np.pi / 2) * de * e) / -np.expm1(-0.5 * e * e)
    return np.where(eta > 0, np.minimum(ratio, 1.0), 1.0)


#: floats (levels × time points) of one block of ``peak_distribution``'s levels: ≈ 10 arrays of 2 MB
LEVEL_BLOCK = 250_000


def peak_distribution(time: NDArray[np.float64], mean: NDArray[np.float64], std: NDArray[np.float64],
                      mean_rate: NDArray[np.float64], rate_std: NDArray[np.float64], cov: NDArray[np.float64],
                      lambda1: NDArray[np.float64] | None = None, n_levels: int = 801) -> PeakDistribution:
    """F_P of P = max_t Z(t) for Z Gaussian with the given histories (n_t,): ``mean`` μ, ``std`` σ,
    ``mean_rate`` μ̇, ``rate_std`` σ_Ż, ``cov`` Cov(Z, Ż), ``lambda1`` λ₁ (None: no Vanmarcke
    correction).  Levels from max μ − 5 max σ to max(μ + 8σ)."""
    top = float(std.max(initial=0.0))
    if top == 0.0:
        b = float(mean.max())
        return PeakDistribution(np.array([b, b + 1e-300]), np.array([1.0, 1.0]))
    random = std > 1e-9 * top
    sd = np.where(random, std, 1.0)
    rs = np.where(random, rate_std, 1.0)
    corr = np.where(random & (rate_std > 0), cov / (sd * rs), 0.0)
    if lambda1 is not None:
        q2 = np.where(random & (rate_std > 0), 1.0 - (lambda1 / (sd * rs)) ** 2, 1.0)
        bandwidth = np.sqrt(np.clip(q2, 0.0, 1.0))
    det = float(mean[~random].max()) if np.any(~random) else -np.inf  # where Z is not random it is its mean
    levels = np.linspace(float(mean.max()) - 5.0 * top, float((mean + 8.0 * std).max()), n_levels)
    cdf = np.zeros(n_levels)
    dt = np.diff(time)
    std0 = np.where(random, std, 0.0)
    steps = np.arange(dt.size)
    live = np.flatnonzero(levels >= det)  # below det: F_P = 0
    size = max(1, LEVEL_BLOCK // max(time.size, 1))
    for j0 in range(0, live.size, size):  # a block of levels at a time: (levels, n_t) arrays
        b = levels[live[j0:j0 + size], None]
        up = upcrossing_rate(b, mean, mean_rate, std0, rate_std, corr)
        down = upcrossing_rate(b, mean, -mean_rate, std0, rate_std, -corr)  # up-crossings of the reversed process
        if lambda1 is not None:
            factor = vanmarcke_factor((b - mean) / sd, bandwidth)
            up, down = up * factor, down * factor
        eta = np.where(random, (b - mean) / sd, np.inf)
        k = np.argmin(eta, axis=1)[:, None]  # per level, the time most likely to be above b
        # trapezoids of ν⁺ on the intervals after t*, of ν⁻ on those before it
        after = np.sum(np.where(steps >= k, 0.5 * (up[:, 1:] + up[:, :-1]) * dt, 0.0), axis=1)
        before = np.sum(np.where(steps < k, 0.5 * (down[:, 1:] + down[:, :-1]) * dt, 0.0), axis=1)
        cdf[live[j0:j0 + size]] = ndtr(np.take_along_axis(eta, k, axis=1)[:, 0]) * np.exp(-after - before)
    return PeakDistribution(levels, cdf)


def exceedance_probability(mean: NDArray[np.float64], std: NDArray[np.float64], level: float = 0.0) -> float:
    """The largest probability over time that a Gaussian value with ``mean`` and ``std`` is below
    ``level`` (e.g. a tire force below 0: lift-off at that instant; a lower bound of the
    probability that it happens at some time of the crossing)."""
    ok = std > 0
    p = np.where(ok, ndtr((level - mean) / np.where(ok, std, 1.0)), (mean < level).astype(float))
    return float(p.max(initial=0.0))
