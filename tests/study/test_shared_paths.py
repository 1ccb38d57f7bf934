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
