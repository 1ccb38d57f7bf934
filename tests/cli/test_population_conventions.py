"""One convention across the population commands (``vbikit traffic``, ``lifetime``, ``driveby``, ``rail`` and
``study run``): each test loops over all of them and asserts the same behaviour.

* ``--workers``: one option (``guard.workers_option``), one help (``guard.WORKERS_HELP``, naming the input file's
  key only where the file has one), one default (None: the input file's own setting where it has one, else all cores:
  ``vbikit._validation.default_workers``); ``--json`` one definition on the commands that write a folder;
  ``--scheduler``, ``--progress/--no-progress`` and ``--figures/--no-figures`` one definition each;
* budgets: every budget option's help is ``guard.budget_help``'s (what it counts, per event or the whole run, the
  file's key it overrides, its default — the library's default); every heavy command refuses a run above its
  budget before computing anything, the message naming the option and, where the file has one, the key;
* an input file's errors are listed together: a drive-by file with two bad keys names both, in one message.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import typer.main
from typer.testing import CliRunner

from cli_walk import commands as _commands
from vbikit.cli import app
from vbikit.cli.guard import JSON_HELP, SCHEDULER_HELP, WORKERS_HELP, budget_help

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: the population commands: they run many crossings on local worker processes or a Dask cluster
POPULATION = ("traffic", "lifetime", "driveby", "rail", "study run")
#: those that write a folder (--out-dir: the dataset, a report, a summary JSON and figures)
WITH_FIGURES = ("traffic", "lifetime", "driveby", "rail")
#: a budget option's help (``guard.budget_help``): what it counts, the file's key, the default
BUDGET_HELP = re.compile(r"Budget: the most (?P<counts>.+) \((?:e\.g\. 8GiB; )?(?:overrides the file's (?P<key>\S+); )?"
                         r"default (?P<default>\S+)\); estimated before anything is computed, refused above\.")
#: command -> {budget option: the input file's key it overrides (None: the file has none)}
BUDGETS = {
    "traffic": {"--max-memory": None, "--max-steps": None},
    "lifetime": {"--max-memory": None, "--budget-hours": "budget_hours"},
    "driveby": {"--max-steps": "max_steps"},
    "rail": {"--max-steps": "run.budget", "--max-coupled-steps": "coupled.max_steps"},
    "study run": {"--max-memory": None, "--max-steps": None},
}


def _options(command: str) -> dict:
    """The options of ``command`` by their longest name."""
    cmd = dict(_commands(typer.main.get_command(app)))[command]
    return {max(p.opts, key=len): p for p in cmd.params if p.opts and p.opts[0].startswith("--")}


#: command -> the input file's key of its worker processes (the others' files have none)
WORKERS_KEY = {"rail": "run.workers"}


@pytest.mark.parametrize("command", POPULATION)
def test_workers_and_scheduler_are_one_definition(command):
    opts = _options(command)
    key = WORKERS_KEY.get(command)
    default = "" if key is None else f"the input file's {key}, else "
    assert opts["--workers"].help == WORKERS_HELP.format(default=default) and opts["--workers"].default is None
    # the help names a file's key only where the command's file has one (not a railway key in every command)
    assert ("input file" in opts["--workers"].help) == (key is not None) and "all cores" in opts["--workers"].help
    assert opts["--scheduler"].help == SCHEDULER_HELP
    if command in WITH_FIGURES:
        assert opts["--json"].help == JSON_HELP and opts["--json"].default is False


def test_progress_and_figures_are_one_definition():
    progress = {_options(c)["--progress"].help for c in POPULATION}
    assert len(progress) == 1 and "-q" in progress.pop()
    figures = {_options(c)["--figures"].help for c in WITH_FIGURES}
    assert len(figures) == 1
    for command in WITH_FIGURES:  # the one checked --out-dir option (guard.out_dir_option)
        assert _options(command)["--out-dir"].callback is not None


@pytest.mark.parametrize("command", POPULATION)
def test_budget_options_say_what_they_count_and_the_files_key(command):
    opts = _options(command)
    assert {o for o in opts if o.startswith(("--max-", "--budget")) and o != "--max-vehicles"} == set(BUDGETS[command])
    for name, key in BUDGETS[command].items():
        m = BUDGET_HELP.fullmatch(opts[name].help)
        assert m, opts[name].help
        assert m["key"] == key
        assert re.search(r"\b(each|whole|the run)\b", m["counts"]), m["counts"]  # per event / crossing or the whole run
        assert opts[name].help == budget_help(m["counts"], m["default"], key)  # (one wording)


def test_the_budget_helps_give_the_librarys_defaults():
    """The default a budget's help names is the library's (one truth: a changed default fails here)."""
    from vbikit.driveby.spec import MAX_STEPS
    from vbikit.lifetime.spec import DEFAULT_BUDGET_HOURS
    from vbikit.rail.spec import CoupledSection, RunSection
    from vbikit.solve.budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_STEPS, GIB

    expected = {"--max-memory": DEFAULT_MAX_MEMORY, "--max-steps": DEFAULT_MAX_STEPS}
    by_command = {("driveby", "--max-steps"): MAX_STEPS, ("lifetime", "--budget-hours"): DEFAULT_BUDGET_HOURS,
                  ("rail", "--max-steps"): RunSection().budget,
                  ("rail", "--max-coupled-steps"): CoupledSection().max_steps}
    for command in POPULATION:
        for name, opt in _options(command).items():
            if name in BUDGETS[command]:
                text = BUDGET_HELP.fullmatch(opt.help)["default"]
                value = float(text.removesuffix("GiB")) * (GIB if text.endswith("GiB") else 1)
                assert value == by_command.get((command, name), expected.get(name)), (command, name, text)


def _rail_coupled(tmp_path: Path) -> str:
    """The railway example with coupled cars and a file budget of 1000 filter steps (which the command line raises)."""
    text = (EXAMPLES / "railway" / "hslm_20m.toml").read_text()
    assert "[run]\nworkers = 2" in text
    path = tmp_path / "coupled.toml"
    path.write_text(text.replace('tables = ["talgo_like.csv"]', "").replace(
        "[run]\nworkers = 2", "[coupled]\nenabled = true\n\n[run]\nworkers = 2\nbudget = 1000"))
    return str(path)


#: command -> (arguments, {out} the output, the option and the key the refusal names); the budgets far too small
REFUSALS = {
    "traffic": ([str(EXAMPLES / "traffic" / "stream.csv"), "--bridge", str(EXAMPLES / "traffic" / "base" / "bridge2.toml"),
                 "--out", "{out}/t.nc", "--max-steps", "10"], "--max-steps", None),
    "lifetime": ([str(EXAMPLES / "lifetime" / "lifetime.toml"), "--out-dir", "{out}", "--budget-hours", "1e-6"],
                 "--budget-hours", "budget_hours"),
    "driveby": ([str(EXAMPLES / "driveby" / "DRIVEBY.toml"), "--out-dir", "{out}", "--max-steps", "10"],
                "--max-steps", "max_steps"),
    "rail": ([str(EXAMPLES / "railway" / "hslm_20m.toml"), "--out-dir", "{out}", "--max-steps", "1000"],
             "--max-steps", "run.budget"),
    "rail (coupled)": (["{coupled}", "--out-dir", "{out}", "--max-steps", "1e12", "--max-coupled-steps", "1"],
                       "--max-coupled-steps", "coupled.max_steps"),
    "study run": ([str(EXAMPLES / "studies" / "modes_sensitivity.toml"), "--out", "{out}/s.nc", "--max-steps", "10"],
                  "--max-steps", None),
}


@pytest.mark.parametrize("case", REFUSALS)
def test_each_heavy_command_refuses_over_budget_before_computing(tmp_path, case):
    """Refused (exit 2) before anything is computed or written, naming the option and the file's key (and that the
    command line raises it: rail (coupled) runs on a file budget of 1000 filter steps raised by --max-steps)."""
    args, option, key = REFUSALS[case]
    out = tmp_path / "out"
    command = case.split(" (")[0].split()
    res = runner.invoke(app, [*command, *(a.format(out=out, coupled=_rail_coupled(tmp_path) if "{coupled}" in a else "")
                                          for a in args), "--no-progress"])
    assert res.exit_code == 2, res.output
    message = res.stderr.split("error: ", 1)[-1]  # (study run says the study's size first, as progress)
    assert f"\nerror: {message}" in f"\n{res.stderr}" and option in message, res.stderr
    if key is not None:
        assert f"raise {key} in the input file or {option} on the command line (at most " in message, message
    assert not out.exists() or not any(out.iterdir()), sorted(out.iterdir())  # nothing computed, nothing written


@pytest.mark.parametrize("command, option, value, allowed", [
    ("rail", "--max-steps", "0", "(0, 1e+13]"), ("rail", "--max-coupled-steps", "1e11", "(0, 1e+10]"),
    ("lifetime", "--budget-hours", "-1", "(0, 10000]"), ("driveby", "--max-steps", "0", "[1, 1e+12]"),
])
def test_a_bad_budget_option_names_it_and_the_allowed_range(tmp_path, command, option, value, allowed):
    files = {"rail": "railway/hslm_20m.toml", "lifetime": "lifetime/lifetime.toml", "driveby": "driveby/DRIVEBY.toml"}
    res = runner.invoke(app, [command, str(EXAMPLES / files[command]), "--out-dir", str(tmp_path / "o"), option, value])
    assert res.exit_code == 2
    assert res.stderr.startswith(f"error: {option}: expected a number in {allowed}"), res.stderr


MARKER = "CONTENT-MARKER-51c2"


def test_driveby_lists_every_error_of_its_file_in_one_message(tmp_path, monkeypatch):
    """As a lifetime or railway file's (pydantic): one heading naming the file, one line a key with its range."""
    text = (EXAMPLES / "driveby" / "DRIVEBY.toml").read_text()
    for good in ("rate = 200.0 ", "\nseed = 1"):
        assert good in text
    bad = f"# {MARKER}\n" + text.replace("rate = 200.0 ", "rate = -200.0 ").replace("\nseed = 1", "\nseed = -3")
    (tmp_path / "bad.toml").write_text(bad)
    monkeypatch.chdir(tmp_path)
    for command in (["driveby", "bad.toml", "--out-dir", "o"], ["validate", "bad.toml"]):
        res = runner.invoke(app, command)
        assert res.exit_code == 2
        lines = res.stderr.splitlines()
        assert lines[0] == "error: invalid drive-by file bad.toml:", res.stderr
        assert lines[1:] == ["  seed: expected an integer in [0, 9.22337e+18], got -3",
                             "  sampling.rate: expected a number in [1, 100000] [Hz], got -200.0"], res.stderr
        assert MARKER not in res.output and MARKER not in res.stderr
    assert not (tmp_path / "o").exists()


