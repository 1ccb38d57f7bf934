"""Vehicle records (weigh-in-motion style): one vehicle a row, read from and written to CSV.

Format (docs/traffic.md).  A header row names the columns, each with its unit in brackets;
lines starting with ``#`` and blank lines are skipped; columns may come in any order:

=========================  ========================================================  ==========
column                     meaning                                                   units
=========================  ========================================================  ==========
``time``                   when the front axle passes the vehicle's entry support     [s]
``lane`` or                lane number (1, 2, …; lane centres given to the reader)   —
``lateral_offset``         vehicle centreline from the deck centreline (y, left +)   [m]
``direction``              ``+x`` or ``-x``                                          —
``speed``                  speed at entry                                            [km/h] or [m/s]
``axle_loads``             static axle loads, front to rear, space-separated          [kN] or [N]
``axle_spacings``          spacings, front to rear, space-separated (n_axles − 1)     [m]
``id`` (optional)          the record's name                                         —
``model`` (optional)       a vehicle preset instead of ``axles`` (then leave the      —
                           axle columns empty)
``gross_weight`` (opt.)    checked against the sum of the axle loads (1 %)            [kN] or [N]
=========================  ========================================================  ==========

Every problem is reported with its line number (``records.csv:12: speed [km/h]: …``).
"""
from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional, Sequence

from vbikit.errors import VbikitError

#: the columns, their allowed units and the factor to SI
UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0},
    "lane": {"": 1.0},
    "lateral_offset": {"m": 1.0},
    "direction": {"": 1.0},
    "speed": {"km/h": 1 / 3.6, "m/s": 1.0},
    "axle_loads": {"kN": 1e3, "N": 1.0},
    "axle_spacings": {"m": 1.0},
    "gross_weight": {"kN": 1e3, "N": 1.0},
    "id": {"": 1.0},
    "model": {"": 1.0},
}
REQUIRED = ("time", "direction", "speed")
DIRECTIONS = ("+x", "-x")


class RecordsError(VbikitError):
    """An invalid records file; the message names the line and the column."""


@dataclass(frozen=True)
class VehicleRecord:
    """One vehicle of a stream (SI units).

    Parameters
    ----------
    time : float
        When its front axle passes its entry support [s] (x = 0 driving +x, x = span driving −x).
    direction : str
        "+x" / "−x".
    speed : float
        Speed [m/s].
    axle_loads, axle_spacings : tuple of float
        Axle loads [N] and axle spacings [m] (``model = "axles"``).
    lane : int, optional
        Lane (1-based).
    lateral_offset : float, optional
        Lateral offset [m]; None: from the lane.
    id : str
        The record's identifier.
    model : str
        "axles", or another vehicle preset with no axle data.
    line : int
        Line of the records file (for error messages; 0 if none).
    extra : dict
        Further information on the vehicle (a synthetic stream's truck class, ``{"class": name}``).
    """

    time: float
    direction: str
    speed: float
    axle_loads: tuple[float, ...] = ()
    axle_spacings: tuple[float, ...] = ()
    lane: Optional[int] = None
    lateral_offset: Optional[float] = None
    id: str = ""
    model: str = "axles"
    line: int = field(default=0, compare=False)
    extra: dict = field(default_factory=dict, compare=False)

    @property
    def length(self) -> float:
        """Front-to-rear axle distance [m] (0 for presets: their length comes from the model)."""
        return float(sum(self.axle_spacings))

    @property
    def gross_weight(self) -> float:
        return float(sum(self.axle_loads))


_HEADER = re.compile(r"^\s*([A-Za-z_]+)\s*(?:\[([^\]]*)\])?\s*$")


def _numbers(text: str) -> list[float]:
    return [float(x) for x in text.replace(";", " ").split()]


def parse_records(text: str, source: str = "records") -> list[VehicleRecord]:
    """Parse a records CSV text (see the module docstring); errors name ``source:line``."""
    lines = text.splitlines()
    rows = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if not rows:
        raise RecordsError(f"{source}: no header row (columns: {', '.join(UNITS)})")
    head_no, head = rows[0]
    names = next(csv.reader([head]))
    columns: list[tuple[str, float, str]] = []
    for name in names:
        m = _HEADER.match(name)
        if not m or m.group(1) not in UNITS:
            raise RecordsError(f"{source}:{head_no}: unknown column {name.strip()!r}; allowed: "
                               + ", ".join(f"{k} [{'|'.join(u)}]" if any(u) else k for k, u in UNITS.items()))
        key, unit = m.group(1), (m.group(2) or "").strip()
        if unit not in UNITS[key]:
            allowed = " or ".join(f"[{u}]" for u in UNITS[key]) if any(UNITS[key]) else "no unit"
            raise RecordsError(f"{source}:{head_no}: column {key!r} takes {allowed}, got [{unit}]")
        columns.append((key, UNITS[key][unit], name.strip()))
    keys = [c[0] for c in columns]
    if len(set(keys)) != len(keys):
        raise RecordsError(f"{source}:{head_no}: a column appears twice")
    missing = [k for k in REQUIRED if k not in keys]
    if "lane" not in keys and "lateral_offset" not in keys:
        missing.append("lane or lateral_offset")
    if missing:
        raise RecordsError(f"{source}:{head_no}: missing column(s) {', '.join(missing)}")
    out = []
    for no, ln in rows[1:]:
        cells = next(csv.reader([ln]))
        if len(cells) != len(columns):
            raise RecordsError(f"{source}:{no}: {len(cells)} cells, the header has {len(columns)}")
        out.append(_record(dict(zip(keys, cells)), {c[0]: c for c in columns}, source, no))
    return out


