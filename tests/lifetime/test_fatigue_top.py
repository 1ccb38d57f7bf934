"""Fatigue of a lifetime run: a stress range above the histogram's last bin is kept exactly
(not folded into the top bin), so the limit rule, the damage and the histogram agree."""
from types import SimpleNamespace

import numpy as np
import pytest

from vbikit.lifetime.jobs import Detail
from vbikit.lifetime.results import fatigue_results

MPA = 1e6


def test_one_range_above_the_fatigue_limit_counts_by_hand():
    """Two days, EN 1993-1-9 detail 36 (γ_Mf = 1), 1 MPa bins.  Day 0 closes 10 cycles of 20 MPa
    (its histogram: bin 20, the top bin of the days' histograms); the days' residuals [0, 28 MPa]
    and [0] join into the history 0 → 28 → 0 MPa: two half cycles of 28 MPa, above
    Δσ_D = (2/5)^(1/3) · 36 = 26.53 MPa.  By EN 1993-1-9 Fig. 7.1 (the limit rule of 1.3.3.3:
    one range above Δσ_D, so every range above Δσ_L counts):

        D = 1 / (2·10⁶ (Δσ_C / 28)³)  +  10 / (5·10⁶ (Δσ_D / 20)⁵)

    (m = 3 above Δσ_D, m = 5 between Δσ_L = (5/100)^(1/5) Δσ_D = 14.57 MPa and Δσ_D).  Folding
    the 28 MPa cycle into the [20, 21) MPa bin put the period below Δσ_D: static damage 0."""
    c = 36.0
    d_lim = (2 / 5) ** (1 / 3) * c
    d_20 = 10 / (5e6 * (d_lim / 20.0) ** 5)  # the day's closed damage, as the static pass stores it
    expected = 1 / (2e6 * (c / 28.0) ** 3) + d_20
    import xarray as xr

    static = xr.Dataset({
        "day_damage_closed": (("day", "detail"), np.array([[d_20], [0.0]])),
        "day_damage_alone": (("day", "detail"), np.array([[d_20], [0.0]])),
        "day_max_range": (("day", "detail"), np.array([[20.0 * MPA], [0.0]])),
        "res_day": ("res", np.array([0, 0, 1], np.int64)),
        "res_detail": ("res", np.array([0, 0, 0], np.int64)),
        "res_value": ("res", np.array([0.0, 28.0 * MPA, 0.0])),
        "hist_day": ("hist", np.array([0], np.int64)),
        "hist_detail": ("hist", np.array([0], np.int64)),
        "hist_bin": ("hist", np.array([20], np.int64)),
        "hist_count": ("hist", np.array([10.0])),
    })
    prep = SimpleNamespace(spec=SimpleNamespace(days_per_year=365, ci=0.95,
                                                fatigue=SimpleNamespace(damage_so_far=0.0, design_life=100.0)),
                           details=(Detail("d", 0, 1.0, "EN 36", 1.0, 1.0 * MPA),), n_days=2)
    got = fatigue_results(prep, static, {"sample": np.zeros(0, np.int64), "gid": np.zeros(0), "results": {}})
    v = got["variables"]
    assert v["fatigue_damage_static"][1][0] == pytest.approx(expected, rel=1e-12)
    assert v["fatigue_damage"][1][0] == pytest.approx(expected, rel=1e-12)
    assert v["below_fatigue_limit"][1][0] == 0
    hist = v["stress_range_histogram"][1][0]
    assert hist[20] == 10 and hist[28] == 1.0 and hist.sum() == 11  # the two half cycles in their own bin
    assert v["max_stress_range_static"][1][0] == 28.0 * MPA


