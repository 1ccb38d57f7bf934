"""Finished trains of a railway sweep kept on disk, so that an interrupted ``vbikit rail`` (Ctrl-C,
kill -9, a crash) started again resumes: every train's envelopes (and refined peaks) are written
atomically to ``out_dir/rail.parts/<key>.npz`` as soon as the train is swept; a later run with the
same sweep reads them instead of sweeping again.  The key is the SHA-256 of everything the result
depends on (the file's settings, the bridge's frequencies and mode shapes at the points, the
train's axles, the speeds and the sweep setup), so a changed input never reuses an old result.
A stored file that cannot be read, or lacks a field of the envelopes (one written before the
peaks' time sampling, ``MovingLoadEnvelopes.*_sampling_*``), is swept again (never trusted)."""
from __future__ import annotations

import hashlib
import io
import logging
import zipfile
from dataclasses import fields
from pathlib import Path
from typing import Any, Optional

import numpy as np

log = logging.getLogger(__name__)

WORK = Path("rail.parts")


def train_key(spec_json: str, setup: Any, train: Any, speeds: np.ndarray, kind: str) -> str:
    """The SHA-256 naming one train's stored sweep (``kind``: "forces" or "coupled")."""
    h = hashlib.sha256()
    bridge = setup.bridge
    phi = bridge.mode_shapes(setup.points, np.full(setup.points.size, setup.y))
    for part in (spec_json, kind, train.name, repr(setup.effect_specs), repr((setup.dx, setup.free_vibration, setup.y))):
        h.update(part.encode())
    for arr in (np.asarray(bridge.frequencies_hz, float), np.asarray(phi, float), setup.points,
                np.asarray(train.axle_positions, float), np.asarray(train.axle_loads, float), np.asarray(speeds, float)):
        h.update(np.ascontiguousarray(arr).tobytes())
    return h.hexdigest()[:32]


#: the envelopes' fields that may be None (not stored then): the coupled cars' unconverged steps
OPTIONAL_FIELDS = ("unconverged_steps",)


def _arrays(obj: Any, prefix: str) -> dict[str, np.ndarray]:
    """The fields of ``obj`` as arrays under ``prefix`` (a field that is None is left out: read back as None)."""
    return {f"{prefix}{f.name}": np.asarray(getattr(obj, f.name)) for f in fields(obj) if getattr(obj, f.name) is not None}


def save(work: Path, key: str, env: Any, refined: Optional[Any]) -> None:
    """Write one train's ``MovingLoadEnvelopes`` and ``RefinedPeaks`` (or None) atomically."""
    from vbikit._files import atomic_write

    arrays = _arrays(env, "env.")
    if refined is not None:
        arrays.update(_arrays(refined, "ref."))

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays)

    atomic_write(work / f"{key}.npz", write)


def load(work: Path, key: str) -> Optional[tuple[Any, Optional[Any]]]:
    """One train's stored (envelopes, refined peaks or None), or None when not stored or unreadable."""
    from vbikit._files import read_bytes
    from vbikit.rail.refine import RefinedPeaks
    from vbikit.solve.moving_loads import MovingLoadEnvelopes

    path = work / f"{key}.npz"
    if not path.is_file():
        return None
    try:
        data = read_bytes(path, ValueError, "stored train sweep")
        with np.load(io.BytesIO(data), allow_pickle=False) as npz:
            arr = {name: npz[name] for name in npz.files}
        env = MovingLoadEnvelopes(**{f.name: (float(arr[f"env.{f.name}"]) if f.name == "dx"
                                              else arr.get(f"env.{f.name}") if f.name in OPTIONAL_FIELDS
                                              else arr[f"env.{f.name}"]) for f in fields(MovingLoadEnvelopes)})
        refined = (RefinedPeaks(**{f.name: arr[f"ref.{f.name}"] for f in fields(RefinedPeaks)})
                   if any(k.startswith("ref.") for k in arr) else None)
    except (ValueError, KeyError, OSError, EOFError, zipfile.BadZipFile) as err:  # a torn or foreign file: sweep again
        log.warning("stored train sweep %s is not used (%s); sweeping the train again", path.name, type(err).__name__)
        return None
    return env, refined
