"""The first-run notice: numba compiles a kernel once per machine, and says so beforehand (a kernel shipped
compiled and put into numba's cache, ``vbikit.solve.prebuilt``, is in the cache already: no notice).

``announce_compile`` logs (logger ``vbikit.solve.compile``, which the CLI shows) that a compiled
kernel is about to be compiled when it is neither compiled in this process nor in numba's on-disk
cache, with its expected CPU time ``COMPILE_SECONDS``, once per kernel.  The solver (``simulate``, the many-lane
runner in ``integrators``), studies and the railway sweeps call it before their first kernel call.
"""
from __future__ import annotations

import logging
import os

#: says when numba compiles the kernels (the first run on a machine, ≈ 5 s of CPU; benchmarks/bench_compile.py)
#: and where its cache goes; the CLI shows it
compile_log = logging.getLogger("vbikit.solve.compile")


#: CPU seconds numba takes to compile each kernel the first time, by the kernel's name (the one place
#: these live).  ``lean``, the one-lane path a single crossing (``vbikit run``, ``demo``) runs:
#: benchmarks/bench_compile.py, 4.8–4.9 s for the demo on a quiet 2-core machine, 2026-12-04.
#: ``lean_lanes``, the many-lane path a study's batches run: 16.1 s with the one-lane kernels already
#: in numba's cache (a 2-lane batch of ``warmup._tiny_crossing("exact")`` in a fresh process over an
#: empty ``NUMBA_CACHE_DIR`` holding only ``simulate``'s kernels, ``time.process_time``; 2026-12-04,
#: load ≈ 1–2).  Both rounded up ≈ 1.4× for a busier or slower machine.  ``implicit``, the full
#: contact kernel (a contact opening or closing within a step: a wheel leaving the road, rigid-disk
#: tires; ``integrators._full``): 59.5 s with ``lean`` already compiled (the demo crossing under
#: ``without_lean`` in a fresh process over an empty ``NUMBA_CACHE_DIR``, ``time.process_time``;
#: 2026-12-06, the machine's slow state, in which the demo's cold compile is 8.0 s against 5.7 s) —
#: ``implicit`` itself 15 s, ``contact_forces`` 9 s, the rest its 140 helpers.  ``run_in_loads`` and
#: ``linear_recursion``, the run-in's loops (``vbikit.solve.run_in``): 1.7 s the two with ``lean`` already
#: compiled (an HS20-44 with a 40 m run-in after one without, fresh ``NUMBA_CACHE_DIR``, ``time.process_time``;
#: 2026-12-06, slow state), rounded up.  The variants with the wheel loads held quadratic (the default
#: integrator's since 2026-12-07), measured alternating with the linear ones the same way, slow state:
#: ``lean_quadratic`` 6.3 / 6.6 s against ``lean`` 6.1 / 5.8 s (bench_compile.py, the demo),
#: ``lean_lanes_quadratic`` 24.4 s against ``lean_lanes`` 21.0 s (the 2-lane batch above).  Any other
#: kernel: ``lean``'s.
#: ``run_state_pass`` and ``line_sums``, the load effects' compiled passes (``vbikit.analysis.instants``,
#: ``vbikit.analysis.line_sums``): 2.3 and 0.6 s in the first ``vbikit demo`` of a fresh cache compiling for the host
#: (``VBIKIT_HOST_KERNELS=1``; numba's compile events; 2026-12-07 on the 2-core machine), rounded up.
COMPILE_SECONDS: dict[str, int] = {"lean": 7, "lean_lanes": 22, "lean_quadratic": 7, "lean_lanes_quadratic": 26,
                                   "implicit": 60, "run_in_loads": 2, "linear_recursion": 1, "run_state_pass": 3,
                                   "line_sums": 1}


def compile_seconds(kernel) -> int:
    """The expected CPU seconds [s] of ``kernel``'s first compilation (``COMPILE_SECONDS``)."""
    return COMPILE_SECONDS.get(_name(kernel), COMPILE_SECONDS["lean"])


def _name(kernel) -> str:
    return str(getattr(kernel, "__name__", type(kernel).__name__))


def kernels_cached(kernel) -> bool:
    """Whether ``kernel`` (a numba dispatcher) is compiled in this process or in numba's on-disk cache
    (its index file exists); True for a plain function (NUMBA_DISABLE_JIT=1)."""
    overloads = getattr(kernel, "overloads", None)  # not ``signatures``: listing them costs ≈ 16 µs a call
    if overloads is None or overloads:
        return True
    index = getattr(getattr(getattr(kernel, "_cache", None), "_cache_file", None), "_index_path", None)
    return index is not None and os.path.exists(index)


#: the kernels (by name) this process has announced, "*" for all (its parent announced them for it:
#: ``announced_elsewhere``): each is announced once a process, however many callers (a study, then its
#: first crossing) ask
_ANNOUNCED: set[str] = set()


def announced_kernels() -> frozenset[str]:
    """The kernels (by name) whose first compilation this process has announced so far (a caller
    compares two calls to tell whether a run in between compiled one: ``vbikit compare-tires``)."""
    return frozenset(_ANNOUNCED)


def announced_elsewhere() -> None:
    """Say no more in this process: a study's worker processes, whose parent announced the
    compilation of every kernel their batches run for all of them (``vbikit.study.run``)."""
    _ANNOUNCED.add("*")


def announce_compile(kernels, who: str = "") -> None:
    """Log (``vbikit.solve.compile``, shown by the CLI), for each of ``kernels`` (a dispatcher or a
    sequence of them) neither compiled in this process nor in numba's on-disk cache, that it is about
    to be compiled and its expected CPU time (``COMPILE_SECONDS``), once a process and kernel;
    ``who`` says where (e.g. "each of the 2 worker processes, on its first batch")."""
    for kernel in kernels if isinstance(kernels, (list, tuple)) else (kernels,):
        name = _name(kernel)
        if "*" in _ANNOUNCED or name in _ANNOUNCED or kernels_cached(kernel):
            continue
        _ANNOUNCED.add(name)
        where = getattr(getattr(kernel, "_cache", None), "cache_path", None)
        compile_log.info("compiling the kernel %s%s, first run only: about %d s of CPU (later runs load it from numba's "
                         "cache%s in under a second; `vbikit compile` compiles every kernel in advance)", name,
                         f" in {who}" if who else "", compile_seconds(kernel), f" in {where}" if where else "")
