"""A traffic stream's dataset shared with others carries no folder of the machine it ran on, and its
identity (the ``study`` attribute, the resume check) names the inputs by their content: a moved project
folder still resumes, a changed road profile does not."""
from __future__ import annotations

import hashlib
import json

import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

HEAD = "time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
ROW = "0.0,1,+x,80,53.4 75.6,5.5\n"


def _texts(ds) -> list[str]:
    """Every attribute value of the dataset and of its variables, and its text coordinates, as text."""
    out = [str(v) for v in ds.attrs.values()]
    for v in ds.variables.values():
        out += [str(a) for a in v.attrs.values()]
        if v.dtype.kind in "OUS":
            out += [str(x) for x in v.values.ravel()]
    return out


def _run(folder, out):
    return runner.invoke(app, ["traffic", str(folder / "r.csv"), "--bridge", str(folder / "base.toml"), "--out", str(out),
                               "--workers", "1", "--no-progress"])


def test_the_stream_dataset_names_no_folder_and_resumes_by_content(tmp_path):
    """Records, base scenario and its measured road (``road.profile_file = "road.csv"``) in a project
    folder given by absolute paths: no attribute holds that folder (before 2026-12-06 the ``study``
    attribute held it as ``base_dir``), the identity holds the road file's SHA-256 instead; the folder
    moved, the same command finds its finished run; the road file changed, the run is refused."""
    project = tmp_path / "project"
    project.mkdir()
    (project / "r.csv").write_text(HEAD + ROW)
    (project / "road.csv").write_text("x [m],elevation [m]\n-80,0\n0,0.001\n80,0\n")
    (project / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 3\n[road]\n'
                                       'profile_file = "road.csv"\n[crossing]\napproach = 5.0\nfree_vibration = 0.1\n')
    out = tmp_path / "out" / "s.nc"
    res = _run(project, out)
    assert res.exit_code == 0, res.output
    with xr.open_dataset(out) as ds:
        texts = _texts(ds)
        study = json.loads(ds.attrs["study"])
    assert not [t for t in texts if str(tmp_path) in t]
    assert "base_dir" not in study
    assert study["input_sha256"] == {"road.profile_file": hashlib.sha256((project / "road.csv").read_bytes()).hexdigest()}
    assert study["base"]["road"]["profile_file"] == "road.csv"
    moved = tmp_path / "moved"
    project.rename(moved)
    res = _run(moved, out)
    assert res.exit_code == 0 and "already holds this finished run" in res.output, res.output
    (moved / "road.csv").write_text("x [m],elevation [m]\n-80,0\n0,0.002\n80,0\n")
    res = _run(moved, out)
    assert res.exit_code != 0 and "is not this study's finished dataset" in res.output, res.output


def test_an_absolute_file_in_the_base_is_stored_by_its_name(tmp_path):
    """``profile_file = "/…/road.csv"`` (absolute) in the base scenario: the identity keeps ``road.csv`` and
    the file's SHA-256, no folder."""
    (tmp_path / "r.csv").write_text(HEAD + ROW)
    (tmp_path / "road.csv").write_text("x [m],elevation [m]\n-80,0\n0,0.001\n80,0\n")
    (tmp_path / "base.toml").write_text(f'[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 3\n[road]\n'
                                        f'profile_file = "{tmp_path / "road.csv"}"\n[crossing]\napproach = 5.0\n')
    res = _run(tmp_path, tmp_path / "s.nc")
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        assert not [t for t in _texts(ds) if str(tmp_path) in t]
        assert json.loads(ds.attrs["study"])["base"]["road"]["profile_file"] == "road.csv"


def test_a_run_interrupted_under_the_earlier_identity_resumes(tmp_path):
    """Parts written before 2026-12-06 (the marker and each part's checksum of the identity with ``base_dir``,
    built here by hand as that version wrote it) are this stream's: the run resumes from them, none is moved
    aside as another study's, and the marker holds the identity of now."""
    import numpy as np

    from vbikit.study.run import run_study
    from vbikit.study.storage import parts_dir, save_part
    from vbikit.traffic.records import parse_records
    from vbikit.traffic.study import base_scenario, traffic_study

    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 3\n[road]\nclass = "none"\n'
                                        '[crossing]\napproach = 5.0\nfree_vibration = 0.1\n')
    base, base_dir = base_scenario(str(tmp_path / "base.toml"))
    records = parse_records(HEAD + ROW + ROW.replace("0.0,", "30.0,", 1))
    job = traffic_study(records, base, base_dir, batch_size=1, name="r")
    assert job.size == 2
    old = json.loads(job.to_json())
    old["base_dir"] = str(tmp_path)
    del old["population_run_in"]  # (that version's identity had none; its parts without a run_in are run again)
    old = json.dumps(old, sort_keys=True)
    out = tmp_path / "s.nc"
    parts = parts_dir(out)
    parts.mkdir()
    (parts / "study.json").write_text(old)
    first = job.run_batch((0,))
    first["impact_factor"] = first["impact_factor"] + 1.0  # (marked: the stored part is the one used)
    save_part(parts, 0, first, hashlib.sha256(old.encode()).hexdigest())
    ds = run_study(job, out, workers=1, keep_parts=True)
    assert not (parts / "damaged").exists()
    assert np.ravel(ds["impact_factor"].values)[0] == np.ravel(first["impact_factor"])[0]
    assert (parts / "study.json").read_text() == job.to_json()