def _days(maxima_mpa: list[float], dynamic_mpa: float, category: str):
    """``fatigue_results``' inputs for days whose static histories each close 10 cycles of their largest range
    (``maxima_mpa``), and two sampled events whose dynamic histories (largest range ``dynamic_mpa``) do differently
    small damages; a 100-year design life of 365-day years."""
    import xarray as xr

    n = len(maxima_mpa)
    static = xr.Dataset({
        "day_damage_closed": (("day", "detail"), np.full((n, 1), 1e-7)),
        "day_damage_alone": (("day", "detail"), np.full((n, 1), 1e-7)),
        "day_max_range": (("day", "detail"), np.array(maxima_mpa)[:, None] * MPA),
        "res_day": ("res", np.arange(n, dtype=np.int64)),
        "res_detail": ("res", np.zeros(n, np.int64)),
        "res_value": ("res", np.zeros(n)),
        "hist_day": ("hist", np.arange(n, dtype=np.int64)),
        "hist_detail": ("hist", np.zeros(n, np.int64)),
        "hist_bin": ("hist", np.array([int(m) for m in maxima_mpa], np.int64)),
        "hist_count": ("hist", np.full(n, 10.0)),
    })
    results = {0: {"damage_dynamic": [3e-8], "damage_static": [1e-8], "max_range_dynamic": [dynamic_mpa * MPA]},
               1: {"damage_dynamic": [9e-8], "damage_static": [1e-8], "max_range_dynamic": [dynamic_mpa * MPA]}}
    spec = SimpleNamespace(days_per_year=365, ci=0.95,
                           fatigue=SimpleNamespace(damage_so_far=0.0, design_life=100.0))
    prep = SimpleNamespace(spec=spec, details=(Detail("d", 0, 1.0, category, 1.0, 1.0 * MPA),), n_days=n)
    got = fatigue_results(prep, static, {"sample": np.array([0, 1], np.int64), "gid": np.array([0, 1]),
                                         "results": results})
    return prep, got


def test_below_the_fatigue_limit_the_damage_has_no_sampling_error():
    """AASHTO category E ((ΔF)_TH = 31 MPa): five days whose largest static ranges are 10.0 … 10.4 MPa and two
    sampled events whose dynamic histories (largest range 12 MPa) do differently small damages below the
    threshold.  Every range of the loading is below (ΔF)_TH, and so is the design life's largest (its Gumbel
    estimate, upper bound and the dynamics' 12 / 10.4 included), so by the limit rule the damage is exactly 0
    (AASHTO LRFD 6.6.1.2.5), whatever the sample: its standard error and the upper bound of the design-life
    damage are 0 too (before, the sample's spread of sub-threshold damages gave a standard error and an upper
    bound above 0 beside the verdict "no fatigue damage")."""
    from vbikit.lifetime.results import _verdict_variables

    prep, got = _days([10.0, 10.2, 10.4, 10.1, 10.3], 12.0, "AASHTO E")
    v = got["variables"]
    assert v["below_fatigue_limit"][1][0] == 1
    assert v["max_stress_range_design_life_bound"][1][0] < 31.0 * MPA
    assert v["fatigue_damage"][1][0] == 0.0
    assert v["fatigue_damage_se"][1][0] == 0.0
    verdict = _verdict_variables(prep, v, got["ranges"])
    assert verdict["fatigue_damage_design_life_upper"][1][0] == 0.0
    assert verdict["fatigue_verdict"][1][0].startswith("no fatigue damage")


def test_days_below_the_limit_do_not_make_a_design_life_below_it():
    """EN 1993-1-9 1.3.3.3's limit rule judges the design life's loading, not the days simulated: five days
    whose largest ranges are 17 … 21 MPa, all below Δσ_D = 26.53 MPa (detail 36), extrapolate to a 100-year
    largest above it.  The independent number: scipy's Gumbel maximum-likelihood fit of the same five maxima
    (``scipy.stats.gumbel_r.fit``), the level the largest of 100 × 365 days stays below with probability 0.95
    (F(x)^36500 = 0.95).  The rule is then not applied:
    every cycle above Δσ_L counts (here the days' closed damage, 5 × 1e-7), and the verdict says why; with
    fewer than 5 days no estimate is possible and the rule is not applied either."""
    from scipy import stats

    from vbikit.lifetime.results import _verdict_variables

    maxima = [17.0, 18.0, 19.0, 20.0, 21.0]
    prep, got = _days(maxima, 21.0, "EN 36")
    v = got["variables"]
    loc, scale = stats.gumbel_r.fit(np.array(maxima) * MPA)
    level = stats.gumbel_r.ppf(0.95 ** (1.0 / (100 * 365)), loc, scale)  # P(largest of 36,500 days <= level) = 0.95
    assert level > (2 / 5) ** (1 / 3) * 36.0 * MPA  # above Δσ_D: the case is what it claims
    assert v["max_stress_range_design_life"][1][0] == pytest.approx(level, rel=1e-4)
    assert v["max_stress_range_static"][1][0] == 21.0 * MPA
    assert v["below_fatigue_limit"][1][0] == 0
    assert v["fatigue_damage_static"][1][0] == pytest.approx(5e-7, rel=1e-12)
    verdict = _verdict_variables(prep, v, got["ranges"])["fatigue_verdict"][1][0]
    assert verdict.startswith("OK") and "the limit rule does not hold over the design life" in verdict
    assert f"{level / MPA:.2f} MPa" in verdict
    prep, got = _days(maxima[:4], 21.0, "EN 36")
    assert got["variables"]["below_fatigue_limit"][1][0] == 0
    words = _verdict_variables(prep, got["variables"], got["ranges"])["fatigue_verdict"][1][0]
    assert "4 simulated days with a stress range, fewer than 5" in words


