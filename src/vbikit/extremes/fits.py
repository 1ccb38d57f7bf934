"""Maximum-likelihood fits of block maxima (GEV, Gumbel) and of peaks over a threshold (GPD).

The likelihoods are scipy.stats' (``genextreme``, ``gumbel_r``, ``genpareto``); nothing here
writes a density.  Parameters are reported in the sign convention of Coles (2001), *An
Introduction to Statistical Modeling of Extreme Values*:

- GEV (Coles eq. 3.2): G(z) = exp{−[1 + ξ (z − μ)/σ]^(−1/ξ)}; ξ > 0 heavy upper tail
  (Fréchet type), ξ < 0 bounded above at μ − σ/ξ (Weibull type), ξ → 0 the Gumbel
  G(z) = exp{−exp[−(z − μ)/σ]} (eq. 3.3).
- GPD of the excess y = x − u over a threshold u (Coles eq. 4.2):
  H(y) = 1 − (1 + ξ y/σ)^(−1/ξ).

The maximum of the GEV and GPD likelihoods is found by one Nelder–Mead run on scipy's ``nnlf``
from the L-moment estimates (Hosking 1990; ``vbikit.extremes._optimise``), which lands on the
optimum of scipy's own ``fit`` (tested); scipy's ``fit`` from several starts remains the fallback and
decides a fit that lands at ξ < −0.5, where the likelihood is irregular.

**scipy's sign trap:** ``scipy.stats.genextreme`` uses c = −ξ (its c > 0 is the *bounded*
Weibull type), while ``scipy.stats.genpareto`` uses c = +ξ.  ``ExtremeFit.shape`` is always
Coles's ξ; ``ExtremeFit.scipy_c`` is the value scipy wants.

Standard errors come from the observed information (Coles §2.6.4): the inverse of the
numerical Hessian of scipy's negative log-likelihood at the estimate (central differences).
They are asymptotic and valid for ξ > −0.5 (Smith 1985, quoted by Coles §3.3.2).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Any

import numpy as np

from vbikit.extremes._checks import positive, sample
from vbikit.extremes.errors import ExtremesError

log = logging.getLogger(__name__)

#: fewest values accepted per distribution (three parameters need more than two)
MIN_SAMPLE = {"gev": 10, "gumbel": 5, "gpd": 10}
#: the block-maximum distributions ``fit_block_maxima`` knows
BLOCK_DISTRIBUTIONS = ("gev", "gumbel")


@dataclass(frozen=True)
class ExtremeFit:
    """A fitted extreme-value model and what is needed for return levels.

    Attributes
    ----------
    distribution : str
        ``"gev"``, ``"gumbel"`` (block maxima) or ``"gpd"`` (peaks over threshold).
    location : float
        μ of the GEV/Gumbel; for the GPD the threshold u.
    scale : float
        σ > 0 (unit of the data).
    shape : float
        ξ in Coles's convention (0 for the Gumbel); see the module note on scipy's c.
    loglik : float
        Maximised log-likelihood (scipy's ``logpdf`` summed over ``sample``; GPD: over the excesses).
    sample : numpy.ndarray
        The fitted data: the block maxima, or the values above the threshold.
    events_per_year : float
        Block maxima: blocks per year n.  POT: mean number of exceedances of the threshold per
        year λ.
    param_names : tuple of str
        Names of the estimated parameters, in the order of ``covariance``.
    covariance : numpy.ndarray
        Asymptotic covariance of the estimated parameters (inverse observed information);
        NaN where the information matrix is not positive definite.
    threshold : float or None
        The POT threshold u (None for block maxima).
    n_values : int
        Block maxima: number of maxima.  POT: number of values the exceedances were taken from.
    """

    distribution: str
    location: float
    scale: float
    shape: float
    loglik: float
    sample: np.ndarray
    events_per_year: float
    param_names: tuple[str, ...]
    covariance: np.ndarray
    threshold: float | None = None
    n_values: int = 0

    @property
    def scipy_c(self) -> float:
        """scipy's shape parameter: −ξ for ``genextreme``, +ξ for ``genpareto``, 0 for Gumbel."""
        return -self.shape if self.distribution == "gev" else self.shape

    @property
    def standard_errors(self) -> dict[str, float]:
        """Asymptotic standard error of each estimated parameter (sqrt of the covariance diagonal)."""
        diag = np.diag(self.covariance)
        return {n: float(np.sqrt(v)) if v >= 0 else float("nan") for n, v in zip(self.param_names, diag)}

    @property
    def params(self) -> dict[str, float]:
        """The estimated parameters by name (``location``, ``scale``, ``shape``)."""
        return {n: float(getattr(self, n)) for n in self.param_names}

    def frozen(self) -> Any:
        """The fitted distribution as a frozen scipy.stats object: of a block maximum
        (GEV/Gumbel), or of a value given that it exceeds the threshold (GPD, loc = u)."""
        return _frozen(self.distribution, self._theta(), self.threshold)

    def _theta(self) -> np.ndarray:
        return np.array([getattr(self, n) for n in self.param_names])

    def return_period(self, level: float) -> float:
        """Years between exceedances of ``level`` on average: 1 / (n · P[X > level]) (inverse of ``return_level``)."""
        p = float(self.frozen().sf(level))
        return float("inf") if p == 0 else 1.0 / (self.events_per_year * p)

    def to_dict(self) -> dict[str, Any]:
        """Scalars of the fit (for dataset attributes and JSON)."""
        out: dict[str, Any] = {"distribution": self.distribution, "location": self.location, "scale": self.scale,
                               "shape": self.shape, "loglik": self.loglik, "events_per_year": self.events_per_year,
                               "n_sample": int(self.sample.size), "n_values": self.n_values}
        if self.threshold is not None:
            out["threshold"] = self.threshold
        out.update({f"se_{k}": v for k, v in self.standard_errors.items()})
        return out


def _scipy(distribution: str, theta: np.ndarray, threshold: float | None) -> tuple[Any, tuple[float, ...]]:
    """The scipy.stats distribution of a block maximum (GEV/Gumbel) or of a value above the
    threshold (GPD, loc = u) and its arguments (shape first, then loc, scale) for θ."""
    from scipy import stats

    if distribution == "gev":
        mu, sigma, xi = theta
        return stats.genextreme, (-xi, mu, sigma)
    if distribution == "gumbel":
        mu, sigma = theta
        return stats.gumbel_r, (mu, sigma)
    sigma, xi = theta
    return stats.genpareto, (xi, threshold, sigma)


def _frozen(distribution: str, theta: np.ndarray, threshold: float | None) -> Any:
    dist, args = _scipy(distribution, theta, threshold)
    return dist(*args)


def _nll(distribution: str, theta: np.ndarray, data: np.ndarray, threshold: float | None) -> float:
    """scipy's negative log-likelihood −Σ log f(x) (``nnlf``); +∞ for a scale ≤ 0 or data outside the support."""
    scale = theta[1] if distribution != "gpd" else theta[0]
    if scale <= 0:
        return np.inf
    dist, args = _scipy(distribution, theta, threshold)
    val = float(dist.nnlf(args, data))
    return val if np.isfinite(val) else np.inf


def _covariance(distribution: str, theta: np.ndarray, data: np.ndarray, threshold: float | None) -> np.ndarray:
    """Inverse of the observed information: central-difference Hessian of scipy's −log L."""
    k = theta.size
    sigma = theta[1] if distribution != "gpd" else theta[0]
    names = _PARAMS[distribution]
    h = np.array([1e-3 if n == "shape" else 1e-3 * sigma for n in names])
    f0 = _nll(distribution, theta, data, threshold)
    hess = np.empty((k, k))
    for i in range(k):
        for j in range(i, k):
            if i == j:
                e = np.zeros(k)
                e[i] = h[i]
                fp = _nll(distribution, theta + e, data, threshold)
                fm = _nll(distribution, theta - e, data, threshold)
                hess[i, i] = (fp - 2 * f0 + fm) / h[i] ** 2
            else:
                ei = np.zeros(k)
                ej = np.zeros(k)
                ei[i], ej[j] = h[i], h[j]
                fpp = _nll(distribution, theta + ei + ej, data, threshold)
                fpm = _nll(distribution, theta + ei - ej, data, threshold)
                fmp = _nll(distribution, theta - ei + ej, data, threshold)
                fmm = _nll(distribution, theta - ei - ej, data, threshold)
                hess[i, j] = hess[j, i] = (fpp - fpm - fmp + fmm) / (4 * h[i] * h[j])
    if not np.all(np.isfinite(hess)):
        return np.full((k, k), np.nan)
    try:
        np.linalg.cholesky(hess)
    except np.linalg.LinAlgError:
        log.warning("%s fit: observed information not positive definite; standard errors are NaN", distribution)
        return np.full((k, k), np.nan)
    return np.linalg.inv(hess)


_PARAMS = {"gev": ("location", "scale", "shape"), "gumbel": ("location", "scale"), "gpd": ("scale", "shape")}


#: below this ξ the likelihood is irregular (Smith 1985; Coles §3.3.2) and may grow without bound
#: toward ξ < −1, where a fit's end point is the optimiser's: a fit landing there is redone as
#: scipy's ``fit`` from several starts
IRREGULAR_SHAPE = -0.5


def _fast_mle(distribution: str, data: np.ndarray, start: np.ndarray | None) -> np.ndarray | None:
    """θ (``_PARAMS`` order, Coles's ξ) of one Nelder–Mead run on scipy's likelihood from ``start``
    (to a bootstrap refit's tolerances) or, failing that, from the L-moment estimates
    (``vbikit.extremes._optimise``); None if both fail."""
    from scipy import stats

    from vbikit.extremes import _optimise

    lm = _optimise.sample_l_moments(data)
    if distribution == "gev":
        dist, fixed_loc, first = stats.genextreme, False, _optimise.gev_start(data, *lm)
        given = None if start is None else np.array([-start[2], start[0], start[1]])
    else:  # the excesses over the threshold, location 0
        dist, fixed_loc, first = stats.genpareto, True, _optimise.gpd_start(data, *lm[:2])
        given = None if start is None else np.array([start[1], start[0]])
    p = None
    if given is not None:
        p = _optimise.minimise_nnlf(dist, data, given, fixed_loc, _optimise.REFIT_XATOL, _optimise.REFIT_FATOL)
    if p is None:
        p = _optimise.minimise_nnlf(dist, data, first, fixed_loc)
    if p is None:
        return None
    return np.array([p[1], p[2], -p[0]]) if distribution == "gev" else np.array([p[1], p[0]])


def _mle(distribution: str, data: np.ndarray, start: np.ndarray | None = None) -> np.ndarray:
    """Maximum-likelihood parameters (θ in ``_PARAMS`` order, ξ in Coles's sign) of scipy's
    likelihood: ``_fast_mle`` (from ``start``, a θ, for the bootstrap's refits).  Should it fail, or
    end at ξ < ``IRREGULAR_SHAPE`` without a ``start``, scipy's ``fit`` from several starts instead,
    the best kept (the fast fit only if none of these has a finite likelihood)."""
    from scipy import stats

    if distribution == "gumbel":
        mu, sigma = stats.gumbel_r.fit(data)
        return np.array([mu, sigma])
    thr = 0.0 if distribution == "gpd" else None
    fast = _fast_mle(distribution, data, start)
    if fast is not None and (start is not None or fast[-1] >= IRREGULAR_SHAPE):
        return fast
    if distribution == "gev":
        mu0, s0 = stats.gumbel_r.fit(data)
        candidates = [stats.genextreme.fit(data)]
        for c0 in (0.0, 0.2, -0.2):
            candidates.append(stats.genextreme.fit(data, c0, loc=mu0, scale=s0))
        thetas = [np.array([loc, scale, -c]) for c, loc, scale in candidates]
    else:
        candidates = [stats.genpareto.fit(data, floc=0.0)]
        for c0 in (0.1, -0.1):
            candidates.append(stats.genpareto.fit(data, c0, floc=0.0, scale=float(np.mean(data))))
        thetas = [np.array([scale, c]) for c, _, scale in candidates]
    nlls = [_nll(distribution, t, data, thr) for t in thetas]
    best = int(np.argmin(nlls))
    if not np.isfinite(nlls[best]) and fast is not None:
        return fast
    if not np.isfinite(nlls[best]):
        raise ExtremesError(f"sample: the {distribution.upper()} maximum-likelihood fit did not converge "
                            f"(no finite likelihood); check the data")
    return thetas[best]


def fit_block_maxima(maxima: Any, distribution: str = "gev", blocks_per_year: float = 1.0) -> ExtremeFit:
    """Fit a GEV or Gumbel distribution to block maxima by maximum likelihood (scipy.stats).

    Parameters
    ----------
    maxima : array_like
        One maximum per block (e.g. per day), any unit; at least 10 (GEV) or 5 (Gumbel), finite.
    distribution : {"gev", "gumbel"}
        The model: GEV (Coles eq. 3.2) or its ξ = 0 limit, the Gumbel (eq. 3.3).
    blocks_per_year : float
        Number of blocks in a year n (365 for daily maxima of every day, 250 for working days,
        52 for weeks, 1 for annual maxima); used by the return levels.

    Returns
    -------
    ExtremeFit
        Parameters (ξ in Coles's sign), log-likelihood, standard errors, the sample.

    Raises
    ------
    ExtremesError
        Too few or non-finite maxima, an unknown distribution, blocks_per_year ≤ 0.
    """
    if distribution not in BLOCK_DISTRIBUTIONS:
        raise ExtremesError(f"distribution: unknown block-maximum distribution {distribution!r}; "
                            f"allowed: {', '.join(BLOCK_DISTRIBUTIONS)}")
    n_per_year = positive(blocks_per_year, "blocks_per_year")
    data = sample(maxima, "maxima", MIN_SAMPLE[distribution])
    theta = _mle(distribution, data)
    cov = _covariance(distribution, theta, data, None)
    loglik = -_nll(distribution, theta, data, None)
    names = _PARAMS[distribution]
    values = dict(zip(names, theta.tolist()))
    return ExtremeFit(distribution, values["location"], values["scale"], values.get("shape", 0.0), loglik,
                      data.copy(), n_per_year, names, cov, None, int(data.size))


def fit_peaks_over_threshold(values: Any, threshold: float, rate_per_year: float) -> ExtremeFit:
    """Fit a generalised Pareto distribution to the excesses over a threshold (scipy.stats.genpareto).

    Parameters
    ----------
    values : array_like
        Independent peak values (e.g. one per event or per declustered storm of events), finite.
        Those above ``threshold`` are the exceedances (at least 10 are needed).
    threshold : float
        The threshold u (same unit as the values), below the largest value.
    rate_per_year : float
        How many of ``values`` occur per year on average (Coles's n_y).  The exceedance rate is
        λ = rate_per_year · k / n (k exceedances among n values; Coles §4.3.3, ζ_u = k/n).
        When ``values`` holds only the exceedances, this is the number of exceedances per year.

    Returns
    -------
    ExtremeFit
        ``distribution="gpd"``, location = threshold, scale σ, shape ξ (= scipy's c), the
        exceedances as ``sample`` and λ as ``events_per_year``.

    Raises
    ------
    ExtremesError
        Non-finite values, a threshold at or above all values, fewer than 10 exceedances, rate ≤ 0.
    """
    data = sample(values, "values", 1)
    try:
        u = float(threshold)
    except (TypeError, ValueError):
        raise ExtremesError(f"threshold: needs a number, got {threshold!r}") from None
    if not np.isfinite(u):
        raise ExtremesError(f"threshold: needs a finite number, got {threshold!r}")
    rate = positive(rate_per_year, "rate_per_year")
    above = data[data > u]
    if above.size == 0:
        raise ExtremesError(f"threshold: {u:.6g} is at or above every value (largest {float(data.max()):.6g}); "
                            "choose a threshold below the largest values")
    if above.size < MIN_SAMPLE["gpd"]:
        raise ExtremesError(f"threshold: only {above.size} values exceed {u:.6g}; a GPD fit needs at least "
                            f"{MIN_SAMPLE['gpd']} — lower the threshold")
    excess = above - u
    if excess.min() == excess.max():
        raise ExtremesError(f"values: all {above.size} exceedances of {u:.6g} are equal; nothing to fit")
    theta = _mle("gpd", excess)
    cov = _covariance("gpd", theta, above, u)
    loglik = -_nll("gpd", theta, above, u)
    lam = rate * above.size / data.size
    return ExtremeFit("gpd", u, float(theta[0]), float(theta[1]), loglik, above.copy(), lam,
                      _PARAMS["gpd"], cov, u, int(data.size))


__all__ = ["BLOCK_DISTRIBUTIONS", "ExtremeFit", "MIN_SAMPLE", "fit_block_maxima", "fit_peaks_over_threshold"]
