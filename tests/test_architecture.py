"""Layering contracts (pyproject.toml [tool.importlinter]): physics models never import the solver,
analysis, scenario, plots or the CLI; the solver never imports analysis, scenario or plots."""
from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_import_contracts_hold():
    beside = Path(sys.executable).with_name("lint-imports")  # the venv's, also when it is not on PATH
    exe = str(beside) if beside.is_file() else shutil.which("lint-imports")
    cmd = [exe] if exe else [sys.executable, "-m", "importlinter.cli"]
    res = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "kept" in res.stdout and "broken" in res.stdout


def test_readme_test_command_is_what_ci_runs():
    readme = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text()
    command = next(line.strip() for line in ci.splitlines() if "pytest" in line and not line.strip().startswith("#"))
    assert command in readme
