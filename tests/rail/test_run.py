"""run_rail / `vbikit rail`: the schema's errors, the budget, the dataset contract and a cut-down of
examples/railway through the command line."""
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vbikit.rail import codes
from vbikit.rail.run import RailBudgetError, plan_rail, run_rail
from vbikit.rail.spec import RailSpecError, parse_rail_spec

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "railway"


def spec(**over):
    data = {"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0},
            "trains": {"presets": ["hslm-a1"]},
            "speeds": {"min": 200.0, "max": 260.0, "step": 20.0}}
    for key, value in over.items():
        data[key] = {**data.get(key, {}), **value}
    return data


def test_errors_name_keys_and_ranges_before_computing():
    with pytest.raises(RailSpecError) as err:
        parse_rail_spec(spec(bridge={"deck": "timber", "damping": 0.5}, trains={"presets": ["hslm-a12"]},
                             speeds={"line_max": 300.0}))
    msg = str(err.value)
    assert "bridge.deck: deck must be one of steel, composite" in msg
    assert "bridge.damping: expected a number in [0, 0.2)" in msg
    assert "trains.presets: unknown train 'hslm-a12'" in msg
    assert "speeds.max: give either max (km/h) or line_max" in msg
    with pytest.raises(RailSpecError, match="speeds.step"):
        parse_rail_spec(spec(speeds={"step": 0.0}))


def test_a_given_damping_with_additional_damping_set_is_refused():
    """A given ζ replaces the code's ζ and its Δζ (EN 1991-2 Eq. 6.13) both: ``additional_damping = true``
    beside it would be ignored, so it is refused naming the key; either alone is accepted."""
    with pytest.raises(RailSpecError, match=r"bridge.*additional_damping: a given damping replaces"):
        parse_rail_spec(spec(bridge={"damping": 0.02, "additional_damping": True}))
    assert parse_rail_spec(spec(bridge={"damping": 0.02})).bridge.damping == 0.02
    assert parse_rail_spec(spec(bridge={"damping": 0.02, "additional_damping": False})).bridge.damping == 0.02
    assert parse_rail_spec(spec(bridge={"additional_damping": True})).bridge.additional_damping


def test_budget_refused_before_the_sweep():
    with pytest.raises(RailBudgetError, match="run.budget: the sweep needs"):
        run_rail(spec(run={"budget": 1e5}), figures=False)
    with pytest.raises(RailBudgetError, match="coupled.max_steps: the coupled cars need"):
        run_rail(spec(trains={"presets": ["ice3"]}, coupled={"enabled": True, "max_steps": 1e4}), figures=False)
    with pytest.raises(RailSpecError, match="coupled.enabled: none of the trains has car data"):
        run_rail(spec(coupled={"enabled": True}), figures=False)


def test_dataset_contract_and_a_one_axle_train_against_closed_forms(tmp_path):
    (tmp_path / "one.csv").write_text("position_m,load_kN\n0,200\n")
    data = spec(trains={"presets": ["hslm-a1", "hslm-a2"], "tables": [str(tmp_path / "one.csv")]})
    result = run_rail(data, tmp_path / "out", figures=False)
    ds = result.dataset
    assert list(ds.train.values) == ["HSLM-A1", "HSLM-A2", "one"]
    assert ds["max_deck_acceleration"].dims == ("train", "speed")
    assert ds["max_deck_acceleration"].attrs["units"] == "m s-2"
    assert ds.speed.attrs["units"] == "m s-1"
    # one 200 kN axle over the 20 m span: M = P L / 4 = 1000 kN m (sampled at midspan); deflection within the
    # retained modes (1, 2, 3 at midspan: odd ones) = P L³/(48 EI) × (1 + 3⁻⁴) / (π⁴/96)
    one = ds.sel(train="one")
    assert float(one["static_moment"]) == pytest.approx(1000e3, rel=1e-9)
    # shear just right of the support: an axle on the support carries none (vbikit.bridge.effects), an axle
    # just past it all of P: the peak is that one-sided limit (read KNOT_OFFSET steps in, 1e-6 Δx/L of P
    # short), not the first sample Δx in, P (1 − Δx/L)
    assert float(one["static_shear"]) == pytest.approx(200e3, rel=1e-8)
    w = 200e3 * 20.0**3 / (48 * 7.9e10) * (1 + 3.0**-4) / (math.pi**4 / 96)
    assert int(ds.attrs["n_modes"]) == 3
    assert float(one["static_deflection"]) == pytest.approx(w, rel=1e-4)
    # the deck damping of Table 6.6 (prestressed concrete, L = 20 m: 1.0 %) plus Δζ(20) = 0.118/0.398 %
    assert ds.attrs["damping_ratio"] == pytest.approx((1.0 + 0.118 / 0.398) / 100, rel=1e-12)
    assert (tmp_path / "out" / "rail.nc").exists() and "result:" in result.report


