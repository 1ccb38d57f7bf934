"""`vbikit field` on the committed synthetic example (examples/field/)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "field" / "FIELD.toml"
runner = CliRunner()


def test_field_command_writes_figures_and_tables(tmp_path):
    res = runner.invoke(app, ["field", str(EXAMPLE), "--out-dir", str(tmp_path), "--tires", "point,multipoint"])
    assert res.exit_code == 0, res.output
    assert "G5_acc: removed offset" in res.output
    for name in ("field-case1.png", "field-case2.png", "field-metrics.json", "field-metrics.csv"):
        assert (tmp_path / name).stat().st_size > 0
    table = json.loads((tmp_path / "field-metrics.json").read_text())
    # the field file as given, an absolute path (EXAMPLE's) by its name only (before 2026-12-06 the whole path)
    assert table["field_file"] == "FIELD.toml"
    assert str(EXAMPLE.parent) not in (tmp_path / "field-metrics.json").read_text()
    case1 = table["cases"][0]
    assert case1["trigger_time_s"] == pytest.approx(1.237)  # the file's trigger, used as given
    assert set(case1["metrics"]) == {"point", "multipoint"}
    assert case1["lowpass_hz"] == 40.0
    assert case1["drift"]["G5_acc"]["offset"] == pytest.approx(0.03, abs=1e-3)  # truth of make_synthetic.py
    # each channel's SI unit (its peaks, RMS error and offset), as every JSON spells units (a trial found none)
    assert case1["channel_units"] == {"G5_disp": "m", "G5_acc": "m s-2", "G5_strain": "1"}
    # and what it wrote, one line a file
    assert f"wrote {tmp_path / 'field-metrics.json'}" in res.stdout.splitlines()
    rows = (tmp_path / "field-metrics.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * 2 * 3  # header + cases × tires × channels


def test_field_bad_tires(tmp_path):
    res = runner.invoke(app, ["field", str(EXAMPLE), "--out-dir", str(tmp_path), "--tires", "point,tyre"])
    assert res.exit_code == 2
    assert "--tires: unknown tire model 'tyre'" in res.output


def test_field_takes_every_tire_model():
    from vbikit.field.workflow import parse_tires

    assert parse_tires("point,multipoint,disk,rigid-disk") == ["point", "multipoint", "disk", "rigid-disk"]


def test_field_missing_file(tmp_path):
    res = runner.invoke(app, ["field", str(tmp_path / "FIELD.toml")])
    assert res.exit_code == 2
    assert "field file not found" in res.output


@pytest.mark.slow
def test_field_calibrate_example(tmp_path):
    res = runner.invoke(app, ["field", str(EXAMPLE), "--out-dir", str(tmp_path), "--calibrate"])
    assert res.exit_code == 0, res.output
    cal = json.loads((tmp_path / "field-metrics.json").read_text())["calibration"]
    assert abs(cal["stiffness_factor"] - 1.10) < 3 * cal["stiffness_factor_std"]
