"""A drive-by dataset's identity (its ``study`` attribute, the resume check) names no folder: the files
the scenario reads by their content, an absolute path by its file name."""
from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

from vbikit._toml import read_toml
from vbikit.driveby.spec import DriveByError, parse_driveby

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "driveby" / "DRIVEBY.toml"
ROAD = "x [m],elevation [m]\n-80,0\n0,0.001\n80,0\n"


def _data(profile_file: str) -> dict:
    data = read_toml(EXAMPLE, DriveByError)
    data["road"] = {"profile_file": profile_file}
    data["sweep"].pop("road_class", None)
    return data


def test_the_identity_holds_the_files_content_not_their_folder(tmp_path):
    """A measured road ``road.csv`` beside the drive-by file in a project folder: the identity holds its
    SHA-256, not the folder (before 2026-12-06: ``base_dir``, the folder as given, absolute for an absolute
    file name); the folder moved, the identity is the same (the run resumes); the file changed, it is not;
    ``profile_file`` given as an absolute path is stored as ``road.csv``."""
    project = tmp_path / "project"
    project.mkdir()
    (project / "road.csv").write_text(ROAD)
    text = parse_driveby(_data("road.csv"), project).to_json()
    assert str(tmp_path) not in text and "base_dir" not in text
    identity = json.loads(text)
    assert identity["input_sha256"] == {"road.profile_file": hashlib.sha256(ROAD.encode()).hexdigest()}
    moved = tmp_path / "moved"
    shutil.move(project, moved)
    assert parse_driveby(_data("road.csv"), moved).to_json() == text
    (moved / "road.csv").write_text(ROAD.replace("0.001", "0.002"))
    assert parse_driveby(_data("road.csv"), moved).to_json() != text
    absolute = parse_driveby(_data(str(moved / "road.csv")), ".").to_json()
    assert str(tmp_path) not in absolute and json.loads(absolute)["scenario"]["road"]["profile_file"] == "road.csv"
