"""Worker processes end with the coordinating process, even when it is killed with SIGKILL (no
clean-up code runs then)."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from vbikit.study.run import parts_dir

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads process states from /proc")

SCRIPT = """
import json, sys
from vbikit.study import parse_study, run_study
run_study(parse_study(json.loads(sys.argv[1])), sys.argv[2], workers=2)
"""


def _children(pid: int) -> list[int]:
    """Live processes whose parent is ``pid`` (from /proc/*/stat)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid and fields[0] != "Z":
            out.append(int(stat.parent.name))
    return out


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie waiting for its reaper counts as ended)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_sigkill_of_the_coordinator_ends_its_workers(tmp_path, small_study_dict):
    small_study_dict["batch_size"] = 1
    small_study_dict["axes"]["road.seed"] = {"samples": 20}
    small_study_dict["base"]["crossing"]["speed_kmh"] = 20  # slow crossings: the workers are busy when killed
    out = tmp_path / "k.nc"
    proc = subprocess.Popen([sys.executable, "-c", SCRIPT, json.dumps(small_study_dict), str(out)],
                            stderr=subprocess.DEVNULL)
    workers: list[int] = []
    try:
        deadline = time.time() + 120
        while time.time() < deadline and not list(parts_dir(out).glob("batch-*.npz")):
            time.sleep(0.05)
        workers = [p for p in _children(proc.pid) if _alive(p)]
        assert len(workers) >= 2, "the study's worker processes were not found"
        os.kill(proc.pid, signal.SIGKILL)  # the coordinator only, not its process group
        proc.wait()
        deadline = time.time() + 5
        while time.time() < deadline and any(_alive(p) for p in workers):
            time.sleep(0.05)
        assert not [p for p in workers if _alive(p)], "worker processes outlived the coordinator by 5 s"
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        for p in workers:  # this test's own processes, if the check failed
            if _alive(p):
                os.kill(p, signal.SIGKILL)


def _blas_threads() -> list[int]:
    from threadpoolctl import threadpool_info

    return [lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"]


def test_a_worker_runs_its_blas_on_one_thread():
    # one process per core already: BLAS threads would only spin (vbikit.study.workers docstring)
    from vbikit.study.workers import local_pool, shutdown_workers

    try:
        threads = local_pool(2).submit(_blas_threads).result(timeout=120)
    finally:
        shutdown_workers()
    assert threads and all(n == 1 for n in threads)
