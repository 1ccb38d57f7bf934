"""``vbikit.analysis.sample_intervals``: the intervals cover the true mean and quantile as often as
they say — checked by simulation against known distributions (the truth from scipy.stats), with
binomial bounds on the count of misses."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from vbikit.analysis.sample_intervals import mean_interval, quantile_interval

TRIALS = 400


def _covered(draw, truth, interval) -> int:
    rng = np.random.default_rng(11)
    hits = 0
    for _ in range(TRIALS):
        ci = interval(draw(rng))
        hits += bool(ci.lower <= truth <= ci.upper)
    return hits


def _at_least_95_percent(hits: int) -> bool:
    # with true coverage 0.95 the count of 400 is below 368 with probability ≈ 0.1 %
    return hits >= stats.binom.ppf(0.001, TRIALS, 0.95)


@pytest.mark.parametrize("n", [30, 300])
def test_the_mean_interval_covers_the_true_mean(n):
    dist = stats.gamma(a=3.0, scale=0.1)  # skewed, like impact factors; mean 0.3
    hits = _covered(lambda rng: dist.rvs(size=n, random_state=rng), dist.mean(), mean_interval)
    assert _at_least_95_percent(hits) and hits < TRIALS  # (an interval that always covers is too wide)


@pytest.mark.parametrize("n", [100, 1000])
def test_the_quantile_interval_covers_the_true_95_percent_quantile(n):
    dist = stats.gamma(a=3.0, scale=0.1)
    truth = dist.ppf(0.95)
    hits = _covered(lambda rng: dist.rvs(size=n, random_state=rng), truth, lambda x: quantile_interval(x, 0.95))
    assert _at_least_95_percent(hits) and hits < TRIALS


def test_an_end_the_sample_cannot_bound_is_nan_and_printed_as_a_question_mark():
    ci = quantile_interval(np.arange(10.0), 0.95)  # 10 values: no order statistic above x_0.95 bounds it at 95 %
    assert ci.estimate == pytest.approx(8.55) and ci.lower <= 8.55 and math.isnan(ci.upper)
    assert ci.text(".2f").endswith("– ?)") and "95 % CI" in ci.text()
    assert math.isnan(mean_interval([1.0]).lower) and mean_interval([]).estimate != mean_interval([]).estimate
    assert mean_interval([math.nan]).text() == "n/a"  # nothing to estimate: said so, never "nan"


def test_a_stored_statistic_reads_with_its_interval_or_alone_when_written_before_the_intervals():
    from vbikit.analysis.sample_intervals import stored_interval_text

    stats = {"im_mean": 0.16123, "im_mean_ci_lower": 0.15, "im_mean_ci_upper": None, "im_q95": 0.31291}
    assert stored_interval_text(stats, "im_mean") == "0.1612 (95 % CI 0.1500 – ?)"  # (None, from JSON: unbounded)
    assert stored_interval_text(stats, "im_q95") == "0.3129"  # no ends stored: the number alone
    assert stored_interval_text({"im_q95": None}, "im_q95") == "n/a"
