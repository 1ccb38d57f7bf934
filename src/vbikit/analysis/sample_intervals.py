"""Confidence intervals of a sample's mean and quantiles — how well a population of events (a traffic
stream's, a lifetime's random sample) fixes the statistics quoted from it.  Numbers only.

* the mean: Student's t interval, x̄ ± t_{(1+c)/2, n−1} s/√n (s the sample standard deviation with
  n − 1); exact for normal data, asymptotically right for any finite variance;
* a quantile x_p: the distribution-free interval between two order statistics, from the binomial
  distribution of the number of observations below x_p (``scipy.stats.quantile_test``'s
  ``confidence_interval``; e.g. Conover, *Practical Nonparametric Statistics*, 3rd ed., 1999, §3.2):
  coverage at least c for any continuous distribution; an end the sample cannot bound (too few
  observations beyond x_p) is NaN.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np
from numpy.typing import ArrayLike

#: the confidence level of the intervals quoted with a population's statistics
CONFIDENCE = 0.95


@dataclass(frozen=True)
class Interval:
    """An estimate with the lower and upper ends of its ``confidence`` interval (NaN: not bounded)."""

    estimate: float
    lower: float
    upper: float
    confidence: float = CONFIDENCE

    def text(self, fmt: str = ".4f") -> str:
        """``0.1612 (95 % CI 0.1502 – 0.1722)``; an end the sample does not bound as ``?``; ``n/a`` without
        an estimate (no value in the sample)."""
        if math.isnan(self.estimate):
            return "n/a"
        end = lambda v: "?" if math.isnan(v) else format(v, fmt)  # noqa: E731
        return f"{self.estimate:{fmt}} ({self.confidence * 100:g} % CI {end(self.lower)} – {end(self.upper)})"


def mean_interval(sample: ArrayLike, confidence: float = CONFIDENCE) -> Interval:
    """The mean of the finite values of ``sample`` with its Student-t interval (NaN ends below 2 values)."""
    from scipy import stats

    x = np.asarray(sample, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return Interval(math.nan, math.nan, math.nan, confidence)
    mean = float(x.mean())
    if x.size < 2:
        return Interval(mean, math.nan, math.nan, confidence)
    half = float(stats.t.ppf(0.5 + confidence / 2, x.size - 1) * x.std(ddof=1) / math.sqrt(x.size))
    return Interval(mean, mean - half, mean + half, confidence)


def quantile_interval(sample: ArrayLike, p: float, confidence: float = CONFIDENCE) -> Interval:
    """The ``p`` quantile of the finite values of ``sample`` (numpy's default, linear interpolation) with
    the distribution-free order-statistic interval (module docstring)."""
    from scipy import stats

    x = np.asarray(sample, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return Interval(math.nan, math.nan, math.nan, confidence)
    estimate = float(np.quantile(x, p))
    if x.size < 2:
        return Interval(estimate, math.nan, math.nan, confidence)
    ci = stats.quantile_test(x, q=estimate, p=p).confidence_interval(confidence_level=confidence)
    finite = lambda v: float(v) if np.isfinite(v) else math.nan  # noqa: E731
    return Interval(estimate, finite(ci.low), finite(ci.high), confidence)


def stored_interval_text(stats: Mapping[str, Any], name: str) -> str:
    """``stats[name]`` with the ends of its interval stored beside it (``NAME_ci_lower``, ``NAME_ci_upper``:
    a dataset's attributes, a summary's facts; None reads as NaN) as ``Interval.text``; statistics
    written before the intervals (no ends stored): the number alone, "n/a" without one."""
    value = lambda key: math.nan if stats.get(key) is None else float(stats[key])  # noqa: E731
    if f"{name}_ci_lower" not in stats:
        return "n/a" if math.isnan(value(name)) else f"{value(name):.4f}"
    return Interval(value(name), value(f"{name}_ci_lower"), value(f"{name}_ci_upper")).text()