def test_driveby_lists_the_errors_of_every_table():
    """Errors in several tables and several items of one (sensors, sweep) are all listed, each once."""
    from vbikit.driveby.spec import DriveByError, parse_driveby
    from vbikit._toml import read_toml

    data = read_toml(EXAMPLES / "driveby" / "DRIVEBY.toml", DriveByError)
    data["batch_size"] = 0
    data["colour"] = "red"
    data["identification"] = {**data.get("identification", {}), "spectrum": "fft"}
    data["sweep"] = {**data["sweep"], "speed": [-1.0], "road_seed": [1.5]}
    data["sensors"] = [{**data["sensors"][0], "quantity": "smell"}, {"body": "body"}]
    with pytest.raises(DriveByError) as err:
        parse_driveby(data)
    lines = str(err.value).splitlines()
    assert lines[0] == "invalid drive-by file:"
    keys = [line.strip().split(":")[0] for line in lines[1:]]
    assert keys == ["colour", "batch_size", "sensors.cart_acc.quantity", "sensors[2].name", "identification.spectrum",
                    "sweep.speed", "sweep.road_seed"], str(err.value)


@pytest.mark.parametrize("command", POPULATION)
def test_the_input_file_argument_is_one_definition(command):
    """``guard.input_file_argument``: the kind of file, its format and its page, in one form."""
    cmd = dict(_commands(typer.main.get_command(app)))[command]
    (argument,) = [p for p in cmd.params if not p.opts[0].startswith("-")]
    assert re.fullmatch(r"[A-Z][\w -]+ \((TOML|CSV), docs/\w+\.md\)\.", argument.help), argument.help
    assert argument.metavar.rsplit(".", 1)[-1].upper() in argument.help
