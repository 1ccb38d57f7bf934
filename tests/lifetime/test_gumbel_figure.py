"""lifetime-gumbel.png shows what docs/lifetime.md ("Probability paper") describes: the return
levels with their confidence intervals and a top axis of return periods in years (on main: the
levels as bare markers, no interval, no return-period axis).  A small dataset built here with
closed-form Gumbel numbers; no lifetime run."""
import numpy as np
import pytest
import xarray as xr

from vbikit.lifetime import figures


def _dataset():
    rng = np.random.default_rng(3)
    days, per_year, periods = 40, 250.0, np.array([50.0, 100.0, 1000.0])
    loc, scale = 1000.0, 50.0
    y = -np.log(-np.log(1 - 1 / (per_year * periods)))
    level = loc + scale * y  # Gumbel quantile, closed form
    maxima = loc + scale * rng.gumbel(size=(days, 1))
    dims = ("load_effect", "return_period")
    data = {"effect_sign": ("load_effect", [1.0]), "load_effect_units": ("load_effect", ["kN m"]),
            "assessment_dynamic_ratio": ("load_effect", [1.1])}
    for which, f in (("static", 1.0), ("total", 1.1)):
        data[f"daily_max_{which}"] = (("day", "load_effect"), maxima * f)
        data[f"fit_{which}_location"] = ("load_effect", [loc * f])
        data[f"fit_{which}_scale"] = ("load_effect", [scale * f])
        data[f"fit_{which}_shape"] = ("load_effect", [0.0])
        data[f"return_level_{which}"] = (dims, [level * f])
        data[f"return_level_{which}_lower"] = (dims, [level * f - 30.0])
        data[f"return_level_{which}_upper"] = (dims, [level * f + 40.0])
    ds = xr.Dataset(data, coords={"load_effect": ["M"], "return_period": periods})
    ds.attrs.update(block="day", days_per_year=per_year, distribution="gumbel", ci=0.95)
    return ds, level


def test_return_levels_carry_their_intervals_and_the_top_axis_reads_years(tmp_path, monkeypatch):
    ds, level = _dataset()
    figs = []
    real = figures.save_figure
    monkeypatch.setattr(figures, "save_figure", lambda fig, path, **kw: figs.append(fig) or real(fig, path, **kw))
    path = figures.gumbel_figure(ds, tmp_path / "g.png")
    assert path.stat().st_size > 5000
    ax = figs[0].axes[0]
    bars = [c for c in ax.containers if c.__class__.__name__ == "ErrorbarContainer"]
    assert len(bars) == 2  # static and total
    static = bars[0]
    segments = static.lines[2][0].get_segments()  # one vertical bar per return period
    lows = sorted(min(s[:, 1]) for s in segments)
    highs = sorted(max(s[:, 1]) for s in segments)
    np.testing.assert_allclose(lows, np.sort(level - 30.0))
    np.testing.assert_allclose(highs, np.sort(level + 40.0))
    assert any("95 % interval" in t.get_text() for t in ax.get_legend().get_texts())
    tops = [a for a in ax.child_axes if a.get_xlabel() == "return period [years]"]
    assert tops, "no return-period axis"
    ticks = tops[0].get_xticks()
    labels = [t.get_text() for t in tops[0].get_xticklabels()]
    assert "100" in labels
    # the tick labelled 100 years sits at the reduced variate of T = 100 years: −ln(−ln(1 − 1/(100 n)))
    assert ticks[labels.index("100")] == pytest.approx(-np.log(-np.log(1 - 1 / (100 * 250.0))))
