"""A study's identity (the dataset's ``study`` attribute, the resume check) names no folder and holds
the files its scenarios read by their content."""
from __future__ import annotations

import hashlib
import json
import shutil

from vbikit.study.spec import parse_study

ROAD = "x [m],elevation [m]\n-100,0\n0,0.001\n100,0\n"


def _study(profile_file: str) -> dict:
    return {"name": "measured", "seed": 1, "batch_size": 2,
            "base": {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "two-axle"},
                     "road": {"profile_file": profile_file}, "crossing": {"speed_kmh": 90}},
            "axes": {"crossing.speed_kmh": [60, 90]}}


def test_the_identity_holds_the_files_content_not_their_folder(tmp_path):
    """``road.profile_file`` absolute in the base: stored as ``road.csv`` (before 2026-12-06 the whole path,
    and the file's content was in no identity: a study over a changed road resumed from the old one's
    batches); its SHA-256 beside it, the same after the folder is moved, another once the file changes.
    A study without files keeps the identity it had (no ``input_sha256``)."""
    project = tmp_path / "project"
    project.mkdir()
    (project / "road.csv").write_text(ROAD)
    text = parse_study(_study(str(project / "road.csv")), project).to_json()
    assert str(tmp_path) not in text
    identity = json.loads(text)
    assert identity["base"]["road"]["profile_file"] == "road.csv"
    assert identity["input_sha256"] == {"road.profile_file": hashlib.sha256(ROAD.encode()).hexdigest()}
    moved = tmp_path / "moved"
    shutil.move(project, moved)
    assert parse_study(_study("road.csv"), moved).to_json() == text  # (relative now: the same file, the same study)
    (moved / "road.csv").write_text(ROAD.replace("0.001", "0.002"))
    assert parse_study(_study("road.csv"), moved).to_json() != text
    plain = _study("x")
    plain["base"]["road"] = {"class": "none"}
    assert "input_sha256" not in json.loads(parse_study(plain).to_json())


def test_shared_spec_reduces_absolute_file_paths_only():
    """The one rule (``vbikit._files.shared_spec``): a string under a key naming a file, absolute, by its
    name; relative as given; any other string (a name that happens to start with "/") as it is."""
    from vbikit._files import shared_spec

    spec = {"name": "/not/a/file", "traffic": {"records": "/home/ann/wim/r.csv", "mode": "fitted"},
            "base": "sub/base.toml", "bridge": {"modes_file": "/data/m.txt", "span": 20.0},
            "trains": {"tables": ["/t/a.csv", "b.csv"]}, "load_effects": [{"name": "/M"}]}
    assert shared_spec(spec) == {"name": "/not/a/file", "traffic": {"records": "r.csv", "mode": "fitted"},
                                 "base": "sub/base.toml", "bridge": {"modes_file": "m.txt", "span": 20.0},
                                 "trains": {"tables": ["a.csv", "b.csv"]}, "load_effects": [{"name": "/M"}]}
    assert spec["traffic"]["records"] == "/home/ann/wim/r.csv"  # (a copy)


def test_an_axis_over_road_files_names_no_folder(tmp_path):
    """``axes."road.profile_file"`` over two absolute ``road.csv`` of two folders: the dataset's coordinate
    tells them apart without the folders (``road.csv (1)``, ``road.csv (2)``; before 2026-12-06 the paths as
    given), the identity holds each file's SHA-256, and no attribute or coordinate holds the folder."""
    import xarray as xr

    from vbikit.study.run import run_study

    for k, bump in ((1, "0.001"), (2, "0.003")):
        (tmp_path / f"site{k}").mkdir()
        (tmp_path / f"site{k}" / "road.csv").write_text(ROAD.replace("0.001", bump))
    data = _study(str(tmp_path / "site1" / "road.csv"))
    data["axes"] = {"road.profile_file": [str(tmp_path / "site1" / "road.csv"), str(tmp_path / "site2" / "road.csv")]}
    ds = run_study(parse_study(data, tmp_path), tmp_path / "s.nc", workers=1)
    with xr.open_dataset(tmp_path / "s.nc") as stored:
        assert [str(v) for v in stored["road_profile_file"].values] == ["road.csv (1)", "road.csv (2)"]
        texts = [str(v) for v in stored.attrs.values()] + [str(v) for c in stored.coords.values() for v in c.values.ravel()]
        identity = json.loads(stored.attrs["study"])
    assert not [t for t in texts if str(tmp_path) in t]
    assert set(identity["input_sha256"]) == {"road.profile_file", "road.profile_file[0]", "road.profile_file[1]"}
    im = ds["impact_factor"].values
    assert im[0] != im[1]  # (two roads: the axis ran)
