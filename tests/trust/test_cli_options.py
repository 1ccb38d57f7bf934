"""Bad command-line options and output paths found by trying every command (wt/fuzz, 2026-12-06):
each is refused with exit 2 and one ``error:`` line naming the option (or file) and what is allowed,
before any computation — never a traceback, a fork of 100,000 processes, or an input file
overwritten by an output."""
from __future__ import annotations

import time
from pathlib import Path

import pytest
from fuzz_commands import BASES, RECORDS, write_input
from fuzzing import cli_refused
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
TRAIN = "position_m,load_kN\n0,170\n3,170\n14,170\n17,170\n"
STREAM = (ROOT / "examples" / "traffic" / "stream.csv").read_text().splitlines()


def _command(tmp_path: Path, kind: str) -> list[str]:
    """A small valid invocation of ``kind`` whose files are in ``tmp_path``."""
    if kind in ("lifetime", "driveby", "rail"):
        files = {"lifetime": {"records.csv": "\n".join(RECORDS) + "\n"}, "rail": {"train.csv": TRAIN}, "driveby": {}}[kind]
        path = write_input(tmp_path, kind, BASES[kind], files)
        return [kind, str(path), "--out-dir", str(tmp_path / "out"), "--no-progress", "--no-figures"]
    if kind == "traffic":
        (tmp_path / "rec.csv").write_text("\n".join(STREAM[:4]) + "\n")
        return ["traffic", str(tmp_path / "rec.csv"), "--bridge", "paper-bridge-2-beam", "--lanes", "-1.8,1.8",
                "--out", str(tmp_path / "t.nc"), "--no-progress"]
    study = ROOT / "examples" / "studies" / "modes_sensitivity.toml"
    return ["study", "run", str(study), "--out", str(tmp_path / "r.nc"), "--no-progress"]


COMMANDS = ["traffic", "lifetime", "driveby", "rail", "study"]


@pytest.mark.parametrize("kind", COMMANDS)
@pytest.mark.parametrize("address, words", [("garbage", "not a scheduler address"), ("tcp://host", "missing port"),
                                            ("tcp://host:99999", "port 99999 is not in [0, 65535]")])
def test_a_malformed_scheduler_address_is_refused_before_computing(tmp_path, kind, address, words):
    """Was: a traceback (distributed's ValueError 'missing port number'), after the records were read,
    the study checked or (lifetime) the static pass prepared."""
    t0 = time.process_time()
    res = runner.invoke(app, [*_command(tmp_path, kind), "--scheduler", address])
    err = cli_refused(res, f"--scheduler {address!r}", words, "tcp://host:port")
    assert time.process_time() - t0 < 5.0, err
    assert not (tmp_path / "out").exists() and not (tmp_path / "t.nc").exists()


@pytest.mark.parametrize("kind", COMMANDS)
@pytest.mark.parametrize("workers", ["100000", "0", "-3"])
def test_workers_outside_the_range_are_refused_before_any_process_starts(tmp_path, kind, workers):
    """Was: ``--workers 100000`` forked worker processes until the machine ran out of memory
    (the kernel's OOM killer ended the run); 0 and -3 gave click's usage text."""
    from vbikit._validation import workers_limit

    res = runner.invoke(app, [*_command(tmp_path, kind), "--workers", workers])
    cli_refused(res, "--workers: expected an integer in [1, ", f"{workers_limit()}], got {workers}")


def test_the_workers_limit_is_the_railway_files_limit():
    """One truth: ``run.workers`` of a railway file and ``--workers`` share ``MAX_WORKERS``."""
    from vbikit._validation import MAX_WORKERS, workers_limit
    from vbikit.rail.spec import RunSection

    bound = [m.le for m in RunSection.model_fields["workers"].metadata if getattr(m, "le", None) is not None]
    assert bound == [MAX_WORKERS] and workers_limit() >= MAX_WORKERS


def test_dask_client_refuses_a_malformed_address_with_the_callers_error():
    from vbikit.study.workers import dask_client
    from vbikit.errors import VbikitError

    with pytest.raises(VbikitError, match="--scheduler 'garbage': not a scheduler address"):
        dask_client("garbage", VbikitError, 1.0)


