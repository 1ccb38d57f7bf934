"""Coverage of the compiled kernels (slow job).

numba-compiled functions are invisible to coverage.py, so this job runs the kernel-path tests
with ``NUMBA_DISABLE_JIT=1`` (the kernels then run as plain Python: 11–15 min, measured 2026-12-05
on a shared 2-core machine) under pytest-cov and reads the line coverage of the kernels
(``vbikit/solve/kernels/``) from the JSON report.  Run it with

    python -m pytest -m slow tests/verification/test_kernel_coverage.py -s

It prints the figure and the lines still not run, and fails below :data:`MIN_KERNEL_COVERAGE`.
The selection (:data:`SELECTION`) is the small crossings written for this purpose
(``test_kernel_paths.py``: every integrator × every tire model at rest and over a launching
bump, repeated damped landings of a rigid disk, the batch solver with lanes and a user step and
with lanes that lift off, a vehicle without DOFs, the static start's fall-back), the full Newton on
small contrived systems (``test_full_newton.py``) and the pinned random streams.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SELECTION = [
    "tests/verification/test_kernel_paths.py",
    "tests/verification/test_pinned_streams.py",
    # heavy wheel hop on a 3D deck (many wheels and points; with the secant road rate its landings
    # settle without the full Newton)
    "tests/verification/test_heavy_hop_convergence.py::test_deck_class_d",
    "tests/unit/test_newton_coupling.py",  # the full Newton's capacitance form (disk tires)
    # the full Newton against a brute-force contact set, a landing held at zero penetration, the
    # rigid disk's rate clamp in ``_penetration``
    "tests/unit/test_full_newton.py",
    # landings held at the road surface: skipped points touch-tested, a non-level patch split by depth
    # (``newton._touch_points``, ``_split_touch``)
    "tests/unit/test_touching_landings.py",
    # ``implicit``'s count of steps that did not converge (one iteration allowed)
    "tests/unit/test_unconverged_steps.py::test_every_step_of_a_rough_road_at_one_iteration_is_counted_and_flagged",
    # the quasi-Newton update's wheel part against numpy, with a matrix that needs row swaps (``dense.solve_held``)
    "tests/unit/test_woodbury.py",
]
# With the secant road rate (2026-12-05) the heavy-hop deck runs above settle every landing with the
# one-evaluation step or the quasi-Newton updates, so no crossing here reached the full Newton
# (``newton._full_newton``, ``_penetration``), nor did any batch that lifts off reach the many-lane
# kernels' freezing and the many-lane ``implicit`` (added 2026-12-04): 91.9 % of 2027 statements.
# test_full_newton.py and, in test_kernel_paths.py, the damped rigid-disk landings (24 full Newton
# updates) and the batch lanes that lift off reach them again.
#: measured 98.7 % of 2303 statements of the kernels' package (2026-12-06, with test_woodbury.py; 9.2 min
#: CPU), 98.4 % of 2132 (2026-12-05, with the touching landings'
#: split; 98.5 % of 2027 before it; 97.6 % of 1149 on
#: 2026-12-04, 98.2 % of 665 in the one module on 2026-12-01).  The lines not run: ``shapes_at``, an
#: eager helper no solver path calls; ``implicit``'s count of steps that did not converge and a
#: touching point's width at a step's end; its vehicle accelerations without DOFs (the lean kernels
#: take moving forces); the one-evaluation step's exits for a point leaving the lazy test (``lean``,
#: ``_lean_refine``) and for corrections that do not settle (``_lean_refine``, ``lean_lanes``); the
#: vehicle factors' row swaps in the crossings (``dense.solve_held``: those matrices need no pivoting;
#: test_woodbury.py runs them); a point left out by
#: the lazy test in the full Newton; ``lean_lanes``' cell-slope road rate (a vehicle at rest: no
#: secant span), its points that the lazy test keeps but no lane presses (watched by their bound) and
#: its return when every lane is frozen.
MIN_KERNEL_COVERAGE = 97.0


@pytest.mark.slow
def test_kernel_coverage_without_jit(tmp_path):
    pytest.importorskip("pytest_cov")
    report = tmp_path / "coverage.json"
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-o", "addopts=", "--cov=vbikit",
           f"--cov-report=json:{report}", "--cov-report=", *SELECTION]
    res = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=3600)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    files = json.loads(report.read_text())["files"]
    parts = {k: v for k, v in files.items() if "vbikit/solve/kernels/" in k.replace("\\", "/")}
    statements = sum(v["summary"]["num_statements"] for v in parts.values())
    covered = sum(v["summary"]["covered_lines"] for v in parts.values())
    percent = 100.0 * covered / statements
    kernels = {"summary": {"num_statements": statements},
               "missing_lines": {k.rsplit("/", 1)[-1]: v["missing_lines"] for k, v in parts.items()}}
    total = json.loads(report.read_text())["totals"]["percent_covered"]
    print(f"\nkernel coverage (NUMBA_DISABLE_JIT=1): {percent:.1f} % of {kernels['summary']['num_statements']} "
          f"statements; lines not run: {kernels['missing_lines']}; whole package in this selection: {total:.1f} %")
    assert percent >= MIN_KERNEL_COVERAGE
