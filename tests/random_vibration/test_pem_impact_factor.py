"""Validation (c) of the impact-factor distribution, and of the peak statistics on a closed form."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import norm

from vbikit.analysis.impact import impact_factor, static_modal_history
from vbikit.random import PseudoRoad
from vbikit.random.montecarlo import monte_carlo
from vbikit.random.peaks import peak_distribution, upcrossing_rate
from vbikit.random.response import random_response
from vbikit.road.psd import RoadPSD


def test_stationary_zero_mean_peak_is_rice_poisson():
    """Constant σ, σ_Ż, ρ = 0, zero mean: ν_b = σ_Ż/(2πσ)·exp(−b²/2σ²) (Rice) and, without the
    correction, F_P(b) = Φ(b/σ)·exp(−ν_b T) (closed forms written here)."""
    t = np.linspace(0.0, 10.0, 2001)
    sigma, sigma_dot = 2.0, 30.0
    one = np.ones_like(t)
    for b in (0.5, 3.0, 7.0):
        nu = upcrossing_rate(b, 0 * one, 0 * one, sigma * one, sigma_dot * one, 0 * one)
        assert np.allclose(nu, sigma_dot / (2 * np.pi * sigma) * np.exp(-b * b / (2 * sigma**2)), rtol=1e-12)
    dist = peak_distribution(t, 0 * one, sigma * one, 0 * one, sigma_dot * one, 0 * one, None, n_levels=2001)
    b = dist.levels
    rice = norm.cdf(b / sigma) * np.exp(-sigma_dot / (2 * np.pi * sigma) * np.exp(-b * b / (2 * sigma**2)) * 10.0)
    upper = b > 2 * sigma  # where the Poisson term is below the single-time bound
    assert np.allclose(dist.cdf[upper], rice[upper], rtol=1e-9)


def test_vanmarcke_correction_lowers_the_peak_of_a_narrow_band_process():
    """A narrow-band process (λ₁² ≈ λ₀λ₂) clumps its crossings: the corrected 95 % peak is lower."""
    t = np.linspace(0.0, 10.0, 2001)
    one = np.ones_like(t)
    plain = peak_distribution(t, 0 * one, one, 0 * one, 30 * one, 0 * one, None)
    narrow = peak_distribution(t, 0 * one, one, 0 * one, 30 * one, 0 * one, 0.99 * 30 * one)
    assert narrow.quantile(0.95) < plain.quantile(0.95) - 0.1


@pytest.mark.slow
def test_impact_factor_quantiles_within_monte_carlo_bootstrap():
    """(c) the demo (bilateral tires), class C: PEM's IM mean and 50/90/95 % quantiles (peaks of
    Gaussian histories with PEM's covariance) inside the 99 % bootstrap intervals of 1,000
    crossings' mean and empirical quantiles; the Poisson up-crossing cross-check's 90/95 % too.  Its
    median is not: the Poisson count undercounts the many chances the response has near the mean's
    peak, so the lower half of that distribution is too wide; the test pins that known bias."""
    from tests.random_vibration.test_pem_monte_carlo import _plan

    plan = _plan(20, {"model": "multipoint", "n_points": 6, "contact_length": 0.254})
    crossing, dt = plan.built.crossing, plan.run.dt
    road = PseudoRoad(RoadPSD.iso("C"))
    rr = random_response(crossing, plan.built.plan, road, dt, data=plan.run.kernel_data)
    x, y = rr.points[0].x, rr.points[0].y

    def im(r):
        return impact_factor(r.time, r.displacement(x, y), static_modal_history(r) @ r.crossing.bridge.mode_shapes(
            [x], [y])[0], r.velocity(x, y)).impact_factor

    sample = np.array(monte_carlo(crossing, road, range(1, 1001), im))
    rng = np.random.default_rng(0)
    boot = []
    for _ in range(2000):
        draw = rng.choice(sample, sample.size)
        boot.append([draw.mean(), *np.quantile(draw, [0.5, 0.9, 0.95])])
    lo, hi = np.quantile(np.array(boot), [0.005, 0.995], axis=0)
    s = rr.summary
    pem = np.array([s["impact_factor_mean"], *(s["impact_factor_quantiles"][k] for k in ("0.5", "0.9", "0.95"))])
    assert np.all((lo <= pem) & (pem <= hi)), (pem, lo, hi)
    cross = np.array([s["impact_factor_quantiles_crossings"][k] for k in ("0.5", "0.9", "0.95")])
    assert np.all((lo[2:] <= cross[1:]) & (cross[1:] <= hi[2:])), (cross, lo, hi)
    assert cross[0] < lo[1]


def _peak_cdf_level_by_level(time, mean, std, mean_rate, rate_std, cov, lambda1, n_levels):
    """``peak_distribution``'s F_P one level at a time: the module's formulas as the code evaluated
    them before the levels were blocked (vbikit 2026-12-04), kept here as the reference."""
    from scipy.special import ndtr

    from vbikit.random.peaks import vanmarcke_factor

    top = float(std.max())
    random = std > 1e-9 * top
    sd, rs = np.where(random, std, 1.0), np.where(random, rate_std, 1.0)
    corr = np.where(random & (rate_std > 0), cov / (sd * rs), 0.0)
    bandwidth = np.sqrt(np.clip(np.where(random & (rate_std > 0), 1.0 - (lambda1 / (sd * rs)) ** 2, 1.0), 0.0, 1.0))
    det = float(mean[~random].max()) if np.any(~random) else -np.inf
    levels = np.linspace(float(mean.max()) - 5.0 * top, float((mean + 8.0 * std).max()), n_levels)
    cdf, dt, std0 = np.zeros(n_levels), np.diff(time), np.where(random, std, 0.0)
    for j, b in enumerate(levels):
        if b < det:
            continue
        factor = vanmarcke_factor((b - mean) / sd, bandwidth)
        up = upcrossing_rate(b, mean, mean_rate, std0, rate_std, corr) * factor
        down = upcrossing_rate(b, mean, -mean_rate, std0, rate_std, -corr) * factor
        eta = np.where(random, (b - mean) / sd, np.inf)
        k = int(np.argmin(eta))
        after = float(np.sum(0.5 * (up[k + 1:] + up[k:-1]) * dt[k:]))
        before = float(np.sum(0.5 * (down[1:k + 1] + down[:k]) * dt[:k]))
        cdf[j] = float(ndtr(eta[k])) * np.exp(-after - before)
    return levels, cdf


@pytest.mark.parametrize("block", [1_000, 250_000])
def test_blocked_levels_equal_level_by_level(monkeypatch, block):
    """The levels evaluated in blocks (several (levels × time) arrays at once) give the F_P of the
    level-by-level loop to round-off, on a crossing-like history: a moving mean, σ zero before the
    vehicle arrives (a deterministic stretch whose maximum cuts the low levels off), ρ ≠ 0 and
    Vanmarcke's correction; blocks of a few levels and of all of them."""
    import vbikit.random.peaks as peaks

    monkeypatch.setattr(peaks, "LEVEL_BLOCK", block)
    t = np.linspace(0.0, 2.0, 1201)
    bump = np.clip(np.sin(np.pi * (t - 0.3) / 1.5), 0.0, None) * (t > 0.3)
    mean = 1e-3 * (bump + 0.05 * np.sin(20 * t) * bump) + 8e-4 * (t < 0.3)
    std = 1e-4 * bump * (1 + 0.3 * np.cos(9 * t))
    rate, rate_std = np.gradient(mean, t), 3e-3 * bump
    cov = 0.2 * std * rate_std * np.sin(5 * t)
    lambda1 = 0.8 * std * rate_std
    dist = peak_distribution(t, mean, std, rate, rate_std, cov, lambda1, n_levels=301)
    levels, cdf = _peak_cdf_level_by_level(t, mean, std, rate, rate_std, cov, lambda1, 301)
    assert np.array_equal(dist.levels, levels)
    assert np.any(cdf == 0.0) and np.any((cdf > 0.01) & (cdf < 0.99))  # both regimes are exercised
    assert np.allclose(dist.cdf, cdf, rtol=1e-12, atol=1e-15)


