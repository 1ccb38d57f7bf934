"""On-disk cache of solved modes: ``<cache dir>/modes/<prefix>-<key>.npz`` holding ``omega`` [rad/s]
and ``modes`` (the nodal mode matrix over all DOFs).

A model keys its modes by ``cache_key`` of every parameter that changes them (with a model
version that is bumped whenever the model changes its modes).  The cache only saves time: an
unreadable file is ignored (and solved again), a file that cannot be written is skipped.
"""
from __future__ import annotations

import hashlib
import json
import logging
import os
from pathlib import Path
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

log = logging.getLogger(__name__)


def default_cache_dir() -> Path:
    """``$VBIKIT_CACHE_DIR`` if set, else ``~/.cache/vbikit``."""
    env = os.environ.get("VBIKIT_CACHE_DIR")
    return Path(env) if env else Path.home() / ".cache" / "vbikit"


def cache_key(version: str, params: dict[str, Any]) -> str:
    """First 32 hex digits of the sha256 of the JSON of ``{"version": version, **params}`` (sorted keys,
    non-JSON numbers as floats)."""
    text = json.dumps({"version": version, **params}, sort_keys=True, default=float)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def cache_path(prefix: str, key: str, cache_dir: Optional[str | Path] = None) -> Path:
    """``<cache_dir>/modes/<prefix>-<key>.npz`` (``cache_dir`` None: ``default_cache_dir``)."""
    base = Path(cache_dir) if cache_dir else default_cache_dir()
    return base / "modes" / f"{prefix}-{key}.npz"


def load_modes(path: Path) -> Optional[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """(omega, modes) from ``path``, or None when there is no file or it cannot be read (logged)."""
    if not path.is_file():
        return None
    try:
        with np.load(path) as data:
            omega, full = data["omega"], data["modes"]
    except Exception as err:  # noqa: BLE001 - a broken cache is only a lost speed-up
        log.warning("ignoring unreadable mode cache %s: %s", path, err)
        return None
    log.debug("modes read from cache %s", path)
    return omega, full


def save_modes(path: Path, omega: NDArray[np.float64], modes: NDArray[np.float64]) -> None:
    """Write (omega, modes) to ``path`` atomically (a temporary file, then a rename); a failure is logged."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
        np.savez(tmp, omega=omega, modes=modes)
        os.replace(tmp, path)
    except OSError as err:
        log.warning("could not write mode cache %s: %s", path, err)
