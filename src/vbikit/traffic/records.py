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

Every problem is reported with its line number and column (``records.csv:12: column 4 (speed [km/h]): …``),
never with the text found there.  Limits: ``MAX_RECORDS`` records a file, ``MAX_LINE`` characters a
line, ``MAX_AXLES`` axles a vehicle, times up to ``MAX_TIME`` (ten years); axle loads above ``AXLE_LOAD_MAX``
are refused, above ``AXLE_LOAD_WARNING`` warned of, as are vehicles that overlap the one ahead of
them in their lane and direction (entering before its rear axle has: ``_overlaps``).
"""
from __future__ import annotations

import csv
import io
import logging
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional, Sequence

from vbikit._files import csv_rows, read_text, write_text
from vbikit._limits import MAX_LATERAL_OFFSET, MIN_SPEED
from vbikit.errors import VbikitError

log = logging.getLogger(__name__)

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

#: the most vehicle records read from one file (``read_records(max_records=…)``, ``vbikit traffic --max-vehicles``)
MAX_RECORDS = 100_000
#: the longest line of a records file [characters]
MAX_LINE = 10_000
#: the most axles of one record
MAX_AXLES = 30
#: an axle load above this is warned of as far beyond legal limits [N] (30 t; legal single-axle
#: limits are about 10–13 t)
AXLE_LOAD_WARNING = 30e3 * 9.80665
#: an axle load above this is refused as impossible for a road vehicle [N] (1,000 t)
AXLE_LOAD_MAX = 1e6 * 9.80665
#: a speed above this is warned of as implausible for a road vehicle [m/s] (200 km/h)
SPEED_WARNING = 200 / 3.6
#: the largest speed of a record [m/s] (252 km/h; the smallest is a scenario's, ``MIN_SPEED``: 0.0036 km/h)
MAX_RECORD_SPEED = 70.0
#: the speeds a record may have, in words: from ``MIN_SPEED`` and ``MAX_RECORD_SPEED``, the bounds checked
SPEED_RANGE_TEXT = f"{MIN_SPEED * 3.6:g} … {MAX_RECORD_SPEED * 3.6:g} km/h ({MIN_SPEED:g} … {MAX_RECORD_SPEED:g} m/s)"


def _past(value: float, bound: str, side: int) -> str:
    """``value`` printed with the fewest significant digits (four at least) that put it on its ``side`` of
    the printed ``bound`` (+1 above, −1 below): 252.01 km/h is "252.01", not "252", beside "the largest
    speed 252 km/h" (a refusal an engineer would read as wrong)."""
    for digits in range(4, 18):
        text = f"{value:.{digits}g}"
        if (float(text) - float(bound)) * side > 0:
            return text
    return repr(value)


#: the latest time of a record [s]: ten years (365.25-day years) from the stream's start
MAX_TIME = 10 * 365.25 * 86400.0


def parse_records(text: str, source: str = "records", max_records: int = MAX_RECORDS) -> list[VehicleRecord]:
    """Parse a records CSV text (see the module docstring); errors name ``source:line`` and the
    column, never the text found there.  More than ``max_records`` records are refused before any
    is parsed; implausible values (axle loads above ``AXLE_LOAD_WARNING``, speeds above
    ``SPEED_WARNING``) are logged as warnings."""
    def too_many(rows: int) -> str:  # the header is one of the rows
        return (f"{source}: {rows - 1:,} vehicle records, more than the {max_records:,} allowed in one stream; split "
                "the file, or raise the limit (vbikit traffic --max-vehicles, read_records(..., max_records=...))")

    rows = csv_rows(text, RecordsError, source, MAX_LINE, "records", max_records + 1, too_many)
    if not rows:
        raise RecordsError(f"{source}: no header row (columns: {', '.join(UNITS)})")
    head_no, head = rows[0]
    columns = _header(head, f"{source}:{head_no}")
    keys = list(columns)
    out = []
    implausible: dict[str, list[int]] = {}
    for no, cells in rows[1:]:
        if len(cells) != len(columns):
            raise RecordsError(f"{source}:{no}: {len(cells)} cells, the header has {len(columns)}")
        record = _record(dict(zip(keys, cells)), columns, source, no)
        if record.axle_loads and max(record.axle_loads) > AXLE_LOAD_WARNING:
            implausible.setdefault(f"an axle load above {AXLE_LOAD_WARNING / 9.80665e3:.0f} t "
                                   f"({AXLE_LOAD_WARNING / 1e3:.0f} kN), far beyond legal axle limits", []).append(no)
        if record.speed > SPEED_WARNING:
            implausible.setdefault(f"a speed above {SPEED_WARNING * 3.6:.0f} km/h", []).append(no)
        out.append(record)
    overlaps = _overlaps(out)
    if overlaps:
        implausible[f"its front axle reaching the entry before the rear axle of the vehicle ahead in its lane and "
                    f"direction ({len(overlaps)} overlapping pair(s): vehicles closer than their own length)"] = overlaps
    for what, lines in implausible.items():
        shown = ", ".join(map(str, lines[:5])) + (", …" if len(lines) > 5 else "")
        log.warning("%s: %d record(s) with %s (line %s); check the values and their units", source, len(lines), what,
                    shown)
    return out


