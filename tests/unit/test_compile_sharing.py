"""The test run's workers share the kernel groups out (tests/conftest.py ``_share_the_kernel_compilation``):
every group compiled once, by one worker, and a group of ``_AFTER`` only once its prerequisite is done
(then its kernels load the prerequisite's from numba's cache instead of compiling them again).  Workers
are threads here (each lock is its own open file, so threads exclude each other as processes do), and the
compilation a recorder: nothing is compiled."""
from __future__ import annotations

import threading
import time
from pathlib import Path

import pytest


@pytest.fixture
def sharing(request, monkeypatch):
    """The root conftest module (already loaded by pytest) with fake groups: ``first`` slow, ``after`` and
    ``later`` waiting for it, two small ones; returns (module, the recorded (name, start, end) rows)."""
    path = str(Path(__file__).resolve().parents[1] / "conftest.py")
    module = next(p for p in request.config.pluginmanager.get_plugins() if getattr(p, "__file__", None) == path)
    rows: list[tuple[str, float, float]] = []
    lock = threading.Lock()

    def compile_in_subprocess(name: str) -> bool:
        t0 = time.perf_counter()
        time.sleep(0.2 if name == "first" else 0.02)
        with lock:
            rows.append((name, t0, time.perf_counter()))
        return name != "broken"

    names = ["first", "after", "small", "later", "other"]
    monkeypatch.setattr(module, "_compile_groups", lambda: {n: None for n in names})
    monkeypatch.setattr(module, "_AFTER", {"after": "first", "later": "first"})
    monkeypatch.setattr(module, "_compile_in_subprocess", compile_in_subprocess)
    return module, rows, names


def _run_workers(module, folder: str, n: int) -> list[bool]:
    results: list[bool] = []
    threads = [threading.Thread(target=lambda: results.append(module._share_the_kernel_compilation(folder)))
               for _ in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(30.0)
    return results


def test_each_group_once_and_the_waiting_ones_after_their_prerequisite(sharing, tmp_path):
    module, rows, names = sharing
    results = _run_workers(module, str(tmp_path), 3)
    assert results == [True, True, True]
    assert sorted(r[0] for r in rows) == sorted(names)  # each group compiled once
    end_first = next(end for name, _, end in rows if name == "first")
    for name, start, _ in rows:
        if name in ("after", "later"):
            assert start >= end_first, f"{name} started before its prerequisite was done"
    # the groups that do not wait ran meanwhile (the other workers did not sit idle)
    assert any(start < end_first for name, start, _ in rows if name in ("small", "other"))


def test_a_failed_prerequisite_fails_the_sharing_and_its_dependents_still_compile(sharing, tmp_path, monkeypatch):
    module, rows, names = sharing
    monkeypatch.setattr(module, "_compile_groups", lambda: {n: None for n in ["broken", "after", "small"]})
    monkeypatch.setattr(module, "_AFTER", {"after": "broken"})
    assert _run_workers(module, str(tmp_path), 2) == [False, False]
    assert sorted(r[0] for r in rows) == ["after", "broken", "small"]
