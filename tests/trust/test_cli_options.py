"""Bad command-line options and output paths found by trying every command (wt/fuzz, 2026-12-06):
each is refused with exit 2 and one ``error:`` line naming the option (or file) and what is allowed,
before any computation — never a traceback, a fork of 100,000 processes, or an input file
overwritten by an output."""
from __future__ import annotations

import time
from pathlib import Path

import pytest
from fuzz_commands import BASES, RECORDS, write_input
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
TRAIN = "position_m,load_kN\n0,170\n3,170\n14,170\n17,170\n"
STREAM = (ROOT / "examples" / "traffic" / "stream.csv").read_text().splitlines()


def _refused(res, *parts: str) -> str:
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)
    assert res.exit_code == 2, res.output
    errors = [line for line in res.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and "Traceback" not in res.output, res.output
    for part in parts:
        assert part in res.stderr, res.stderr
    return res.stderr


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
    err = _refused(res, f"--scheduler {address!r}", words, "tcp://host:port")
    assert time.process_time() - t0 < 5.0, err
    assert not (tmp_path / "out").exists() and not (tmp_path / "t.nc").exists()


@pytest.mark.parametrize("kind", COMMANDS)
@pytest.mark.parametrize("workers", ["100000", "0", "-3"])
def test_workers_outside_the_range_are_refused_before_any_process_starts(tmp_path, kind, workers):
    """Was: ``--workers 100000`` forked worker processes until the machine ran out of memory
    (the kernel's OOM killer ended the run); 0 and -3 gave click's usage text."""
    from vbikit._validation import workers_limit

    res = runner.invoke(app, [*_command(tmp_path, kind), "--workers", workers])
    _refused(res, "--workers: expected an integer in [1, ", f"{workers_limit()}], got {workers}")


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