#: the columns of the header that every error of a header shows as an example (docs/traffic.md)
EXAMPLE_COLUMNS = ("id", "time", "lane", "direction", "speed", "axle_loads", "axle_spacings")


def _spelled(key: str) -> str:
    """The ways a header may write column ``key``: ``speed [km/h]`` or ``speed [m/s]``; ``lane``."""
    return " or ".join(f"`{key} [{u}]`" if u else f"`{key}`" for u in UNITS[key])


def _header(head: list[str], where: str) -> dict[str, tuple[float, str, int]]:
    """The columns of a header row: key -> (factor to SI, header text, column number), or one
    ``RecordsError`` (``where``: ``file:line``) naming every problem — the unknown columns by number,
    a column without its unit or with one it does not take, a repeated column, the required columns
    missing — and how the header must read; no text of the file is repeated but the column names
    the format defines."""
    columns: dict[str, tuple[float, str, int]] = {}
    unknown: list[int] = []
    problems: list[str] = []
    for j, name in enumerate(head, start=1):
        m = _HEADER.match(name)
        if not m or m.group(1) not in UNITS:
            unknown.append(j)
            continue
        key, unit = m.group(1), (m.group(2) or "").strip()
        if unit not in UNITS[key]:
            what = ("has no unit" if not unit else "takes no unit" if not any(UNITS[key]) else
                    "has a unit it does not take")
            problems.append(f"column {j} ({key}) {what}: write {_spelled(key)}")
        elif key in columns:
            problems.append(f"column {j} ({key}) appears twice (also column {columns[key][2]})")
        else:
            columns[key] = (UNITS[key][unit], f"{key} [{unit}]" if unit else key, j)
    named = {m.group(1) for m in map(_HEADER.match, head) if m}
    missing = [k for k in REQUIRED if k not in named]
    if "lane" not in named and "lateral_offset" not in named:
        missing.append("lane or lateral_offset")
    if unknown:
        problems.insert(0, f"column{'s' if len(unknown) > 1 else ''} {', '.join(map(str, unknown))} of the header "
                           f"{'are not known columns' if len(unknown) > 1 else 'is not a known column'}; allowed: "
                           + ", ".join(f"{k} [{'|'.join(u)}]" if any(u) else k for k, u in UNITS.items()))
    if missing:
        problems.append(f"missing required column(s) {', '.join(missing)} (required: {', '.join(REQUIRED[:1])}, lane "
                        f"or lateral_offset, {', '.join(REQUIRED[1:])}; id, model, gross_weight optional)")
    if problems:
        example = ",".join(f"{k} [{next(iter(UNITS[k]))}]" if any(UNITS[k]) else k for k in EXAMPLE_COLUMNS)
        raise RecordsError(f"{where}: " + "; ".join(problems) + f". A header reads, e.g.: {example}")
    return columns