def test_example_cut_down_through_the_cli(tmp_path, summary_on_stdout):
    for name in ("hslm_20m.toml", "talgo_like.csv"):
        shutil.copy(EXAMPLE / name, tmp_path / name)
    text = (tmp_path / "hslm_20m.toml").read_text()
    text = text.replace('presets = ["hslm-a", "ice3"]', 'presets = ["hslm-a3", "ice3"]')
    text = text.replace("step = 2.0", "step = 20.0").replace("fine_step = 0.5", "fine_step = 5.0")
    text = text.replace("workers = 2", "workers = 1")
    (tmp_path / "hslm_20m.toml").write_text(text)
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-c", "from vbikit.cli import app; app(prog_name='vbikit')", "rail", str(tmp_path / "hslm_20m.toml"), "--out-dir", str(out)],
                         capture_output=True, text=True, env=os.environ.copy(), timeout=300)
    assert run.returncode == 0, run.stderr
    assert "deck acceleration: peak" in run.stdout
    # the files written and the closing summary are results: stdout, as every command's (stderr: progress)
    assert f"wrote {out / 'rail.nc'}" in run.stdout and "3 trains × " in run.stdout.splitlines()[-1]
    assert "wrote " not in run.stderr and "trains × " not in run.stderr
    import xarray as xr

    with xr.open_dataset(out / "rail.nc") as ds:
        assert list(ds.train.values) == ["HSLM-A3", "ICE 3", "talgo_like"]
        assert np.all(np.isfinite(ds["max_deck_acceleration"].values))
        assert float(ds["acceleration_limit"]) == 3.5
    assert (out / "rail-acceleration.png").stat().st_size > 10_000
    # --json (the finished trains read back): the summary's object alone on standard output, units in CF spelling
    js = summary_on_stdout(["rail", str(tmp_path / "hslm_20m.toml"), "--out-dir", str(out), "--no-figures"],
                           out / "rail-summary.json")
    assert "deck acceleration: peak" in js.stderr
    import json

    assert json.loads(js.stdout)["checks"]["acceleration"]["units"]["peak"] == "m s-2"


def test_coupled_cars_on_an_irregular_track_join_the_sweep():
    data = spec(trains={"presets": ["ice3"]}, speeds={"min": 250.0, "max": 260.0, "step": 10.0},
                coupled={"enabled": True, "irregularity": "german-low", "seed": 3})
    ds = run_rail(data, figures=False).dataset
    assert list(ds.train.values) == ["ICE 3", "ICE 3 (coupled)"]
    acc = ds["max_deck_acceleration"].values
    assert acc.shape == (2, 2) and (acc > 0).all() and (acc[1] != acc[0]).all()
    # the static reference of the coupled cars is the moving-force train's (same static axle loads)
    assert float(ds["static_deflection"][1]) == pytest.approx(float(ds["static_deflection"][0]), rel=1e-9)


def test_speed_grid_refines_near_resonance():
    from vbikit.rail.sweep import speed_grid

    v = speed_grid(30.0, 40.0, 5.0, resonances=[33.3], fine_step=0.5, width=1.0)
    assert list(v[:2]) == [30.0, 32.3] and 35.0 in v and v[-1] == 40.0
    assert all(abs(x - y) < 0.5 + 1e-9 for x, y in zip(v[1:], v[2:]) if 32.3 <= x < 34.3)


