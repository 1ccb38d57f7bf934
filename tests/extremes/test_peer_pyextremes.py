"""Peer check against pyextremes 2.6.1 (its own block extraction, MLE wrapper and return-period
conversion): the same return levels from the same daily series, and scipy's c = −ξ sign."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy import stats

from vbikit.extremes import fit_block_maxima, fit_peaks_over_threshold, return_levels

pd = pytest.importorskip("pandas")
pyextremes = pytest.importorskip("pyextremes")

YEAR = "365.2425D"     # pyextremes' return_period_size: blocks of one day → 365.2425 blocks a year
PERIODS = [75.0, 100.0, 1000.0]


def _series(values):
    return pd.Series(values, index=pd.date_range("2000-01-01", periods=len(values), freq="D"))


def test_block_maxima_return_levels_match_pyextremes():
    x = stats.genextreme.rvs(-0.1, loc=100, scale=10, size=730, random_state=np.random.default_rng(4))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        eva = pyextremes.EVA(_series(x))
        eva.get_extremes(method="BM", block_size="1D")
        eva.fit_model(model="MLE", distribution="genextreme")
        peer = eva.get_return_value(return_period=PERIODS, return_period_size=YEAR)[0]
    fit = fit_block_maxima(eva.extremes.values, "gev", blocks_per_year=365.2425)
    level = return_levels(fit, PERIODS)[0]
    np.testing.assert_allclose(level, peer, rtol=1e-4)           # achieved ≈ 1e-5 (optimiser tolerances)
    assert fit.shape == pytest.approx(-eva.model.fit_parameters["c"], abs=2e-3)   # scipy's c = −ξ


def test_peaks_over_threshold_return_levels_match_pyextremes():
    rng = np.random.default_rng(5)
    x = rng.normal(size=3000) + rng.exponential(size=3000)
    u = float(np.quantile(x, 0.95))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        eva = pyextremes.EVA(_series(x))
        eva.get_extremes(method="POT", threshold=u, r="1h")     # no declustering of the daily values
        eva.fit_model(model="MLE", distribution="genpareto")
        peer = eva.get_return_value(return_period=[10.0, 100.0], return_period_size=YEAR)[0]
    fit = fit_peaks_over_threshold(x, u, rate_per_year=365.2425)
    level = return_levels(fit, [10.0, 100.0])[0]
    # pyextremes takes the record length from the first to the last date (2999 days, ours 3000 values)
    np.testing.assert_allclose(level, peer, rtol=2e-4)
    assert fit.shape == pytest.approx(eva.model.fit_parameters["c"], abs=2e-3)   # genpareto's c = +ξ