def test_sampled_histories_are_the_pseudo_responses_times_normal_weights():
    """``sample_displacement``: y(t) = Σ_k Re(ỹ_k(t) w_k), w_k = a_k + i b_k with a_k, b_k the
    generator's standard normals in the documented order (written here with complex numbers), and
    the study's channel subset draws the same weights, so gives the same histories of its points."""
    from vbikit.random.lines import Lines
    from vbikit.random.pem import PEMResult

    rng = np.random.default_rng(3)
    n_t, n_pt, n_lines = 40, 3, 7
    z = rng.standard_normal((n_t, n_pt, n_lines)) + 1j * rng.standard_normal((n_t, n_pt, n_lines))
    res = PEMResult(np.arange(n_t) * 0.01, Lines(np.ones(n_lines), np.ones(n_lines)),
                    lines_displacement=np.ascontiguousarray(z).view(np.float64).reshape(n_t, n_pt, 2 * n_lines))
    y = np.concatenate(list(res.sample_displacement(300, seed=5, chunk=128)))  # (300, n_t, n_pt)
    draws = np.random.default_rng(5)
    w = np.concatenate([draws.standard_normal((2 * n_lines, m)) for m in (128, 128, 44)], axis=1)
    expected = np.real(np.einsum("tpk,ks->stp", z, w[0::2] + 1j * w[1::2]))
    assert np.allclose(y, expected, rtol=1e-12, atol=1e-12)
    sub = np.concatenate([b for b in res._sample_blocks(300, seed=5, chunk=128, channels=[2, 0])], axis=2)
    assert np.allclose(np.moveaxis(sub, 2, 0), y[:, :, [2, 0]], rtol=1e-12, atol=1e-12)


def test_peaks_choice_is_checked():
    """An unknown ``peaks`` is refused naming the allowed values, before any computation."""
    from vbikit.random.response import PEAKS

    with pytest.raises(ValueError, match="peaks must be one of all, study.*'some'"):
        random_response(None, None, None, 0.01, peaks="some")
    assert set(PEAKS) == {"all", "study"}
