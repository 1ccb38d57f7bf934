"""``vbikit traffic --out-dir DIR`` writes its folder as lifetime, driveby and rail do (the dataset, the report,
the summary JSON and the figure); ``--out FILE.nc`` stays the dataset-only form; exactly one of them."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BASE = str(EXAMPLES / "traffic" / "base" / "bridge2.toml")


def _stream(tmp_path: Path, n: int = 8) -> str:
    """The example stream's first ``n`` records."""
    lines = (EXAMPLES / "traffic" / "stream.csv").read_text().splitlines()
    path = tmp_path / "short.csv"
    path.write_text("\n".join(lines[:n + 1]) + "\n")
    return str(path)


def test_out_dir_writes_the_dataset_report_summary_and_figure(tmp_path, summary_on_stdout):
    out = tmp_path / "out"
    res = runner.invoke(app, ["traffic", _stream(tmp_path), "--bridge", BASE, "--out-dir", str(out), "--no-progress",
                              "--workers", "1"])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in out.iterdir()) == ["traffic-im.png", "traffic-report.txt", "traffic-summary.json",
                                                      "traffic.nc"]
    report = (out / "traffic-report.txt").read_text()
    assert report.splitlines()[0].startswith("sprung vehicles start") and report in res.stdout  # what it printed
    summary = json.loads((out / "traffic-summary.json").read_text())
    with xr.open_dataset(out / "traffic.nc") as ds:
        assert summary["n_events"] == ds.sizes["event"]
        assert summary["im_mean"] == pytest.approx(float(ds.attrs["im_mean"]))
        assert summary["governing_static_event"] == int(ds.attrs["governing_static_event"])
    assert summary["dataset"] == "traffic.nc" and summary["start"].startswith("sprung vehicles start")
    for name in ("traffic.nc", "traffic-report.txt", "traffic-summary.json", "traffic-im.png"):
        assert f"wrote {out / name}" in res.stdout
    again = runner.invoke(app, ["traffic", _stream(tmp_path), "--bridge", BASE, "--out-dir", str(out), "--no-progress",
                                "--no-figures", "--workers", "1"])  # the finished run, read as it is
    assert again.exit_code == 0 and "already holds this finished run" in again.stdout
    assert "give another --out-dir" in again.stdout and "wrote" in again.stdout
    # --json: the summary's object alone on standard output, the report on standard error
    js = summary_on_stdout(["traffic", _stream(tmp_path), "--bridge", BASE, "--out-dir", str(out), "--no-progress",
                            "--no-figures", "--workers", "1"], out / "traffic-summary.json")
    assert report in js.stderr


def test_out_dir_without_figures_writes_no_figure(tmp_path):
    out = tmp_path / "out"
    res = runner.invoke(app, ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out-dir", str(out), "--no-progress",
                              "--no-figures", "--workers", "1"])
    assert res.exit_code == 0, res.output
    assert not (out / "traffic-im.png").exists() and (out / "traffic-summary.json").is_file()


def test_out_still_writes_the_dataset_only(tmp_path):
    res = runner.invoke(app, ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out", str(tmp_path / "s.nc"),
                              "--no-progress", "--workers", "1"])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.nc", "short.csv"]
    # --json with --out: the summary's object on standard output all the same, no summary file written
    js = runner.invoke(app, ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out", str(tmp_path / "s.nc"),
                             "--no-progress", "--workers", "1", "--json"])
    assert js.exit_code == 0, js.output
    summary = json.loads(js.stdout)
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        assert summary["n_events"] == ds.sizes["event"] == 3
    assert summary["dataset"] == "s.nc"  # (the file --out named, not the folder's traffic.nc)
    assert "impact factor" in js.stderr and sorted(p.name for p in tmp_path.iterdir()) == ["s.nc", "short.csv"]
    # -q (errors only): the JSON alone, nothing on standard error
    quiet = runner.invoke(app, ["-q", "traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out", str(tmp_path / "s.nc"),
                                "--no-progress", "--workers", "1", "--json"])
    assert quiet.exit_code == 0 and json.loads(quiet.stdout) == summary and quiet.stderr == "", quiet.stderr


