"""Measured road profiles from CSV files: two columns, x [m from the bridge entry], elevation [m]."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import csv_rows, read_text
from vbikit.errors import VbikitError
from vbikit.road.profile import RoadOrigin, RoadProfile


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class RoadFileError(VbikitError):
    """A road profile file that cannot be used; the message names the file and line."""


def read_profile_csv(path: str | Path) -> RoadProfile:
    """Read a measured profile: optional header row (first cell not a number), then ``x, elevation`` rows (SI: m, m).

    Stations must be finite and strictly increasing; comments start with ``#``.  Any bad
    row raises [`RoadFileError`][vbikit.road.RoadFileError] naming the line.
    """
    path = Path(path)
    text = read_text(path, RoadFileError, "road profile (CSV: x, elevation)")
    xs: list[float] = []
    zs: list[float] = []
    header_seen = False
    for lineno, cells in csv_rows(text, RoadFileError, str(path)):
        if not any(cells):
            continue
        if len(cells) < 2:
            raise RoadFileError(f"{path}:{lineno}: expected 2 columns (x, elevation), got {len(cells)}")
        first_row = not header_seen
        header_seen = True
        if first_row and not _is_number(cells[0]):
            continue  # header row: only a first row whose first cell is not a number
        try:
            x, z = float(cells[0]), float(cells[1])
        except ValueError:
            raise RoadFileError(f"{path}:{lineno}: not a number (x and elevation [m] expected)") from None
        if not (np.isfinite(x) and np.isfinite(z)):
            raise RoadFileError(f"{path}:{lineno}: non-finite value")
        if xs and x <= xs[-1]:
            raise RoadFileError(f"{path}:{lineno}: x = {x} m is not greater than the previous x = {xs[-1]} m")
        xs.append(x)
        zs.append(z)
    if len(xs) < 2:
        raise RoadFileError(f"{path}: needs at least 2 data rows, found {len(xs)}")
    return RoadProfile(np.array(xs), np.array(zs), f"measured {path.name}", origin=RoadOrigin("measured", file=path.name))