def _record(cells: dict[str, str], columns: dict, source: str, no: int) -> VehicleRecord:
    def fail(key: str, msg: str) -> RecordsError:
        return RecordsError(f"{source}:{no}: {columns[key][2]}: {msg}")

    def number(key: str, lo: float = -math.inf, strict: bool = False) -> float:
        try:
            v = float(cells[key]) * columns[key][1]
        except ValueError:
            raise fail(key, f"not a number: {cells[key]!r}") from None
        if not math.isfinite(v) or (v <= lo if strict else v < lo):
            raise fail(key, f"must be {'>' if strict else '>='} {lo:g}, got {cells[key].strip()}")
        return v

    time = number("time", 0.0)
    direction = cells["direction"].strip()
    if direction not in DIRECTIONS:
        raise fail("direction", f"must be +x or -x, got {direction!r}")
    speed = number("speed", 0.0, strict=True)
    if speed > 70:
        raise fail("speed", f"{speed * 3.6:.0f} km/h is beyond the allowed 0 … 252 km/h")
    lane = lateral = None
    if "lane" in cells and cells["lane"].strip():
        try:
            lane = int(cells["lane"])
        except ValueError:
            raise fail("lane", f"must be a lane number 1, 2, …, got {cells['lane']!r}") from None
        if lane < 1:
            raise fail("lane", f"must be >= 1, got {lane}")
    if "lateral_offset" in cells and cells["lateral_offset"].strip():
        lateral = number("lateral_offset")
    if lane is None and lateral is None:
        raise RecordsError(f"{source}:{no}: give lane or lateral_offset")
    model = cells.get("model", "").strip() or "axles"
    loads: list[float] = []
    spacings: list[float] = []
    if model == "axles":
        for key in ("axle_loads", "axle_spacings"):
            if key not in cells:
                raise RecordsError(f"{source}:{no}: model axles needs the column {key}")
        try:
            loads = [v * columns["axle_loads"][1] for v in _numbers(cells["axle_loads"])]
        except ValueError:
            raise fail("axle_loads", f"not a list of numbers: {cells['axle_loads']!r}") from None
        try:
            spacings = [v * columns["axle_spacings"][1] for v in _numbers(cells["axle_spacings"])]
        except ValueError:
            raise fail("axle_spacings", f"not a list of numbers: {cells['axle_spacings']!r}") from None
        if not loads or not all(math.isfinite(v) and v > 0 for v in loads):
            raise fail("axle_loads", f"needs one or more loads > 0, got {cells['axle_loads']!r}")
        if len(spacings) != len(loads) - 1:
            raise fail("axle_spacings", f"needs {len(loads) - 1} spacing(s) for {len(loads)} axles, got {len(spacings)}")
        if not all(math.isfinite(v) and 0 < v <= 30 for v in spacings):
            raise fail("axle_spacings", f"spacings must be in (0, 30] m, got {cells['axle_spacings']!r}")
        if "gross_weight" in cells and cells["gross_weight"].strip():
            gw = number("gross_weight", 0.0, strict=True)
            if abs(gw - sum(loads)) > 0.01 * gw:
                raise fail("gross_weight", f"{gw:.0f} N differs from the sum of the axle loads {sum(loads):.0f} N by > 1 %")
    else:
        from vbikit.vehicle.presets import VEHICLE_PRESETS

        if model not in VEHICLE_PRESETS or VEHICLE_PRESETS[model].required:
            allowed = [k for k, p in VEHICLE_PRESETS.items() if not p.required]
            raise fail("model", f"unknown vehicle preset {model!r}; allowed: axles, {', '.join(allowed)}")
        if any(cells.get(k, "").strip() for k in ("axle_loads", "axle_spacings")):
            raise RecordsError(f"{source}:{no}: a preset vehicle ({model}) takes no axle_loads / axle_spacings")
    return VehicleRecord(time, direction, speed, tuple(loads), tuple(spacings), lane, lateral,
                         cells.get("id", "").strip(), model, no)


def read_records(path: str | Path) -> list[VehicleRecord]:
    """Read a records CSV file (errors name ``file:line``)."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as err:
        raise RecordsError(f"cannot read records file {path}: {err.strerror}") from None
    return parse_records(text, path.name)


def format_records(records: Sequence[VehicleRecord]) -> str:
    """CSV text of ``records`` (loads in kN, speed in km/h) that [`parse_records`][vbikit.traffic.parse_records] reads back."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["id", "time [s]", "lane", "lateral_offset [m]", "direction", "speed [km/h]", "model",
                "axle_loads [kN]", "axle_spacings [m]"])
    for r in records:
        w.writerow([r.id, f"{r.time:.3f}", "" if r.lane is None else r.lane,
                    "" if r.lateral_offset is None else f"{r.lateral_offset:g}", r.direction, f"{r.speed * 3.6:.2f}",
                    r.model, " ".join(f"{v / 1e3:.2f}" for v in r.axle_loads),
                    " ".join(f"{v:.3f}" for v in r.axle_spacings)])
    return buf.getvalue()


def write_records(records: Sequence[VehicleRecord], path: str | Path) -> None:
    Path(path).write_text(format_records(records))
