"""A study's lock file and parts: a symbolic link is never followed, a part changed after it was
written is never merged (its SHA-256 is recorded when written: recomputed on resume, refused when
assembled), and a resumed dataset stays identical to an unbroken run."""
from __future__ import annotations

import hashlib
import logging
import os
import shutil
import subprocess

import numpy as np
import pytest
import xarray as xr

from vbikit.study import StudyError, parse_study, run_study
from vbikit.study.run import assemble
from vbikit.study.storage import CHECKSUMS, PartChangedError, parts_dir


@pytest.fixture
def study(small_study_dict):
    small_study_dict["axes"] = {"road.class": ["B", "D"], "road.seed": {"samples": 2}}
    small_study_dict["batch_size"] = 2
    return parse_study(small_study_dict)


def test_a_dangling_lock_link_is_refused_and_nothing_is_created_outside(tmp_path, study):
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    target = outside / "created-by-the-lock"
    out = tmp_path / "res" / "r.nc"
    out.parent.mkdir()
    os.symlink(target, str(out) + ".lock")
    with pytest.raises(StudyError, match=r"r\.nc\.lock is a symbolic link; a study's lock file must be a regular file "
                                         r"in the output folder: remove it or write to another path"):
        run_study(study, out, workers=1)
    assert not target.exists() and list(outside.iterdir()) == []
    assert not parts_dir(out).exists() and not out.exists()  # refused before anything ran
    # a link to an existing file is refused too, and the file is left as it was
    target.write_text("keep")
    with pytest.raises(StudyError, match="is a symbolic link"):
        run_study(study, out, workers=1)
    assert target.read_text() == "keep"
    os.unlink(str(out) + ".lock")
    os.mkdir(str(out) + ".lock")
    with pytest.raises(StudyError, match=r"r\.nc\.lock is a folder"):
        run_study(study, out, workers=1)


def test_a_linked_parts_folder_is_refused(tmp_path, study):
    (tmp_path / "other").mkdir()
    out = tmp_path / "r.nc"
    os.symlink(tmp_path / "other", parts_dir(out))
    with pytest.raises(StudyError, match=r"r\.nc\.parts is a symbolic link"):
        run_study(study, out, workers=1)
    assert list((tmp_path / "other").iterdir()) == []


def _rewrite(path, change):
    """Rewrite an .npz part as a valid file with every array kept, ``impact_factor`` changed."""
    with np.load(path) as part:
        arrays = {k: part[k] for k in part.files}
    arrays["impact_factor"] = change(arrays["impact_factor"])
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)


@pytest.mark.parametrize("change", [lambda a: 2 * a, lambda a: np.full_like(a, np.nan)], ids=["doubled", "nan"])
def test_a_part_rewritten_with_other_values_is_recomputed(tmp_path, study, caplog, change):
    clean = run_study(study, tmp_path / "clean.nc", workers=1)
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    part = parts_dir(out) / "batch-000001.npz"
    _rewrite(part, change)
    with caplog.at_level(logging.WARNING, logger="vbikit.study.run"):
        resumed = run_study(study, out, workers=1)
    xr.testing.assert_identical(clean, resumed)  # merged silently before: doubled or NaN impact factors
    assert (f"study part {part} is unusable: its contents changed after it was written (the SHA-256 differs from "
            f"the one in {CHECKSUMS}); moved to") in caplog.text


def test_assembling_refuses_a_part_changed_since_it_was_written(tmp_path, study):
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    parts = parts_dir(out)
    xr.testing.assert_identical(assemble(study, parts), xr.open_dataset(out).load())
    _rewrite(parts / "batch-000000.npz", lambda a: 2 * a)
    with pytest.raises(PartChangedError, match=r"batch-000000\.npz is not used: its contents changed after it was "
                                               r"written .*; run the same command again to recompute it"):
        assemble(study, parts)


def test_a_part_without_a_recorded_checksum_is_recomputed(tmp_path, study, caplog):
    clean = run_study(study, tmp_path / "clean.nc", workers=1)
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    (parts_dir(out) / CHECKSUMS).unlink()
    with caplog.at_level(logging.WARNING, logger="vbikit.study.run"):
        xr.testing.assert_identical(clean, run_study(study, out, workers=1))
    assert caplog.text.count(f"no checksum of it is recorded in {CHECKSUMS}") == 2


def test_checksums_are_those_of_the_part_files(tmp_path, study):
    """SHA256SUMS holds the SHA-256 of each part file's bytes, in sha256sum's format (checked with
    hashlib here, and with the coreutils tool when it is installed)."""
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    parts = parts_dir(out)
    lines = (parts / CHECKSUMS).read_text().splitlines()
    names = sorted(p.name for p in parts.glob("batch-*.npz"))
    assert sorted(line.split("  ")[1] for line in lines) == names == ["batch-000000.npz", "batch-000001.npz"]
    for line in lines:
        digest, name = line.split("  ")
        assert digest == hashlib.sha256((parts / name).read_bytes()).hexdigest()
    if shutil.which("sha256sum"):
        res = subprocess.run(["sha256sum", "-c", CHECKSUMS], cwd=parts, capture_output=True, text=True)
        assert res.returncode == 0 and res.stdout.count(": OK") == 2, res.stdout + res.stderr


def test_a_fifo_in_place_of_a_part_is_recomputed_without_blocking(tmp_path, study, caplog):
    """A FIFO named like a part (reading it would wait for a writer for ever) is moved aside and
    its batch recomputed."""
    clean = run_study(study, tmp_path / "clean.nc", workers=1)
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    part = parts_dir(out) / "batch-000000.npz"
    part.unlink()
    os.mkfifo(part)
    with caplog.at_level(logging.WARNING, logger="vbikit.study.run"):
        xr.testing.assert_identical(clean, run_study(study, out, workers=1))
    assert f"study part {part} is unusable: it cannot be read" in caplog.text
