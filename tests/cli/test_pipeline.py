"""One run pipeline: `vbikit.run` from Python gives exactly what `vbikit run --json` prints, for
every example scenario and the demo; several response points from TOML, Python, CSV and datasets."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import vbikit
from vbikit._files import json_text
from vbikit.analysis import ResponsePlan, ResponsePoint
from vbikit.cli import app
from vbikit.scenario import ScenarioError, demo_scenario_text

ROOT = Path(__file__).resolve().parents[2]
#: every scenario in examples/ that `vbikit run` takes (studies, field files, traffic bases, drive-by, lifetime and railway files are other formats)
EXAMPLES = sorted(p for p in (ROOT / "examples").rglob("*.toml")
                  if p.parent.name not in ("studies", "field", "base", "driveby", "lifetime", "railway"))
runner = CliRunner()


def cli_json(args: list[str]) -> dict:
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def as_json(summary: dict) -> dict:
    return json.loads(json_text(summary))


def test_the_examples_are_found():
    assert len(EXAMPLES) >= 8 and {p.parent.name for p in EXAMPLES} >= {"bridges", "paper", "traffic", "verification"}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_python_run_equals_the_command_line(path: Path):
    assert as_json(vbikit.run(path).summary) == cli_json(["run", str(path), "--json"])


def test_demo_from_python_equals_the_command_line(tmp_path: Path):
    cli = cli_json(["demo", "--json", "--out-dir", str(tmp_path)])
    assert as_json(vbikit.run(demo_scenario_text()).summary) == cli


def test_a_scenario_as_path_text_and_dict_gives_one_report():
    path = ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"
    import tomllib

    by_path = vbikit.run(path).summary
    assert vbikit.run(str(path)).summary == by_path
    assert vbikit.run(path.read_text(), base_dir=path.parent).summary == by_path
    assert vbikit.run(tomllib.loads(path.read_text()), base_dir=path.parent).summary == by_path


BEAM = """
[bridge]
model = "beam"
span = 25.0
EI = 8.323e9
mass_per_length = 2303.0
damping_ratio = 0.0
n_modes = 60
[vehicle]
model = "moving-force"
force = 100e3
[road]
class = "none"
[crossing]
speed = 5.0
approach = 0.0
"""


def test_several_points_static_peaks_match_the_closed_form():
    """A moving force P over a simply supported beam: by Maxwell's reciprocity the static peak
    deflection at x = a over all load positions is the largest deflection of the beam under P at a,
    P b (L² − b²)^{3/2} / (9 √3 EI L) with b = min(a, L − a) (Gere & Timoshenko, Mechanics of
    Materials, table of beam deflections); three points in a deliberately unsorted order — a
    swapped index or a point read at the wrong x fails."""
    text = BEAM + "".join(f'[[response.points]]\nname = "{n}"\nx = {x}\n' for n, x in (("q3", 18.75), ("mid", 12.5), ("q1", 5.0)))
    report = vbikit.run(text)
    s = report.summary
    L, EI, P = 25.0, 8.323e9, 100e3
    assert [p["name"] for p in s["points"]] == ["q3", "mid", "q1"]
    for entry, a in zip(s["points"], (18.75, 12.5, 5.0)):
        b = min(a, L - a)
        exact = -P * b * (L**2 - b**2) ** 1.5 / (9 * 3**0.5 * EI * L)
        assert entry["x"] == a and entry["y"] == 0.0
        # 60 modes: the modal series of a point deflection converges as 1/n^4 (< 1e-5 here)
        assert entry["max_static_displacement"] == pytest.approx(exact, rel=1e-5)
    # the top-level keys describe the first point
    assert s["response_x"] == 18.75
    assert s["max_static_displacement"] == s["points"][0]["max_static_displacement"]
    assert s["impact_factor"] == s["points"][0]["impact_factor"]


def test_each_point_equals_a_run_at_that_point_alone():
    several = vbikit.run(BEAM + '[[response.points]]\nx = 7.0\n[[response.points]]\nx = 16.0\nname = "b"\n').summary
    for entry, x in zip(several["points"], (7.0, 16.0)):
        alone = vbikit.run(BEAM + f"[response]\nx = {x}\n").summary
        assert {k: entry[k] for k in alone["points"][0] if k != "name"} == \
            {k: v for k, v in alone["points"][0].items() if k != "name"}
    assert [p["name"] for p in several["points"]] == ["p1", "b"]


def test_several_points_from_python_with_a_crossing():
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.solve import Crossing
    from vbikit.vehicle import VEHICLE_PRESETS

    crossing = Crossing(EulerBernoulliBeam(span=25.0, EI=8.323e9, mass_per_length=2303.0, damping_ratio=0.0, n_modes=60),
                        VEHICLE_PRESETS["moving-force"].build(force=100e3), speed=5.0, approach=0.0)
    report = vbikit.run(crossing, ResponsePlan((ResponsePoint(x=5.0, name="a"), ResponsePoint(x=12.5, name="b"))))
    from_toml = vbikit.run(BEAM + '[[response.points]]\nname = "a"\nx = 5.0\n[[response.points]]\nname = "b"\nx = 12.5\n')
    assert report.summary["points"] == from_toml.summary["points"]
    ds = report.to_xarray()
    assert list(ds["point"].values) == ["a", "b"] and list(ds["x"].values) == [5.0, 12.5]
    np.testing.assert_allclose(ds["displacement"].values[:, 1], report.points[1].displacement, rtol=1e-12, atol=1e-17)


def test_csv_columns_carry_the_point_names(tmp_path: Path):
    path = tmp_path / "s.toml"
    path.write_text(BEAM + '[[response.points]]\nname = "left"\nx = 6.0\n[[response.points]]\nname = "mid"\nx = 12.5\n')
    res = runner.invoke(app, ["run", str(path), "--out", str(tmp_path / "h.csv"), "--json"])
    assert res.exit_code == 0, res.output
    header = (tmp_path / "h.csv").read_text().splitlines()[0].split(",")
    for col in ("displacement_left [m]", "displacement_mid [m]", "static_strain_mid [-]", "acceleration_left [m/s^2]"):
        assert col in header
    assert "displacement [m]" not in header
    data = np.loadtxt(tmp_path / "h.csv", delimiter=",", skiprows=1)
    s = json.loads(res.stdout)
    static_mid = data[:, header.index("static_displacement_mid [m]")]
    assert static_mid.min() == pytest.approx(s["points"][1]["max_static_displacement"], rel=1e-8)


@pytest.mark.parametrize("extra, message", [
    ('[response]\nx = 3.0\n[[response.points]]\nx = 4.0\n', "response.x: give the point in [response] or in [[response.points]]"),
    ('[[response.points]]\nname = "a"\nx = 3.0\n[[response.points]]\nname = "a"\nx = 4.0\n', "names must be unique; repeated: a"),
    ('[[response.points]]\nx = 3.0\n[[response.points]]\nx = 40.0\n', "response.points[2].x: must be within the span 0 … 25.0 m"),
    ('[[response.points]]\nx = 3.0\ngirder = 2\n', "response.points[1].girder: bridge model 'beam' has no girders"),
    ('[[response.points]]\nname = "2x"\n', "response.points[1].name"),
])
def test_bad_points_are_refused_naming_the_key(extra: str, message: str):
    with pytest.raises(ScenarioError) as err:
        vbikit.run(BEAM + extra)
    assert message in str(err.value)


def test_a_scenario_takes_no_separate_response_plan():
    with pytest.raises(ScenarioError, match="carries its own response plan"):
        vbikit.run(BEAM, ResponsePlan())


def test_a_report_computes_nothing_twice(monkeypatch):
    """One `vbikit.run` chooses the step, checks the budgets and tabulates the mode shapes once for its run: the
    preflight's run plan goes on to the integration and its tables to the static reference; the half-step check
    (``step_check``) plans its own run at half the step, once more."""
    import vbikit.solve.plan
    import vbikit.solve.system

    calls = {"choose_time_step": 0, "check_run": 0, "tabulate_tracks": 0}

    def counted(module, name):
        real = getattr(module, name)

        def wrapper(*args, **kwargs):
            calls[name] += 1
            return real(*args, **kwargs)
        monkeypatch.setattr(module, name, wrapper)

    counted(vbikit.solve.plan, "choose_time_step")
    counted(vbikit.solve.plan, "check_run")
    counted(vbikit.solve.system, "tabulate_tracks")
    vbikit.run(ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml")
    assert calls == {"choose_time_step": 2, "check_run": 2, "tabulate_tracks": 2}


def test_a_point_given_by_its_girder_reads_that_girders_line():
    """`ResponsePoint(girder=2)` from Python is read on Girder 2's line, as `girder = 2` in TOML."""
    from vbikit.bridge import BRIDGE_PRESETS
    from vbikit.solve import Crossing
    from vbikit.vehicle import hs20_44

    text = ('[bridge]\nmodel = "paper-bridge-2"\nn_modes = 6\n[vehicle]\nmodel = "hs20-44"\n[road]\nclass = "none"\n'
            '[crossing]\nspeed_kmh = 60\n[[response.points]]\ngirder = 2\n')
    from_toml = vbikit.run(text).summary["points"][0]
    bridge = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=6)
    crossing = Crossing(bridge, hs20_44(), speed=60 / 3.6)
    from_python = vbikit.run(crossing, ResponsePlan((ResponsePoint(girder=2),))).summary["points"][0]
    assert from_python["y"] == from_toml["y"] == float(bridge.girder_y[1])
    assert from_python["max_static_displacement"] == from_toml["max_static_displacement"]
    with pytest.raises(ValueError, match="girder = 2 lies at y"):
        vbikit.run(crossing, ResponsePlan((ResponsePoint(girder=2, y=0.0),)))


def test_a_path_with_an_equals_sign_is_a_path(tmp_path: Path):
    path = tmp_path / "speed=80.toml"
    path.write_text(BEAM + "[response]\nx = 12.5\n")
    assert vbikit.run(str(path)).summary == vbikit.run(path).summary


def test_an_unknown_figure_format_is_refused_before_the_run(tmp_path: Path, monkeypatch):
    import vbikit.scenario.pipeline

    monkeypatch.setattr(vbikit.scenario.pipeline, "run_planned", lambda *a, **k: pytest.fail("the run started"))
    path = tmp_path / "s.toml"
    path.write_text(BEAM)
    res = runner.invoke(app, ["run", str(path), "--plot", str(tmp_path / "f.xyz")])
    assert res.exit_code == 2 and "figures are written as" in res.output and "not 'xyz'" in res.output
