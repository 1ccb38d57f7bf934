"""Every command that reads an input file names that file, as given on the command line, in the
first line of a user error (``vbikit.cli.guard.guard(file=…)`` and ``vbikit.errors.naming_file``, the
one place), and never prints the file's content; and the ``validate`` commands print their summary
on stdout, warnings and errors on stderr."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.errors import naming_file

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: a line of every bad file that no message may show (a message quoting the file would)
MARKER = "CONTENT-MARKER-7f3a"
STREAM = str(EXAMPLES / "traffic" / "stream.csv")
BASE = str(EXAMPLES / "traffic" / "base" / "bridge2.toml")

#: kind -> (example file, (text, its bad replacement), first line of the error with {f} the file as given)
KINDS = {
    "scenario": ("paper/fig9_tire_models.toml", ("speed_kmh = 75", "speed_kmh = -5"), "error: invalid scenario {f}:"),
    # (vbikit bridge reads the [bridge] table alone: its error is of a bridge key)
    "scenario-bridge": ("paper/fig9_tire_models.toml", ("n_modes = 20", "n_modes = -20"), "error: {f}: bridge.n_modes"),
    "scenario-check": ("paper/fig9_tire_models.toml", ("speed_kmh = 75", "speed_kmh = 75\nlateral_offset = 40"),
                       "error: {f}: crossing.lateral_offset = 40 m puts wheels"),
    "study": ("studies/modes_sensitivity.toml", ("batch_size = 5", "batch_size = -5"), "error: invalid study {f}:"),
    "study-base": ("studies/modes_sensitivity.toml", ("speed_kmh = 75", "speed_kmh = -5"),
                   "error: {f}: base + axes (bridge.model = "),
    "lifetime": ("lifetime/lifetime.toml", ("days = 7", "days = -7"), "error: invalid lifetime file {f}:"),
    "rail": ("railway/hslm_20m.toml", ("span = 20.0 ", "span = -20.0 "), "error: invalid rail file {f}:"),
    "driveby": ("driveby/DRIVEBY.toml", ("rate = 200.0 ", "rate = -200.0 "), "error: invalid drive-by file {f}:"),
    "field": ("field/FIELD.toml", ("speed_kmh = 64.4", "speed_kmh = -5"), "error: {f}: crossing.speed_kmh: expected a number in [0.0036, 1080] [km/h]"),
    "records": ("traffic/stream.csv", ("v000002,2.905,2,,-x,60.38", f"{MARKER},2.905,2,,-x,-60.38"),
                "error: {f}:3: column 6 (speed [km/h]): -60.38 km/h is below the smallest speed 0.0036 km/h (a speed is "
                "positive: the direction column, +x or -x, gives the sense of travel); allowed 0.0036 … 252 km/h"),
    "traffic-base": ("traffic/base/bridge2.toml", ("n_modes = 10", "n_modes = -10"), "error: invalid scenario {f}:"),
}

#: (kind, command line with {f} the bad file): every command that reads each kind ({base}, {stream}: good files)
CASES = [
    *[("scenario", c) for c in ("run {f}", "run {f} --random", "validate {f}", "cite {f}", "compare-tires {f}")],
    ("scenario-bridge", "bridge {f}"),
    ("scenario-check", "run {f}"), ("scenario-check", "validate {f}"),
    *[("study", c) for c in ("study validate {f}", "study run {f} --out x.nc", "validate {f}")],
    ("study-base", "study validate {f}"), ("study-base", "validate {f}"),
    ("lifetime", "lifetime {f}"), ("lifetime", "validate {f}"),
    ("rail", "rail {f}"), ("rail", "validate {f}"),
    ("driveby", "driveby {f}"), ("driveby", "validate {f}"),
    ("field", "field {f}"), ("field", "validate {f}"),
    ("records", "traffic {f} --bridge {base} --out x.nc"), ("records", "validate {f}"),
    ("traffic-base", "traffic {stream} --bridge {f} --out x.nc"), ("traffic-base", "validate {f}"),
]


@pytest.mark.parametrize("kind, command", CASES, ids=[f"{k}: {c.format(f='FILE', base='BASE', stream='STREAM')}"
                                                     for k, c in CASES])
def test_an_input_files_error_names_it_in_the_first_line(tmp_path, monkeypatch, kind, command):
    example, (good, bad), first = KINDS[kind]
    text = (EXAMPLES / example).read_text()
    assert good in text, f"{example} changed: update the test's bad value"
    folder = tmp_path / "inputs"
    folder.mkdir()
    name = f"bad{Path(example).suffix}"
    comment = "" if name.endswith(".csv") else f"# {MARKER}\n"
    (folder / name).write_text(comment + text.replace(good, bad, 1))
    monkeypatch.chdir(tmp_path)
    given = f"inputs/{name}"  # as typed: a relative path in a folder (not the basename, not resolved)
    res = runner.invoke(app, command.format(f=given, base=BASE, stream=STREAM).split())
    assert res.exit_code == 2, res.output
    assert res.stderr.splitlines()[0].startswith(first.format(f=given)), res.stderr
    assert MARKER not in res.output and MARKER not in res.stderr
    assert res.stdout == ""


def test_naming_file_keeps_a_message_that_names_the_file_or_an_option():
    assert naming_file("invalid study:\n  seed: x", "a/s.toml") == "invalid study a/s.toml:\n  seed: x"
    assert naming_file("a/s.toml: not valid TOML: …", "a/s.toml") == "a/s.toml: not valid TOML: …"
    assert naming_file("scenario file not found: a/s.toml", "a/s.toml") == "scenario file not found: a/s.toml"
    assert naming_file("data.toml: x", "a.toml") == "a.toml: data.toml: x"  # another file, not this one
    assert naming_file("b/a.toml: x", "a.toml") == "a.toml: b/a.toml: x"
    assert naming_file("--scheduler tcp://h:1: cannot connect", "r.toml") == "--scheduler tcp://h:1: cannot connect"


@pytest.mark.parametrize("command", ["validate", "study validate"])
def test_validate_commands_print_the_summary_once_on_stdout(command):
    study = str(EXAMPLES / "studies" / "modes_sensitivity.toml")
    res = runner.invoke(app, [*command.split(), study])
    assert res.exit_code == 0, res.output
    lines = res.stdout.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{study}: ok — ")
    assert "40 crossings (bridge.model (2) × bridge.n_modes (2) × tire.n_points (2) × road.seed (5)) in 8 batches; " \
           "8 set-ups checked" in lines[0]
    assert res.stderr == ""  # the size is the summary's; no second copy on stderr


@pytest.mark.parametrize("command", ["validate", "study validate"])
def test_validate_commands_print_warnings_on_stderr_and_not_with_quiet(tmp_path, command):
    text = (EXAMPLES / "studies" / "modes_sensitivity.toml").read_text()
    path = tmp_path / "fast.toml"  # 160 km/h: a speed warning for every set-up
    path.write_text(text.replace("speed_kmh = 75", "speed_kmh = 160"))
    res = runner.invoke(app, [*command.split(), str(path)])
    assert res.exit_code == 0, res.output
    assert len(res.stdout.splitlines()) == 1 and res.stdout.startswith(f"{path}: ok — ")
    warnings = res.stderr.splitlines()
    assert warnings and all(w.startswith("warning: ") for w in warnings), res.stderr
    quiet = runner.invoke(app, [*command.split(), str(path), "-q"])
    assert quiet.exit_code == 0 and quiet.stderr == "" and quiet.stdout == res.stdout


def test_a_missing_file_given_relative_says_where_it_was_looked_for(tmp_path, monkeypatch):
    """A relative path that is not there (a lifetime file's records copied without them, a new user's trial) is
    named as given and with the absolute path it was looked for at; an absolute one as given only."""
    import os

    from vbikit._files import input_file

    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError) as err:
        input_file("wim.csv", ValueError, "records file (CSV)")
    assert str(err.value) == f"records file (CSV) not found: wim.csv (looked for {os.path.join(str(tmp_path), 'wim.csv')})"
    with pytest.raises(ValueError) as err:
        input_file(tmp_path / "wim.csv", ValueError, "records file (CSV)")
    assert str(err.value) == f"records file (CSV) not found: {tmp_path / 'wim.csv'}"
