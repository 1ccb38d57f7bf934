"""``vbikit run --random``: its JSON keys, equal to ``vbikit.run_random``; bad input refused by key."""
from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

import vbikit
from vbikit.cli import app

runner = CliRunner()

SCENARIO = """
name = "random check"
[bridge]
model = "paper-bridge-2-beam"
n_modes = 4
[vehicle]
model = "hs20-44"
[tire]
model = "point"
[road]
class = "B"
[crossing]
speed_kmh = 75
approach = 2
"""


def test_cli_json_equals_python_entry(tmp_path, monkeypatch):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO)
    res = runner.invoke(app, ["run", str(path), "--random", "--json", "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    cli = json.loads(res.stdout)
    for key in ("impact_factor_mean", "impact_factor_std", "impact_factor_quantiles", "lift_off_probability",
                "grid_change", "quality", "warnings"):
        assert key in cli, key
    assert set(cli["impact_factor_quantiles"]) == {"0.5", "0.9", "0.95"}
    q = cli["impact_factor_quantiles"]
    assert q["0.5"] < q["0.9"] < q["0.95"]
    assert cli["impact_factor_std"] > 0
    assert (tmp_path / "s.png").stat().st_size > 10_000
    csv = (tmp_path / "s.csv").read_text().splitlines()
    # every column headed with its unit, as vbikit run's CSV
    assert csv[0].split(",")[:2] == ["time [s]", "point"] and "displacement_std [m]" in csv[0]
    assert "acceleration_std [m/s^2]" in csv[0] and "strain_mean [-]" in csv[0]
    assert json.loads((tmp_path / "s.json").read_text())["impact_factor_std"] == cli["impact_factor_std"]
    rr = vbikit.run_random(path)
    for key in ("impact_factor_mean", "impact_factor_std", "lift_off_probability"):
        assert rr.summary[key] == cli[key], key
    # the text report of that result
    import vbikit.scenario.pipeline as pipeline

    monkeypatch.setattr(pipeline, "run_random", lambda *a, **k: rr)
    text = runner.invoke(app, ["run", str(path), "--random"])
    assert text.exit_code == 0 and "impact factor" in text.output and "quantiles" in text.output
    assert f"{rr.summary['impact_factor_mean']:9.4f}" in text.output
    # the sampling error the quality line promises, printed beside the statistics
    assert f"the mean's sampling error ±{rr.summary['points'][0]['impact_factor_sampling_error']:.4f}" in text.output
    assert "!" not in text.stdout  # (class B at 75 km/h: nothing in doubt)
    # a flag that puts every IM statistic in doubt (a tire lifting off) marks them "!" and says so
    from vbikit.analysis.checks import Flag, flag_fields

    flagged = dict(rr.summary, **flag_fields([Flag("lift_off", "a tire lifts off", value=0.005, threshold=0.001)]))
    monkeypatch.setattr(pipeline, "run_random", lambda *a, **k: type(rr)(rr.mean, rr.points, rr.pem, flagged, rr.effects))
    text = runner.invoke(app, ["run", str(path), "--random"])
    line = next(x for x in text.stdout.splitlines() if x.strip().startswith("impact factor"))
    assert f"{rr.summary['impact_factor_mean']:9.4f}!" in line and line.count("!") == 4, line  # the mean, 3 quantiles
    assert "not design values" in text.stdout
    # a small static reference at a point marks that point's statistics only (the flag's subject names it)
    from vbikit.random.response import point_label

    small = dict(rr.summary, **flag_fields([Flag("small_static", "small", output="impact_factor_mean",
                                                 subject=point_label(rr.summary["points"][0]), value=0.1, threshold=0.2)]))
    monkeypatch.setattr(pipeline, "run_random", lambda *a, **k: type(rr)(rr.mean, rr.points, rr.pem, small, rr.effects))
    text = runner.invoke(app, ["run", str(path), "--random"]).stdout
    lines = [x for x in text.splitlines() if x.strip().startswith("impact factor")]
    assert lines[0].count("!") == 4 and all("!" not in x for x in lines[1:]), lines  # (the load effects: not marked)
    assert "not design values" not in text


def test_smooth_road_and_disk_tires_are_refused(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO.replace('class = "B"', 'class = "none"'))
    res = runner.invoke(app, ["run", str(path), "--random"])
    assert res.exit_code != 0 and "road.class" in res.output
    path.write_text(SCENARIO.replace('model = "point"', 'model = "disk"'))
    res = runner.invoke(app, ["run", str(path), "--random"])
    assert res.exit_code != 0 and "tire.model" in res.output and "Monte Carlo" in res.output


def test_a_random_runs_json_gives_its_step_and_every_numbers_unit():
    """`run --random --json`, as `run --json`: the step it ran at and each top-level number's unit in CF spelling (a
    trial found none)."""
    import json

    from typer.testing import CliRunner

    from vbikit.cli import app

    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "paper" / "bridge2_hs20_girder4.toml"
    res = CliRunner().invoke(app, ["run", str(example), "--random", "--json"])
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    assert s["dt"] > 0 and s["units"]["dt"] == "s" and s["units"]["static_peak"] == "m" and s["static_peak"] < 0
    assert s["units"]["impact_factor_mean"] == "1" and s["units"]["wheel_force_std_max"] == "N"
    assert set(s["units"]) <= set(s)


@pytest.mark.parametrize("quantiles", [(1.5,), (0.0,), (0.5, 1.0), ("0.9",), ()])
def test_bad_quantiles_are_refused_before_any_computation(quantiles, monkeypatch):
    """``run_random(…, quantiles=(1.5,))`` ran the whole analysis, then failed in numpy's words (a trial); the
    quantiles are checked first, naming the key and the range."""
    from pathlib import Path

    import vbikit.scenario.pipeline as pipeline
    from vbikit.scenario import ScenarioError

    def no_run(*args, **kwargs):
        raise AssertionError("the analysis ran before the quantiles were checked")

    monkeypatch.setattr(pipeline, "preflight", no_run)
    example = Path(__file__).resolve().parents[2] / "examples" / "paper" / "bridge2_hs20_girder4.toml"
    with pytest.raises(ScenarioError, match=r"quantiles: "):
        vbikit.run_random(example, quantiles=quantiles)
