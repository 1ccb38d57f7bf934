"""`vbikit study` commands: run, validate, errors naming the key, paper study spec."""
from __future__ import annotations

import json

import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

STUDY = """
name = "cli study"
seed = 3
[base.bridge]
model = "paper-bridge-2-beam"
n_modes = 4
[base.vehicle]
model = "two-axle"
[base.road]
class = "C"
length = 200
[base.crossing]
speed_kmh = 90
[axes]
"crossing.speed_kmh" = [60, 90]
"road.seed" = { samples = 2 }
"""


def test_study_run_and_validate(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY)
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 0 and "4 crossings" in res.output
    res = runner.invoke(app, ["study", "run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r.nc"),
                              "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "4 crossings" in res.output and "impact factor" in res.output
    ds = xr.open_dataset(tmp_path / "r.nc")
    assert ds.sizes == {"crossing_speed_kmh": 2, "sample": 2}
    ds.close()


def test_study_errors_name_the_key(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY.replace('"crossing.speed_kmh" = [60, 90]', '"crossing.speed_kmh" = [60, -1]'))
    res = runner.invoke(app, ["study", "validate", str(tmp_path / "s.toml")])
    assert res.exit_code == 2
    assert "crossing.speed_kmh = -1" in res.output and "crossing.speed_kmh" in res.output
    res = runner.invoke(app, ["study", "run", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "r.nc")])
    assert res.exit_code == 2 and "study file not found" in res.output
    (tmp_path / "ok.toml").write_text(STUDY)
    res = runner.invoke(app, ["study", "run", str(tmp_path / "ok.toml"), "--out", str(tmp_path / "r.zip")])
    assert res.exit_code == 2 and "--out must be a NetCDF" in res.output


def test_paper_spec_printout():
    res = runner.invoke(app, ["study", "paper-fig11", "--samples", "2", "--print-spec"])
    assert res.exit_code == 0
    spec = json.loads(res.output)
    assert spec["axes"]["tire.model"] == ["point", "multipoint", "disk"]
    assert spec["axes"]["crossing.speed_kmh"] == [15, 30, 45, 60, 75, 90, 105, 120]
    assert spec["base"]["road"]["defects"] == [{"kind": "depression", "position": 0.0}]
    assert spec["base"]["bridge"]["model"] == "paper-bridge-2"  # the 3D deck, response at Girder 4
    assert spec["base"]["response"] == {"girder": 4}
    res = runner.invoke(app, ["study", "paper-fig11", "--samples", "2", "--print-spec", "--beam"])
    spec = json.loads(res.output)
    assert spec["base"]["bridge"]["model"] == "paper-bridge-2-beam" and "response" not in spec["base"]


def test_paper_study_end_to_end_small(tmp_path):
    """One paper study from one command (1 profile per point): dataset and figure."""
    res = runner.invoke(app, ["study", "paper-fig8", "--samples", "1", "--workers", "1", "--no-progress",
                              "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "paper-fig8-1samples.png").stat().st_size > 10_000
    ds = xr.open_dataset(tmp_path / "paper-fig8-1samples.nc")
    assert ds.sizes == {"tire_n_points": 8, "crossing_speed_kmh": 3, "road_class": 3, "sample": 1}
    assert "two-axle" in ds.attrs["study"]
    ds.close()


def test_paper_all_runs_every_figure(tmp_path):
    """`vbikit study paper-all`: the six paper studies one after another, each with its dataset
    and figure (1 profile per point to keep it short)."""
    res = runner.invoke(app, ["study", "paper-all", "--print-spec"])
    assert res.exit_code == 0
    names = [json.loads(line)["name"] for line in res.output.splitlines() if line.strip()]
    assert names == [f"paper-{f}" for f in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11")]
    res = runner.invoke(app, ["study", "paper-all", "--samples", "1", "--workers", "2", "--no-progress",
                              "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    for f in ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11"):
        assert (tmp_path / f"paper-{f}-1samples.png").stat().st_size > 10_000
        with xr.open_dataset(tmp_path / f"paper-{f}-1samples.nc") as ds:
            assert ds.sizes["sample"] == 1 and ds["impact_factor"].notnull().all()
