"""One BLAS thread while a block of small linear algebra runs (``single_thread_blas``).

numpy and scipy ship OpenBLAS, which splits a matrix product over every core from a few hundred
thousand flops up.  A drive-by pass multiplies histories of a few thousand samples by matrices of
a few dozen rows: on 2 shared cores (or with one worker process per core) those threads only
contend — a (2302 × 11) · (11 × 30) product measured 16 ms with the default threads and 0.05 ms
with one (2026-12-04, the 2-core CI machine under load).  ``threadpoolctl`` (the scikit-learn
project's library for exactly this) limits every BLAS the process has loaded to one thread and
restores the previous counts on exit.
"""
from __future__ import annotations

import contextlib
from typing import Iterator


@contextlib.contextmanager
def single_thread_blas() -> Iterator[None]:
    """Run the block with one BLAS thread, the previous counts restored after (module docstring)."""
    import numpy  # noqa: F401 - loads numpy's BLAS before the limit is set
    import scipy.linalg  # noqa: F401 - and scipy's
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        yield