@pytest.mark.parametrize("n", ["0", "101", "100000000"])
def test_compare_tires_n_points_outside_the_tire_models_range(tmp_path, n):
    """Was: a pydantic traceback above 100 (the multi-point tire's own n_points range), after the
    scenario was read; 0 gave click's usage text.  Now the tire model's range, named as the option."""
    res = runner.invoke(app, ["compare-tires", str(ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"),
                              "--n-points", n, "--out-dir", str(tmp_path / "out")])
    cli_refused(res, f"--n-points: expected an integer in [1, 100], got {n}")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("argv", [
    ["traffic", "@rec.csv", "--bridge", "paper-bridge-2-beam", "--lanes", "-1.8,1.8", "--out", "@t.nc", "--no-progress"],
    ["bridge", "paper-bridge-2"],
    ["run", "@s.toml"],
])
def test_a_figure_format_matplotlib_cannot_write_is_refused_before_computing(tmp_path, argv):
    """Was: ``vbikit traffic`` ran every event, and ``vbikit bridge`` solved the modes, before refusing
    ``--plot x.xyz`` (``vbikit run`` checked it in its body; now one option checks it for all three)."""
    (tmp_path / "rec.csv").write_text("\n".join(STREAM[:4]) + "\n")
    (tmp_path / "s.toml").write_text((ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text())
    argv = [a.replace("@", f"{tmp_path}/") for a in argv]
    t0 = time.process_time()
    res = runner.invoke(app, [*argv, "--plot", str(tmp_path / "x.xyz")])
    cli_refused(res, f"--plot {tmp_path / 'x.xyz'}: figures are written as", "png", "not 'xyz'")
    assert time.process_time() - t0 < 1.5  # (the paper-bridge-2 deck's modes alone take longer)
    assert "events ->" not in res.output and "mode  1" not in res.output
    assert not (tmp_path / "t.nc").exists()


@pytest.mark.parametrize("option", ["--out", "--summary"])
@pytest.mark.parametrize("spelling", ["same", "link", "dotted"])
def test_run_never_writes_an_output_over_its_scenario(tmp_path, option, spelling):
    """Was: ``vbikit run s.toml --out s.toml`` replaced the scenario by the time histories (exit 0)."""
    scenario = tmp_path / "s.toml"
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    scenario.write_text(text)
    target = {"same": scenario, "link": tmp_path / "l.toml", "dotted": tmp_path / "sub" / ".." / "s.toml"}[spelling]
    (tmp_path / "sub").mkdir()
    if spelling == "link":
        target.symlink_to(scenario)
    res = runner.invoke(app, ["run", str(scenario), option, str(target)])
    cli_refused(res, f"{option} {target}: is the input file {scenario}", "give another path")
    assert scenario.read_text() == text


@pytest.mark.parametrize("make, words", [(lambda p: p.mkdir(), "is a folder, not a regular file; give the scenario file"),
                                         (lambda p: None, "scenario file not found: ")])
def test_run_random_names_a_folder_as_run_does(tmp_path, make, words):
    """Was: ``vbikit run FOLDER --random`` said 'no such scenario file' (``scenario_of``'s own check);
    now the one reader's words, as ``vbikit run FOLDER``."""
    path = tmp_path / "d.toml"
    make(path)
    for extra in ([], ["--random"]):
        cli_refused(runner.invoke(app, ["run", str(path), *extra]), str(path), words)


def test_binary_input_message_is_grammatical(tmp_path):
    (tmp_path / "b.toml").write_bytes(b"a\x00b")
    cli_refused(runner.invoke(app, ["validate", str(tmp_path / "b.toml")]), "binary content); expected an input file")


@pytest.mark.parametrize("kind, damage, words", [
    ("rail", {"rail.nc": "folder"}, "rail.nc exists and is not a file; the run writes its rail.nc there"),
    ("rail", {"rail.parts": "file"}, "rail.parts exists and is not a folder; the run keeps its finished work"),
    ("lifetime", {"work": "file"}, "work exists and is not a folder; the run keeps its finished work"),
    ("lifetime", {"lifetime.nc": "folder"}, "lifetime.nc exists and is not a file"),
    ("driveby", {"driveby.nc": "folder"}, "driveby.nc exists and is not a file"),
])
def test_an_output_name_taken_in_the_out_dir_is_refused_before_computing(tmp_path, kind, damage, words):
    """Was: the whole sweep (rail, lifetime: every stage) ran, then ``[Errno 21] cannot write
    out/rail.nc: Is a directory``; a file ``work`` or ``rail.parts``: ``[Errno 17] File exists``."""
    out = tmp_path / "out"
    out.mkdir()
    for name, what in damage.items():
        (out / name).mkdir() if what == "folder" else (out / name).write_text("x\n")
    argv = _command(tmp_path, kind)
    t0 = time.process_time()
    err = cli_refused(runner.invoke(app, [*argv, *(["--workers", "1"] if kind != "rail" else [])]), f"--out-dir {out}: ",
                   words, "remove it or choose another --out-dir")
    assert time.process_time() - t0 < 3.0 and "Errno" not in err


def test_a_resumed_stage_that_is_no_dataset_names_no_option_the_command_lacks(tmp_path):
    """``vbikit driveby`` has no --out: the message names no option (the library's words: "write to another
    path"), not an --out the command does not take."""
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "driveby.nc").write_text("not a dataset\n")
    cli_refused(runner.invoke(app, [*_command(tmp_path, "driveby"), "--workers", "1"]), "write to another path")


@pytest.mark.parametrize("make, words", [(lambda p: p.mkdir(), "resp.csv is a folder, not a regular file; give the file as a file"),
                                         (lambda p: None, "case[1].responses: file not found: ")])
def test_a_field_response_file_that_is_a_folder_is_named_so(tmp_path, make, words):
    """Was: 'file not found' for a folder (the field reader's own check, not the one reader's)."""
    field = ROOT / "examples" / "field"
    text = (field / "FIELD.toml").read_text().replace("case1_responses.csv", "resp.csv")
    (tmp_path / "F.toml").write_text(text)
    for name in ("case2_responses.csv", "profile_left.csv", "profile_right.csv"):
        (tmp_path / name).write_text((field / name).read_text())
    make(tmp_path / "resp.csv")
    cli_refused(runner.invoke(app, ["field", str(tmp_path / "F.toml"), "--out-dir", str(tmp_path / "o")]),
             f"{tmp_path / 'F.toml'}: case[1].responses: ", words)


REC_HEAD = "time [s],{col},direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"


@pytest.mark.parametrize("col, row, words", [
    ("lane", "30,1,+x,0.001,50 50,4", "rec.csv:3: column 4 (speed [km/h]): 0.001 km/h is below the smallest speed 0.0036 km/h"),
    ("lateral_offset [m]", "30,1e5,+x,80,50 50,4", "rec.csv:3: column 2 (lateral_offset [m]): 100000 m is beyond the allowed ±50 m"),
])
def test_records_share_the_scenarios_speed_and_offset_limits(tmp_path, col, row, words):
    """Was: a record at 0.001 km/h passed the reader, the events before it were simulated, then the
    crossing's step budget refused it without naming the record (and advised ``--max-steps``, which
    ``vbikit traffic`` does not have); a lateral offset of 100 km ran on a beam.  The records now take
    the scenario's MIN_SPEED and MAX_LATERAL_OFFSET (vbikit._limits, one truth), as ``--lanes`` does."""
    from vbikit._limits import MAX_LATERAL_OFFSET, MIN_SPEED
    from vbikit.scenario import schema

    assert (schema.MIN_SPEED, schema.MAX_LATERAL_OFFSET) == (MIN_SPEED, MAX_LATERAL_OFFSET) == (1e-3, 50.0)
    first = "1,1,+x,80,50 50,4" if col == "lane" else "1,0,+x,80,50 50,4"
    (tmp_path / "rec.csv").write_text(REC_HEAD.format(col=col) + first + "\n" + row + "\n")
    t0 = time.process_time()
    res = runner.invoke(app, ["traffic", str(tmp_path / "rec.csv"), "--bridge", "paper-bridge-2-beam",
                              "--out", str(tmp_path / "t.nc"), "--workers", "1", "--no-progress"])
    cli_refused(res, words)
    assert time.process_time() - t0 < 1.0 and not (tmp_path / "t.nc").exists()


def test_lanes_take_the_same_bound_as_a_lateral_offset(tmp_path):
    res = runner.invoke(app, ["traffic", str(tmp_path / "rec.csv"), "--bridge", "paper-bridge-2-beam", "--out",
                              str(tmp_path / "t.nc"), "--lanes", "-60,60"])
    cli_refused(res, "--lanes: lane centres must be finite numbers within ±50 m")


def test_a_traffic_event_above_the_step_budget_is_refused_before_any_event_runs(tmp_path, monkeypatch):
    """Was: the events before it were simulated, then the step budget refused the slow one naming no
    record, and advised ``--max-steps``, which ``vbikit traffic`` did not have.  The longest event is now
    planned before any runs (0.01 km/h over Bridge 2's beam: (10 + 16.76 + 4) m / 2.78 mm/s ≈ 1.1e4 s at
    its 1.37 ms step ≈ 8.1e6 steps, above the default 5e6), and ``--max-steps`` raises the budget."""
    (tmp_path / "rec.csv").write_text(REC_HEAD.format(col="lane") + "1,1,+x,80,50 50,4\n30,1,+x,0.01,50 50,4\n")
    monkeypatch.setattr("vbikit.traffic.study.TrafficStudy.run_event",
                        lambda self, e: pytest.fail("an event was simulated before the budget was checked"))
    argv = ["traffic", str(tmp_path / "rec.csv"), "--bridge", "paper-bridge-2-beam", "--out", str(tmp_path / "t.nc"),
            "--workers", "1", "--no-progress"]
    cli_refused(runner.invoke(app, argv), "rec.csv:3: an event of the stream", "needs 8.09e+06 time steps, above the limit 5e+06",
             "raise --max-steps")
    cli_refused(runner.invoke(app, [*argv, "--max-steps", "1e7", "--max-memory", "1MB"]), "rec.csv:3: ", "raise --max-memory")
    cli_refused(runner.invoke(app, [*argv, "--max-steps", "0"]), "--max-steps: expected a number in [1, 1e+12], got 0")
    assert not (tmp_path / "t.nc").exists()


def test_run_refuses_two_outputs_to_one_file(tmp_path):
    """Was: ``--out r.csv --summary r.csv`` wrote the histories, then the summary over them (exit 0)."""
    scenario = ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"
    target = tmp_path / "r.csv"
    cli_refused(runner.invoke(app, ["run", str(scenario), "--out", str(target), "--summary", str(target)]),
             f"--summary {target}: is also --out's file; give each output its own path")
    assert not target.exists()


@pytest.mark.parametrize("value", ["0", "nan", "-1", "0.5"])
@pytest.mark.parametrize("kind", ["run", "driveby", "study", "traffic"])
def test_max_steps_has_one_check_and_one_wording(tmp_path, kind, value):
    """``--max-steps 0``/``nan``/``-1`` gave click's usage text (for nan: 'greater than or equal to 1'),
    ``inf`` the project's ``error:`` line; now every value goes through ``steps_option``."""
    argv = (["run", str(ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml")] if kind == "run"
            else _command(tmp_path, kind))
    cli_refused(runner.invoke(app, [*argv, "--max-steps", value]), "--max-steps: expected a number in [1, 1e+12], got ")


def test_a_foreign_stage_file_is_not_announced_as_resumable_work(tmp_path):
    """Was: ``static.nc`` in the output folder's ``work`` folder that is no dataset of this run was refused, and a note then said the
    finished simulations (stage static) were kept and the same command would resume from them — it
    would only be refused again."""
    argv = _command(tmp_path, "lifetime")
    (tmp_path / "out" / "work").mkdir(parents=True)
    (tmp_path / "out" / "work" / "static.nc").write_text("not a dataset\n")
    err = cli_refused(runner.invoke(app, [*argv, "--workers", "1"]), "holds work this run cannot use")
    assert "note:" not in err and "resume" not in err


@pytest.mark.parametrize("option", ["--out", "--summary", "--plot"])
@pytest.mark.parametrize("read", ["profile", "modes"])
def test_run_never_writes_an_output_over_a_file_its_scenario_reads(tmp_path, option, read):
    """Was: ``vbikit run s.toml --out p.csv`` with ``road.profile_file = "p.csv"`` (or a bridge's
    ``modes_file``) replaced the measured profile (the modes) by the run's output: only the scenario
    itself was checked.  ``Scenario.input_files`` names them; the refusal comes before any computation."""
    (tmp_path / "p.png").write_text("x,elevation\n0,0\n100,0\n")  # (a name every option may write)
    (tmp_path / "m.png").write_text("not read: refused first\n")
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    text = text.replace('class = "none"', 'profile_file = "p.png"')
    if read == "modes":
        text = text.replace('model = "beam"\nspan = 25.0\nEI = 8.323e9            # E = 2.87e9 Pa × I = 2.9 m^4\n'
                            'mass_per_length = 2303.0\ndamping_ratio = 0.0\nn_modes = 10\n',
                            'model = "modes-file"\nmodes_file = "m.png"\n')
        assert 'modes_file = "m.png"' in text
    scenario = tmp_path / "s.toml"
    scenario.write_text(text)
    target = tmp_path / ("p.png" if read == "profile" else "sub/../m.png")
    (tmp_path / "sub").mkdir()
    before = target.read_text()
    res = runner.invoke(app, ["run", str(scenario), option, str(target)])
    cli_refused(res, f"{option} {target}: is the input file {tmp_path / ('p.png' if read == 'profile' else 'm.png')}",
                "give another path")
    assert target.read_text() == before



def test_run_names_out_dir_when_the_file_it_names_is_an_input(tmp_path):
    """``--out-dir D`` writes D/SCENARIO.csv: with ``road.profile_file = "SCENARIO.csv"`` in D that is the
    profile, refused (``Scenario.input_files``), naming the option given (was: ``--out``, not on the
    command line).  An ``--out`` given beside ``--out-dir`` keeps its own name."""
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    (tmp_path / "s.toml").write_text(text.replace('class = "none"', 'profile_file = "s.csv"'))
    (tmp_path / "s.csv").write_text("x,elevation\n0,0\n100,0\n")
    res = runner.invoke(app, ["run", str(tmp_path / "s.toml"), "--out-dir", str(tmp_path)])
    err = cli_refused(res, f"--out-dir {tmp_path / 's.csv'}: is the input file {tmp_path / 's.csv'}")
    assert "--out " not in err and (tmp_path / "s.csv").read_text() == "x,elevation\n0,0\n100,0\n"
    res = runner.invoke(app, ["run", str(tmp_path / "s.toml"), "--out-dir", str(tmp_path / "o"), "--out",
                              str(tmp_path / "s.csv")])
    cli_refused(res, f"--out {tmp_path / 's.csv'}: is the input file")

def test_traffic_names_the_records_file_as_given_in_every_error(tmp_path):
    """Was: the reader's errors named the records file as given (``sub/rec.csv:3: …``), the stream's
    checks by its bare name (``rec.csv:3: lane 3 has no centre``): docs/cli.md's rule is the path as given."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "rec.csv").write_text(REC_HEAD.format(col="lane") + "1,1,+x,80,50 50,4\n3,3,+x,80,50 50,4\n")
    res = runner.invoke(app, ["traffic", str(tmp_path / "sub" / "rec.csv"), "--bridge", "paper-bridge-2-beam", "--out",
                              str(tmp_path / "t.nc"), "--workers", "1", "--no-progress"])
    cli_refused(res, f"{tmp_path / 'sub' / 'rec.csv'}:3: lane 3 has no centre")


def test_a_dimensionless_range_is_not_followed_by_a_unit():
    """A range of a number without unit reads "expected a number in [0, 1)", not "… [0, 1) [1]" (a new user's trial,
    drive-by noise keys); a unit is given after a range with one."""
    from vbikit._validation import expected

    assert expected(0.0, 1.0, hi_open=True, unit="1") == "expected a number in [0, 1)"
    assert expected(0.0, 1.0, hi_open=True, unit="-") == "expected a number in [0, 1)"
    assert expected(0.0, 1.0, unit="m") == "expected a number in [0, 1] [m]"
