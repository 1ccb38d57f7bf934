"""The Gumbel plot is drawn for block-maximum and peaks-over-threshold fits."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy import stats

from vbikit.extremes import ExtremesError, fit_block_maxima, fit_peaks_over_threshold, plot_gumbel


def test_gumbel_plot_files(tmp_path):
    rng = np.random.default_rng(1)
    bm = fit_block_maxima(stats.gumbel_r.rvs(loc=50, scale=4, size=120, random_state=rng), "gev", blocks_per_year=250)
    out = plot_gumbel(bm, tmp_path / "gumbel.png", unit="kN m")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pot = fit_peaks_over_threshold(10 + stats.genpareto.rvs(0.1, size=200, random_state=rng), 10.0, rate_per_year=20)
    out = plot_gumbel(pot, tmp_path / "pot.png", periods=[10, 100])
    assert out.stat().st_size > 10_000


def test_gumbel_plot_of_annual_maxima_has_finite_axes(tmp_path):
    # annual maxima (n = 1): the 1-year mark of the top axis would sit at p = 1 − 1/1 = 0, y = −∞;
    # it is left out, and a marked period with T·n ≤ 1 is refused naming ``periods``
    x = stats.gumbel_r.rvs(loc=50, scale=4, size=40, random_state=np.random.default_rng(2))
    fit = fit_block_maxima(x, "gumbel", blocks_per_year=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        out = plot_gumbel(fit, tmp_path / "annual.png")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pot = fit_peaks_over_threshold(10 + stats.genpareto.rvs(0.1, size=50, random_state=np.random.default_rng(3)),
                                   10.0, rate_per_year=2.0)
    with pytest.raises(ExtremesError) as err:
        plot_gumbel(pot, tmp_path / "pot.png", periods=[0.5, 100])
    assert err.value.key == "periods"
