"""One BLAS thread while a block of small linear algebra runs (``single_thread_blas``).

numpy and scipy ship OpenBLAS, which splits a matrix product over every core from a few hundred
thousand flops up.  A drive-by pass multiplies histories of a few thousand samples by matrices of
a few dozen rows: on 2 shared cores (or with one worker process per core) those threads only
contend — a (2302 × 11) · (11 × 30) product measured 16 ms with the default threads and 0.05 ms
with one (2026-12-04, the 2-core CI machine under load).  The library's own thread-count setters
(``openblas_set_num_threads`` and the prefixed/suffixed names of the scipy-openblas builds, as
``threadpoolctl`` finds them) are called through ``ctypes`` on the OpenBLAS libraries the process has
loaded; the previous counts are restored on exit.  Where none is found (another BLAS, another
platform) the block runs unchanged.
"""
from __future__ import annotations

import contextlib
import ctypes
import logging
from typing import Iterator

log = logging.getLogger(__name__)

#: (getter, setter) symbol pairs of OpenBLAS builds
_SYMBOLS = (("openblas_get_num_threads", "openblas_set_num_threads"),
            ("openblas_get_num_threads64_", "openblas_set_num_threads64_"),
            ("scipy_openblas_get_num_threads64_", "scipy_openblas_set_num_threads64_"),
            ("scipy_openblas_get_num_threads", "scipy_openblas_set_num_threads"))

_CONTROLS: list | None = None


def _controls() -> list:
    """(get, set) functions of every OpenBLAS the process has loaded (found once)."""
    global _CONTROLS
    if _CONTROLS is None:
        _CONTROLS = []
        try:
            with open("/proc/self/maps") as f:
                paths = sorted({line.split()[-1] for line in f if "openblas" in line.lower() and ".so" in line})
        except OSError:
            paths = []
        for path in paths:
            try:
                lib = ctypes.CDLL(path)
            except OSError:
                continue
            for get, set_ in _SYMBOLS:
                if hasattr(lib, get) and hasattr(lib, set_):
                    getter, setter = getattr(lib, get), getattr(lib, set_)
                    getter.restype, setter.restype, setter.argtypes = ctypes.c_int, None, [ctypes.c_int]
                    _CONTROLS.append((getter, setter))
                    break
        log.debug("OpenBLAS thread controls found: %d", len(_CONTROLS))
    return _CONTROLS


@contextlib.contextmanager
def single_thread_blas() -> Iterator[None]:
    """Run the block with one OpenBLAS thread, the previous counts restored after (module docstring)."""
    import numpy  # noqa: F401 - loads numpy's OpenBLAS before the search
    import scipy.linalg  # noqa: F401 - and scipy's

    controls = _controls()
    before = [get() for get, _ in controls]
    for _, set_ in controls:
        set_(1)
    try:
        yield
    finally:
        for (_, set_), n in zip(controls, before):
            set_(n)
