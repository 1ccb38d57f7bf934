"""ADR when the dynamics vanish, and the dataset contract."""
import re

import numpy as np
import pytest
from scipy import stats

from vbikit.analysis.sample_intervals import quantile_interval
from vbikit.lifetime.run import run_lifetime


def _spec(**kw):
    spec = {"name": "quasi-static", "seed": 4, "days": 10, "amplification": 0.05,
            "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 16, "speed_kmh": 5.0},
            "vehicle_model": "moving-forces",
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "road": {"class": "none"},
            "load_effects": [{"kind": "moment", "x": 3.3, "name": "M"}, {"kind": "deflection", "x": 5.0, "name": "w"},
                             {"kind": "shear", "x": 2.0, "name": "V"}]}
    spec.update(kw)
    return spec


def test_adr_is_one_without_dynamics(tmp_path):
    """Moving constant axle forces on a smooth road at 5 km/h (quasi-static: the dynamic response
    equals the static one): ADR = 1 within 1e-3 for moment, deflection and shear (achieved
    ≤ 4e-4 with ten daily maxima), and every simulated event's total peak equals its static peak
    within 1e-3 (achieved ≤ 4e-4: the moving forces' own small dynamics at 5 km/h and the coupled
    run's sampling of the shear jump); the contract's variables carry units and the load_effect
    dimension."""
    ds = run_lifetime(_spec(), tmp_path, base_dir=".", workers=1, figures=False)
    adr = ds["assessment_dynamic_ratio"].values
    assert np.all(np.abs(adr - 1.0) < 1e-3), adr
    sim = ds["event_simulated"].values.astype(bool)
    ratio = ds["event_total"].values[sim] / ds["event_static"].values[sim]
    assert np.all(np.abs(ratio - 1.0) < 1e-3)
    for name in ("characteristic_static", "characteristic_total", "assessment_dynamic_ratio"):
        # a unit per variable, or (effects of several units) the coordinate holding each effect's
        assert ds[name].dims == ("load_effect",)
        assert ds[name].attrs.get("units") or ds[name].attrs["units_by_load_effect"] == "load_effect_units"
    assert list(ds["load_effect"].values) == ["M", "w", "V"]
    assert (tmp_path / "lifetime.nc").is_file()


def test_fatigue_limit_judges_the_whole_period(tmp_path):
    """EN 1993-1-9 1.3.3.3: no damage when every stress range of the loading — the design life's — is below
    Δσ_D, and every cycle above Δσ_L counts otherwise.  Quasi-static traffic (as above): the largest stress
    range of a day is its largest static midspan-moment peak over the section modulus (the stress returns to
    0 between events; the moment at x = 3.3 m is ≥ 0 under downward loads), and the design life's largest is
    the level the largest of 100 years of 365 days stays below with probability 0.95 (F(x)^36500 = 0.95) — by
    hand with scipy's maximum-likelihood fit
    (``scipy.stats.gumbel_r``) of the daily maxima of the run without details.  A detail whose largest range
    of the five days sits 60 % below Δσ_D does no damage; one 20 % below it in the days but not over the
    design life does: its days' cycles above Δσ_L count (the rule is not applied, said in words); one whose
    largest range sits 20 % above Δσ_D does, more than its cycles above Δσ_D alone would (the m = 5 cycles
    count)."""
    from vbikit.fatigue import sn_curve

    first = run_lifetime(_spec(days=5), tmp_path / "a", base_dir=".", workers=1, figures=False)
    m_max = float(first["event_static"].sel(load_effect="M").max())
    d_d = sn_curve("EN 36").threshold  # Δσ_D of category 36 [Pa]
    details = [{"name": "below", "effect": "M", "section_modulus": m_max / (0.4 * d_d), "category": "EN 36"},
               {"name": "days_only", "effect": "M", "section_modulus": m_max / (0.8 * d_d), "category": "EN 36"},
               {"name": "above", "effect": "M", "section_modulus": m_max / (1.2 * d_d), "category": "EN 36"}]
    ds = run_lifetime(_spec(days=5, fatigue={"details": details, "histogram_bin": 1e5}), tmp_path / "b", base_dir=".",
                      workers=1, figures=False)
    below, days_only, above = ds.sel(detail="below"), ds.sel(detail="days_only"), ds.sel(detail="above")
    daily = first["daily_max_static"].sel(load_effect="M").values
    loc, scale = stats.gumbel_r.fit(daily / m_max)  # in units of the largest peak: each detail's ranges scale by 1/W
    level = stats.gumbel_r.ppf(0.95 ** (1.0 / (100 * 365)), loc, scale)  # P(the life's largest <= level) = 0.95
    for detail, share in ((below, 0.4), (days_only, 0.8)):
        assert float(detail["max_stress_range_static"]) == pytest.approx(share * d_d, rel=1e-9)
        assert float(detail["max_stress_range_design_life"]) == pytest.approx(level * share * d_d, rel=1e-3)
    assert 0.4 * level < 1.0 < 0.8 * level  # the 100-year largest: below Δσ_D for the first, above for the second
    assert int(below["below_fatigue_limit"]) == 1 and float(below["fatigue_damage"]) == 0.0
    assert int(days_only["below_fatigue_limit"]) == 0
    # its days' cycles above Δσ_L (on the m = 5 slope) now count: the damage is theirs, not 0
    assert float(days_only["fatigue_damage_static"]) == pytest.approx(float(days_only["damage_per_day_static"].sum()),
                                                                     rel=0.05)
    assert float(days_only["fatigue_damage_static"]) > 0.0
    assert "the limit rule does not hold over the design life" in str(days_only["fatigue_verdict"].values)
    assert int(above["below_fatigue_limit"]) == 0 and float(above["fatigue_damage_static"]) > 0.0
    # the cycles of the 'below' detail, scaled by 1.2 / 0.4, are those of 'above' on the m = 5 slope and
    # beyond: its damage exceeds what the ranges above Δσ_D alone (on m = 3) would do
    hist = above["stress_range_histogram"].values
    edges = ds["stress_range_bin"].values
    high = edges >= d_d
    upper = edges + 1e5
    only_high = float(np.sum(hist[high] / (2e6 * (36e6 / upper[high]) ** 3)))  # an upper bound of their damage
    assert float(above["fatigue_damage_static"]) > only_high


