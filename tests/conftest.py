"""Test-wide settings: the slab-on-girder mode cache goes to a throw-away directory, so tests
never read modes cached by an earlier version of the code and never write to the user's home."""
from __future__ import annotations

import atexit
import json
import os
import shutil
import tempfile

import pytest

_CACHE = tempfile.mkdtemp(prefix="vbikit-test-cache-")
os.environ["VBIKIT_CACHE_DIR"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)


def _silence_process_exit() -> None:
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)


def pytest_unconfigure(config) -> None:
    """Keep pytest's summary the last line of the run: OpenSees (optional cross-check) prints
    "Process 0 Terminating" from its exit handler after pytest has finished, so once pytest is
    done (and its output capture restored) the process's stdout/stderr go to /dev/null."""
    import sys

    if any(name.startswith("openseespy") for name in sys.modules):
        sys.stdout.flush()
        sys.stderr.flush()
        atexit.register(_silence_process_exit)


def _study_toml(d: dict) -> str:
    """A study file's text from its dict form (name, seed, batch_size, base sections, axes)."""
    lines = [f"name = {json.dumps(d['name'])}", f"seed = {d['seed']}", f"batch_size = {d['batch_size']}"]
    for section, table in d["base"].items():
        lines.append(f"[base.{section}]")
        lines += [f"{k} = {json.dumps(v)}" for k, v in table.items()]
    lines.append("[axes]")
    for k, v in d["axes"].items():
        lines.append(f'"{k}" = ' + (f"{{samples = {v['samples']}}}" if isinstance(v, dict) else json.dumps(v)))
    return "\n".join(lines) + "\n"


@pytest.fixture
def study_toml():
    """The function writing a study dict as study-file text (shared by the study and trust tests)."""
    return _study_toml
