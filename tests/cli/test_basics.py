"""CLI conventions: version, bare command, help texts, verbosity flags, completion, output folder."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit import __version__
from vbikit.cli import app

runner = CliRunner()
COMMANDS = [["run"], ["validate"], ["demo"], ["compare-tires"], ["presets"], ["bridge"], ["field"], ["cite"],
            ["study"], ["study", "run"], ["study", "validate"], ["study", "paper-fig6"]]


def test_version():
    res = runner.invoke(app, ["--version"])
    assert res.exit_code == 0 and res.output.strip() == f"vbikit {__version__}"


def test_bare_command_prints_help_and_succeeds():
    res = runner.invoke(app, [], prog_name="vbikit")
    assert res.exit_code == 0
    assert "Usage: vbikit" in res.output and "compare-tires" in res.output


@pytest.mark.parametrize("command", COMMANDS, ids=" ".join)
def test_every_help_text_renders(command):
    res = runner.invoke(app, [*command, "--help"])
    assert res.exit_code == 0, res.output
    assert "Usage:" in res.output


def test_brackets_in_help_texts_are_kept():
    # "[tire]" was once swallowed as markup
    assert "its [tire] section" in runner.invoke(app, ["compare-tires", "--help"]).output


def test_completion_and_verbosity_options_exist():
    out = runner.invoke(app, ["--help"]).output
    for opt in ("--install-completion", "--show-completion", "--quiet", "--verbose", "--version"):
        assert opt in out
    assert runner.invoke(app, ["-q", "presets"]).exit_code == 0
    assert runner.invoke(app, ["-vv", "presets"]).exit_code == 0


def test_bridge_figure_goes_to_the_output_folder(tmp_path: Path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["bridge", "paper-bridge-1-beam", "--modes", "3"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "vbikit-out" / "paper-bridge-1-beam-modes.png").is_file()
    assert not (tmp_path / "paper-bridge-1-beam-modes.png").exists()


@pytest.mark.parametrize("argv, words", [
    (["traffic", "records.csv", "--seed", "-1"], ["vbikit traffic:", "'--seed'", "greater than or equal to 0"]),
    (["run"], ["vbikit run:", "Missing argument 'SCENARIO.toml'"]),
    (["run", "x.toml", "--bogus"], ["vbikit run:", "No such option: --bogus"]),
    (["nosuchcommand"], ["vbikit:", "No such command 'nosuchcommand'"]),
    (["study", "run"], ["vbikit study run:", "Missing argument 'STUDY.toml'"]),
    (["traffic", "records.csv", "--batch-size", "0"], ["vbikit traffic:", "'--batch-size'"]),
])
def test_a_usage_error_is_one_error_line_like_every_other(argv, words):
    """What the parser refuses before any command runs (a value out of an option's range, an unknown
    option or command, a missing argument) ends as every error of the command line: exit 2 and one
    line ``error: …`` naming the command and its --help — not click's usage text and ``Error: …``."""
    res = runner.invoke(app, argv, prog_name="vbikit")
    assert res.exit_code == 2, res.output
    lines = [line for line in res.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert "Usage:" not in res.output and "Traceback" not in res.output
    command = words[0].rstrip(":")
    assert lines[0].endswith(f"see '{command} --help'"), lines[0]
    for word in words:
        assert word in lines[0], lines[0]


def test_a_closed_output_pipe_exits_141_without_a_traceback():
    """``vbikit presets | head -1``: the reader closes the pipe; the run ends as a program SIGPIPE ends (141),
    not with 1, the code of a bug in vbikit (click's own), and prints nothing on stderr.  The read end is closed
    before vbikit writes, so every write meets the closed pipe."""
    import os
    import subprocess
    import sys

    from vbikit.cli import EXIT_BROKEN_PIPE

    read, write = os.pipe()
    proc = subprocess.Popen([sys.executable, "-c", "from vbikit.cli import main; main()", "presets"], stdout=write, stderr=subprocess.PIPE)
    os.close(write)
    os.close(read)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == EXIT_BROKEN_PIPE == 141, err.decode()
    assert err.decode().strip() == ""