def test_impact_factor_statistics_of_the_sample_by_hand(tmp_path):
    """The IM statistics of the dataset, recomputed from its own per-event variables: IM = R_dyn/R_st − 1
    over the random sample (``event_in_sample``); the sampled events whose |R_st| is below 20 % of the
    largest |R_st| of all events are counted (``n_small_static_sample``) and left out of
    ``im_mean_loaded`` / ``im_q95_loaded``.  Two lanes and a deflection off the centre line, so that
    far-lane light trucks load some effects little (a mask on the wrong events, the dynamic peaks or the
    sample's complement moves these figures by far more than round-off)."""
    import tomllib

    with open("examples/lifetime/lifetime.toml", "rb") as fh:
        spec = tomllib.load(fh)
    spec.update(days=5, seed=2027)  # a seed whose sample holds light events (2026's does not since the
    # generator's hour-by-hour flows, 2026-12-06)
    spec["traffic"]["records"] = "examples/lifetime/wim.csv"
    ds = run_lifetime(spec, tmp_path, base_dir=".", workers=1, figures=False)
    sample = ds["event_in_sample"].values.astype(bool)
    st, total = ds["event_static"].values, ds["event_total"].values
    assert sample.sum() >= 10
    for j in range(ds.sizes["load_effect"]):
        im = total[sample, j] / st[sample, j] - 1.0
        small = np.abs(st[sample, j]) < 0.2 * np.nanmax(np.abs(st[:, j]))
        assert abs(ds["im_mean"].values[j] - np.mean(im)) <= 1e-12 * max(1.0, abs(np.mean(im)))
        assert int(ds["n_small_static_sample"].values[j]) == int(small.sum())
        kept = im[~small]
        assert abs(ds["im_mean_loaded"].values[j] - kept.mean()) <= 1e-12 * max(1.0, abs(kept.mean()))
        assert abs(ds["im_q95_loaded"].values[j] - np.quantile(kept, 0.95)) <= 1e-12
        # the 95 % intervals: Student's t by hand for the means, the order-statistic interval for the quantiles
        for name, values in (("im_mean", im), ("im_mean_loaded", kept)):
            half = stats.t.ppf(0.975, values.size - 1) * values.std(ddof=1) / np.sqrt(values.size)
            ends = (ds[f"{name}_ci_lower"].values[j], ds[f"{name}_ci_upper"].values[j])
            assert ends == pytest.approx((values.mean() - half, values.mean() + half), rel=1e-10)
        for name, values in (("im_q95", im), ("im_q95_loaded", kept)):
            q = quantile_interval(values, 0.95)
            assert (ds[f"{name}_ci_lower"].values[j], ds[f"{name}_ci_upper"].values[j]) == (q.lower, q.upper)
            assert q.lower <= ds[name].values[j] <= q.upper
    assert int(ds["n_small_static_sample"].sum()) > 0  # the case the loaded statistics are for occurs here
    report = (tmp_path / "report.txt").read_text()
    assert ds.attrs["distribution"] == "gumbel" and "BM ξ = 0 (Gumbel)" in report and "BM ξ = 0.000" not in report
    name = str(ds["load_effect"].values[0])
    assert (f"  {name}: IM of the random sample ({int(sample.sum())} events): mean {ds['im_mean'].values[0]:.4f} "
            f"(95 % CI {ds['im_mean_ci_lower'].values[0]:.4f} – {ds['im_mean_ci_upper'].values[0]:.4f}), 95th "
            f"percentile {ds['im_q95'].values[0]:.4f} (95 % CI ") in report
    # the design values (the events that load the effect) with their intervals too, as the page says
    # (before 2026-12-06 the report printed them bare, and the quantile as "95 %" beside "95 % CI")
    j = int(np.argmax(ds["n_small_static_sample"].values))
    v = {k: ds[k].values[j] for k in ds.data_vars if k.startswith("im_") and "loaded" in k}
    assert (f"the others' IM mean {v['im_mean_loaded']:.4f} (95 % CI {v['im_mean_loaded_ci_lower']:.4f} – "
            f"{v['im_mean_loaded_ci_upper']:.4f}), 95th percentile {v['im_q95_loaded']:.4f} (95 % CI "
            f"{v['im_q95_loaded_ci_lower']:.4f} – {v['im_q95_loaded_ci_upper']:.4f})") in report
    assert not re.search(r"95 % -?\d", report)  # (the quantile is "95th percentile", never "95 % 0.31")
