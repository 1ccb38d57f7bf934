"""Running, storing and resuming studies: identical datasets whatever happens in between."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

from vbikit import __version__
from vbikit.study import StudyError, parse_study, run_study
from vbikit.study.run import parts_dir


def test_dataset_layout_and_attrs(tmp_path, small_study_dict):
    study = parse_study(small_study_dict)
    calls = []
    ds = run_study(study, tmp_path / "r.nc", workers=1, progress=lambda d, t: calls.append((d, t)))
    assert dict(ds.sizes) == {"tire_n_points": 2, "road_class": 2, "sample": 3}
    assert list(ds["road_class"].values) == ["B", "D"]
    assert list(ds["road_seed"].values) == list(study.axes[2].seeds)
    assert ds.attrs["vbikit_version"] == __version__
    assert json.loads(ds.attrs["study"])["axes"]["road.seed"] == {"samples": 3}
    assert np.all(np.isfinite(ds["impact_factor"])) and np.all(ds["max_static_displacement"] < 0)
    assert calls[0] == (0, 12) and calls[-1] == (12, 12)
    assert not parts_dir(tmp_path / "r.nc").exists()
    on_disk = xr.open_dataset(tmp_path / "r.nc")
    xr.testing.assert_identical(on_disk.load(), ds)
    on_disk.close()
    # worse road -> larger IM on average (same seeds)
    im = ds["impact_factor"].mean("sample")
    assert np.all(im.sel(road_class="D") > im.sel(road_class="B"))


def test_study_result_equals_single_crossings(tmp_path, small_study_dict):
    """A stored IM equals (to round-off: the study runs its roads as lanes of one kernel call) the
    IM of the same scenario run alone through simulate + point_response."""
    from vbikit.analysis import point_response
    from vbikit.scenario import build, parse_scenario
    from vbikit.solve import simulate

    study = parse_study(small_study_dict)
    ds = run_study(study, tmp_path / "r.nc", workers=1)
    for idx in [(0, 0, 0), (1, 1, 2)]:
        built = build(parse_scenario(study.scenario_dict(idx)))
        resp = point_response(simulate(built.crossing))
        assert ds["impact_factor"].values[idx] == pytest.approx(resp.displacement_impact.impact_factor, abs=1e-12)
        assert ds["strain_impact_factor"].values[idx] == pytest.approx(resp.strain_impact.impact_factor, abs=1e-12)


def test_parallel_equals_serial_and_resume_skips_finished(tmp_path, small_study_dict):
    study = parse_study(small_study_dict)
    serial = run_study(study, tmp_path / "a.nc", workers=1)
    parallel = run_study(study, tmp_path / "b.nc", workers=2)
    xr.testing.assert_identical(serial, parallel)
    # an interrupted run: only some batch files exist; the restart runs only the rest
    out = tmp_path / "c.nc"
    run_study(study, out, workers=1, keep_parts=True)
    out.unlink()
    parts = sorted(parts_dir(out).glob("batch-*.npz"))
    for p in parts[1::2]:
        p.unlink()
    seen = []
    resumed = run_study(study, out, workers=1, progress=lambda d, t: seen.append(d))
    assert seen[0] == sum(3 for _ in parts[0::2])  # finished batches counted as done at start
    xr.testing.assert_identical(serial, resumed)
    # a finished dataset is recognised, a different study is refused
    xr.testing.assert_identical(serial, run_study(study, out, workers=1))
    other = parse_study({**small_study_dict, "seed": 12})
    with pytest.raises(StudyError, match="not this study's finished dataset"):
        run_study(other, out, workers=1)
    (tmp_path / "d.nc.parts").mkdir()
    (tmp_path / "d.nc.parts" / "study.json").write_text("{}")
    with pytest.raises(StudyError, match=r"partial results of a different run \(other inputs, options or version\)"):
        run_study(study, tmp_path / "d.nc", workers=1)


def test_histories_are_stored(tmp_path, small_study_dict):
    small_study_dict["histories"] = True
    small_study_dict["axes"] = {"road.seed": {"samples": 2}}
    ds = run_study(parse_study(small_study_dict), tmp_path / "h.nc", workers=1)
    h = ds["displacement_history"]
    assert h.dims == ("sample", "step")
    assert np.nanmin(h.values) == pytest.approx(ds["max_dynamic_displacement"].min())


KILL_SCRIPT = """
import json, sys
from vbikit.study import parse_study, run_study
run_study(parse_study(json.loads(sys.argv[1])), sys.argv[2], workers=2)
"""


def test_sigkill_mid_run_then_restart_gives_identical_dataset(tmp_path, small_study_dict):
    small_study_dict["batch_size"] = 1
    small_study_dict["axes"]["road.seed"] = {"samples": 6}
    small_study_dict["base"]["crossing"]["speed_kmh"] = 40  # slower crossings: a longer run to interrupt
    study = parse_study(small_study_dict)
    out = tmp_path / "killed.nc"
    proc = subprocess.Popen([sys.executable, "-c", KILL_SCRIPT, json.dumps(small_study_dict), str(out)],
                            start_new_session=True, stderr=subprocess.PIPE)
    parts = parts_dir(out)
    deadline = time.time() + 60
    while time.time() < deadline and len(list(parts.glob("batch-*.npz"))) < 3:
        time.sleep(0.005)
    os.killpg(proc.pid, signal.SIGKILL)  # the runner and its worker processes, mid-run
    proc.wait()
    n_done = len(list(parts.glob("batch-*.npz")))
    assert 3 <= n_done < len(study.batches()), "the run was not interrupted mid-way"
    assert not out.exists()
    resumed = run_study(study, out, workers=2)
    unbroken = run_study(study, tmp_path / "unbroken.nc", workers=1)
    xr.testing.assert_identical(unbroken, resumed)


# the CLI as a terminal starts it: SIGINT raises KeyboardInterrupt (a shell's background job starts with SIGINT
# ignored, which Python keeps: Ctrl-C would then not reach the run)
CLI_SCRIPT = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); from vbikit.cli import main; main()"


def test_ctrl_c_keeps_finished_batches_and_resume_is_identical(tmp_path, small_study_dict, study_toml):
    """SIGINT (Ctrl-C) to `vbikit study run`: exit code 130, finished batches kept, resume identical."""
    small_study_dict["batch_size"] = 1
    small_study_dict["axes"]["road.seed"] = {"samples": 6}
    small_study_dict["base"]["crossing"]["speed_kmh"] = 40
    toml = study_toml(small_study_dict)
    (tmp_path / "s.toml").write_text(toml)
    out = tmp_path / "int.nc"
    proc = subprocess.Popen([sys.executable, "-c", CLI_SCRIPT, "study", "run", str(tmp_path / "s.toml"), "--out",
                             str(out), "--workers", "2", "--no-progress"], start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    parts = parts_dir(out)
    t0 = time.time()
    seen = 0
    while time.time() < t0 + 60 and seen < 3:
        seen = len(list(parts.glob("batch-*.npz")))
        time.sleep(0.005)
    waited = time.time() - t0
    os.killpg(proc.pid, signal.SIGINT)  # like Ctrl-C in a terminal: the whole process group
    stdout, err = proc.communicate(timeout=30)
    assert proc.returncode == 130, (f"exit {proc.returncode} after {waited:.2f} s ({seen} parts seen); stdout "
                                    f"{stdout!r}; stderr {err!r}")
    assert "resume" in err and "Traceback" not in err
    n_done = len(list(parts.glob("batch-*.npz")))
    study = parse_study(small_study_dict)
    assert 3 <= n_done < len(study.batches())
    resumed = run_study(study, out, workers=2)
    xr.testing.assert_identical(run_study(study, tmp_path / "ref.nc", workers=1), resumed)


def test_study_without_axes_is_one_crossing(tmp_path, small_study_dict):
    small_study_dict["axes"] = {}
    small_study_dict["histories"] = True
    ds = run_study(parse_study(small_study_dict), tmp_path / "one.nc", workers=1)
    assert ds["impact_factor"].dims == () and np.isfinite(float(ds["impact_factor"]))
    assert ds["displacement_history"].dims == ("step",)


def test_second_writer_on_the_same_output_is_refused(tmp_path, small_study_dict):
    """While one run holds <out>.lock, another run on the same --out stops with a clear error
    before computing anything; once the lock is released the study runs."""
    from filelock import FileLock

    study = parse_study(small_study_dict)
    out = tmp_path / "r.nc"
    with FileLock(str(out) + ".lock"):
        with pytest.raises(StudyError, match="another vbikit study is writing to"):
            run_study(study, out, workers=1)
        assert not parts_dir(out).exists()
    assert run_study(study, out, workers=1)["impact_factor"].size == study.size
