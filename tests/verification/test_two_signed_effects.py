# A load effect whose static history takes both signs: the moment over a soft pier of a two-span
# continuous beam (12 + 18 m) sags while the truck is near the pier (the spring settles) and hogs
# while it is on the far span.  Both extremes are reported (vbikit.analysis.effects: ``opposite``,
# the summary's ``opposite_*`` keys, the flag ``sagging_over_pier``).
#
# Independent numbers: the pier moment's influence line by the force method (our own, below): the
# 30 m simply supported beam with the pier reaction R as the redundant, compatibility
# f(c, a) = R (f(c, c) + 1/k) with the closed-form flexibility of a simply supported beam
# f(x, a) = b x (L² − b² − x²)/(6 EI L), x ≤ a, b = L − a (Roark's Formulas for Stress and Strain,
# 7th ed., Table 8.1 case 1e), and M(c) = M₀(c; a) − R c (L − c)/L.  The end springs of 1e12 N/m
# (rigid in the closed form) move the pier moment by about 1e-5 of its peak (their settlement
# under 0.3 MN, 3e-7 m, against the pier's 4e-3 m).  The dynamic extremes are brute-force
# minima/maxima of the dynamic history, refined between the samples (bounded by hand).
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.checks import SMALL_STATIC_FRACTION
from vbikit.analysis.effects import effect_sign_flags, load_effect_responses, load_effect_summary
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.solve import Crossing, simulate
from vbikit.vehicle.presets import hs20_44

SPANS, PIER = (12.0, 18.0), 12.0
EI, MASS = 1.286e10, 7537.0  # Bridge 2's whole cross-section (docs/bridges.md)


def moment_influence(a, k: float, section: float = PIER):
    """M at ``section`` ≤ the pier [N m per N, sagging positive] for a downward unit load at a
    (force method, header; k = inf: a rigid pier)."""
    length, c, xs = sum(SPANS), PIER, section
    a = np.asarray(a, float)

    def flex(x, s):
        x, s = np.minimum(x, s), np.maximum(x, s)
        b = length - s
        return b * x * (length**2 - b**2 - x**2) / (6 * EI * length)

    r = flex(c, a) / (flex(c, c) + 1.0 / k)
    m0 = np.where(a >= xs, (length - a) * xs / length, a * (length - xs) / length)
    return np.where((a >= 0) & (a <= length), m0 - r * xs * (length - c) / length, 0.0)


def _run(k: float, section: float = PIER):
    beam = ContinuousBeam(SPANS, EI, MASS, n_modes=8, support_stiffness=[1e12, k, 1e12])
    res = simulate(Crossing(beam, hs20_44(), speed=60 / 3.6))
    r = load_effect_responses(res, [beam.load_effect("moment", x=section)])[0]
    wheels = res.crossing.vehicle.wheels
    x = res.front_position[:, :1] - np.array([w.offset for w in wheels])[None, :]
    closed = (moment_influence(x, k, section) * res.crossing.vehicle.static_wheel_loads()[None, :]).sum(axis=1)
    return r, closed


@pytest.fixture(scope="module")
def soft():  # k = 7e7 N/m: sagging +332 kN m, hogging −144 kN m (43 %) by the closed form
    return _run(7e7)


def test_static_history_is_the_force_method_influence_line(soft):
    r, closed = soft
    np.testing.assert_allclose(r.static, closed, atol=1e-3 * np.abs(closed).max())
    assert closed.max() > 0 > closed.min() and -closed.min() / closed.max() > SMALL_STATIC_FRACTION


def test_both_extremes_reported(soft):
    r, closed = soft
    assert r.impact.static_peak == pytest.approx(closed.max(), rel=1e-3)  # the existing keys: the largest, sagging
    assert r.two_signed and r.opposite_share == pytest.approx(-closed.min() / closed.max(), rel=2e-3)
    opp = r.opposite
    assert opp.static_peak == pytest.approx(closed.min(), rel=1e-3)
    # the dynamic minimum: the smallest sample, or the parabola's vertex through it and its neighbours
    # (``impact.smooth_vertices``), at most a step's second difference / 8 beyond it
    i = int(np.argmin(r.dynamic))
    assert 0.0 <= r.dynamic[i] - opp.dynamic_peak <= abs(r.dynamic[i - 1] - 2 * r.dynamic[i] + r.dynamic[i + 1]) / 8
    assert opp.impact_factor == pytest.approx((opp.dynamic_peak - opp.static_peak) / opp.static_peak, rel=1e-12)
    entry = load_effect_summary([r])["moment"]
    assert (entry["sense"], entry["opposite_sense"]) == ("sagging", "hogging") and entry["two_signed"]
    assert entry["opposite_static_peak"] == opp.static_peak and entry["opposite_impact_factor"] == opp.impact_factor
    assert entry["static_peak"] == r.impact.static_peak and entry["impact_factor"] == r.impact.impact_factor
    assert entry["governing"] == ("sagging" if r.dynamic.max() > -r.dynamic.min() else "hogging")
    (flag,) = effect_sign_flags([r])
    assert flag.code == "sagging_over_pier" and flag.value == pytest.approx(r.opposite_share)
    assert "hogging" in flag.message and "opposite_*" in flag.message


def test_negligible_hogging_is_flagged_not_reported():
    r, closed = _run(5e7)  # closed form: +468 kN m, −60.6 kN m (13 %)
    assert r.opposite_static_peak == pytest.approx(closed.min(), rel=1e-3)
    assert not r.two_signed and r.opposite is None
    entry = load_effect_summary([r])["moment"]
    assert "opposite_impact_factor" not in entry and entry["governing"] == "sagging"
    (flag,) = effect_sign_flags([r])
    assert flag.code == "sagging_over_pier" and "negligible" in flag.message


def test_pier_that_never_hogs_says_so_briefly():
    """A pier of 1e5 N/m barely supports the 30 m beam (its settlement under the truck's 0.3 MN would
    be metres): the moment at x = 12 m is that of a simply supported beam, sagging for every load
    position (closed form ≥ 0), so the flag says it never hogs instead of listing a zero extreme."""
    r, closed = _run(1e5)
    assert closed.min() >= 0.0 and r.opposite_static_peak == 0.0
    (flag,) = effect_sign_flags([r])
    assert flag.code == "sagging_over_pier" and flag.value == 0.0
    assert "never hogging under this vehicle" in flag.message and "negligible" not in flag.message
    assert "+0 kN" not in flag.message and " and hogging " not in flag.message


def test_rigid_pier_is_one_signed():
    r, closed = _run(np.inf)
    assert closed.max() <= 0.0 and r.impact.static_peak == pytest.approx(closed.min(), rel=1e-3)
    assert not r.two_signed and r.opposite is None and effect_sign_flags([r]) == []


def test_short_span_midspan_is_two_signed():
    # rigid pier, x = 6 m: sagging while the truck is on the short span, hogging (closed form 62 % of
    # it) while it is on the long one: both extremes, no flag (not over a pier)
    r, closed = _run(np.inf, 6.0)
    assert r.impact.static_peak == pytest.approx(closed.max(), rel=1e-3)
    assert r.opposite.static_peak == pytest.approx(closed.min(), rel=1e-3)
    assert r.governing in ("sagging", "hogging")
    assert r.opposite_share == pytest.approx(-closed.min() / closed.max(), rel=2e-3)
    assert effect_sign_flags([r]) == []
