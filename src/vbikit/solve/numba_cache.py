"""Where numba caches vbikit's compiled kernels (``cache=True``).

numba writes a cached kernel beside its source file (the package's ``__pycache__``) or, when the
package directory is read-only, in the user's cache directory (``~/.cache/numba``); when neither
is writable (and ``NUMBA_CACHE_DIR`` is not set) it refuses to define the kernels, so
``import vbikit`` would fail.  ``ensure_cache_location``, called by
``vbikit.solve.kernels`` before its first kernel, then points numba at a private per-user
directory in the system's temporary directory (logged).  This module lies beside the kernels'
package (solve/kernels/), so probing a function of this file probes the kernels' own cache
locations.
"""
from __future__ import annotations

import getpass
import logging
import os
import stat
import tempfile

import numba

log = logging.getLogger(__name__)


def _cache_probe() -> None:
    """A function of this file (beside the kernels' package), for ``ensure_cache_location``."""


def _private_dir(path: str) -> str:
    """``path`` if it is (or can be made) a directory of this user only (mode 0o700), else a fresh
    ``mkdtemp`` directory: numba's cache files are pickles, so a shared temporary directory that
    someone else created (or can write) must not be used."""
    try:
        os.mkdir(path, 0o700)
    except FileExistsError:
        pass
    except OSError:
        return tempfile.mkdtemp(prefix="vbikit-numba-cache-")
    st = os.lstat(path)
    owner_ok = not hasattr(os, "getuid") or st.st_uid == os.getuid()
    if not stat.S_ISDIR(st.st_mode) or not owner_ok or st.st_mode & 0o077:
        return tempfile.mkdtemp(prefix="vbikit-numba-cache-")
    return path


def ensure_cache_location() -> str | None:
    """Make sure numba can cache the kernels (``cache=True``): numba writes them beside this file
    (``__pycache__``) or, when the package directory is read-only, in the user's cache directory
    (``~/.cache/numba``); when neither is writable (and ``NUMBA_CACHE_DIR`` is not set) numba
    would refuse to define the kernels.  Then the cache goes to a per-user directory in the
    system's temporary directory (logged).  Before that, numba is set to compile for the portable CPU model
    (``vbikit.solve.prebuilt.portable_codegen``); after it, the kernels shipped compiled are put in the
    cache (``vbikit.solve.prebuilt.seed``, once per process).  Returns the directory chosen, or None."""
    from vbikit.solve.prebuilt import portable_codegen, seed

    portable_codegen()
    path, throwaway = _cache_directory()
    seed(throwaway)
    return path


def _cache_directory() -> tuple[str | None, bool]:
    """``ensure_cache_location``'s choice of numba's cache folder (None: numba's own), and whether it is this
    process's own (a fresh temporary folder no later process reads)."""
    from numba.core.caching import FunctionCache

    try:
        FunctionCache(_cache_probe)
        return None, False
    except RuntimeError:
        pass
    try:
        user = getpass.getuser()
    except Exception:  # no user name (some containers): one directory per process
        user = None
    path = _private_dir(os.path.join(tempfile.gettempdir(), f"vbikit-numba-cache-{user}")) if user else tempfile.mkdtemp(
        prefix="vbikit-numba-cache-")
    throwaway = user is None
    numba.config.CACHE_DIR = path
    try:
        FunctionCache(_cache_probe)
    except RuntimeError:
        numba.config.CACHE_DIR = path = tempfile.mkdtemp(prefix="vbikit-numba-cache-")
        throwaway = True
    log.warning("numba cannot write its cache beside vbikit or in the user's cache directory: compiled kernels "
                "go to %s (set NUMBA_CACHE_DIR to choose a directory)", path)
    return path, throwaway


def cache_location() -> str:
    """Where numba keeps vbikit's compiled kernels: its cache directory (``NUMBA_CACHE_DIR`` or the one
    chosen by ``ensure_cache_location``), else ``__pycache__`` in the kernels' package."""
    if numba.config.CACHE_DIR:
        return str(numba.config.CACHE_DIR)
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "kernels", "__pycache__")
