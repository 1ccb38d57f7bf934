"""Outputs are written atomically (temporary file + rename): a failure mid-write or a full disk
leaves the previous file (or none), never a partial one, and exits 2 with a message; JSON never
holds NaN or Infinity; names from input files cannot form paths outside the output folder."""
from __future__ import annotations

import csv
import errno
import json
import math
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit._files import OutputError, atomic_write, inside, json_text
from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml"
runner = CliRunner()
_CSV_WRITER = csv.writer


class _FullDisk:
    """A csv writer whose 4th row fails as a full disk does."""

    def __init__(self, fh, *args, **kwargs) -> None:
        self.inner, self.rows = _CSV_WRITER(fh), 0

    def writerow(self, row):
        self.rows += 1
        if self.rows > 3:
            raise OSError(errno.ENOSPC, "No space left on device")
        return self.inner.writerow(row)


def test_full_disk_keeps_the_previous_csv(tmp_path, monkeypatch):
    out = tmp_path / "h.csv"
    out.write_text("previous good file\n")
    monkeypatch.setattr("vbikit.scenario.report.csv.writer", _FullDisk)
    res = runner.invoke(app, ["run", str(SCENARIO), "--out", str(out)])
    assert res.exit_code == 2
    assert f"cannot write {out}: no space left on the device" in res.output
    assert out.read_text() == "previous good file\n"
    assert [p.name for p in tmp_path.iterdir()] == ["h.csv"]  # no temporary file left behind


def test_interrupted_write_leaves_no_partial_file(tmp_path):
    target = tmp_path / "x.json"

    def write(tmp: Path) -> None:
        tmp.write_text('{"half": ')
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(target, write)
    assert not target.exists() and list(tmp_path.iterdir()) == []
    with pytest.raises(OutputError, match="cannot write"):
        atomic_write(tmp_path / "y", lambda tmp: (_ for _ in ()).throw(OSError(errno.ENOSPC, "full")))


def test_json_never_holds_nan_or_infinity():
    text = json_text({"a": math.nan, "b": [1.0, math.inf], "c": {"d": -math.inf}})
    assert json.loads(text) == {"a": None, "b": [1.0, None], "c": {"d": None}}


def test_names_cannot_leave_the_output_folder(tmp_path):
    assert inside(tmp_path, "field-case1.png") == tmp_path / "field-case1.png"
    for name in ("x/../../../escaped.png", "/etc/x.png", "..", "a/../../b"):
        with pytest.raises(ValueError, match="leaves the output folder"):
            inside(tmp_path, name)


def test_field_case_name_cannot_escape(tmp_path):
    field = tmp_path / "field"
    shutil.copytree(ROOT / "examples" / "field", field)
    toml = field / "FIELD.toml"
    text = toml.read_text()
    assert 'name = "case1"' in text
    toml.write_text(text.replace('name = "case1"', 'name = "x/../../../escaped"', 1))
    res = runner.invoke(app, ["field", str(toml), "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 2, res.output
    assert "case[1].name" in res.output and "cannot be used in a file name" in res.output
    assert not list(tmp_path.rglob("*escaped*"))


def test_divergence_is_reported_with_step_and_time():
    """Integrator states are checked: a non-finite state is an error naming the step and time."""
    import dataclasses

    import numpy as np

    from vbikit.bridge.presets import paper_beam
    from vbikit.solve import Crossing, simulate
    from vbikit.solve.result import DivergenceError, check_finite
    from vbikit.vehicle.presets import sprung_mass

    result = simulate(Crossing(paper_beam(16.76, "II", n_modes=2), sprung_mass(), speed=20.0))
    xi = result.xi.copy()
    xi[123:, 0] = np.inf
    with pytest.raises(DivergenceError, match=rf"diverged at step 123 of {result.n_steps} \(t = {result.time[123]:.6g} s"):
        check_finite(dataclasses.replace(result, xi=xi))


def _field_copy(tmp_path: Path) -> Path:
    field = tmp_path / "field"
    shutil.copytree(ROOT / "examples" / "field", field)
    return field / "FIELD.toml"


def test_field_unknown_bridge_parameter_is_exit_2(tmp_path):
    """An unknown key in [bridge.deck] (formerly [bridge_parameters]) used to end in a TypeError traceback."""
    toml = _field_copy(tmp_path)
    toml.write_text(toml.read_text() + "\n[bridge.deck]\nspan_x = 3.0\n")
    res = runner.invoke(app, ["field", str(toml), "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 2 and "bridge.deck" in res.output and "span_x" in res.output, res.output


def test_field_all_zero_record_is_refused(tmp_path):
    """An all-zero field record gave NaN metrics at exit 0."""
    toml = _field_copy(tmp_path)
    csv_path = toml.parent / "case1_responses.csv"
    lines = csv_path.read_text().splitlines()
    head = [ln for ln in lines if ln.startswith("#") or "[" in ln]
    rows = [ln for ln in lines if ln not in head]
    csv_path.write_text("\n".join(head + [r.split(",")[0] + ",0,0,0" for r in rows]) + "\n")
    res = runner.invoke(app, ["field", str(toml), "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 2 and "case1_responses.csv" in res.output and "constant" in res.output, res.output


def test_a_non_finite_summary_value_is_null_with_a_warning(tmp_path, monkeypatch):
    """y = inf on a beam used to write Infinity into --json (not valid JSON)."""
    import vbikit.scenario.pipeline

    real = vbikit.scenario.pipeline.summary

    def summary(*args, **kwargs):
        s = real(*args, **kwargs)
        s["max_abs_acceleration"] = math.inf
        return s

    monkeypatch.setattr(vbikit.scenario.pipeline, "summary", summary)
    summ = tmp_path / "s.json"
    res = runner.invoke(app, ["run", str(SCENARIO), "--json", "--summary", str(summ)])
    assert res.exit_code == 0, res.output

    def refuse(name):
        raise AssertionError(f"{name} in JSON")

    for text in (res.stdout, summ.read_text()):
        data = json.loads(text, parse_constant=refuse)
        assert data["max_abs_acceleration"] is None
        assert "max_abs_acceleration is not a finite number (written as null)" in data["warnings"]
    text = runner.invoke(app, ["run", str(SCENARIO)])
    assert text.exit_code == 0 and "inf m/s²" in text.stdout


def test_field_channel_that_is_not_a_table_is_exit_2(tmp_path):
    """Found by the fuzz test: channel = [3] ended in a TypeError traceback."""
    toml = _field_copy(tmp_path)
    text = toml.read_text()
    cut = text.index("[[case.channel]]")
    toml.write_text(text[:cut] + "channel = [3]\n")
    res = runner.invoke(app, ["field", str(toml), "--out-dir", str(tmp_path / "out")])
    assert res.exit_code == 2 and "case[1].channel[1]" in res.output and "must be tables" in res.output, res.output
