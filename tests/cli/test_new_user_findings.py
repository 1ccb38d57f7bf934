"""What a new user found in the command line, each reproduced with the shipped examples and each
test failing on the code before the fix (main at c7b4b9b):

1. ``--out-dir`` naming a file or ``/dev/null``: ``vbikit run`` (and demo, compare-tires, bridge,
   field, study paper-*) ran the whole simulation, then failed with ``[Errno 17] … File exists``;
2. ``vbikit run`` of a scenario with load effects printed each step warning twice (a log record
   and ``warning:``);
3. a bound error said ``Input should be greater than or equal to 0.0036 (got -75)``: one bound,
   no unit;
4. ``vbikit rail`` with ``min`` above 1.2 × ``line_max`` named ``speeds.max``, a key the file lacks;
5. a drive-by sensor's bad body named vehicle ``'sprung-mass'`` for the file's ``test-cart``;
6. the compile notice once per study worker (and once more in the parent); ``bridge --help``
   called its argument ``name``; ``study validate --yes`` said "Run a study".
"""
from __future__ import annotations

import logging
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest
import typer.main
from typer.testing import CliRunner

from vbikit.cli import app
from cli_walk import commands as _commands

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: every command that takes --out-dir, with the arguments that make it run (the shipped examples)
OUT_DIR_COMMANDS = {
    "run": [str(EXAMPLES / "paper" / "bridge2_hs20_girder4.toml")],
    "demo": [],
    "compare-tires": [str(EXAMPLES / "paper" / "fig9_tire_models.toml")],
    "bridge": ["paper-bridge-1-beam"],
    "field": [str(EXAMPLES / "field" / "FIELD.toml")],
    "driveby": [str(EXAMPLES / "driveby" / "DRIVEBY.toml")],
    "lifetime": [str(EXAMPLES / "lifetime" / "lifetime.toml")],
    "rail": [str(EXAMPLES / "railway" / "hslm_20m.toml")],
    "traffic": [str(EXAMPLES / "traffic" / "stream.csv"), "--bridge", str(EXAMPLES / "traffic" / "base" / "bridge2.toml")],
    **{f"study paper-{fig}": [] for fig in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11", "all")},
}


def test_every_out_dir_option_is_the_one_checked_option():
    """Every command with --out-dir checks it through the one shared callback (guard.check_out_dir),
    and every such command is exercised below."""
    from vbikit.cli.guard import check_out_dir

    found = {}
    for name, cmd in _commands(typer.main.get_command(app)):
        for param in cmd.params:
            if "--out-dir" in getattr(param, "opts", ()):
                found[name] = param.callback
    assert set(found) == set(OUT_DIR_COMMANDS)
    for name, callback in found.items():  # typer wraps the callback (functools.wraps)
        assert getattr(callback, "__wrapped__", None) is check_out_dir, name


@pytest.mark.parametrize("command", sorted(OUT_DIR_COMMANDS))
def test_out_dir_naming_a_file_or_dev_null_is_refused_before_computing(tmp_path, command):
    afile = tmp_path / "afile"
    afile.write_text("x")
    for out_dir, message in ((str(afile), "exists and is not a folder"), ("/dev/null", "lies in /dev")):
        t0 = time.process_time()
        res = runner.invoke(app, [*command.split(), *OUT_DIR_COMMANDS[command], "--out-dir", out_dir])
        assert res.exit_code == 2, res.output
        assert f"error: --out-dir {out_dir}: {message}" in res.stderr, res.stderr
        assert time.process_time() - t0 < 2.0  # refused as the command line is read (the run took ~7 s of CPU)
    assert afile.read_text() == "x"


def test_check_out_dir_passes_a_new_folder_and_none(tmp_path):
    from vbikit.cli.guard import check_out_dir

    assert check_out_dir(None) is None
    assert check_out_dir(tmp_path / "new" / "deeper") == tmp_path / "new" / "deeper"
    assert not (tmp_path / "new").exists()  # checked, not created: the writers create it


def test_step_warning_printed_once(monkeypatch):
    """examples/verification/fryba_moving_force.toml asks for shears and reactions at a step too
    coarse for them: each warning once, in the CLI's words, no log record of it."""
    from vbikit.analysis import effects

    monkeypatch.setattr(effects, "_LOGGED", set())  # as in a fresh process
    res = runner.invoke(app, ["run", str(EXAMPLES / "verification" / "fryba_moving_force.toml")])
    assert res.exit_code == 0, res.output
    text = "shear at x = 0 m: the step"
    assert res.stderr.count(text) == 1 and f"warning: {text}" in res.stderr, res.stderr
    assert "WARNING vbikit.analysis.effects" not in res.stderr, res.stderr


def test_step_warning_still_logged_for_direct_library_calls(monkeypatch, caplog):
    """load_effect_responses (no summary to carry the warning) keeps logging it."""
    from dataclasses import replace

    from vbikit.analysis import effects
    from vbikit.scenario import load_scenario
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import simulate

    monkeypatch.setattr(effects, "_LOGGED", set())
    crossing = preflight(load_scenario(EXAMPLES / "verification" / "fryba_moving_force.toml")).built.crossing
    result = simulate(replace(crossing, dt=0.00209))
    shear = crossing.bridge.load_effect("shear", x=0.0)
    with caplog.at_level(logging.WARNING, logger="vbikit.analysis.effects"):
        resp = effects.load_effect_responses(result, [shear])[0]
    assert resp.step_warning is not None and resp.step_warning in caplog.text


def test_bound_error_shows_both_bounds_and_the_unit(tmp_path):
    """speed_kmh = -75: the range is [MIN_SPEED, MAX_SPEED] × 3.6 = [1e-3, 300] m/s × 3.6 =
    [0.0036, 1080] km/h (vbikit.scenario.schema)."""
    text = (EXAMPLES / "paper" / "bridge2_hs20_girder4.toml").read_text()
    lines = [("speed_kmh = -75" if line.split("=")[0].strip() == "speed_kmh" else line) for line in text.splitlines()]
    path = tmp_path / "neg.toml"
    path.write_text("\n".join(lines) + "\n")
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 2
    assert "crossing.speed_kmh: expected a number in [0.0036, 1080] [km/h], got -75" in res.stderr, res.stderr


def test_bound_message_reads_both_bounds_the_unit_and_integers():
    from typing import Annotated, Optional

    from pydantic import BaseModel, Field, ValidationError

    from vbikit._validation import bound_message, validation_message

    class Section(BaseModel):
        depth: Optional[float] = Field(None, gt=0, le=0.5, description="depth [m]")
        count: int = Field(1, ge=1, le=100, description="points [-]")
        spans: list[Annotated[float, Field(ge=0.5, le=5000)]] = []

    class File(BaseModel):
        s: Section

    for data, words in (({"depth": -0.02}, "s.depth: expected a number in (0, 0.5] [m], got -0.02"),
                        ({"count": 0}, "s.count: expected an integer in [1, 100], got 0"),
                        ({"spans": [20.0, 1e9]}, "s.spans[2]: expected a number in [0.5, 5000], got 1000000000.0")):
        with pytest.raises(ValidationError) as err:
            File.model_validate({"s": data})
        assert words in validation_message(err.value, "", model=File)
    assert bound_message({"type": "missing"}) is None
    assert bound_message({"type": "less_than", "ctx": {"lt": 1}, "input": 5}) == "expected a number < 1, got 5"


def test_rail_min_above_the_line_speed_top_names_min_and_line_max(tmp_path):
    """min = 400 with line_max = 300: the top speed is 1.2 × 300 = 360 km/h (EN 1991-2 6.4.6.2(1))."""
    text = (EXAMPLES / "railway" / "hslm_20m.toml").read_text().replace("min = 100.0", "min = 400.0")
    (tmp_path / "talgo_like.csv").write_text((EXAMPLES / "railway" / "talgo_like.csv").read_text())
    path = tmp_path / "RAIL.toml"
    path.write_text(text)
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 2
    assert "speeds.min: must be below the sweep's highest speed 1.2 × line_max = 1.2 × 300 = 360 km/h, got 400" \
        in res.stderr and "raise line_max above 333.3 km/h" in res.stderr, res.stderr
    assert "speeds.max" not in res.stderr


def test_driveby_sensor_error_names_the_files_vehicle(tmp_path):
    text = (EXAMPLES / "driveby" / "DRIVEBY.toml").read_text()
    assert 'body = "body"' in text and 'model = "test-cart"' in text
    path = tmp_path / "DRIVEBY.toml"
    path.write_text(text.replace('body = "body"', 'body = "bdy"'))
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 2
    assert "sensors.cart_acc.body: 'bdy' is not a body of vehicle 'test-cart'; bodies: body" in res.stderr, res.stderr


class _Fresh:  # a dispatcher with nothing compiled and no on-disk cache
    overloads: dict = {}


def test_compile_notice_once_a_process(monkeypatch, caplog):
    from vbikit.solve import compile_notice

    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())
    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        compile_notice.announce_compile(_Fresh(), "this process")  # the study, then its first crossing
        compile_notice.announce_compile(_Fresh())
    assert caplog.text.count("compiling the kernel") == 1


