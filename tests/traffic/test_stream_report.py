"""What an engineer reads of a traffic stream: the statistics of the events that load the point
come first, and the figure marks the events whose IM rests on a small static reference."""
from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.traffic import write_records
from vbikit.traffic.records import VehicleRecord

runner = CliRunner()


def test_loaded_events_statistics_are_printed_first(tmp_path):
    """A 350 kN truck and, 10 s later, a 50 kN two-axle van over the Bridge 2 beam (two events): the
    van's static peak is about 50/350 = 14 % of the truck's (a beam's deflection is linear in the
    loads; below the 20 % rule), so only the truck's event loads the point.  Its line — the
    design value, the mean of one event being that event's IM in the dataset — comes before the line
    of all events, which names the other event's IM as no design value."""
    records = [VehicleRecord(time=0.0, direction="+x", speed=20.0, axle_loads=(70e3, 140e3, 140e3),
                             axle_spacings=(4.0, 1.3), lane=1, id="truck"),
               VehicleRecord(time=10.0, direction="+x", speed=20.0, axle_loads=(25e3, 25e3), axle_spacings=(3.0,),
                             lane=1, id="van")]
    write_records(records, tmp_path / "r.csv")
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n[road]\nclass = "none"\n'
                                        "[crossing]\napproach = 5.0\nfree_vibration = 0.1\n")
    res = runner.invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"), "--out",
                              str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    lines = res.stdout.splitlines()
    loaded = next(i for i, x in enumerate(lines) if x.startswith("impact factor of the events loading the point"))
    every = next(i for i, x in enumerate(lines) if x.startswith("impact factor of all events"))
    assert loaded < every
    assert "deflection impact factors at y = 0 m, midspan of the first span (the stream's statistics are of this point)" in lines
    ds = xr.open_dataset(tmp_path / "s.nc")
    st = np.abs(ds["max_static_displacement"].values)
    assert 0.1 < st[1] / st[0] < 0.2  # (the setup: the van's share, as the docstring says)
    truck_im = float(ds["impact_factor"].values[0])
    # one loaded event: its mean has no interval, said so ("?"), not printed as nan
    assert f"(1 of 2, static peak ≥ 20% of the stream's largest): mean {truck_im:.4f} (95 % CI ? – ?)," in lines[loaded]
    # the quantile is named as one (not "95 %" beside "95 % CI"), and "?" is explained (before 2026-12-06: neither)
    assert ", 95th percentile " in lines[loaded] and ", 95th percentile " in lines[every]
    assert ", 95 % " not in lines[loaded] + lines[every]
    assert "  (95 % CI: of the statistic over this stream's events; ?: too few events to bound that end)" in lines
    # no multiple presence in this stream: said in words, not printed as "several nan" (before 2026-12-05)
    assert "mean of the events with one vehicle " in lines[every] and "several: no such event;" in lines[every]
    assert "nan" not in lines[every] and "nan" not in lines[loaded]
    assert lines[every].endswith("the other event's IM rests on small static references (light vehicles, far lanes): "
                                 "not design values")
    # the van's event without an IM (NaN): the finished run's statistics say so and over how many events they are
    from vbikit.traffic.study import stream_statistics

    ds = ds.load()
    ds.close()
    ds["impact_factor"].values[1] = np.nan
    ds.attrs.update(stream_statistics(ds))
    ds.to_netcdf(tmp_path / "nan.nc")
    (tmp_path / "nan.nc").replace(tmp_path / "s.nc")
    res = runner.invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"), "--out",
                              str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0 and "already holds this finished run" in res.output, res.output
    lines = res.stdout.splitlines()
    assert f"impact factor of all events with one at the point (1 of 2) (each loads the point): mean {truck_im:.4f} " \
           "(95 % CI ? – ?)" in res.stdout
    assert "  (1 event without an impact factor at the point (NaN: no usable static reference) left out of these " \
           "statistics)" in lines
    assert not any(x.startswith("impact factor of the events loading the point") for x in lines)
    assert "nan" not in res.stdout
    # the same finished run as written before 2026-12-06: its identity held the base's folder (base_dir), it had no
    # n_events_without_impact_factor and its IM mean was NaN; recognised, its statistics read again from its events
    import json

    old = json.loads(ds.attrs["study"])
    old["base_dir"] = str(tmp_path)  # (base_scenario's folder of --bridge, as given)
    del old["population_run_in"]  # (a stream of then started its trucks at rest: no run-in in its identity)
    for key in [k for k in ds.attrs if k.startswith("im_") or k.startswith("n_events_without")]:
        ds.attrs[key] = math.nan if not key.startswith("n_") and "histogram" not in key else ds.attrs[key]
    del ds.attrs["n_events_without_impact_factor"]
    ds.attrs["study"] = json.dumps(old, sort_keys=True)
    ds.to_netcdf(tmp_path / "old.nc")
    (tmp_path / "old.nc").replace(tmp_path / "s.nc")
    res = runner.invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"), "--out",
                              str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0 and "already holds this finished run" in res.output, res.output
    assert f"impact factor of all events with one at the point (1 of 2) (each loads the point): mean {truck_im:.4f} " \
           "(95 % CI ? – ?)" in res.stdout
    assert "  (1 event without an impact factor at the point (NaN: no usable static reference) left out of these " \
           "statistics)" in res.stdout.splitlines()
    # no event with an IM: said in one line (was "all events with one at the point (0 of 2) (each loads the point):
    # mean n/a …, max nan")
    ds["impact_factor"].values[:] = np.nan
    ds.attrs.update(stream_statistics(ds))
    ds.to_netcdf(tmp_path / "none.nc")
    (tmp_path / "none.nc").replace(tmp_path / "s.nc")
    res = runner.invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"), "--out",
                              str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "impact factor: no event has one at the point (2 of 2 without a usable static reference): no IM statistics" \
        in res.stdout.splitlines()
    assert "nan" not in res.stdout and "impact factor of " not in res.stdout and "95 % CI" not in res.stdout