def _record(cells: dict[str, str], columns: dict[str, tuple[float, str, int]], source: str, no: int) -> VehicleRecord:
    def fail(key: str, msg: str) -> RecordsError:
        return RecordsError(f"{source}:{no}: column {columns[key][2]} ({columns[key][1]}): {msg}")

    def number(key: str, lo: float = -math.inf, strict: bool = False) -> float:
        try:
            v = float(cells[key]) * columns[key][0]
        except ValueError:
            raise fail(key, "not a number") from None
        if not math.isfinite(v):
            raise fail(key, "not a finite number")
        if v <= lo if strict else v < lo:
            raise fail(key, f"must be {'>' if strict else '>='} {lo:g}, got {v / columns[key][0]:g}")
        return v

    def numbers(key: str) -> list[float]:
        items = cells[key].replace(";", " ").split()
        if len(items) > MAX_AXLES:
            raise fail(key, f"{len(items)} values; a vehicle has at most {MAX_AXLES} axles")
        try:
            values = [float(x) * columns[key][0] for x in items]
        except ValueError:
            raise fail(key, "not a list of numbers separated by spaces") from None
        if not all(math.isfinite(v) for v in values):
            raise fail(key, "not a list of finite numbers")
        return values

    time = number("time", 0.0)
    if time > MAX_TIME:
        raise fail("time", f"{time:.3g} s is beyond the {MAX_TIME:.4g} s (ten years) a records file may span")
    direction = cells["direction"].strip()
    if direction not in DIRECTIONS:
        raise fail("direction", "must be +x or -x")
    speed = number("speed")
    if speed < MIN_SPEED:  # (the scenario's smallest speed; 0 and a negative speed too, with the range: not "> 0")
        why = "a speed is positive: the direction column, +x or -x, gives the sense of travel" if speed <= 0 else \
            "such a crossing would last days"
        raise fail("speed", f"{_past(speed * 3.6, f'{MIN_SPEED * 3.6:g}', -1)} km/h is below the smallest speed "
                            f"{MIN_SPEED * 3.6:g} km/h ({why}); allowed {SPEED_RANGE_TEXT}")
    if speed > MAX_RECORD_SPEED:
        raise fail("speed", f"{_past(speed * 3.6, f'{MAX_RECORD_SPEED * 3.6:g}', 1)} km/h is above the largest speed "
                            f"{MAX_RECORD_SPEED * 3.6:g} km/h; allowed {SPEED_RANGE_TEXT}")
    lane = lateral = None
    if "lane" in cells and cells["lane"].strip():
        try:
            lane = int(cells["lane"])
        except ValueError:
            raise fail("lane", "must be a lane number 1, 2, …") from None
        if not 1 <= lane <= 1000:
            raise fail("lane", "must be a lane number 1, 2, … (at most 1000)")
    if "lateral_offset" in cells and cells["lateral_offset"].strip():
        lateral = number("lateral_offset")
        if abs(lateral) > MAX_LATERAL_OFFSET:  # (the scenario's bound of a vehicle centreline)
            raise fail("lateral_offset", f"{lateral:g} m is beyond the allowed ±{MAX_LATERAL_OFFSET:g} m")
    if lane is None and lateral is None:
        raise RecordsError(f"{source}:{no}: give lane or lateral_offset")
    model = cells.get("model", "").strip() or "axles"
    loads: list[float] = []
    spacings: list[float] = []
    if model == "axles":
        for key in ("axle_loads", "axle_spacings"):
            if key not in cells:
                raise RecordsError(f"{source}:{no}: model axles needs the column {key}")
        loads = numbers("axle_loads")
        spacings = numbers("axle_spacings")
        if not loads or not all(v > 0 for v in loads):
            bad = next((v for v in loads if not v > 0), None)
            raise fail("axle_loads", "every axle load must be > 0" + (f" (got {bad / 1e3:g} kN)" if bad is not None
                                                                     else " (none given)"))
        if max(loads) > AXLE_LOAD_MAX:
            raise fail("axle_loads", f"an axle load of {max(loads) / 9.80665e3:.3g} t is impossible for a road "
                                     f"vehicle (at most {AXLE_LOAD_MAX / 9.80665e3:.0f} t are read; check the unit)")
        if len(spacings) != len(loads) - 1:
            raise fail("axle_spacings", f"needs {len(loads) - 1} spacing(s) for {len(loads)} axles, got {len(spacings)}")
        if not all(0 < v <= 30 for v in spacings):
            raise fail("axle_spacings", "spacings must be in (0, 30] m")
        if "gross_weight" in cells and cells["gross_weight"].strip():
            gw = number("gross_weight", 0.0, strict=True)
            if abs(gw - sum(loads)) > 0.01 * gw:
                raise fail("gross_weight", f"{gw:.0f} N differs from the sum of the axle loads {sum(loads):.0f} N by > 1 %")
    else:
        from vbikit.vehicle.presets import VEHICLE_PRESETS

        if model not in VEHICLE_PRESETS or VEHICLE_PRESETS[model].required:
            allowed = [k for k, p in VEHICLE_PRESETS.items() if not p.required]
            raise fail("model", f"not a vehicle preset; allowed: axles, {', '.join(allowed)}")
        if any(cells.get(k, "").strip() for k in ("axle_loads", "axle_spacings")):
            raise RecordsError(f"{source}:{no}: a preset vehicle ({model}) takes no axle_loads / axle_spacings")
    return VehicleRecord(time, direction, speed, tuple(loads), tuple(spacings), lane, lateral,
                         cells.get("id", "").strip(), model, no)


def _overlaps(records: Sequence[VehicleRecord]) -> list[int]:
    """Line numbers of the records that enter before the vehicle ahead of them (same lane or lateral
    offset, same direction) has entered whole: t − t_ahead < L_ahead / v_ahead (impossible traffic:
    the two vehicles overlap, e.g. times written with too few digits or a record repeated)."""
    last: dict[tuple, VehicleRecord] = {}
    out = []
    for r in sorted(records, key=lambda r: r.time):
        key = (r.lane, r.lateral_offset, r.direction)
        ahead = last.get(key)
        if ahead is not None and r.time - ahead.time < sum(ahead.axle_spacings) / ahead.speed:
            out.append(r.line)
        last[key] = r
    return sorted(out)


def read_records(path: str | Path, max_records: int = MAX_RECORDS) -> list[VehicleRecord]:
    """Read a records CSV file (errors name ``file:line`` and the column).  The file is opened only if
    it is a regular file within the input size limit (``vbikit._files.read_text``: no
    FIFO, device or folder); more than ``max_records`` records are refused before parsing."""
    path = Path(path)
    text = read_text(path, RecordsError, "records file (CSV)")
    return parse_records(text, str(path), max_records)


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
    """Write ``records`` as a records CSV file (``format_records``), atomically."""
    write_text(path, format_records(records))
