"""One error guard: user errors (VbikitError, OSError) exit 2 with one line, programming errors
show their traceback; global flags work after the subcommand too."""
from __future__ import annotations

import logging
import pickle
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.bridge.modefile import ModeFileError
from vbikit.cli import app
from vbikit.errors import OptionError, VbikitError
from vbikit.field.io import FieldFileError
from vbikit.road.measured import RoadFileError
from vbikit.scenario import ScenarioError, scenario_from_toml
from vbikit.solve.budget import BudgetError
from vbikit.solve.result import DivergenceError
from vbikit.solve.timestep import UnstableTimeStepError
from vbikit.study.spec import StudyError
from vbikit.traffic.records import RecordsError

runner = CliRunner()

FAST = """
[bridge]
model = "beam"
span = 20.0
EI = 1e10
mass_per_length = 5000.0
n_modes = 3
[vehicle]
model = "sprung-mass"
[crossing]
speed = 75.0
"""


def _scenario(tmp_path: Path, text: str = FAST) -> Path:
    path = tmp_path / "s.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("cls", [ScenarioError, StudyError, BudgetError, UnstableTimeStepError, RoadFileError,
                                 DivergenceError, FieldFileError, RecordsError, ModeFileError, OptionError])
def test_every_user_error_is_a_vbikit_error_and_a_value_error(cls):
    assert issubclass(cls, VbikitError) and issubclass(cls, ValueError)


def test_scenario_errors_carry_their_key_through_pickling():
    with pytest.raises(ScenarioError) as info:
        scenario_from_toml(FAST.replace("speed = 75.0", "speed = 0.0"))
    assert info.value.key == "crossing.speed"
    again = pickle.loads(pickle.dumps(info.value))  # study workers send errors between processes
    assert again.key == "crossing.speed" and str(again) == str(info.value)
    assert VbikitError("no key here").key is None and VbikitError("x", key="road.seed").key == "road.seed"
    assert ScenarioError("bridge.damage.0: the region ends beyond the bridge").key == "bridge.damage.0"
    assert ScenarioError("s.toml: not valid TOML: …").key is None  # a file, not a key


def test_quiet_after_the_subcommand(tmp_path):
    path = _scenario(tmp_path)  # 75 m/s = 270 km/h: an input warning
    loud = runner.invoke(app, ["run", str(path), "--json"])
    assert loud.exit_code == 0 and "warning: crossing.speed" in loud.stderr
    for argv in (["run", str(path), "--json", "-q"], ["run", "-q", str(path), "--json"], ["-q", "run", str(path), "--json"]):
        quiet = runner.invoke(app, argv)
        assert quiet.exit_code == 0, quiet.output
        assert "warning:" not in quiet.stderr and quiet.stdout == loud.stdout


def test_debug_and_verbose_after_the_subcommand(tmp_path):
    bad = _scenario(tmp_path, FAST.replace("speed = 75.0", "speed = 0.0"))
    plain = runner.invoke(app, ["validate", str(bad)])
    assert plain.exit_code == 2 and plain.stderr.startswith("error: invalid scenario")
    debug = runner.invoke(app, ["validate", str(bad), "--debug"])
    assert isinstance(debug.exception, ScenarioError)
    runner.invoke(app, ["presets", "-vv"])
    assert logging.getLogger().getEffectiveLevel() == logging.DEBUG
    runner.invoke(app, ["presets", "--verbose"])
    assert logging.getLogger().getEffectiveLevel() == logging.INFO
    runner.invoke(app, ["presets"])
    assert logging.getLogger().getEffectiveLevel() == logging.WARNING


def test_arguments_after_double_dash_stay_arguments(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["cite", "--", "-q"])
    assert res.exit_code == 2 and "-q" in res.stderr and "not found" in res.stderr