def _stream(static_mm, multiple):
    """A hand-made stream dataset with the variables and attributes ``plot_stream`` reads."""
    st = -np.asarray(static_mm, float) * 1e-3
    dyn = 1.2 * st
    im = dyn / st - 1.0
    return xr.Dataset(
        {"impact_factor": ("event", im), "multiple_presence": ("event", np.asarray(multiple, int)),
         "max_static_displacement": ("event", st), "max_dynamic_displacement": ("event", dyn)},
        attrs={"im_histogram_edges": "[-0.1, 0.1, 0.3, 0.5]", "im_mean": float(im.mean()), "im_mean_loaded": 0.2,
               "small_static_fraction": 0.2, "governing_static_event": int(np.argmax(static_mm)),
               "governing_dynamic_event": int(np.argmax(static_mm)), "governing_static_amplification": 1.2,
               "n_events": len(st), "n_multiple_presence_events": int(sum(multiple))})


def test_the_figure_marks_the_small_static_events():
    """Static peaks 2.0, 1.5, 0.3 and 0.1 mm: 0.3 and 0.1 mm are below 20 % of 2.0 mm (0.4 mm), so
    those two events — and only they — are drawn apart, with their own marker and legend entry; the
    others keep the one-vehicle / several-vehicle colours."""
    import matplotlib.pyplot as plt

    from vbikit.plot.traffic import stream_figure

    fig = stream_figure(_stream([2.0, 1.5, 0.3, 0.1], [0, 1, 0, 1]))
    hist, scatter = fig.axes
    by_label = {c.get_label(): c for c in scatter.collections}
    small = next(c for label, c in by_label.items() if label == "IM not meaningful: static peak < 20% of the largest")
    assert sorted(small.get_offsets()[:, 0].tolist()) == pytest.approx([0.1, 0.3])
    assert by_label["one vehicle"].get_offsets()[:, 0].tolist() == pytest.approx([2.0])
    assert by_label["several vehicles"].get_offsets()[:, 0].tolist() == pytest.approx([1.5])
    assert small.get_paths()[0] != by_label["one vehicle"].get_paths()[0]  # a distinct marker
    assert any(t.get_text() == "IM not meaningful: static peak < 20% of the largest" for t in hist.get_legend().get_texts())
    plt.close(fig)
    fig = stream_figure(_stream([2.0, 1.5, 0.9], [0, 1, 0]))  # no small static reference: no such entry
    assert not any(t.get_text().startswith("IM not meaningful") for ax in fig.axes for t in ax.get_legend().get_texts())
    plt.close(fig)


