"""Fuzz tests (hypothesis): generated scenarios, studies and field files (see ``fuzzing.py``), and the
surfaces added since the paper: [[vehicles]], [bridge.deck], [[bridge.damage]], continuous-beam keys,
load-effect sections and mode files.

Every run ends in exit 0 with finite outputs, or exit 2 with one message naming a key or the file;
never a traceback, a hang, NaN/Infinity in an output, a scenario that ``validate`` accepts and
``run`` then refuses, or (new surfaces, mode files) an input holding a NaN or a stray infinity that
``validate`` accepts (silent acceptance).  The default run tries 200 inputs (derandomised, the same every time); the
``slow`` variants try ten times as many, randomly.  With ``VBIKIT_FUZZ_LOG=path`` every outcome is
appended to that file (JSON lines) instead of asserted — that is how the counts in
docs/changelog.md were measured.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import pytest
from fuzzing import (
    RUN_LIMITS,
    field_files,
    judge,
    mode_file_inputs,
    new_surface_inputs,
    scenarios,
    studies,
    time_limit,
)
from hypothesis import HealthCheck, given, settings
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
LOG = os.environ.get("VBIKIT_FUZZ_LOG")


def _record(kind: str, outcome: str, result, text: bytes) -> None:
    if LOG:
        with open(LOG, "a") as fh:
            fh.write(json.dumps({"kind": kind, "outcome": outcome, "output": result.output[-400:],
                                 "input": text.decode("utf-8", "replace")[:1500]}) + "\n")
        return
    assert outcome in ("ok", "clean"), f"{kind}: {outcome}\n--- input ---\n{text[:2000]!r}\n--- output ---\n{result.output}"


def _invoke(args: list[str]):
    with time_limit():
        return runner.invoke(app, args)


def _settings(n: int, slow: bool):
    return settings(max_examples=10 * n if slow else n, deadline=None, database=None, derandomize=not slow,
                    suppress_health_check=list(HealthCheck), print_blob=True)


def _refusal_announced(validated) -> bool:
    """``vbikit validate`` accepted a file without vehicles as a traffic base and said that ``vbikit run``
    needs one (cli/validate.py): the run's clean refusal is then the announced outcome, not a surprise."""
    return "`vbikit run` needs one" in validated.output


def check_scenario(text: bytes) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fuzz.toml"
        path.write_bytes(text)
        summary = Path(tmp) / "summary.json"
        validated = _invoke(["validate", str(path), *RUN_LIMITS])
        outcome = judge(validated, ("fuzz.toml",))
        if outcome != "ok":
            return _record("scenario-validate", outcome, validated, text)
        ran = _invoke(["run", str(path), "--json", "--summary", str(summary), *RUN_LIMITS])
        outcome = judge(ran, ("fuzz.toml",), (summary,))
        if outcome == "clean" and not _refusal_announced(validated):
            outcome = "validate ok, run refused"
        _record("scenario", outcome, ran, text)