def test_at_most_one_of_out_and_out_dir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["traffic", "missing.csv", "--bridge", BASE, "--out", "x.nc", "--out-dir", "d"])
    assert res.exit_code == 2  # refused before the records are read
    assert res.stderr.startswith("error: --out or --out-dir: give one, not both (--out FILE.nc: the dataset only; ")
    assert not (tmp_path / "d").exists()


def test_neither_writes_into_vbikit_out_as_every_command(tmp_path, monkeypatch):
    """docs/cli.md: a command that writes several files writes them into --out-dir, default vbikit-out/."""
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--no-progress", "--workers", "1",
                              "--no-figures"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "vbikit-out" / "traffic.nc").is_file() and (tmp_path / "vbikit-out" / "traffic-summary.json").is_file()
    # the summary gives the governing events' deflections and every number's unit
    import json

    import numpy as np
    import xarray as xr

    summary = json.loads((tmp_path / "vbikit-out" / "traffic-summary.json").read_text(encoding="utf-8"))
    with xr.open_dataset(tmp_path / "vbikit-out" / "traffic.nc") as ds:
        first = ds.isel(point=0) if "point" in ds.dims else ds
        static = first["max_static_displacement"].values
        dynamic = first["max_dynamic_displacement"].values
    # the governing events are the largest magnitudes; their deflections keep the dataset's sign (z up)
    assert summary["governing_static_deflection"] == float(static[np.argmax(np.abs(static))]) < 0.0
    assert summary["governing_dynamic_deflection"] == float(dynamic[np.argmax(np.abs(dynamic))]) < 0.0
    # a dataset written when the attribute held the magnitude: the summary reads the signed peak from the variable
    from vbikit.traffic.summary import summary as traffic_summary

    with xr.open_dataset(tmp_path / "vbikit-out" / "traffic.nc") as ds:
        ds.attrs["governing_static_deflection"] = abs(ds.attrs["governing_static_deflection"])
        assert traffic_summary(ds)["governing_static_deflection"] == summary["governing_static_deflection"] < 0.0
    # the histogram's edges as written: 0.05, not 0.05000000000000002 (a trial's JSON)
    edges = summary["im_histogram_edges"]
    assert all(e == round(e, 12) for e in edges) and len(edges) == 23
    assert summary["units"]["governing_static_deflection"] == "m" and summary["units"]["im_mean"] == "1"
    assert summary["units"]["governing_static_event"] == "1" and summary["units"]["n_events"] == "1"  # (CF)
    assert "start" not in summary["units"] and "warnings" not in summary["units"]


def test_out_dir_holding_a_folder_where_a_file_goes_is_refused_before_the_run(tmp_path):
    out = tmp_path / "out"
    (out / "traffic-summary.json").mkdir(parents=True)
    res = runner.invoke(app, ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out-dir", str(out)])
    assert res.exit_code == 2 and "traffic-summary.json exists and is not a file" in res.stderr
    assert not (out / "traffic.nc").exists()


def test_a_ctrl_c_while_writing_the_outputs_says_the_dataset_is_complete(tmp_path, monkeypatch):
    """A Ctrl-C after the run, while the report, summary or figure are written: exit 130 and a line saying the
    dataset is complete and the same command writes the rest (a trial's exited 130 without a word); the same
    command then writes them, simulating nothing again."""
    import vbikit.plot.traffic as plot_traffic

    out = tmp_path / "out"
    args = ["traffic", _stream(tmp_path, 3), "--bridge", BASE, "--out-dir", str(out), "--no-progress", "--workers", "1"]

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(plot_traffic, "plot_stream", interrupted)
    res = runner.invoke(app, args)
    assert res.exit_code == 130 and f"{out / 'traffic.nc'} is complete" in res.stderr, res.output
    monkeypatch.undo()
    again = runner.invoke(app, args)
    assert again.exit_code == 0 and "already holds this finished run" in again.stdout
    assert (out / "traffic-im.png").is_file() and (out / "traffic-summary.json").is_file()