def test_rail_distribution_over_three_sleepers(tmp_path):
    from vbikit.vehicle.trains import parse_train_table, rail_distributed

    t = rail_distributed(parse_train_table("0,200\n3,100\n", "two"), 0.6)
    np.testing.assert_allclose(t.axle_positions, [0.0, 0.6, 1.2, 3.0, 3.6, 4.2])
    np.testing.assert_allclose(t.axle_loads, [50e3, 100e3, 50e3, 25e3, 50e3, 25e3])
    # one 200 kN axle over three sleepers a = 0.6 m on the 20 m span: P/4 at L/2 ± a and P/2 at L/2 give
    # M_mid = P L/4 − P a/4 = 1000 − 30 = 970 kN m (the sampling misses the peak by at most P/2 · Δx/2)
    (tmp_path / "one.csv").write_text("0,200\n")
    (tmp_path / "rail.toml").write_text(
        "[bridge]\nspan = 20.0\nEI = 7.9e10\nmass_per_length = 25000.0\n[trains]\ntables = [\"one.csv\"]\n"
        "sleeper_spacing = 0.6\n[speeds]\nmin = 200.0\nmax = 220.0\nstep = 20.0\n")
    ds = run_rail(tmp_path / "rail.toml", figures=False).dataset
    assert list(ds.train.values) == ["one (rail-distributed)"]
    m = float(ds["static_moment"][0])
    assert 970e3 - 100e3 * ds.attrs["dx_m"] / 2 - 1e-6 <= m <= 970e3 + 1e-6


def test_report_warns_when_the_modes_miss_the_required_range():
    result = run_rail(spec(bridge={"n_modes": 1, "damping": 0.015}), figures=False)
    # n0 = (π/(2 L²)) √(EI/m) = 6.98 Hz; n3 = 9 n0 = 62.8 Hz is the required range: modes 1, 2, 3 (n_k = k² n0)
    assert "! 1 modes retained, but the 3 modes up to 62.8 Hz are required" in result.report
    assert "damping 1.500 % (given (bridge.damping)" in result.report


