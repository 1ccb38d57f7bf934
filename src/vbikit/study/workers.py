"""The worker processes of studies: one local pool kept between the studies of a session, whose
workers end with the process that started them; and the connection to a Dask cluster
(``dask_client``) for runs given ``--scheduler``.

The pool is kept so that consecutive studies (e.g. the paper's six) pay the start-up (imports,
compiled-kernel cache, bridge modes, road profiles of the same seeds) once; it is ended at exit or
by ``shutdown_workers``.  A worker ignores Ctrl-C (the coordinating process handles it) and ends
when its parent ends, however it ends (SIGKILL included, when no clean-up runs): on Linux the
kernel sends it SIGKILL (``prctl(PR_SET_PDEATHSIG)``), and on every system a watchdog thread ends
it within ``WATCH_INTERVAL`` once its parent process is gone.

A worker runs its BLAS on one thread (``threadpoolctl``): the pool already has one process per
core, and the products of a crossing are small (51 × 51 mode tables, a few thousand steps × a few
dozen modes), so BLAS threads only wait for a core and spin — on the 2-core machine they doubled
the workers' CPU time per traffic event (41.6 against 19.5 ms on the 1,000-truck stream of
``benchmarks/bench_traffic.py``, 2026-12-04; benchmarks/README.md).
"""
from __future__ import annotations

import atexit
import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from typing import Any, Optional

#: how often a worker checks that its parent process is alive [s]
WATCH_INTERVAL = 0.5

_PR_SET_PDEATHSIG = 1  # linux/prctl.h


def _one_blas_thread() -> None:
    """Limit every BLAS this process has loaded (numpy's, scipy's) to one thread, for good (module docstring)."""
    import numpy  # noqa: F401 - loads numpy's BLAS before the limit is set
    import scipy.linalg  # noqa: F401 - and scipy's
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


def _die_with_parent(parent: int, thread_bound: bool) -> None:
    """Worker initializer: one BLAS thread (``_one_blas_thread``), ignore Ctrl-C, no compile notice
    (the parent gave it for every worker: ``announced_elsewhere``) and end when the process ``parent`` ends.

    ``thread_bound``: the kernel's parent-death signal may be used (it fires when the *thread*
    that started the worker ends, so only when that thread is the parent's main thread)."""
    from vbikit.solve.compile_notice import announced_elsewhere

    _one_blas_thread()
    announced_elsewhere()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if thread_bound and sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):  # pragma: no cover - a libc without prctl
            pass
    direct = os.getppid() == parent  # False: started by a fork server (or the parent already ended)

    def alive() -> bool:
        if direct:
            return os.getppid() == parent
        try:
            os.kill(parent, 0)
        except ProcessLookupError:
            return False
        except PermissionError:  # pragma: no cover - the pid belongs to another user's process now
            return False
        return True

    if not alive():  # the parent ended before the watch was set up
        os._exit(1)

    def watch() -> None:
        while alive():
            time.sleep(WATCH_INTERVAL)
        os._exit(1)

    threading.Thread(target=watch, name="vbikit-parent-watch", daemon=True).start()


_POOL: Optional[ProcessPoolExecutor] = None
_POOL_WORKERS = 0


def local_pool(workers: int) -> ProcessPoolExecutor:
    """The session's pool of ``workers`` local processes (a new one if the count changed or the
    pool broke)."""
    global _POOL, _POOL_WORKERS
    if _POOL is None or _POOL_WORKERS != workers or getattr(_POOL, "_broken", False):
        shutdown_workers()
        main = threading.current_thread() is threading.main_thread()
        _POOL = ProcessPoolExecutor(max_workers=workers, initializer=_die_with_parent, initargs=(os.getpid(), main))
        _POOL_WORKERS = workers
    return _POOL


def shutdown_workers(kill: bool = False) -> None:
    """End the local worker processes kept between studies (``kill``: at once, dropping running work)."""
    global _POOL
    pool, _POOL = _POOL, None
    if pool is None:
        return
    if kill:
        processes = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for proc in processes:  # the running batches are lost anyway; do not wait for them
            proc.terminate()
    else:
        pool.shutdown()


atexit.register(shutdown_workers)


#: the Dask address schemes whose location is ``host:port``
_HOST_PORT_SCHEMES = ("tcp", "tls", "ucx", "ws", "wss")


def check_scheduler(scheduler: str, error: type[Exception]) -> str:
    """``scheduler`` if it has the form of a Dask scheduler address (``tcp://host:port``, ``host:port``,
    ``inproc://…``), else ``error`` naming ``--scheduler`` and the form allowed; nothing is connected
    (the one check of the address, of ``dask_client`` and of every command's ``--scheduler`` before
    it computes).  ``error`` too when dask.distributed is not installed."""
    try:
        from distributed.comm.addressing import parse_address, parse_host_port
    except ImportError:  # pragma: no cover - depends on the install
        raise error("--scheduler needs dask.distributed: pip install 'vbikit[dask]'") from None
    allowed = "give the scheduler's address as tcp://host:port (e.g. tcp://10.0.0.5:8786)"
    try:
        scheme, location = parse_address(str(scheduler))
        port = parse_host_port(location)[1] if scheme in _HOST_PORT_SCHEMES else 0
    except (ValueError, TypeError) as err:
        raise error(f"--scheduler {scheduler!r}: not a scheduler address ({err}); {allowed}") from None
    if not 0 <= int(port) <= 65535:
        raise error(f"--scheduler {scheduler!r}: port {port} is not in [0, 65535]; {allowed}")
    return scheduler


#: how long [s] a run tries to reach its Dask scheduler before it gives up (every command's --scheduler)
SCHEDULER_CONNECT_TIMEOUT = 10.0


def dask_client(scheduler: str, error: type[Exception], connect_timeout: float = SCHEDULER_CONNECT_TIMEOUT) -> Any:
    """A ``dask.distributed.Client`` of the scheduler at ``scheduler``; ``error`` (the caller's
    error class, naming ``--scheduler``) when dask.distributed is not installed, the address is
    malformed (``check_scheduler``) or the scheduler cannot be reached within ``connect_timeout``
    [s].  The caller closes it."""
    check_scheduler(scheduler, error)
    from dask.distributed import Client

    try:
        return Client(scheduler, timeout=f"{connect_timeout}s")
    except OSError as err:
        raise error(f"--scheduler {scheduler}: cannot connect ({err})") from None