def test_size_factor_reduces_the_en_category():
    """EN 1993-1-9's size effect: a detail of category Δσ_C with k_s has the curve of k_s·Δσ_C — here
    EN 80 with k_s = 0.9: N = 2e6 (72 MPa / Δσ)³ above the constant-amplitude limit (the standard's
    m = 3 branch, by hand: 100 MPa → 2e6 × 0.72³ = 746,496 cycles); k_s is refused on AASHTO curves and
    outside 0.1 … 1, naming the key."""
    from vbikit.lifetime.spec import DetailSpec

    mpa = 1e6
    reduced = Detail("d", 0, 1.0, "EN 80", 1.0, 1.0 * mpa, size_factor=0.9).sn()
    assert float(reduced.cycles_to_failure(np.array([100.0 * mpa]))[0]) == pytest.approx(2e6 * 0.72**3, rel=1e-12)
    plain = Detail("d", 0, 1.0, "EN 80", 1.0, 1.0 * mpa).sn()
    assert float(plain.cycles_to_failure(np.array([100.0 * mpa]))[0]) == pytest.approx(2e6 * 0.8**3, rel=1e-12)
    spec = dict(name="d", effect="m", section_modulus=0.01, category="AASHTO C", size_factor=0.9)
    with pytest.raises(ValueError, match="size_factor"):
        DetailSpec(**spec)
    with pytest.raises(ValueError, match="size_factor"):
        DetailSpec(**(spec | {"category": "EN 80", "size_factor": 1.2}))
    assert DetailSpec(**(spec | {"category": "EN 80"})).size_factor == 0.9
    # reports name the reduced curve, not the plain category (the same label with 55× the damage before)
    assert Detail("d", 0, 1.0, "EN 80", 1.0, 1.0 * mpa, size_factor=0.9).label == "EN 80 × k_s 0.9 = 72 MPa"
    assert Detail("d", 0, 1.0, "EN 80", 1.0, 1.0 * mpa).label == "EN 80"


def test_a_large_damage_ratio_is_explained_in_words():
    """A dynamic / static damage ratio above 2 (the example week's EN 36 detail: 5.4 with an IM mean of
    0.14) gets the reason in words — the S-N curve's power m and the ranges near the fatigue limit and
    cut-off — while an ordinary one (1.3) does not."""
    from vbikit.lifetime.accuracy import fatigue_verdict

    big = fatigue_verdict(5.4e-5, 1e-5, 1e-5, 0.0192, 100.0, 0.0, False, 26.5e6, 0.95)
    assert big["ratio"] == pytest.approx(5.4) and "power m = 3 … 5" in big["ratio_words"]
    assert "26.50 MPa" in big["ratio_words"]
    small = fatigue_verdict(1.3e-5, 1e-6, 1e-5, 0.0192, 100.0, 0.0, False, 26.5e6, 0.95)
    assert small["ratio"] == pytest.approx(1.3) and "power m" not in small["ratio_words"]


def test_the_design_life_range_of_degenerate_days():
    """Days whose largest ranges are all equal: the design life's largest is that range (no spread), times the
    dynamics' amplification in the bound; days without any range: 0 (the limit rule holds: nothing to count);
    fewer than 5 days with a range: no estimate, said why."""
    import math

    from vbikit.lifetime.accuracy import design_life_range

    same = design_life_range(np.full(7, 12.0 * MPA), 365, 100.0, 0.95, amplification=1.25)
    assert (same.level, same.upper, same.bound) == (12.0 * MPA, 12.0 * MPA, 15.0 * MPA)
    none = design_life_range(np.zeros(7), 365, 100.0, 0.95, amplification=1.25)
    assert (none.level, none.upper, none.bound) == (0.0, 0.0, 0.0)
    few = design_life_range(np.array([0.0, 0.0, 0.0, 9.0, 10.0, 11.0, 12.0]) * MPA, 365, 100.0, 0.95)
    assert math.isnan(few.bound) and few.why == "4 simulated days with a stress range, fewer than 5"