def check_scenario_files(text: bytes, refuse: bool, files: dict[str, bytes] | None = None,
                         kind: str = "new-surfaces") -> None:
    """``check_scenario`` with further files beside the scenario (a mode file), and the judge of silent
    acceptance: an input that must be refused (``fuzzing.must_refuse``) and passes ``validate``."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fuzz.toml"
        path.write_bytes(text)
        for name, data in (files or {}).items():
            (Path(tmp) / name).write_bytes(data)
        names = ("fuzz.toml", *(files or {}))
        shown = text + b"".join(b"\n--- " + n.encode() + b" ---\n" + d[:1500] for n, d in (files or {}).items())
        summary = Path(tmp) / "summary.json"
        validated = _invoke(["validate", str(path), *RUN_LIMITS])
        outcome = judge(validated, names)
        if outcome == "ok" and refuse:
            outcome = "silent acceptance"
        if outcome != "ok":
            return _record(f"{kind}-validate", outcome, validated, shown)
        ran = _invoke(["run", str(path), "--json", "--summary", str(summary), *RUN_LIMITS])
        outcome = judge(ran, names, (summary,))
        if outcome == "clean" and not _refusal_announced(validated):
            outcome = "validate ok, run refused"
        _record(kind, outcome, ran, shown)


def check_mode_file(inputs: tuple[bytes, bytes, bool]) -> None:
    toml, modes, refuse = inputs
    check_scenario_files(toml, refuse, {"fuzz.modes.csv": modes}, "mode-file")


def check_study(text: bytes) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fuzz-study.toml"
        path.write_bytes(text)
        validated = _invoke(["study", "validate", str(path), *RUN_LIMITS])
        outcome = judge(validated, ("fuzz-study.toml",))
        if outcome != "ok" or b"samples" not in text or len(text) > 3000:
            return _record("study-validate", outcome, validated, text)
        ran = _invoke(["study", "run", str(path), "--out", str(Path(tmp) / "r.nc"), "--workers", "1", "--no-progress",
                       *RUN_LIMITS])
        outcome = judge(ran, ("fuzz-study.toml",))
        if outcome == "clean" and not _refusal_announced(validated):
            outcome = "validate ok, run refused"
        _record("study", outcome, ran, text)


def check_field(files: tuple[bytes, bytes]) -> None:
    toml, csv_text = files
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "FIELD.toml"
        path.write_bytes(toml)
        (Path(tmp) / "resp.csv").write_bytes(csv_text)
        out = Path(tmp) / "out"
        ran = _invoke(["field", str(path), "--out-dir", str(out), "--tires", "point"])
        outcome = judge(ran, ("FIELD.toml", "resp.csv"), (out / "field-metrics.json",))
        escaped = [p for p in Path(tmp).rglob("*") if p.is_file() and out not in p.parents
                   and p.name not in ("FIELD.toml", "resp.csv")]
        if escaped:
            outcome = f"wrote outside --out-dir: {escaped}"
        _record("field", outcome, ran, toml)


@_settings(120, slow=False)
@given(scenarios())
def test_fuzz_scenarios(text):
    check_scenario(text)


@_settings(60, slow=False)
@given(new_surface_inputs())
def test_fuzz_new_surfaces(inputs):
    """[[vehicles]], [bridge.deck], [[bridge.damage]], continuous-beam keys and load-effect sections."""
    check_scenario_files(*inputs)


@_settings(40, slow=False)
@given(mode_file_inputs())
def test_fuzz_mode_files(inputs):
    check_mode_file(inputs)


@_settings(50, slow=False)
@given(studies())
def test_fuzz_studies(text):
    check_study(text)


@pytest.mark.filterwarnings("ignore:.*flat FIELD.toml keys are deprecated:FutureWarning")  # generated on purpose
@_settings(30, slow=False)
@given(field_files())
def test_fuzz_field_files(files):
    check_field(files)


@pytest.mark.slow
@_settings(120, slow=True)
@given(scenarios())
def test_fuzz_scenarios_more(text):
    check_scenario(text)


@pytest.mark.slow
@_settings(50, slow=True)
@given(studies())
def test_fuzz_studies_more(text):
    check_study(text)


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore:.*flat FIELD.toml keys are deprecated:FutureWarning")  # generated on purpose
@_settings(30, slow=True)
@given(field_files())
def test_fuzz_field_files_more(files):
    check_field(files)


@pytest.mark.slow
@_settings(200, slow=True)
@given(new_surface_inputs())
def test_fuzz_new_surfaces_more(inputs):
    """2,000 generated inputs over the surfaces added since the paper."""
    check_scenario_files(*inputs)


@pytest.mark.slow
@_settings(60, slow=True)
@given(mode_file_inputs())
def test_fuzz_mode_files_more(inputs):
    check_mode_file(inputs)
