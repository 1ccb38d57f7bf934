"""The commands that run single crossings outside ``vbikit run`` (``compare-tires``, ``field``) take the step and
memory budgets that their refusals name: a trial's ``compare-tires`` and ``field`` said "raise --max-steps" and
then refused that option (``No such option``), so a fine-step run could not be made at all.  Each refuses a run
above the budget before any crossing is simulated."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.cli.guard import budget_help

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("command", ["run", "compare-tires", "field"])
def test_the_single_crossing_commands_take_the_budgets_their_refusals_name(command):
    """One definition of each budget option (``guard.MAX_STEPS``, ``guard.MAX_MEMORY``): the same help text."""
    res = runner.invoke(app, [command, "--help"], terminal_width=400)
    assert res.exit_code == 0, res.output
    text = " ".join(res.stdout.replace("│", " ").split())
    for option, counts, default in (("--max-steps", "time steps of the run", "5e6"),
                                    ("--max-memory", "memory of the run", "4GiB")):
        assert option in text
        assert " ".join(budget_help(counts, default).split()) in text


def test_compare_tires_refuses_above_the_step_budget_before_any_run(tmp_path, monkeypatch):
    """The four tire models' runs are checked first: a budget below the run's steps stops the command with
    exit 2, naming the option, and nothing is simulated or written."""
    import vbikit.scenario.pipeline

    def no_run(*args, **kwargs):
        raise AssertionError("a run started although its check refused it")

    monkeypatch.setattr(vbikit.scenario.pipeline, "run_planned", no_run)
    res = runner.invoke(app, ["compare-tires", str(EXAMPLES / "paper" / "bridge2_hs20_girder4.toml"), "--out-dir",
                              str(tmp_path / "out"), "--max-steps", "500"])
    assert res.exit_code == 2, res.output
    assert "above the limit 500" in res.stderr and "raise --max-steps" in res.stderr
    assert not (tmp_path / "out").exists()


def test_field_refuses_above_the_step_budget_before_any_run(tmp_path, monkeypatch):
    """``vbikit field --max-steps``: the field file's first case is refused before it is simulated."""
    import vbikit.field.workflow

    def no_run(*args, **kwargs):
        raise AssertionError("a crossing was simulated although its check refused it")

    monkeypatch.setattr(vbikit.field.workflow, "simulate", no_run)
    res = runner.invoke(app, ["field", str(EXAMPLES / "field" / "FIELD.toml"), "--out-dir", str(tmp_path / "out"),
                              "--max-steps", "100"])
    assert res.exit_code == 2, res.output
    assert "case 'case1'" in res.stderr and "above the limit 100" in res.stderr and "--max-steps" in res.stderr
    assert not (tmp_path / "out").exists()


def test_field_passes_its_budget_to_every_run(monkeypatch, tmp_path):
    """The budget given reaches the simulations themselves, not only the check (a raised budget would otherwise
    pass the check and be refused by the run's own default)."""
    import vbikit.field.workflow
    from vbikit.field.report import run_field

    seen = []
    real = vbikit.field.workflow.simulate

    def spy(crossing, *args, **kwargs):
        seen.append(kwargs.get("limits"))
        return real(crossing, *args, **kwargs)

    monkeypatch.setattr(vbikit.field.workflow, "simulate", spy)
    from vbikit.solve.budget import Limits

    budget = Limits(max_steps=int(3e6))
    run_field(EXAMPLES / "field" / "FIELD.toml", tmp_path / "out", ["point"], limits=budget)
    assert seen and all(limits is budget for limits in seen)
