"""Extreme-value fits: parameters of samples drawn from known GEV, Gumbel and GPD distributions are
recovered within the fit's own standard errors, return levels equal the closed-form quantiles of
Coles (2001), and the confidence intervals cover the true value."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from vbikit.extremes import (ExtremeFit, ExtremesError, fit_block_maxima, fit_peaks_over_threshold, return_level,
                             return_levels)


# closed forms, written out here (Coles 2001): ---------------------------------------------------
def gev_level(mu, sigma, xi, p):
    """Coles eq. 3.4: z_p = μ − σ/ξ [1 − {−ln(1 − p)}^(−ξ)] (the level exceeded with probability p)."""
    return mu - sigma / xi * (1.0 - (-math.log(1.0 - p)) ** (-xi))


def gumbel_level(mu, beta, p):
    """Coles eq. 3.5 (ξ = 0): z_p = μ − β ln{−ln(1 − p)}."""
    return mu - beta * math.log(-math.log(1.0 - p))


def gpd_level(u, sigma, xi, lam, years):
    """Coles eq. 4.13 with λ exceedances a year: x_T = u + σ/ξ [(λT)^ξ − 1]."""
    return u + sigma / xi * ((lam * years) ** xi - 1.0)


def _true_fit(distribution, theta, events_per_year, threshold=None):
    names = {"gev": ("location", "scale", "shape"), "gumbel": ("location", "scale"), "gpd": ("scale", "shape")}[distribution]
    vals = dict(zip(names, theta))
    loc = threshold if distribution == "gpd" else vals["location"]
    return ExtremeFit(distribution, loc, vals["scale"], vals.get("shape", 0.0), 0.0, np.zeros(0), events_per_year,
                      names, np.zeros((len(names), len(names))), threshold, 0)


# parameters recovered within 3 standard errors ---------------------------------------------------
@pytest.mark.parametrize("xi, seed", [(0.2, 1), (-0.2, 2)])
def test_gev_parameters_recovered(xi, seed):
    mu, sigma = 120.0, 15.0
    # scipy's genextreme takes c = −ξ: the sample is drawn with c = −xi so that its Coles shape is xi
    x = stats.genextreme.rvs(-xi, loc=mu, scale=sigma, size=400, random_state=np.random.default_rng(seed))
    fit = fit_block_maxima(x, "gev", blocks_per_year=250)
    se = fit.standard_errors
    for name, true in (("location", mu), ("scale", sigma), ("shape", xi)):
        assert abs(fit.params[name] - true) < 3 * se[name], (name, fit.params[name], se[name])
    assert np.sign(fit.shape) == np.sign(xi)          # Coles's sign, not scipy's
    assert fit.scipy_c == -fit.shape
    assert 0.01 < se["shape"] < 0.1                   # the SE itself is of the expected size (≈ 0.04 for n = 400)
    if xi < 0:                                        # bounded above at μ − σ/ξ ≥ the largest maximum
        assert fit.location - fit.scale / fit.shape >= x.max()


def test_gumbel_parameters_recovered():
    mu, beta = 50.0, 4.0
    x = stats.gumbel_r.rvs(loc=mu, scale=beta, size=300, random_state=np.random.default_rng(3))
    fit = fit_block_maxima(x, "gumbel", blocks_per_year=52)
    se = fit.standard_errors
    assert abs(fit.location - mu) < 3 * se["location"]
    assert abs(fit.scale - beta) < 3 * se["scale"]
    # Gumbel asymptotic SEs (Coles §3.3.2 information; known closed form): se(μ) ≈ 1.053 β/√n, se(β) ≈ 0.780 β/√n
    assert se["location"] == pytest.approx(1.053 * beta / math.sqrt(300), rel=0.1)
    assert se["scale"] == pytest.approx(0.780 * beta / math.sqrt(300), rel=0.1)


@pytest.mark.parametrize("xi, seed", [(0.1, 4), (-0.2, 5)])
def test_gpd_parameters_recovered_and_exceedance_rate(xi, seed):
    rng = np.random.default_rng(seed)
    u, sigma = 10.0, 2.0
    above = u + stats.genpareto.rvs(xi, scale=sigma, size=500, random_state=rng)   # scipy's genpareto c = +ξ
    below = rng.uniform(0.0, u, size=1500)
    values = rng.permutation(np.concatenate([above, below]))
    fit = fit_peaks_over_threshold(values, threshold=u, rate_per_year=400.0)
    se = fit.standard_errors
    assert abs(fit.scale - sigma) < 3 * se["scale"]
    assert abs(fit.shape - xi) < 3 * se["shape"]
    assert fit.scipy_c == fit.shape
    # λ = 400 values a year × 500 exceedances / 2000 values = 100 a year
    assert fit.events_per_year == pytest.approx(100.0)
    assert fit.sample.size == 500 and fit.threshold == u


# return levels against closed forms ------------------------------------------------------------
# the fits are scipy's maximum likelihood: the same optimum as scipy's own generic ``fit`` -----------
# scipy's ``fit`` (Nelder–Mead) stops at absolute tolerances of 1e-4 on the parameters and on −log L,
# and from its own moment guess alone can stop far off (here at ξ = −4 on one sample), so the
# reference is the best, by likelihood, of scipy's fits from its guess and from Gumbel starts with
# c = 0, ±0.2 (GPD: from its guess and c = ±0.1).  vbikit starts from L-moments and stops tighter.
# Both must land on the same optimum: location and scale within 1e-3 σ, ξ within 1e-3, and our
# log-likelihood no lower than scipy's by more than 1e-7 of it.  The samples are drawn in units
# where scipy's absolute tolerances are fine (σ = 10) and fitted by vbikit also in metres-like units
# (×1e-4: the fit is equivariant, so its parameters scale back), which scipy's tolerances would not resolve.
def _best(dist, x, fits):
    return min(fits, key=lambda p: dist.nnlf(p, x))


@pytest.mark.parametrize("xi, n, seed", [(-0.3, 40, 21), (0.004, 25, 24), (0.15, 150, 25), (0.35, 60, 26)])
def test_gev_fit_is_scipy_maximum_likelihood(xi, n, seed):
    x = stats.genextreme.rvs(-xi, loc=200.0, scale=10.0, size=n, random_state=np.random.default_rng(seed))
    mu0, s0 = stats.gumbel_r.fit(x)
    c, loc, scale = _best(stats.genextreme, x, [stats.genextreme.fit(x)]
                          + [stats.genextreme.fit(x, c0, loc=mu0, scale=s0) for c0 in (0.0, 0.2, -0.2)])
    ref_loglik = -stats.genextreme.nnlf((c, loc, scale), x)
    for unit in (1.0, 1e-4):
        fit = fit_block_maxima(x * unit, "gev")
        assert fit.shape == pytest.approx(-c, abs=1e-3)
        assert fit.location / unit == pytest.approx(loc, abs=1e-3 * scale)
        assert fit.scale / unit == pytest.approx(scale, abs=1e-3 * scale)
        assert fit.loglik + n * math.log(unit) >= ref_loglik - 1e-7 * abs(ref_loglik)


@pytest.mark.parametrize("xi, n, seed", [(-0.3, 30, 31), (-0.002, 200, 32), (0.25, 80, 33)])
def test_gpd_fit_is_scipy_maximum_likelihood(xi, n, seed):
    x = 50.0 + stats.genpareto.rvs(xi, scale=10.0, size=n, random_state=np.random.default_rng(seed))
    y = x - 50.0
    c, _, scale = _best(stats.genpareto, y, [stats.genpareto.fit(y, floc=0.0)]
                        + [stats.genpareto.fit(y, c0, floc=0.0, scale=y.mean()) for c0 in (0.1, -0.1)])
    ref_loglik = -stats.genpareto.nnlf((c, 0.0, scale), y)
    for unit in (1.0, 1e-4):
        fit = fit_peaks_over_threshold(x * unit, 50.0 * unit, rate_per_year=10.0)
        assert fit.shape == pytest.approx(c, abs=1e-3)
        assert fit.scale / unit == pytest.approx(scale, abs=1e-3 * scale)
        assert fit.loglik + n * math.log(unit) >= ref_loglik - 1e-7 * abs(ref_loglik)


@pytest.mark.parametrize("years", [75.0, 100.0, 1000.0])
def test_return_levels_of_the_true_distributions(years):
    n = 250.0                                    # daily maxima of 250 working days a year
    p = 1.0 / (years * n)
    gev = _true_fit("gev", (120.0, 15.0, 0.2), n)
    assert return_level(gev, years) == pytest.approx(gev_level(120.0, 15.0, 0.2, p), rel=1e-10)
    gev_neg = _true_fit("gev", (120.0, 15.0, -0.25), n)
    assert return_level(gev_neg, years) == pytest.approx(gev_level(120.0, 15.0, -0.25, p), rel=1e-10)
    gum = _true_fit("gumbel", (50.0, 4.0), n)
    assert return_level(gum, years) == pytest.approx(gumbel_level(50.0, 4.0, p), rel=1e-10)
    gpd = _true_fit("gpd", (2.0, 0.1), 100.0, threshold=10.0)
    assert return_level(gpd, years) == pytest.approx(gpd_level(10.0, 2.0, 0.1, 100.0, years), rel=1e-10)
    # the inverse
    assert gum.return_period(return_level(gum, years)) == pytest.approx(years, rel=1e-8)


def test_fitted_return_level_ci_contains_the_true_level():
    mu, sigma, xi, n = 120.0, 15.0, 0.1, 250.0
    x = stats.genextreme.rvs(-xi, loc=mu, scale=sigma, size=500, random_state=np.random.default_rng(11))
    fit = fit_block_maxima(x, "gev", blocks_per_year=n)
    periods = np.array([75.0, 100.0, 1000.0])
    level, lo, hi = return_levels(fit, periods, ci=0.95)
    true = np.array([gev_level(mu, sigma, xi, 1 / (t * n)) for t in periods])
    assert np.all(lo < true) and np.all(true < hi)
    assert np.all(lo < level) and np.all(level < hi)
    blo, bhi = return_levels(fit, periods, method="bootstrap", n_boot=60, seed=5)[1:]
    assert np.all(blo < true) and np.all(true < bhi)
    # seeded: the same seed gives the same interval
    np.testing.assert_array_equal(return_levels(fit, periods, method="bootstrap", n_boot=60, seed=5)[1], blo)


def test_delta_method_coverage_of_gumbel_return_levels():
    # 40 seeded samples of 100 annual-style maxima: the 95 % interval of the 100-year level should
    # hold the true level in at least 85 % of them (34 of 40)
    mu, beta, n, years = 50.0, 4.0, 52.0, 100.0
    true = gumbel_level(mu, beta, 1.0 / (years * n))
    rng = np.random.default_rng(2026)
    hits = 0
    for _ in range(40):
        x = stats.gumbel_r.rvs(loc=mu, scale=beta, size=100, random_state=rng)
        _, lo, hi = return_levels(fit_block_maxima(x, "gumbel", blocks_per_year=n), [years])
        hits += bool(lo[0] < true < hi[0])
    assert hits >= 34, hits


@pytest.mark.parametrize("xi", [0.1, -0.2])
def test_delta_method_coverage_of_gev_return_levels(xi):
    # 40 seeded samples of 300 daily maxima (250 a year): the 95 % interval of the 100-year level
    # holds the true GEV quantile (Coles eq. 3.4) in at least 34 of 40
    mu, sigma, n, years = 100.0, 10.0, 250.0, 100.0
    true = gev_level(mu, sigma, xi, 1.0 / (years * n))
    rng = np.random.default_rng(7)
    hits = 0
    for _ in range(40):
        x = stats.genextreme.rvs(-xi, loc=mu, scale=sigma, size=300, random_state=rng)
        _, lo, hi = return_levels(fit_block_maxima(x, "gev", blocks_per_year=n), [years])
        hits += bool(lo[0] < true < hi[0])
    assert hits >= 34, hits


# bad input -------------------------------------------------------------------------------------
def test_bad_input_raises_naming_the_argument():
    rng = np.random.default_rng(0)
    good = rng.gumbel(size=50)
    cases = [
        (lambda: fit_block_maxima(good[:4], "gev"), "maxima"),
        (lambda: fit_block_maxima(np.r_[good, np.nan], "gumbel"), "maxima"),
        (lambda: fit_block_maxima(np.r_[good, np.inf], "gev"), "maxima"),
        (lambda: fit_block_maxima(good, "weibull"), "distribution"),
        (lambda: fit_block_maxima(good, "gev", blocks_per_year=0), "blocks_per_year"),
        (lambda: fit_peaks_over_threshold(good, threshold=good.max() + 1, rate_per_year=10), "threshold"),
        (lambda: fit_peaks_over_threshold(good, threshold=np.sort(good)[-3], rate_per_year=10), "threshold"),
        (lambda: fit_peaks_over_threshold(good, threshold=0.0, rate_per_year=-1), "rate_per_year"),
        (lambda: return_level(fit_block_maxima(good, "gumbel", blocks_per_year=1), 0.5), "period_years"),
        # T·n = 1 is G⁻¹(0) = −∞ for block maxima (annual maxima, T = 1 year; daily maxima, T = 1 day)
        (lambda: return_level(fit_block_maxima(good, "gumbel", blocks_per_year=1), 1.0), "period_years"),
        (lambda: return_levels(fit_block_maxima(good, "gev", blocks_per_year=365), [1 / 365, 10]), "periods"),
        (lambda: return_levels(fit_block_maxima(good, "gumbel"), [100], ci=1.5), "ci"),
        (lambda: return_levels(fit_block_maxima(good, "gumbel"), [100], method="profile"), "method"),
        (lambda: return_levels(fit_block_maxima(good, "gumbel"), [-5]), "periods"),
    ]
    for call, key in cases:
        with pytest.raises(ExtremesError) as err:
            call()
        assert err.value.key == key, (key, str(err.value))


def test_pot_return_level_at_one_exceedance_a_year_is_the_threshold():
    # Coles eq. 4.13 at λT = 1: x = u + σ/ξ (1^ξ − 1) = u (defined, unlike T·n = 1 for block maxima)
    gpd = _true_fit("gpd", (2.0, 0.1), 4.0, threshold=10.0)
    assert return_level(gpd, 0.25) == pytest.approx(10.0, abs=1e-12)
