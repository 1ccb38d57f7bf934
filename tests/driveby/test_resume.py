"""``vbikit driveby`` killed mid-sweep (kill -9 of the whole process group, or Ctrl-C) keeps its
finished batches; the same command started again resumes to the dataset of an unbroken run."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr

from vbikit.driveby.study import run_driveby
from vbikit.study.storage import parts_dir

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "driveby" / "DRIVEBY.toml"
# the CLI as a terminal starts it: SIGINT raises KeyboardInterrupt (a shell's background job starts with SIGINT
# ignored, which Python keeps: Ctrl-C would then not reach the run)
CLI = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); from vbikit.cli import main; main()"
N_CASES = 12  # 3 speeds × 2 road classes × 2 damage severities


def _interrupt(tmp_path, sig, workers):
    spec = tmp_path / "DRIVEBY.toml"
    spec.write_text(EXAMPLE.read_text().replace("batch_size = 2", "batch_size = 1"))
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-c", CLI, "driveby", str(spec), "--out-dir", str(out), "--no-progress",
                             "--no-figures", "--workers", str(workers)], start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    parts = parts_dir(out / "driveby.nc")
    deadline = time.time() + 120
    while time.time() < deadline and len(list(parts.glob("batch-*.npz"))) < 3 and proc.poll() is None:
        time.sleep(0.005)
    os.killpg(proc.pid, sig)
    _, err = proc.communicate(timeout=60)
    n_done = len(list(parts.glob("batch-*.npz")))
    assert 3 <= n_done < N_CASES, "the sweep was not interrupted mid-way"
    assert not (out / "driveby.nc").exists()
    return spec, out, proc.returncode, err


def _resumed_equals_unbroken(spec, out, tmp_path):
    resumed = run_driveby(spec, out, figures=False)
    unbroken = run_driveby(spec, tmp_path / "unbroken", figures=False)
    xr.testing.assert_equal(resumed, unbroken)  # attributes hold run times
    assert resumed.sizes["case"] == N_CASES


@pytest.mark.slow
def test_kill_9_of_the_process_group_then_resume_is_identical(tmp_path):
    spec, out, code, _ = _interrupt(tmp_path, signal.SIGKILL, workers=2)
    assert code == -signal.SIGKILL
    _resumed_equals_unbroken(spec, out, tmp_path)


@pytest.mark.slow
def test_ctrl_c_exits_130_keeps_finished_batches_and_resume_is_identical(tmp_path):
    spec, out, code, err = _interrupt(tmp_path, signal.SIGINT, workers=1)
    assert code == 130, err
    assert "Traceback" not in err and "run the same command again to resume" in err
    _resumed_equals_unbroken(spec, out, tmp_path)