def test_the_stream_statistics_carry_the_intervals_of_their_means_and_quantiles():
    """A stream's IM mean and 95 % quantile (all events, and those loading the point) come with their 95 %
    confidence intervals: the t interval by hand, the quantile's from ``quantile_interval`` (whose
    coverage tests/unit/test_sample_intervals.py checks by simulation)."""
    from scipy import stats

    from vbikit.analysis.sample_intervals import quantile_interval
    from vbikit.traffic.study import stream_statistics

    rng = np.random.default_rng(3)
    n = 200
    st = -rng.uniform(1.0, 10.0, n) * 1e-3
    im = rng.gamma(3.0, 0.07, n)
    ds = xr.Dataset({"impact_factor": ("event", im), "max_static_displacement": ("event", st),
                     "max_dynamic_displacement": ("event", st * (1 + im)), "multiple_presence": ("event", np.zeros(n, int)),
                     "airborne_wheels": ("event", np.zeros(n))}, coords={"vehicle": np.arange(n)})
    s = stream_statistics(ds)
    half = stats.t.ppf(0.975, n - 1) * im.std(ddof=1) / np.sqrt(n)
    assert (s["im_mean_ci_lower"], s["im_mean_ci_upper"]) == pytest.approx((im.mean() - half, im.mean() + half), rel=1e-12)
    q = quantile_interval(im, 0.95)
    assert (s["im_q95_ci_lower"], s["im_q95_ci_upper"]) == (q.lower, q.upper)
    assert s["im_q95_ci_lower"] < s["im_q95"] < s["im_q95_ci_upper"]
    loaded = np.abs(st) >= 0.2 * np.abs(st).max()
    assert 0 < (~loaded).sum() and s["im_mean_loaded_ci_lower"] < im[loaded].mean() < s["im_mean_loaded_ci_upper"]
    assert s["im_q95_loaded_ci_lower"] < s["im_q95_loaded"] < s["im_q95_loaded_ci_upper"]


def _hand_stream(im, static_mm):
    """A hand-made stream dataset with the variables ``stream_statistics`` reads (one vehicle an event)."""
    im, st = np.asarray(im, float), -np.asarray(static_mm, float) * 1e-3
    n = im.size
    return xr.Dataset({"impact_factor": ("event", im), "max_static_displacement": ("event", st),
                       "max_dynamic_displacement": ("event", st * (1 + np.nan_to_num(im))),
                       "multiple_presence": ("event", np.zeros(n, int)), "airborne_wheels": ("event", np.zeros(n))},
                      coords={"vehicle": np.arange(n)})


