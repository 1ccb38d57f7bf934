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
    """A budget below the run's steps stops the command with exit 2, naming the option, and nothing is simulated or
    written; and the four tire models' runs are all checked first: a refusal of the last model (faked: its check
    refuses) stops the command before the first model runs."""
    import vbikit.scenario.pipeline
    import vbikit.scenario.preflight
    from vbikit.solve.budget import BudgetError

    def no_run(*args, **kwargs):
        raise AssertionError("a run started although a check refused one of the runs")

    monkeypatch.setattr(vbikit.scenario.pipeline, "run_planned", no_run)
    scenario = str(EXAMPLES / "paper" / "bridge2_hs20_girder4.toml")
    res = runner.invoke(app, ["compare-tires", scenario, "--out-dir", str(tmp_path / "out"), "--max-steps", "500"])
    assert res.exit_code == 2, res.output
    assert "above the limit 500" in res.stderr and "raise --max-steps" in res.stderr
    assert not (tmp_path / "out").exists()
    real = vbikit.scenario.preflight.preflight

    def refuse_the_rigid_disk(spec, limits=None):
        if spec.tire.model == "rigid-disk":
            raise BudgetError("the rigid disk's run is above the budget (faked)")
        return real(spec, limits)

    monkeypatch.setattr(vbikit.scenario.preflight, "preflight", refuse_the_rigid_disk)
    res = runner.invoke(app, ["compare-tires", scenario, "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 2 and "the rigid disk's run is above the budget (faked)" in res.stderr, res.output


def test_field_refuses_above_the_step_budget_before_any_run(tmp_path, monkeypatch):
    """``vbikit field --max-steps``: every case is checked before any is simulated — the second case refused (its
    check faked to refuse) stops the command before the first case runs; a real budget below the steps is named."""
    import vbikit.field.workflow
    from vbikit.solve.budget import BudgetError

    def no_run(*args, **kwargs):
        raise AssertionError("a crossing was simulated although a check refused one of them")

    monkeypatch.setattr(vbikit.field.workflow, "simulate", no_run)
    res = runner.invoke(app, ["field", str(EXAMPLES / "field" / "FIELD.toml"), "--out-dir", str(tmp_path / "out"),
                              "--max-steps", "100"])
    assert res.exit_code == 2, res.output
    assert "case 'case1'" in res.stderr and "above the limit 100" in res.stderr and "--max-steps" in res.stderr
    assert not (tmp_path / "out").exists()
    real = vbikit.field.workflow.check_steps
    checked = []

    def refuse_the_second_case(crossing, limits=None):  # (one tire: one check a case, in the file's order)
        checked.append(crossing)
        if len(checked) == 2:
            raise BudgetError("case 2 is above the budget (faked)")
        return real(crossing, limits)

    monkeypatch.setattr(vbikit.field.workflow, "check_steps", refuse_the_second_case)
    res = runner.invoke(app, ["field", str(EXAMPLES / "field" / "FIELD.toml"), "--out-dir", str(tmp_path / "out"),
                              "--tires", "point"])
    assert res.exit_code == 2 and "case 2 is above the budget (faked)" in res.stderr, res.output


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


def test_compare_tires_says_each_step_check_was_refused_by_the_budget(tmp_path):
    """A budget that admits the runs but not their half-step checks: each model's line says its check was not run and
    why (a review found a crash formatting the missing change)."""
    from test_compare_tires import SMALL  # (a 10 m beam: about 1,450 steps a run, 2,900 at half the step)

    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    res = runner.invoke(app, ["compare-tires", str(path), "--out-dir", str(tmp_path / "out"), "--max-steps", "2000"])
    assert res.exit_code == 0, res.output
    lines = [line for line in res.stdout.splitlines() if line.startswith("  step check, ")]
    assert len(lines) == 4 and all("not run: the run at half the step is above the run's budget" in line for line in lines)
