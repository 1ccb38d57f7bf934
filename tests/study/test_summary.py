"""``vbikit.study.summary.axis_means``: an output's mean by each swept axis's values, with its standard
error over the road samples — against the same numbers taken from the array by hand (numpy axes)."""
from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from vbikit.study.summary import axis_means


def test_means_and_standard_errors_by_axis_against_numpy():
    rng = np.random.default_rng(5)
    arr = rng.normal(size=(2, 3, 4))  # (speed, tire, sample): each axis's values differ
    arr[1] += 1.0
    da = xr.DataArray(arr, dims=("speed", "tire", "sample"), coords={"speed": [60, 90], "tire": ["a", "b", "c"]})
    by = {a.dim: a for a in axis_means(da)}
    assert list(by) == ["speed", "tire"]  # not the samples
    assert by["speed"].values == (60, 90) and by["tire"].values == ("a", "b", "c")
    np.testing.assert_allclose(by["speed"].means, arr.mean(axis=(1, 2)), rtol=1e-14)
    np.testing.assert_allclose(by["tire"].means, arr.mean(axis=(0, 2)), rtol=1e-14)
    # the standard error over the 4 samples of the mean over the other axis
    np.testing.assert_allclose(by["speed"].standard_error, arr.mean(axis=1).std(axis=1, ddof=1) / 2.0, rtol=1e-12)
    np.testing.assert_allclose(by["tire"].standard_error, arr.mean(axis=0).std(axis=1, ddof=1) / 2.0, rtol=1e-12)
    # the differences from the first value, paired over the samples: the per-sample difference's scatter
    per_sample = arr.mean(axis=1)  # (speed, sample)
    paired = per_sample[1] - per_sample[0]
    assert by["speed"].difference == pytest.approx((0.0, paired.mean()), abs=1e-14)
    assert by["speed"].difference_error[1] == pytest.approx(paired.std(ddof=1) / 2.0, rel=1e-12)
    assert by["speed"].difference_error[1] < by["speed"].standard_error[1]  # (the shared sample scatter cancels)


def test_without_samples_there_is_no_standard_error_and_single_values_are_skipped():
    da = xr.DataArray(np.arange(6.0).reshape(3, 1, 2), dims=("speed", "model", "tire"))
    speed, tire = axis_means(da)  # (the one-value axis "model" left out)
    assert (speed.dim, tire.dim) == ("speed", "tire")
    assert speed.means == pytest.approx((0.5, 2.5, 4.5)) and tire.means == pytest.approx((2.0, 3.0))
    assert all(math.isnan(s) for s in speed.standard_error + tire.standard_error)