def test_an_event_without_an_impact_factor_is_left_out_and_counted():
    """Six events: IMs 0.1, 0.2, 0.3, 0.4 on static peaks 5, 6, 8, 7 mm, one of 0.9 on 1 mm (below 20 % of
    8 mm: a small static reference), and one event without an IM (NaN, a static peak of 0 mm).  Every IM
    statistic is over the five finite values and says how many events it left out; by hand: the mean
    (0.1+0.2+0.3+0.4+0.9)/5 = 0.38, of the four loading the point 0.25, their 95th percentile (numpy's
    linear rule, position 0.95·3 = 2.85) 0.3 + 0.85·0.1 = 0.385 and the t interval of their mean
    0.25 ± t(0.975, 3) · s/√4 = 0.25 ± 3.182446 · 0.1290994 / 2 = 0.25 ± 0.2054260.  (Before 2026-12-06
    the means and quantiles were plain numpy statistics of all six: NaN, beside intervals over the finite
    values, and the left-out event was not counted.)"""
    from vbikit.traffic.study import stream_statistics

    s = stream_statistics(_hand_stream([0.1, 0.2, 0.3, 0.4, 0.9, np.nan], [5.0, 6.0, 8.0, 7.0, 1.0, 0.0]))
    assert s["n_events"] == 6 and s["n_events_without_impact_factor"] == 1 and s["n_small_static_events"] == 1
    assert s["im_mean"] == pytest.approx(0.38, abs=1e-12)
    assert s["im_mean_loaded"] == pytest.approx(0.25, abs=1e-12)
    assert s["im_q95_loaded"] == pytest.approx(0.385, abs=1e-12)
    assert (s["im_mean_loaded_ci_lower"], s["im_mean_loaded_ci_upper"]) == pytest.approx((0.0445740, 0.4554260), abs=1e-6)
    assert s["im_q95_ci_lower"] <= s["im_q95"] and s["im_mean_ci_lower"] < s["im_mean"] < s["im_mean_ci_upper"]
    assert all(np.isfinite(s[k]) for k in ("im_std", "im_q05", "im_q50", "im_q99", "im_mean_single"))
    assert sum(s["im_histogram_counts"]) == 5
    assert s["governing_static_event"] == 2 and s["governing_static_amplification"] == pytest.approx(1.3)


def test_an_event_without_a_static_peak_does_not_govern():
    """An event whose static peak is NaN (not reduced) is not the largest static effect: the 8 mm one is
    (numpy's argmax returns a NaN's index; before 2026-12-06 that event was reported as governing)."""
    from vbikit.traffic.study import stream_statistics

    s = stream_statistics(_hand_stream([0.1, np.nan, 0.3], [5.0, np.nan, 8.0]))
    assert s["governing_static_event"] == 2 and s["governing_dynamic_event"] == 2
    assert s["n_events_without_impact_factor"] == 1 and s["im_mean"] == pytest.approx(0.2, abs=1e-12)


def test_an_interval_end_the_events_cannot_bound_is_flagged_in_words():
    """A short stream's 95 % quantile has no upper interval end (NaN): the dataset flags it, ``interval_not_bounded``,
    with the events it rests on and the events that end needs — the order-statistic bound, n ≥ ln(0.025) / ln(0.95)
    = 71.9, so 72 (by hand) — where only the CLI's "?" said so; a stream long enough for every end gives none."""
    import math

    from vbikit.traffic.study import open_interval_flags

    stats = {"n_events": 12, "n_events_without_impact_factor": 0, "n_small_static_events": 1,
             "im_mean": 0.2, "im_mean_ci_lower": 0.1, "im_mean_ci_upper": 0.3,
             "im_q95": 0.45, "im_q95_ci_lower": 0.3, "im_q95_ci_upper": math.nan,
             "im_mean_loaded": 0.2, "im_mean_loaded_ci_lower": 0.1, "im_mean_loaded_ci_upper": 0.3,
             "im_q95_loaded": 0.4, "im_q95_loaded_ci_lower": 0.3, "im_q95_loaded_ci_upper": math.nan}
    flags = open_interval_flags(stats)
    assert [(f.code, f.output, f.value, f.threshold) for f in flags] == [
        ("interval_not_bounded", "im_q95", 12.0, 72.0), ("interval_not_bounded", "im_q95_loaded", 11.0, 72.0)]
    assert flags[0].message.startswith("im_q95: its 12 events cannot bound the upper end of its 95 % confidence interval")
    assert math.ceil(math.log(0.025) / math.log(0.95)) == 72
    bounded = {k: (0.5 if isinstance(v, float) and math.isnan(v) else v) for k, v in stats.items()}
    assert open_interval_flags(bounded) == []
