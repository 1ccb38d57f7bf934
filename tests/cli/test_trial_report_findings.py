"""What a new user's trial of ``vbikit run`` / ``vbikit demo`` found, each test failing on the code
before the fix (main at 50791d5):

1. a scenario with two named [[response.points]] printed the last point's name ("beta") as the
   report's header instead of the scenario's ``name``;
2. a random-road IM (the demo, class C, seed 1: IM = 0.2451) was printed beside the code allowances
   with no word that it is one road realisation (``vbikit run --random`` of the demo: 0.203 ± 0.101);
3. ``response.y`` on a beam switched the strain-convergence check off, and was silently ignored;
4. a coarse ``crossing.dt`` left the headline IM unmarked, and the unresolved-modes warning counted
   only the modes the automatic step resolves ("4 of 10" when all 10 were unresolved);
5. [[vehicles]] without a [crossing] table stopped with ``crossing: missing required key``;
6. a traffic base scenario with several moment sections kept only the first, without a word.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from typer.testing import CliRunner

import vbikit
from vbikit.analysis.checks import STEPS_PER_PERIOD
from vbikit.cli import app
from vbikit.cli.render import print_summary
from vbikit.scenario import ScenarioError, load_scenario, scenario_from_toml
from vbikit.scenario.preflight import preflight

ROOT = Path(__file__).resolve().parents[2]
YANG_YAU = ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"
runner = CliRunner()

#: a moving force over a simply supported beam (few modes: a quick run)
BEAM = """
[bridge]
model = "beam"
span = 25.0
EI = 8.323e9
mass_per_length = 2303.0
damping_ratio = 0.0
n_modes = 6
[vehicle]
model = "moving-force"
force = 100e3
[road]
class = "none"
[crossing]
speed = 20.0
approach = 0.0
"""


def _run(text: str, tmp_path: Path, *args: str):
    path, summary = tmp_path / "s.toml", tmp_path / "s.json"
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "--summary", str(summary), *args])
    assert res.exit_code == 0, res.output
    return res, json.loads(summary.read_text())


def _im_line(stdout: str) -> str:
    return next(t for t in stdout.splitlines() if t.startswith("  IMPACT FACTOR"))


def _codes(summary: dict) -> list[str]:
    return [f["code"] for f in summary["flags"]]


# 1 --------------------------------------------------------------------------------------------------

def test_report_header_is_the_scenario_name_with_several_named_points(tmp_path):
    text = 'name = "Bridge A assessment"\n' + BEAM + \
        '[[response.points]]\nname = "mid"\nx = 12.5\n[[response.points]]\nname = "beta"\nx = 6.0\n'
    res, s = _run(text, tmp_path)
    assert res.stdout.splitlines()[0] == "Bridge A assessment"
    assert [p["name"] for p in s["points"]] == ["mid", "beta"]
    assert vbikit.run(text).name == "Bridge A assessment"


# 2 --------------------------------------------------------------------------------------------------

def test_one_realisation_flag_follows_the_road_origin_not_its_label():
    from vbikit.analysis.checks import realisation_flags
    from vbikit.road import RoadOrigin, RoadProfile

    def crossing(origin, label="", z=(0.0, 1e-3)):
        return SimpleNamespace(road=RoadProfile(np.array([0.0, 1.0]), np.array(z), label, origin=origin))

    (flag,) = realisation_flags(crossing(RoadOrigin("random", "C", 7)))
    assert realisation_flags(crossing(RoadOrigin("random", "psd", 7), z=(0.0, 0.0))) == []  # phi0 = 0: smooth
    assert flag.code == "one_realisation" and flag.value == 7 and flag.output == "impact_factor"
    assert "random class-C road (seed 7)" in flag.message and "vbikit run --random" in flag.message
    assert "road.seed" in flag.message  # the study over seeds
    assert realisation_flags(crossing(RoadOrigin("random", "psd", 2, defects=("bump",))))  # still random
    for deterministic in (RoadOrigin("smooth"), RoadOrigin("measured", file="f.csv"),
                          RoadOrigin("smooth", defects=("pothole",)), RoadOrigin("measured", file="f.csv", defects=("bump",))):
        assert realisation_flags(crossing(deterministic)) == []
    assert realisation_flags(crossing(None, "class C, seed 1")) == []  # a label is not data
    assert realisation_flags(SimpleNamespace(road=None)) == []


def test_a_random_road_run_says_it_is_one_realisation(tmp_path):
    res, s = _run(BEAM.replace('class = "none"', 'class = "C"\nseed = 3'), tmp_path)
    (flag,) = [f for f in s["flags"] if f["code"] == "one_realisation"]
    assert flag["value"] == 3 and flag["message"] in s["warnings"]
    lines = res.stdout.splitlines()
    k = lines.index(_im_line(res.stdout))
    end = next(i for i, t in enumerate(lines) if t.startswith("  deflection IM beside"))
    (note,) = [t for t in lines[k + 1:end] if "realisation" in t]  # beside the IM, before the code allowances
    assert "one realisation of the random road (seed 3)" in note and "vbikit run --random" in note
    assert len(note) < 160  # a short note; the warning on stderr says the rest
    assert f"IM = {s['impact_factor']:.4f}  " in _im_line(res.stdout)  # no "!": one sample of a scatter, not wrong
    # smooth road, and a smooth road with a defect only: deterministic, no flag, no note
    for road in ('class = "none"', 'class = "none"\n[[road.defects]]\nkind = "bump"\nposition = 5.0'):
        res, s = _run(BEAM.replace('class = "none"', road), tmp_path)
        assert "one_realisation" not in _codes(s) and "realisation" not in res.stdout
    # a random run (PEM) is the remedy: its checks (the preflight's flags) carry no such flag
    plan = preflight(scenario_from_toml(BEAM.replace('class = "none"', 'class = "C"\nseed = 3')))
    assert "one_realisation" not in [f.code for f in plan.flags]


# 3 --------------------------------------------------------------------------------------------------

def test_response_y_on_a_beam_keeps_the_strain_check_and_is_flagged_as_ignored(tmp_path):
    """The Yang–Yau beam (10 modes) reads 20.32 µε of strain against the exact c·P·L/(4·EI) = 0.5 · 5750 ·
    9.81 · 25 / (4 · 8.323e9) = 21.18 µε (−4.0 %) whatever y a beam is read at: y has no meaning there."""
    text = YANG_YAU.read_text()
    exact = 0.5 * 5750.0 * 9.81 * 25.0 / (4 * 8.323e9)
    flags = {}
    for y in (2.0, 0.001, 0.0):
        _, s = _run(text.replace("x = 12.5", f"x = 12.5\ny = {y}"), tmp_path)
        (flag,) = [f for f in s["flags"] if f["code"] == "strain_not_converged"]
        assert flag["value"] == pytest.approx(s["max_static_strain"] / exact - 1, abs=5e-4)
        assert flag["value"] == pytest.approx(-0.040, abs=0.001)
        flags[y] = s["flags"]
    (ignored,) = [f for f in flags[2.0] if f["code"] == "ignored_input"]
    assert ignored["subject"] == "response.y" and ignored["value"] == 2.0
    assert "response.y = 2 m has no effect" in ignored["message"] and "no lateral dimension" in ignored["message"]
    assert "ignored_input" not in [f["code"] for f in flags[0.0]]  # 0: the beam's own line, harmless


def test_ignored_input_only_for_keys_given_on_a_beam():
    def codes(text):
        return [(f.code, f.subject) for f in preflight(scenario_from_toml(text)).flags if f.code == "ignored_input"]

    assert codes(BEAM) == []  # defaults are not inputs
    assert codes(BEAM + "lateral_offset = 1.5\n") == [("ignored_input", "crossing.lateral_offset")]
    assert codes(BEAM + '[[response.points]]\nx = 5.0\ny = 1.0\n[[response.points]]\nx = 6.0\n') == \
        [("ignored_input", "response.points[1].y")]
    # listed vehicles' lateral_offset separates their lanes (the overlap check): not flagged
    several = BEAM.replace('[vehicle]\nmodel = "moving-force"\nforce = 100e3\n', "").replace(
        "speed = 20.0\n", "") + ('[[vehicles]]\nmodel = "moving-force"\nforce = 1e5\nspeed = 20.0\nlateral_offset = 2.0\n')
    assert codes(several) == []
    # a girder deck has a lateral dimension: its y is an input
    deck = load_scenario(ROOT / "examples" / "bridges" / "three_span_grillage_hs20.toml")
    assert not any(f.code == "ignored_input" for f in preflight(deck).flags)


# 4 --------------------------------------------------------------------------------------------------

def test_coarse_step_marks_the_headline_im_and_counts_every_unresolved_mode(tmp_path):
    """Yang–Yau beam at dt = 0.05 s: it resolves modes to 1/(5 dt) = 4 Hz; the beam's modes are
    f_n = n² (π / 2L²) √(EI/m) (simply supported Euler–Bernoulli beam), f_1 = 4.778 Hz: all 10 above.
    The automatic step (the coarse_step flag's threshold) resolves those with f_n·dt_auto ≤ 0.2."""
    text = YANG_YAU.read_text().replace("free_vibration = 0.5", "free_vibration = 0.5\ndt = 0.05")
    res, s = _run(text, tmp_path)
    f = np.arange(1, 11) ** 2 * math.pi / (2 * 25.0**2) * math.sqrt(8.323e9 / 2303.0)
    assert f[0] == pytest.approx(4.778, abs=5e-4)
    (coarse,) = [x for x in s["flags"] if x["code"] == "coarse_step"]
    auto = coarse["threshold"]
    resolved_by_auto = int(np.sum(f * auto <= 1 / STEPS_PER_PERIOD))
    assert resolved_by_auto == 4 and not np.any(f * 0.05 <= 1 / STEPS_PER_PERIOD)
    (modes,) = [x for x in s["flags"] if x["code"] == "unresolved_modes"]
    assert (f"10 of 10 bridge modes, modes 1–10 ({f[0]:.4g}–{f[-1]:.4g} Hz), are not resolved; the automatic step "
            f"{auto:.3g} s resolves modes 1–4 ({f[0]:.4g}–{f[3]:.4g} Hz) of them") in modes["message"]
    assert modes["value"] == pytest.approx(f[3], rel=1e-6) and modes["threshold"] == pytest.approx(4.0)
    line = _im_line(res.stdout)
    assert f"IM = {s['impact_factor']:.4f}!" in line and f"strain IM = {s['strain_impact_factor']:.4f}!" in line
    assert "! unreliable: the given crossing.dt is too coarse" in res.stdout


def test_coarse_step_mark_comes_from_the_codes(tmp_path, capsys):
    _, s = _run(YANG_YAU.read_text().replace("n_modes = 10", "n_modes = 50"), tmp_path)
    s = s | {"flags": []}  # its load effects' step notes (effect_step) mark no headline

    def line(summary):
        print_summary(SimpleNamespace(name="", summary=summary))
        return _im_line(capsys.readouterr().out)

    assert "!" not in line(s)
    for code in ("coarse_step", "unresolved_modes"):
        record = {"code": code, "message": "any words", "output": None, "subject": "crossing.dt", "girder": None,
                  "point": None, "wheel": None, "value": 0.05, "threshold": 0.002}
        assert line(s | {"flags": [record]}).count("!") == 2


def test_a_mode_the_automatic_step_leaves_is_counted_but_a_lone_one_is_not_flagged():
    """unresolved_modes counts every mode dt leaves unresolved, but is raised only when dt loses a mode the
    automatic step resolves (an exact integrator leaves its high modes to the exact solution)."""
    from vbikit.analysis.checks import step_flags

    crossing = preflight(load_scenario(YANG_YAU)).built.crossing
    f = crossing.bridge.frequencies_hz
    auto = next(x for x in step_flags(crossing, 1.0) if x.code == "coarse_step").threshold
    assert f[4] * auto > 1 / STEPS_PER_PERIOD  # mode 5 beyond the automatic step too
    dt = 1 / (STEPS_PER_PERIOD * f[3]) * 1.001  # loses mode 4 only, among the resolved ones
    (flag,) = [x for x in step_flags(crossing, dt) if x.code == "unresolved_modes"]
    assert "7 of 10 bridge modes, modes 4–10" in flag.message and "resolves mode 4 (" in flag.message
    assert not [x for x in step_flags(crossing, auto) if x.code == "unresolved_modes"]


# 5 --------------------------------------------------------------------------------------------------

def test_missing_crossing_table_is_named_with_what_it_needs(tmp_path):
    text = ('[bridge]\nmodel = "paper-bridge-2-beam"\n[[vehicles]]\nmodel = "hs20-44"\nspeed_kmh = 60\n'
            '[[vehicles]]\nmodel = "two-axle"\nspeed_kmh = 80\nlateral_offset = 3.5\n')
    with pytest.raises(ScenarioError) as err:
        scenario_from_toml(text)
    msg = str(err.value)
    assert "crossing: missing required table [crossing]" in msg
    assert "speed [m/s] or speed_kmh [km/h]" in msg and "empty [crossing] table will do" in msg
    assert "approach" in msg and "hs20-44" not in msg  # the keys it takes, no file content
    path = tmp_path / "v.toml"
    path.write_text(text)
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 2 and "missing required table [crossing]" in res.stderr
    scenario_from_toml(text + "[crossing]\n")  # the advice holds: an empty table will do
    with pytest.raises(ScenarioError, match=r"missing required table \[crossing\]"):  # one [vehicle] too
        scenario_from_toml('[bridge]\nmodel = "beam"\n[vehicle]\nmodel = "hs20-44"\n')


# 6 --------------------------------------------------------------------------------------------------

def test_traffic_base_with_several_sections_warns_of_those_dropped(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text('[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n[road]\nclass = "none"\n'
                    '[crossing]\napproach = 5.0\n[response]\nmoment = [10.0, 5.0]\nreaction = [1, 0]\n')
    res = runner.invoke(app, ["validate", str(base)])
    assert res.exit_code == 0, res.output
    warnings = [t for t in res.stderr.splitlines() if t.startswith("warning: ")]
    assert len(warnings) == 2
    assert "response.moment" in warnings[0] and "(moment at x = 10 m); dropped: x = 5 m" in warnings[0]
    assert "response.reaction" in warnings[1] and "(reaction at support 1); dropped: support 0" in warnings[1]
    from vbikit.traffic import LaneTraffic, synthetic_stream, write_records

    write_records(synthetic_stream([LaneTraffic(1, "+x", 600, 75)], 1, seed=9), tmp_path / "one.csv")
    # vbikit traffic says it as it reads the base (here it then stops on a bad option, before computing)
    res = runner.invoke(app, ["traffic", str(tmp_path / "one.csv"), "--bridge", str(base), "--outputs", "peak",
                              "--out", str(tmp_path / "x.nc")])
    assert res.exit_code == 2 and "(moment at x = 10 m); dropped: x = 5 m" in res.stderr
    # one section each: nothing to say
    base.write_text(base.read_text().replace("[10.0, 5.0]", "[10.0]").replace("[1, 0]", "[1]"))
    assert "warning" not in runner.invoke(app, ["validate", str(base)]).stderr
