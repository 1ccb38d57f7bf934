"""Return levels of a fitted extreme-value model, with confidence intervals.

The T-year return level is the level exceeded on average once in T years.

- Block maxima, n blocks a year: the (1 − 1/(T·n)) quantile of the fitted block-maximum
  distribution, z_T = G⁻¹(1 − 1/(T n)) (Coles 2001, §3.3.3, eq. 3.4 with p = 1/(T n): the
  1/p-block return level; for annual maxima n = 1), defined for T n > 1.
- Peaks over threshold with λ exceedances a year: x_T = u + σ/ξ [(λT)^ξ − 1]
  (ξ → 0: u + σ ln(λT)) — Coles §4.3.3, eq. 4.13 with m = T n_y and ζ_u = λ / n_y; that is the
  (1 − 1/(λT)) quantile of the fitted exceedance distribution, defined for λT ≥ 1.

Both are ``fit.frozen().isf(1 / (T · fit.events_per_year))``.

Confidence intervals: ``method="delta"`` (default) is the delta method of Coles §2.6.4 / §3.3.3:
Var(z_T) ≈ ∇z_Tᵀ V ∇z_T with V the fit's inverse observed information and ∇z_T by central
differences; the interval is z_T ± z_{(1+ci)/2} √Var.  ``method="bootstrap"`` resamples the
fitted sample with replacement (numpy Generator seeded with ``seed``), refits and takes the
percentile interval; for POT the exceedance rate λ is kept fixed.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.extremes._checks import open_unit
from vbikit.extremes._checks import periods as _periods
from vbikit.extremes.errors import ExtremesError
from vbikit.extremes.fits import _PARAMS, ExtremeFit, _frozen, _mle

#: the confidence-interval methods ``return_levels`` knows
CI_METHODS = ("delta", "bootstrap")


def _levels(fit: ExtremeFit, theta: np.ndarray, t: np.ndarray) -> np.ndarray:
    return np.asarray(_frozen(fit.distribution, theta, fit.threshold).isf(1.0 / (t * fit.events_per_year)), dtype=float)


def _check_periods(fit: ExtremeFit, values: Any, name: str) -> np.ndarray:
    if not isinstance(fit, ExtremeFit):
        raise ExtremesError(f"fit: needs an ExtremeFit (from fit_block_maxima or fit_peaks_over_threshold), "
                            f"got {type(fit).__name__}")
    t = _periods(values, name)
    if fit.distribution == "gpd":  # λT = 1 is the threshold itself (Coles eq. 4.13)
        short = t * fit.events_per_year < 1.0
        what, bound = "shorter than the mean interval between exceedances", "at least"
    else:  # T·n = 1 is the quantile G⁻¹(0): −∞ (or the lower end point), not a level
        short = t * fit.events_per_year <= 1.0
        what, bound = "not longer than one block", "longer than"
    if short.any():
        raise ExtremesError(f"{name}: {t[short][0]:g} years is {what} (1/{fit.events_per_year:g} year); "
                            f"the return period must be {bound} 1/{fit.events_per_year:g} year")
    return t


def return_level(fit: ExtremeFit, period_years: float) -> float:
    """The level exceeded on average once in ``period_years`` years (see the module formulas).

    Parameters
    ----------
    fit : ExtremeFit
        From ``fit_block_maxima`` or ``fit_peaks_over_threshold``.
    period_years : float
        Return period T, years (block maxima: T · events_per_year > 1; POT: ≥ 1).

    Returns
    -------
    float
        The return level, unit of the data.
    """
    t = _check_periods(fit, period_years, "period_years")
    if t.size != 1:
        raise ExtremesError("period_years: one return period here; use return_levels for several")
    return float(_levels(fit, fit._theta(), t)[0])


def return_levels(fit: ExtremeFit, periods: Any, ci: float = 0.95, method: str = "delta",
                  n_boot: int = 200, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return levels with a two-sided confidence interval.

    Parameters
    ----------
    fit : ExtremeFit
        The fitted model.
    periods : array_like
        Return periods T, years.
    ci : float
        Confidence level of the interval, in (0, 1).
    method : {"delta", "bootstrap"}
        Delta method on the observed information (fast), or a seeded nonparametric bootstrap
        with ``n_boot`` refits (percentile interval).
    n_boot : int
        Bootstrap resamples (``method="bootstrap"``), ≥ 20.
    seed : int
        Seed of the bootstrap's ``numpy.random.default_rng``.

    Returns
    -------
    level, lower, upper : numpy.ndarray
        One value per period (NaN bounds when the covariance is not available).
    """
    t = _check_periods(fit, periods, "periods")
    level_ci = open_unit(ci, "ci", "a confidence level")
    if method not in CI_METHODS:
        raise ExtremesError(f"method: unknown confidence-interval method {method!r}; allowed: {', '.join(CI_METHODS)}")
    theta = fit._theta()
    level = _levels(fit, theta, t)
    if method == "delta":
        lower, upper = _delta(fit, theta, t, level, level_ci)
    else:
        if not isinstance(n_boot, (int, np.integer)) or n_boot < 20:
            raise ExtremesError(f"n_boot: needs a whole number ≥ 20 of bootstrap resamples, got {n_boot!r}")
        lower, upper = _bootstrap(fit, t, level_ci, int(n_boot), seed)
    return level, lower, upper


def _delta(fit: ExtremeFit, theta: np.ndarray, t: np.ndarray, level: np.ndarray,
           ci: float) -> tuple[np.ndarray, np.ndarray]:
    from scipy import stats

    cov = fit.covariance
    if not np.all(np.isfinite(cov)):
        nan = np.full(t.shape, np.nan)
        return nan, nan.copy()
    grad = np.empty((theta.size, t.size))
    for i, name in enumerate(_PARAMS[fit.distribution]):
        h = 1e-5 if name == "shape" else 1e-5 * fit.scale
        e = np.zeros(theta.size)
        e[i] = h
        grad[i] = (_levels(fit, theta + e, t) - _levels(fit, theta - e, t)) / (2 * h)
    var = np.einsum("it,ij,jt->t", grad, cov, grad)
    half = stats.norm.ppf(0.5 + ci / 2) * np.sqrt(np.maximum(var, 0.0))
    return level - half, level + half


def _bootstrap(fit: ExtremeFit, t: np.ndarray, ci: float, n_boot: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    data = fit.sample if fit.distribution != "gpd" else fit.sample - fit.threshold
    draws = np.empty((n_boot, t.size))
    kept = 0
    for _ in range(n_boot):
        resample = data[rng.integers(0, data.size, data.size)]
        if resample.min() == resample.max():
            continue
        try:
            theta = _mle(fit.distribution, resample, start=fit._theta())
        except ExtremesError:
            continue
        draws[kept] = _levels(fit, theta, t)
        kept += 1
    draws = draws[:kept]
    alpha = (1.0 - ci) / 2
    return np.quantile(draws, alpha, axis=0), np.quantile(draws, 1 - alpha, axis=0)


__all__ = ["CI_METHODS", "return_level", "return_levels"]
