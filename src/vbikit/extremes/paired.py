"""The ratio of two return levels fitted to paired block maxima, with a confidence interval.

Two samples of block maxima taken from the same blocks (e.g. the daily maxima of the total and
of the static load effect of the same days) give two fits θ̂_a, θ̂_b and return levels
z_a(θ̂_a), z_b(θ̂_b).  Their ratio r = z_a / z_b (the assessment dynamic ratio, ADR, when a is
the total and b the static effect) has, by the delta method (Coles 2001, §2.6.4),

    Var r ≈ ∇_a rᵀ V_a ∇_a r + ∇_b rᵀ V_b ∇_b r + 2 ∇_a rᵀ C_ab ∇_b r,
    ∇_a r = ∇z_a / z_b,   ∇_b r = −z_a ∇z_b / z_b²,

with V_a, V_b the covariances of the two estimators and C_ab their cross-covariance.  The
estimators are the roots of the stacked score equations Σ_i ψ_a(x_i) = 0, Σ_i ψ_b(y_i) = 0 of
the paired blocks i; their joint covariance is the sandwich (M-estimation; Stefanski & Boos
2002, *The Calculus of M-Estimation*, Am. Stat. 56(1), 29–38)

    Cov(θ̂_a, θ̂_b) = A⁻¹ (Σ_i ψ_i ψ_iᵀ) A⁻ᵀ,   ψ_i = (ψ_a(x_i), ψ_b(y_i)),

A block-diagonal with the two fits' observed informations (A⁻¹ = diag(V_obs,a, V_obs,b), the
fits' ``covariance``), ψ the per-block score ∇_θ log f (central differences of scipy's
``logpdf``).  The same sandwich gives V_a, V_b and C_ab, so the joint matrix is positive
semi-definite; it is the nonparametric bootstrap's covariance to first order (tested against a
brute-force bootstrap of the blocks).  Highly correlated maxima (the total a little above the
static of the same day) make the ratio much better known than each level alone; ignoring C_ab
would overstate its interval.  The interval is r ± z_{(1+ci)/2} √Var r (NaN where a fit's
covariance is not available).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vbikit.extremes._checks import open_unit
from vbikit.extremes.errors import ExtremesError
from vbikit.extremes.fits import _PARAMS, ExtremeFit, _frozen


@dataclass(frozen=True)
class LevelRatio:
    """r = z_a / z_b with its delta-method interval (module docstring)."""

    ratio: float
    lower: float
    upper: float
    standard_error: float
    correlation: float  # of the two return-level estimators (from C_ab)
    ci: float


def _level(fit: ExtremeFit, theta: np.ndarray, period: float) -> float:
    return float(_frozen(fit.distribution, theta, fit.threshold).isf(1.0 / (period * fit.events_per_year)))


def _steps(fit: ExtremeFit) -> np.ndarray:
    return np.array([1e-5 if n == "shape" else 1e-5 * fit.scale for n in _PARAMS[fit.distribution]])


def _level_gradient(fit: ExtremeFit, period: float) -> np.ndarray:
    theta, h = fit._theta(), _steps(fit)
    grad = np.empty(theta.size)
    for i in range(theta.size):
        e = np.zeros(theta.size)
        e[i] = h[i]
        grad[i] = (_level(fit, theta + e, period) - _level(fit, theta - e, period)) / (2 * h[i])
    return grad


def _scores(fit: ExtremeFit) -> np.ndarray:
    """ψ_i = ∇_θ log f(x_i; θ̂) of every fitted value, shape (n, k)."""
    theta, h = fit._theta(), _steps(fit)
    data = fit.sample
    out = np.empty((data.size, theta.size))
    for i in range(theta.size):
        e = np.zeros(theta.size)
        e[i] = h[i]
        up = _frozen(fit.distribution, theta + e, fit.threshold).logpdf(data)
        down = _frozen(fit.distribution, theta - e, fit.threshold).logpdf(data)
        out[:, i] = (up - down) / (2 * h[i])
    return out


def level_ratio(fit_a: ExtremeFit, fit_b: ExtremeFit, period: float, ci: float = 0.95) -> LevelRatio:
    """The ratio of the ``period``-year return levels of two block-maximum fits of paired blocks.

    Parameters
    ----------
    fit_a, fit_b : ExtremeFit
        Block-maximum fits (``fit_block_maxima``) of samples of equal length whose i-th values
        come from the same block.
    period : float
        Return period T [years].
    ci : float
        Confidence level of the interval, in (0, 1).

    Returns
    -------
    LevelRatio
        r = z_a / z_b, the delta-method interval with the sandwich cross-covariance (module
        docstring), its standard error and the correlation of the two level estimators.
    """
    from scipy import stats

    level_ci = open_unit(ci, "ci", "a confidence level")
    for name, fit in (("fit_a", fit_a), ("fit_b", fit_b)):
        if not isinstance(fit, ExtremeFit) or fit.distribution == "gpd":
            raise ExtremesError(f"{name}: needs a block-maximum fit (fit_block_maxima)")
    if fit_a.sample.size != fit_b.sample.size:
        raise ExtremesError(f"fit_b: the two fits need paired samples of equal length, got {fit_a.sample.size} "
                            f"and {fit_b.sample.size} maxima")
    za, zb = _level(fit_a, fit_a._theta(), period), _level(fit_b, fit_b._theta(), period)
    ratio = za / zb if zb != 0 else np.nan
    va, vb = fit_a.covariance, fit_b.covariance
    if zb == 0 or not (np.all(np.isfinite(va)) and np.all(np.isfinite(vb))):
        return LevelRatio(ratio, np.nan, np.nan, np.nan, np.nan, level_ci)
    ga, gb = _level_gradient(fit_a, period), _level_gradient(fit_b, period)
    ka = ga.size
    bread = np.zeros((ka + gb.size, ka + gb.size))
    bread[:ka, :ka], bread[ka:, ka:] = va, vb
    scores = np.concatenate([_scores(fit_a), _scores(fit_b)], axis=1)
    joint = bread @ (scores.T @ scores) @ bread
    d = np.concatenate([ga / zb, -za * gb / zb**2])
    var = float(d @ joint @ d)
    la, lb = np.concatenate([ga, np.zeros(gb.size)]), np.concatenate([np.zeros(ka), gb])
    var_a, var_b = float(la @ joint @ la), float(lb @ joint @ lb)
    corr = float(la @ joint @ lb / np.sqrt(var_a * var_b)) if var_a > 0 and var_b > 0 else np.nan
    if not np.isfinite(var) or var < 0:
        return LevelRatio(ratio, np.nan, np.nan, np.nan, corr, level_ci)
    se = float(np.sqrt(var))
    half = float(stats.norm.ppf(0.5 + level_ci / 2)) * se
    return LevelRatio(float(ratio), float(ratio - half), float(ratio + half), se, corr, level_ci)


__all__ = ["LevelRatio", "level_ratio"]
