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