def test_scenario_bridge_is_the_same_beam(tmp_path):
    (tmp_path / "deck.toml").write_text('[bridge]\nmodel = "beam"\nspan = 20.0\nEI = 7.9e10\nmass_per_length = 25000.0\n')
    base = {"trains": {"presets": ["hslm-a4"]}, "speeds": {"min": 230.0, "max": 290.0, "step": 20.0}}
    a = run_rail({"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0}, **base}, figures=False).dataset
    b = run_rail({"bridge": {"scenario": str(tmp_path / "deck.toml")}, **base}, figures=False).dataset
    for name in ("max_deck_acceleration", "max_deflection", "max_moment", "max_shear", "lm71_moment", "lm71_shear"):
        np.testing.assert_array_equal(a[name].values, b[name].values)
    assert a.attrs["damping_ratio"] == b.attrs["damping_ratio"] and a.attrs["n_modes"] == b.attrs["n_modes"] == 3


def test_scenario_bridge_errors(tmp_path):
    (tmp_path / "two.toml").write_text('[bridge]\nmodel = "continuous-beam"\nspans = [20.0, 20.0]\nEI = 7.9e10\n'
                                       'mass_per_length = 25000.0\n')
    with pytest.raises(RailSpecError, match="bridge.scenario: two.toml is a bridge of 2 spans"):
        run_rail({"bridge": {"scenario": str(tmp_path / "two.toml")}, "trains": {"presets": ["hslm-a1"]},
                  "speeds": {"max": 300.0}}, figures=False)
    with pytest.raises(RailSpecError, match="bridge.span: give either scenario or span"):
        parse_rail_spec({"bridge": {"scenario": "x.toml", "span": 20.0}, "trains": {"presets": ["hslm-a1"]},
                         "speeds": {"max": 300.0}})
    with pytest.raises(RailSpecError, match="bridge.EI: give span, EI and mass_per_length"):
        parse_rail_spec({"bridge": {"span": 20.0}, "trains": {"presets": ["hslm-a1"]}, "speeds": {"max": 300.0}})


def test_hslm_b_outside_its_range_is_flagged(tmp_path):
    """EN 1991-2:2003 6.4.6.1.1(5) and Annex E: HSLM-B for simply supported spans below 7 m only,
    HSLM-A otherwise.  A new user's HSLM-B (N = 10, d = 3.5 m) on a 20 m span passed with no word:
    now the report, the JSON and the Python checks carry the warning (a flag, not a refusal: the run
    may be meant as research), and its resonance line names d the force spacing, not a coach length."""
    import json

    data = spec(trains={"presets": [], "hslm_b": [{"n": 10, "d": 3.5}]}, speeds={"min": 200.0, "max": 220.0})
    res = run_rail(data, tmp_path / "out", figures=False)
    assert len(res.checks["warnings"]) == 1
    w = res.checks["warnings"][0]
    assert w.startswith("HSLM-B outside its range of application") and "is not the EN 1991-2 one" in w
    assert "use HSLM-A" in w and "this span is 20 m" in w and "which this sweep does not run" in w
    report = (tmp_path / "out" / "rail-report.txt").read_text()
    assert f"! {w}" in report
    assert "1 WARNING(s) above: not the EN 1991-2 check as run" in report.splitlines()[-1]
    assert "HSLM-B (N = 10, d = 3.5 m) (D = 3.500 m, force spacing d)" in report and "coach length)" not in report
    saved = json.loads((tmp_path / "out" / "rail-summary.json").read_text())
    assert saved["warnings"] == [w] and "warnings" not in saved["checks"]
    assert saved["trains"]["HSLM-B (N = 10, d = 3.5 m)"]["wavelength_source"] == "force spacing d"
    # within the ranges: no warning (HSLM-B below 7 m, HSLM-A at 7 m and above); outside, both ways
    short = {"bridge": {"span": 6.0}, "speeds": {"min": 100.0, "max": 120.0}}
    assert plan_rail(spec(trains={"presets": [], "hslm_b": [{"n": 10, "d": 3.5}]}, **short)).warnings == []
    assert plan_rail(spec(trains={"presets": ["hslm-a"]})).warnings == []  # (all ten HSLM-A trains)
    assert [w.split(":")[0] for w in plan_rail(spec()).warnings] == ["HSLM-A incomplete"]  # (some of them only)
    (w_a,) = plan_rail(spec(**short)).warnings
    assert w_a.startswith("HSLM-A outside its range of application: span 6 m < 7 m")
    assert codes.hslm_range_warnings(7.0, ["HSLM-B (N = 1, d = 1 m)", "HSLM-A1"])[0].endswith('presets = ["hslm-a"])')
    assert codes.hslm_range_warnings(6.99, ["HSLM-B (N = 1, d = 1 m)"]) == []


def test_hslm_b_from_the_rail_file(tmp_path):
    """``[[trains.hslm_b]]`` (N, d) runs ``vbikit.vehicle.hslm_b(N, d)``: N = 3 forces of 170 kN 25 m
    apart never share the 20 m span, so the static midspan moment and deflection are one force's,
    P L/4 = 850 kN m and P L³/(48 EI) within the retained modes (closed forms, as the one-axle table
    train above); its N and d are checked against hslm_b's ranges, naming the key."""
    data = spec(trains={"presets": [], "hslm_b": [{"n": 3, "d": 25.0}]})
    ds = run_rail(data, tmp_path / "out", figures=False).dataset
    assert list(ds.train.values) == ["HSLM-B (N = 3, d = 25 m)"]
    b = ds.sel(train="HSLM-B (N = 3, d = 25 m)")
    assert float(b["static_moment"]) == pytest.approx(170e3 * 20.0 / 4, rel=1e-9)
    w = 170e3 * 20.0**3 / (48 * 7.9e10) * (1 + 3.0**-4) / (math.pi**4 / 96)
    assert float(b["static_deflection"]) == pytest.approx(w, rel=1e-4)
    with pytest.raises(RailSpecError) as err:
        parse_rail_spec(spec(trains={"hslm_b": [{"n": 0, "d": 3.5}, {"n": 10, "d": 60.0}, {"n": 10}]}))
    msg = str(err.value)
    assert "trains.hslm_b[1].n: expected an integer in [1, 100], got 0" in msg
    assert "trains.hslm_b[2].d: expected a number in [0.5, 50], got 60.0" in msg
    assert "trains.hslm_b[3].d: missing required key" in msg
    with pytest.raises(RailSpecError, match="train names must differ, repeated: HSLM-B"):
        run_rail(spec(trains={"hslm_b": [{"n": 10, "d": 3.5}, {"n": 10, "d": 3.5}]}), figures=False)


def test_a_peak_at_the_top_of_the_sweep_is_said_to_be_still_rising():
    """HSLM-A1 (coach length D = 18 m) over the 20 m span: n0 = (π/(2 L²)) √(EI/m) = 6.98 Hz puts the
    second-order resonance n0 D / 2 at 62.8 m/s = 226 km/h.  Swept 180 … 220 km/h the largest deck
    acceleration is at the top speed, climbing towards that resonance: the report says so.  Swept on to
    260 km/h the peak is at the resonance, inside the sweep: nothing said."""
    n0 = math.pi / (2 * 20.0**2) * math.sqrt(7.9e10 / 25000.0)
    assert 3.6 * n0 * 18.0 / 2 == pytest.approx(226.1, abs=0.1)
    below = run_rail(spec(speeds={"min": 180.0, "max": 220.0, "step": 2.0}), figures=False)
    acc = below.checks["acceleration"]
    assert acc["at_top_speed"] and 3.6 * acc["speed"] == pytest.approx(220.0)
    assert "the peak is at the sweep's highest speed, where the response is still rising" in below.report
    across = run_rail(spec(speeds={"min": 180.0, "max": 260.0, "step": 2.0}), figures=False)
    acc = across.checks["acceleration"]
    assert not acc["at_top_speed"] and abs(3.6 * acc["speed"] - 226.1) < 3.0
    assert "still rising" not in across.report



def test_a_peak_at_the_bottom_of_the_sweep_is_said_to_be_still_rising():
    """HSLM-A1 on the 20 m span: n0 D / 2 = 226.1 km/h (n0 = (π/(2 L²)) √(EI/m) = 6.98 Hz, D = 18 m).
    Swept 230 … 270 km/h, just above that resonance, the largest deck acceleration is at the lowest
    speed, climbing towards it: the report and rail-summary.json say so, as they do at the top speed
    (on main neither said anything)."""
    result = run_rail(spec(speeds={"min": 230.0, "max": 270.0, "step": 10.0}), figures=False)
    acc = result.checks["acceleration"]
    assert acc["at_bottom_speed"] and not acc["at_top_speed"] and 3.6 * acc["speed"] == pytest.approx(230.0)
    assert "the peak is at the sweep's lowest speed, where the response is still rising towards lower speeds" in result.report


def test_the_governing_acceleration_is_read_between_the_deck_points_too():
    """A 60 m span under HSLM-A1 at its first resonance n0 D (n0 = (π/(2 L²)) √(EI/m) = 3.98 Hz,
    258 km/h): the higher modes' antisymmetric parts give the acceleration envelope a corner at
    midspan, so its maximum lies off the sweep's 9 points (x = L/10 … 9L/10).  The check reads the
    governing train and speed again on 99 points: the peak rises 0.30 % (x = 31.2 m), the report says
    so, and a sweep read at 99 points throughout lands within 0.05 % of it.  With one mode (a sine,
    largest at midspan, which is one of the 9 points) nothing lies between the points."""
    n0 = math.pi / (2 * 60.0**2) * math.sqrt(2.5e12 / 30000.0)
    assert 3.6 * n0 * 18.0 == pytest.approx(258.1, abs=0.1)
    beam = {"span": 60.0, "EI": 2.5e12, "mass_per_length": 30000.0}
    speeds = {"min": 230.0, "max": 290.0, "step": 2.0}
    run = run_rail(spec(bridge=beam, speeds=speeds), figures=False)
    nine = run.checks["acceleration"]
    pts = nine["points"]
    assert pts["n_read"] == 9 and pts["x_read"] == pytest.approx(30.0) and abs(pts["x_dense"] - 30.0) > 0.5
    assert pts["error"] > 1e-3 and nine["peak"] == pytest.approx(pts["dense"]) and pts["dense"] > pts["read"]
    dense = run_rail(spec(bridge=beam, speeds=speeds, run={"points": 99}), figures=False)
    assert dense.checks["acceleration"]["peak"] == pytest.approx(nine["peak"], rel=5e-4)
    assert "the sweep's 9 points read" in run.report
    one = run_rail(spec(bridge={**beam, "n_modes": 1}, speeds=speeds), figures=False).checks["acceleration"]
    assert one["points"]["x_dense"] == pytest.approx(30.0) and one["points"]["error"] == pytest.approx(0.0, abs=1e-12)
