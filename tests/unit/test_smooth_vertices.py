"""The extremes of sampled histories between their samples (``vbikit.analysis.impact.smooth_vertices``),
against closed forms: a cosine peak between two samples (its amplitude and instant known exactly),
bounded by the three-point Lagrange remainder h³ max|y‴| / (9√3) (the largest of |(s + h) s (s − h)| / 3!
on [−h, h] is h³ / (9√3)), against the sampled peak's miss 1 − cos(2π f θ h) of the amplitude."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.impact import smooth_vertices

H = 1e-3  # step [s]
F = 20.0  # [Hz]: 50 steps a period
AMP = 3.0
T = np.arange(170, 236) * H  # 0.170 … 0.235 s: one crest (0.2004 s) and two troughs, half a period either side
T_PEAK = 0.2 + 0.37 * H  # between the samples at 0.200 and 0.201 s
BOUND = H**3 * AMP * (2 * np.pi * F) ** 3 / (9 * np.sqrt(3))


def _cosine(sign: float = 1.0) -> np.ndarray:
    return sign * AMP * np.cos(2 * np.pi * F * (T - T_PEAK))


def test_a_cosine_peak_between_samples_is_found_within_the_lagrange_bound():
    dynamic = _cosine()
    static = 5.0 + 2.0 * T  # linear: its parabola is exact at any instant
    t, d, s = smooth_vertices(T, dynamic, static, np.zeros(0))
    sampled_miss = AMP - dynamic.max()
    assert sampled_miss > 5 * BOUND  # the case is one where reading the samples misses (8.5 bounds)
    top = int(np.argmax(d))
    assert abs(d[top] - AMP) <= BOUND
    assert abs(t[top] - T_PEAK) <= 0.05 * H
    np.testing.assert_allclose(s, 5.0 + 2.0 * t, rtol=0, atol=1e-12)  # the other history read off its own parabola
    # the smallest too (a trough half a period away; the static line's extremes are at the ends: none)
    low = int(np.argmin(d))
    assert d[low] == pytest.approx(-AMP, abs=BOUND) and d[low] < dynamic.min()
    assert t.size == 2


def test_each_sense_of_each_history():
    """A static history with an interior maximum gives its own vertex, at its own instant."""
    static = -((T - 0.2111) ** 2)  # a parabola: its vertex exactly
    t, d, s = smooth_vertices(T, _cosine(-1.0), static, np.zeros(0))
    k = int(np.argmax(s))
    assert t[k] == pytest.approx(0.2111, abs=1e-12) and s[k] == pytest.approx(0.0, abs=1e-15)
    assert d[k] == pytest.approx(-AMP * np.cos(2 * np.pi * F * (0.2111 - T_PEAK)), abs=BOUND)


def test_no_vertex_where_a_kink_lies_on_the_two_steps():
    dynamic = _cosine()
    i = int(np.argmax(dynamic))
    for kink in (T[i - 1], T[i] + 0.5 * H, T[i + 1]):  # (the interval's ends included)
        t, _, _ = smooth_vertices(T, dynamic, np.zeros_like(T), np.array([kink]))
        assert not np.any(np.abs(t - T_PEAK) < H)
    t, _, _ = smooth_vertices(T, dynamic, np.zeros_like(T), np.array([T[i + 1] + 1e-9]))  # just outside
    assert np.any(np.abs(t - T_PEAK) < 0.05 * H)


def test_ends_and_flat_tops_keep_their_samples():
    rising = np.linspace(0.0, 1.0, T.size)  # extremes at the ends
    assert smooth_vertices(T, rising, rising, np.zeros(0))[0].size == 0
    flat = np.zeros(T.size)
    assert smooth_vertices(T, flat, flat, np.zeros(0))[0].size == 0
    assert smooth_vertices(T[:2], rising[:2], rising[:2], np.zeros(0))[0].size == 0
