"""Command-line options shared by the benchmark scripts (``--repeat``, ``--cold``).

Import and call :func:`benchmark_args` before numpy/numba/vbikit are imported: ``--cold`` points
numba at a fresh, empty cache directory, which must happen before numba loads.
"""
from __future__ import annotations

import argparse
import os
import tempfile

_COLD_CACHE: tempfile.TemporaryDirectory | None = None


def benchmark_args(doc: str, repeat_help: str, parser: argparse.ArgumentParser | None = None) -> argparse.Namespace:
    """Parse ``--repeat N`` and ``--cold`` (plus whatever ``parser`` already defines)."""
    global _COLD_CACHE
    p = parser or argparse.ArgumentParser(description=doc.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=5, help=repeat_help)
    p.add_argument("--cold", action="store_true", help="use a fresh, empty numba cache so the warm-up includes compilation")
    args = p.parse_args()
    if args.cold:
        _COLD_CACHE = tempfile.TemporaryDirectory(prefix="vbikit-numba-cache-")  # removed at exit
        os.environ["NUMBA_CACHE_DIR"] = _COLD_CACHE.name
    return args


def default_step_loops() -> tuple[str, str]:
    """The names in ``vbikit.solve.kernels`` of the step loops the default integrator runs, one lane and many
    (its ``Integrator.kernel`` and ``lanes_kernel``: ``lean_quadratic`` and ``lean_lanes_quadratic`` while the
    wheel loads are held quadratic, ``builtin_integrators.QUADRATIC_WHEEL_LOADS``), so that a benchmark times
    the kernels that run rather than a variant by name."""
    from vbikit.solve.crossing import DEFAULT_INTEGRATOR, get_integrator

    integrator = get_integrator(DEFAULT_INTEGRATOR)
    one = getattr(integrator, "kernel", None)  # (``bench_per_crossing.py --compare`` may load a tree older than
    many = getattr(integrator, "lanes_kernel", None)  # ``Integrator.lanes_kernel``, 2026-12-05: its kernels' names)
    return (one().__name__ if one else "lean"), (many().__name__ if many else "lean_lanes")
