"""Plotting positions and named return periods, by hand."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.extremes import RETURN_PERIODS, ExtremesError, exceedance_return_period, plotting_positions, return_period


def test_gringorten_and_weibull_positions_by_hand():
    x = [4.0, 1.0, 3.0, 2.0]
    g = plotting_positions(x, "gringorten", blocks_per_year=2.0)
    assert g.values.tolist() == [1.0, 2.0, 3.0, 4.0]
    expected = [(i - 0.44) / 4.12 for i in (1, 2, 3, 4)]          # Gringorten (1963): (i − 0.44)/(n + 0.12)
    np.testing.assert_allclose(g.probability, expected, rtol=1e-15)
    np.testing.assert_allclose(g.reduced_variate, [-math.log(-math.log(p)) for p in expected], rtol=1e-14)
    np.testing.assert_allclose(g.return_period, [1 / (2.0 * (1 - p)) for p in expected], rtol=1e-14)
    w = plotting_positions(x, "weibull")
    np.testing.assert_allclose(w.probability, [0.2, 0.4, 0.6, 0.8], rtol=1e-15)  # i/(n + 1)
    with pytest.raises(ExtremesError) as err:
        plotting_positions(x, "blom")
    assert err.value.key == "method"


def test_named_return_periods():
    assert return_period("aashto-75") == 75.0
    assert return_period("100-year") == 100.0
    assert return_period("eurocode-1000") == 1000.0
    # 10 % probability of exceedance in 100 years: T = 1 / (1 − 0.9^(1/100)) = 949.6 years ≈ 1000
    assert exceedance_return_period(0.10, 100.0) == pytest.approx(1.0 / (1.0 - 0.9 ** 0.01), rel=1e-14)
    assert exceedance_return_period(0.10, 100.0) == pytest.approx(949.6, abs=0.05)
    assert all(r.source for r in RETURN_PERIODS.values())
    with pytest.raises(ExtremesError) as err:
        return_period("eurocode")
    assert err.value.key == "name"