def _announced() -> bool:
    from vbikit.solve import compile_notice

    return "*" in compile_notice._ANNOUNCED


def test_study_workers_do_not_announce_again(monkeypatch):
    """The workers' initializer marks the notice given (their parent announced it for all)."""
    import os

    from vbikit.solve import compile_notice
    from vbikit.study.workers import _die_with_parent

    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())
    with ProcessPoolExecutor(max_workers=1, initializer=_die_with_parent, initargs=(os.getpid(), False)) as pool:
        assert pool.submit(_announced).result(timeout=60) is True
    assert "*" not in compile_notice._ANNOUNCED


def test_bridge_argument_and_validate_yes_help():
    text = runner.invoke(app, ["bridge", "--help"]).output
    assert "PRESET|SCENARIO.toml" in text and "name <str>" not in text
    text = runner.invoke(app, ["study", "validate", "--help"]).output
    assert "Run a study" not in text and "Accept a study of more than 1e6 crossings" in text


def test_list_items_are_named_from_one_in_every_validation_message():
    """A new user read `trains.tables[1]` (1-based) beside pydantic's `trains.hslm_b.0.d` and
    `fatigue.details.0.category` (0-based): every key now names a list item `name[k]`, k from 1
    (`vbikit._validation.key_name`, also behind the scenario files' `error_path`)."""
    from vbikit._validation import key_name
    from vbikit.rail.spec import RailSpecError, parse_rail_spec
    from vbikit.scenario.schema import error_path

    assert key_name(("trains", "hslm_b", 0, "d")) == "trains.hslm_b[1].d"
    assert key_name(("a", 2, 0, "b")) == "a[3][1].b" and key_name(("__root__", "x")) == "x"
    assert error_path(("road", "defects", 0, "depth")) == "road.defects[1].depth"
    with pytest.raises(RailSpecError, match=r"trains\.hslm_b\[2\]\.d: expected a number in \[0\.5, 50\]"):
        parse_rail_spec({"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0}, "speeds": {"max": 300.0},
                         "trains": {"hslm_b": [{"n": 10, "d": 3.5}, {"n": 10, "d": 60.0}]}})
