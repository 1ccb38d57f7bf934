"""The first-run notice: numba compiles the kernels once per machine, and says so beforehand.

``announce_compile`` logs (logger ``vbikit.solve.compile``, which the CLI shows) that a compiled
kernel is about to be compiled when it is neither compiled in this process nor in numba's on-disk
cache, with the expected CPU time ``COMPILE_SECONDS``.  The solver (``simulate``, the many-lane
runner in ``integrators``), studies and the railway sweeps call it before their first kernel call.
"""
from __future__ import annotations

import logging
import os

#: says when numba compiles the kernels (the first run on a machine, ≈ 5 s of CPU; benchmarks/bench_compile.py)
#: and where its cache goes; the CLI shows it
compile_log = logging.getLogger("vbikit.solve.compile")


#: CPU seconds numba takes to compile the default path (benchmarks/bench_compile.py: 4.8–4.9 s for the
#: demo on a quiet 2-core machine, 2026-12-04; rounded up for a busier or slower one)
COMPILE_SECONDS = 7


def kernels_cached(kernel) -> bool:
    """Whether ``kernel`` (a numba dispatcher) is compiled in this process or in numba's on-disk cache
    (its index file exists); True for a plain function (NUMBA_DISABLE_JIT=1)."""
    overloads = getattr(kernel, "overloads", None)  # not ``signatures``: listing them costs ≈ 16 µs a call
    if overloads is None or overloads:
        return True
    index = getattr(getattr(getattr(kernel, "_cache", None), "_cache_file", None), "_index_path", None)
    return index is not None and os.path.exists(index)


#: whether this process has announced the compilation (or its parent did for it: ``announced_elsewhere``);
#: the notice is given once a process, however many callers (a study, then its first crossing) ask
_ANNOUNCED = [False]


def announced_elsewhere() -> None:
    """Say no more in this process: a study's worker processes, whose parent announced the
    compilation for all of them (``vbikit.study.run``); each worker said it again before."""
    _ANNOUNCED[0] = True


def announce_compile(kernel, who: str = "") -> None:
    """Log (``vbikit.solve.compile``, shown by the CLI) that the kernels are about to be compiled when
    ``kernel`` is neither compiled in this process nor in numba's on-disk cache, once a process;
    ``who`` says where (e.g. "each of the 2 worker processes, on its first batch")."""
    if _ANNOUNCED[0] or kernels_cached(kernel):
        return
    _ANNOUNCED[0] = True
    where = getattr(getattr(kernel, "_cache", None), "cache_path", None)
    compile_log.info("compiling the kernels%s, first run only: about %d s of CPU (later runs load them from numba's "
                     "cache%s in under a second; `vbikit compile` does it in advance)", f" in {who}" if who else "",
                     COMPILE_SECONDS, f" in {where}" if where else "")
