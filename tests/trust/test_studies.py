"""Studies: size printed and refused above 1e6 crossings without --yes, validation that never
hangs, strict types and duplicate values refused, parts that carry their batch index and the
study checksum (a damaged or foreign part is reported by path, moved aside and recomputed), and a
full disk that ends in exit 2 and a later resume."""
from __future__ import annotations

import copy
import errno
import shutil
import time

import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.study.run import parts_dir, run_study
from vbikit.study.spec import StudyError, parse_study

runner = CliRunner()

SMALL = {
    "name": "trust study", "seed": 3, "batch_size": 2,
    "base": {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "two-axle"},
             "tire": {"model": "multipoint"}, "road": {"class": "C", "length": 200}, "crossing": {"speed_kmh": 90}},
    "axes": {"tire.n_points": [1, 3], "road.seed": {"samples": 2}},
}


def test_ten_million_crossings_refused_quickly_without_yes(tmp_path, study_toml):
    d = copy.deepcopy(SMALL)
    d["axes"] = {"crossing.speed_kmh": list(range(40, 140, 10)), "crossing.approach": list(range(1, 11)),
                 "crossing.free_vibration": [0.1 * i for i in range(1, 11)], "tire.n_points": list(range(1, 11)),
                 "tire.contact_length": [0.1 + 0.01 * i for i in range(10)], "road.n_max": [1.0 + i for i in range(10)],
                 "road.seed": list(range(10))}
    path = tmp_path / "big.toml"
    path.write_text(study_toml(d))
    t0 = time.perf_counter()
    for cmd in (["study", "validate", str(path)], ["study", "run", str(path), "--out", str(tmp_path / "b.nc")]):
        res = runner.invoke(app, cmd)
        # the refusal gives the size (study run also announced it before the check; validate gives it here only)
        assert res.exit_code == 2 and "this study has 1e+07 crossings" in res.stderr and "--yes" in res.stderr, res.output
    assert time.perf_counter() - t0 < 20  # measured ≈ 2 s; it used to hang in validate
    res = runner.invoke(app, ["study", "validate", str(path), "--yes"])
    assert res.exit_code == 0, res.output
    assert not (tmp_path / "b.nc.parts").exists()


@pytest.mark.parametrize("axis,values,words", [
    ("tire.n_points", [1, 3, 1], "repeats a value"),
    ("crossing.speed_kmh", [60, 60.0], "repeats a value"),
    ("crossing.speed_kmh", ["60", 70], "expected a number"),
    ("crossing.speed_kmh", [True, 70], "expected a number"),
])
def test_bad_axis_values(axis, values, words):
    d = copy.deepcopy(SMALL)
    d["axes"] = {axis: values}
    with pytest.raises(StudyError, match=words):
        parse_study(d)


def test_strict_study_keys():
    for key, value in (("seed", "3"), ("batch_size", 2.0), ("seed", True)):
        with pytest.raises(StudyError, match=key):
            parse_study({**SMALL, key: value})


def test_damaged_and_foreign_parts_are_moved_aside_and_recomputed(tmp_path, caplog):
    study = parse_study(SMALL)
    clean = run_study(study, tmp_path / "clean.nc", workers=1)
    out = tmp_path / "r.nc"
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    parts = sorted(parts_dir(out).glob("batch-*.npz"))
    assert len(parts) == 2
    parts[0].write_bytes(parts[0].read_bytes()[:100])  # truncated (used to give BadZipFile naming no file)
    other = parse_study({**SMALL, "seed": 4})
    run_study(other, tmp_path / "o.nc", workers=1, keep_parts=True)
    shutil.copy(sorted(parts_dir(tmp_path / "o.nc").glob("batch-*.npz"))[1], parts[1])  # a part of another study
    with caplog.at_level("WARNING"):
        again = run_study(study, out, workers=1)
    xr.testing.assert_identical(clean, again)
    text = caplog.text
    assert f"{parts[0]} is unusable: it cannot be read" in text
    assert f"{parts[1]} is unusable: it belongs to another study" in text
    # a valid part of this study copied over another batch (used to be merged: NaN cells, n_steps = -9.2e18)
    out.unlink()
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    shutil.copy(parts[0], parts[1])
    caplog.clear()
    with caplog.at_level("WARNING"):
        xr.testing.assert_identical(clean, run_study(study, out, workers=1))
    assert f"{parts[1]} is unusable: it holds batch 0, not batch 1" in caplog.text


def test_full_disk_exits_2_and_resumes(tmp_path, monkeypatch, study_toml):
    path = tmp_path / "s.toml"
    path.write_text(study_toml(SMALL))
    out = tmp_path / "r.nc"
    import vbikit.study.run as run_mod

    real = run_mod._to_netcdf

    def full(ds, tmp):
        tmp.write_bytes(b"partial")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(run_mod, "_to_netcdf", full)
    res = runner.invoke(app, ["study", "run", str(path), "--out", str(out), "--workers", "1", "--no-progress"])
    assert res.exit_code == 2, res.output
    assert "no space left on the device" in res.output and "resume" in res.output
    assert not out.exists() and len(list(parts_dir(out).glob("batch-*.npz"))) == 2
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    monkeypatch.setattr(run_mod, "_to_netcdf", real)
    res = runner.invoke(app, ["study", "run", str(path), "--out", str(out), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    assert out.exists() and not parts_dir(out).exists()


def test_unwritable_out_is_not_reported_as_a_lock(tmp_path, study_toml):
    path = tmp_path / "s.toml"
    path.write_text(study_toml(SMALL))
    res = runner.invoke(app, ["study", "run", str(path), "--out", "/proc/x.nc", "--workers", "1"])
    assert res.exit_code == 2 and "another vbikit study" not in res.output and "/proc" in res.output, res.output


def test_full_disk_while_writing_a_part_exits_2_and_resumes(tmp_path, monkeypatch, study_toml):
    path = tmp_path / "s.toml"
    path.write_text(study_toml(SMALL))
    out = tmp_path / "r.nc"
    import vbikit.study.run as run_mod

    real, calls = run_mod.np.savez, []

    def savez(fh, **arrays):
        calls.append(1)
        if len(calls) == 2:  # the second batch hits a full disk
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(fh, **arrays)

    monkeypatch.setattr(run_mod.np, "savez", savez)
    res = runner.invoke(app, ["study", "run", str(path), "--out", str(out), "--workers", "1", "--no-progress"])
    assert res.exit_code == 2, res.output
    assert "no space left on the device" in res.output and "run the same command again to resume" in res.output
    assert len(list(parts_dir(out).glob("batch-*.npz"))) == 1 and not list(parts_dir(out).glob("*.tmp"))
    monkeypatch.setattr(run_mod.np, "savez", real)
    res = runner.invoke(app, ["study", "run", str(path), "--out", str(out), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output


def test_histories_must_fit_the_memory_budget(tmp_path, study_toml):
    path = tmp_path / "s.toml"
    d = copy.deepcopy(SMALL)
    d["axes"]["road.seed"] = {"samples": 1000}
    path.write_text(study_toml(d))
    assert runner.invoke(app, ["study", "validate", str(path), "--max-memory", "8MB"]).exit_code == 0
    path.write_text(study_toml(d).replace('batch_size = 2', 'batch_size = 2\nhistories = true'))
    res = runner.invoke(app, ["study", "validate", str(path), "--max-memory", "8MB"])
    assert res.exit_code == 2 and "histories = true" in res.output, res.output