def test_a_programming_error_shows_its_traceback(tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise ValueError("an internal inconsistency")

    monkeypatch.setattr("vbikit.scenario.preflight.preflight", broken)
    res = runner.invoke(app, ["validate", str(_scenario(tmp_path))])
    assert res.exit_code == 1 and isinstance(res.exception, ValueError)
    assert "error: an internal inconsistency" not in res.output


def test_user_errors_and_unreadable_inputs_exit_2_with_one_line(tmp_path, monkeypatch):
    def refused(*args, **kwargs):
        raise BudgetError("this run needs too much")

    res = runner.invoke(app, ["validate", str(tmp_path)])  # a folder, not a file
    assert res.exit_code == 2 and res.stderr.startswith("error:") and len(res.stderr.splitlines()) == 1
    monkeypatch.setattr("vbikit.scenario.preflight.preflight", refused)
    path = _scenario(tmp_path)
    res = runner.invoke(app, ["validate", str(path)])  # a refusal of the file's run names the file
    assert res.exit_code == 2 and res.stderr == f"error: {path}: this run needs too much\n"


def test_option_values_are_user_errors(tmp_path):
    res = runner.invoke(app, ["validate", str(_scenario(tmp_path)), "--max-memory", "4XB"])
    assert res.exit_code == 2 and res.stderr.startswith("error: --max-memory")
    res = runner.invoke(app, ["field", str(tmp_path / "f.toml"), "--tires", "balloon"])
    assert res.exit_code == 2 and res.stderr.startswith("error: --tires: unknown tire model 'balloon'")


def test_a_bridge_models_own_check_is_a_user_error(tmp_path):
    """`vbikit bridge FILE.toml` builds the bridge alone: its model's ValueError is the scenario's error."""
    text = FAST.replace('model = "beam"\nspan = 20.0', 'model = "continuous-beam"\nspans = [20.0, 20.0]').replace(
        "n_modes = 3", "n_modes = 3\n[[bridge.damage]]\nposition = 39.0\nlength = 5.0\nseverity = 0.3")
    res = runner.invoke(app, ["bridge", str(_scenario(tmp_path, text)), "--no-plot"])
    assert res.exit_code == 2, res.output
    assert res.stderr.startswith("error:") and "beyond" in res.stderr and "Traceback" not in res.output


def test_a_ctrl_c_inside_a_compiled_kernel_is_an_interrupt():
    """numba turns a KeyboardInterrupt raised while a compiled kernel runs into "SystemError: CPUDispatcher(…)
    returned a result with an exception set" (the interrupt as its context): `vbikit rail --workers 1` printed that
    traceback and exited 1. guard raises it as the KeyboardInterrupt it is, which each command turns into its
    "interrupted: … kept …" line and exit 130; any other error is left as it is."""
    import pytest

    from vbikit.cli.guard import guard

    def wrapped():
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise SystemError("CPUDispatcher(<function _peaks>) returned a result with an exception set")

    with pytest.raises(KeyboardInterrupt):
        guard(wrapped)

    def plain():
        raise SystemError("not an interrupt")

    with pytest.raises(SystemError):
        guard(plain)


def test_a_resumed_run_says_so_in_one_line(tmp_path, capsys):
    """No command said it had resumed (a new user's trial, 2026-12-07): traffic's bar just started at 23 %, a lifetime
    round's bars jumped ahead, and the closing time covered the resumed part only. Each command now takes what the run
    itself reported finished before it started (after its checks: a part moved aside or run again is not counted)
    and, once the run is done, says so in one line on standard error; ``-q`` not."""
    from vbikit.cli.guard import STATE, say_resumed
    from vbikit.cli.lifetime import _Bars
    from vbikit.cli.study import _Bar

    bar = _Bar("s", enabled=False, unit="event")
    for done in (3, 5, 9):
        bar(done, 9)
    assert bar.first == (3, 9)  # (the first report: what the run found done)
    bars = _Bars(enabled=False)
    for stage, done, total in (("static pass", 5, 5), ("dynamics round 1", 40, 40), ("dynamics round 2", 7, 20),
                               ("dynamics round 2", 20, 20), ("dynamics round 1", 0, 40), ("dynamics round 1", 40, 40)):
        bars(stage, done, total, {})
    assert bars.resumed() == "1 stage and part of 1 more"  # (round 1 run again from the start: not counted)
    only_part = _Bars(enabled=False)
    for stage, done, total in (("dynamics round 1", 7, 20), ("dynamics round 2", 3, 20)):
        only_part(stage, done, total, {})
    assert only_part.resumed() == "parts of 2 stages"
    only_part("static pass", 5, 5, {})
    assert only_part.resumed() == "1 stage and parts of 2 more"
    say_resumed("", tmp_path)
    assert capsys.readouterr().err == ""
    say_resumed("3 of 9 events", tmp_path)
    assert capsys.readouterr().err.startswith(f"resumed: 3 of 9 events finished before were kept from {tmp_path}")
    STATE["quiet"] = True
    try:
        say_resumed("3 of 9 events", tmp_path)
    finally:
        STATE["quiet"] = False
    assert capsys.readouterr().err == ""


def test_quiet_study_run_prints_no_size_announcement(tmp_path):
    """``-q`` prints errors only: ``study run``'s size line (progress, on stderr) is left out, as the population
    commands leave out theirs (a trial saw it printed under ``-q``).  The run is refused by its step budget after
    the announcement, so the test simulates nothing; the error itself is still printed."""
    study = Path(__file__).resolve().parents[2] / "examples" / "studies" / "modes_sensitivity.toml"
    argv = ["study", "run", str(study), "--out", str(tmp_path / "s.nc"), "--max-steps", "10", "--workers", "1"]
    loud = runner.invoke(app, argv)
    quiet = runner.invoke(app, ["-q", *argv])
    assert loud.exit_code == quiet.exit_code == 2, (loud.output, quiet.output)
    assert "crossings" in loud.stderr.splitlines()[0]  # (the announcement: "<name>: N crossings … in M batches")
    assert quiet.stderr.startswith("error:") and "crossings (" not in quiet.stderr
