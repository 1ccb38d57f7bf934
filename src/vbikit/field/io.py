"""Measured field data: the response CSV and the ``FIELD.toml`` that describes a field test.

Response CSV (one file per loading case)::

    # comment lines start with '#'
    time [s], G5_disp [mm], G5_acc [m/s^2], G5_strain [microstrain]
    0.000, 0.012, 0.031, 0.4
    ...

The first non-comment row is the header: every cell is ``name [unit]``; the first column is
time.  Time must be finite, strictly increasing and uniform (relative deviation of each step
from the median step ≤ ``TIME_TOLERANCE``); every value finite (no NaN, no empty cell).
Units are converted to SI (m, m/s², strain [-], s) with ``UNITS``.  See docs/field.md for
``FIELD.toml``.  Every error is a [`FieldFileError`][vbikit.field.FieldFileError] naming the file, line and column or
the TOML key.
"""
from __future__ import annotations

import logging
import math
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from vbikit._files import check_name, csv_rows, input_file, read_text
from vbikit._limits import MAX_SPEED, MIN_SPEED, MAX_RUN_IN
from vbikit._toml import read_toml
from vbikit._validation import number
from vbikit.errors import VbikitError

#: the speeds [km/h] a field file accepts: a scenario's (``vbikit._limits``)
SPEED_RANGE_KMH = (round(MIN_SPEED * 3.6, 12), MAX_SPEED * 3.6)
_SPEED_RANGE_TEXT = f"{SPEED_RANGE_KMH[0]:g} … {SPEED_RANGE_KMH[1]:g}"

log = logging.getLogger(__name__)

#: unit → (quantity, factor to SI)
UNITS: dict[str, tuple[str, float]] = {
    "s": ("time", 1.0),
    "ms": ("time", 1e-3),
    "m": ("displacement", 1.0),
    "mm": ("displacement", 1e-3),
    "in": ("displacement", 0.0254),
    "m/s^2": ("acceleration", 1.0),
    "m/s2": ("acceleration", 1.0),
    "g": ("acceleration", 9.80665),
    "-": ("strain", 1.0),
    "strain": ("strain", 1.0),
    "microstrain": ("strain", 1e-6),
    "ue": ("strain", 1e-6),
    "µε": ("strain", 1e-6),
}
QUANTITIES = ("displacement", "acceleration", "strain")
#: allowed relative deviation of a time step from the median step
TIME_TOLERANCE = 0.01

_HEADER = re.compile(r"^\s*(?P<name>[^\[\]]+?)\s*\[(?P<unit>[^\]]*)\]\s*$")


class FieldFileError(VbikitError):
    """A field-data file (CSV or FIELD.toml) that cannot be used; the message names the place."""


@dataclass(frozen=True)
class MeasuredRecord:
    """A response CSV in SI units: ``time`` [s], ``channels[name]`` [m, m/s² or -], ``units[name]`` as written."""

    path: Path
    time: NDArray[np.float64]
    channels: dict[str, NDArray[np.float64]]
    units: dict[str, str]
    quantities: dict[str, str]

    @property
    def sampling_rate(self) -> float:
        """1 / median time step [Hz]."""
        return float(1.0 / np.median(np.diff(self.time)))


def read_response_csv(path: str | Path) -> MeasuredRecord:
    """Read a response CSV (format in the module docstring); values are returned in SI units."""
    path = Path(path)
    text = read_text(path, FieldFileError, "response file (CSV)")
    names: list[str] = []
    units: list[str] = []
    rows: list[list[float]] = []
    lines: list[int] = []
    for lineno, cells in csv_rows(text, FieldFileError, str(path)):
        if not any(cells):
            continue
        if not names:
            for col, cell in enumerate(cells, start=1):
                m = _HEADER.match(cell)
                if not m:
                    raise FieldFileError(f"{path}:{lineno}: header column {col} is not 'name [unit]' (e.g. 'G5_disp [mm]')")
                unit = m["unit"].strip()
                if unit not in UNITS:
                    raise FieldFileError(f"{path}:{lineno}: header column {col}: unknown unit; "
                                         f"allowed: {', '.join(UNITS)}")
                names.append(m["name"])
                units.append(unit)
            if UNITS[units[0]][0] != "time":
                raise FieldFileError(f"{path}:{lineno}: the first column must be time in [s] or [ms], got [{units[0]}]")
            if len(set(names)) != len(names):
                raise FieldFileError(f"{path}:{lineno}: duplicate channel names in the header")
            continue
        if len(cells) != len(names):
            raise FieldFileError(f"{path}:{lineno}: expected {len(names)} columns, got {len(cells)}")
        values = []
        for col, (cell, name) in enumerate(zip(cells, names), start=1):
            try:
                v = float(cell)
            except ValueError:
                raise FieldFileError(f"{path}:{lineno}: column {col} ({name}): not a number") from None
            if not np.isfinite(v):
                raise FieldFileError(f"{path}:{lineno}: column {col} ({name}): not finite (NaN/inf)")
            values.append(v)
        rows.append(values)
        lines.append(lineno)
    if not names:
        raise FieldFileError(f"{path}: no header row")
    if len(rows) < 4:
        raise FieldFileError(f"{path}: needs at least 4 data rows, found {len(rows)}")
    data = np.array(rows)
    t = data[:, 0] * UNITS[units[0]][1]
    dt = np.diff(t)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        raise FieldFileError(f"{path}:{lines[i]}: time {t[i]:.6g} s is not greater than the previous {t[i - 1]:.6g} s "
                             "(time must be strictly increasing)")
    step = float(np.median(dt))
    bad = np.flatnonzero(np.abs(dt - step) > TIME_TOLERANCE * step)
    if bad.size:
        i = int(bad[0]) + 1
        raise FieldFileError(f"{path}:{lines[i]}: non-uniform time step {dt[i - 1]:.6g} s (median {step:.6g} s); "
                             "resample the record to a uniform rate first")
    channels, quantities = {}, {}
    for j in range(1, len(names)):
        q, f = UNITS[units[j]]
        if q == "time":
            raise FieldFileError(f"{path}: column {names[j]!r} has a time unit [{units[j]}]; only the first column is time")
        channels[names[j]] = data[:, j] * f
        quantities[names[j]] = q
        if np.ptp(data[:, j]) == 0.0:
            raise FieldFileError(f"{path}: column {names[j]!r} is constant ({data[0, j]:g} [{units[j]}] in every row): "
                                 "no signal to compare")
    log.info("read %s: %d samples at %.4g Hz, channels %s", path.name, t.size, 1 / step, ", ".join(channels))
    return MeasuredRecord(path, t, channels, dict(zip(names[1:], units[1:])), quantities)


# ---------------------------------------------------------------------------------------- FIELD.toml
@dataclass(frozen=True)
class ChannelSpec:
    """One sensor: CSV column ``name``, ``quantity``, location (``girder`` 1-based, ``x`` [m]), ``unit`` as in the CSV."""

    name: str
    quantity: str
    girder: int
    x: float
    unit: str


@dataclass(frozen=True)
class CaseSpec:
    """One loading case (one crossing) of a field test; paths are resolved against the TOML's folder."""

    name: str
    responses: Path
    lateral_offset: float
    channels: tuple[ChannelSpec, ...]
    sampling_rate: float | None = None
    trigger_time: float | None = None
    align: str = "trigger"
    profile_left: Path | None = None
    profile_right: Path | None = None
    speed: float | None = None


@dataclass(frozen=True)
class FieldSpec:
    """A field test: bridge and truck presets, speed [m/s], signal-processing options, loading cases."""

    path: Path
    name: str
    bridge: str
    truck: str
    speed: float
    approach: float
    free_vibration: float
    n_modes: int
    damping_ratio: float
    stiffness_factor: float
    lowpass_hz: float | None
    drift: str
    quiet_tail: float
    bands: tuple[tuple[float, float], ...]
    cases: tuple[CaseSpec, ...]
    dt: float | None = None
    bridge_overrides: dict[str, Any] = field(default_factory=dict)
    #: road [m] the truck drives alone before the approach (``crossing.run_in``; 0: it starts at rest)
    run_in: float = 0.0


#: Every key of a FIELD.toml: section → key → (type, range, default, unit, meaning).  The loader
#: takes its allowed keys and defaults from here and docs/reference/field-keys.md is generated
#: from it.  Sections as in a scenario file: [bridge], [vehicle], [crossing]; then [signal] and
#: the loading cases [[case]] with their sensors [[case.channel]].
FIELD_KEYS: dict[str, dict[str, tuple[str, str, Any, str, str]]] = {
    "": {
        "name": ("text", "", None, "", "label of the test; default the file name"),
    },
    "bridge": {
        "model": ("text", "a bridge preset", ..., "", "bridge preset (`vbikit presets`)"),
        "n_modes": ("integer", "≥ 1", 10, "-", "retained modes"),
        "damping_ratio": ("number", "≥ 0", 0.02, "-", "modal damping ratio of the model, every mode"),
        "stiffness_factor": ("number", "> 0", 1.0, "-", "every stiffness × f, i.e. every ω × √f; the calibration fits it"),
        "deck": ("table", "", None, "", "overrides of a slab-on-girder preset, keys as [bridge.deck] of a scenario"),
    },
    "vehicle": {
        "model": ("text", "a vehicle preset", ..., "", "the test truck (`vbikit presets`)"),
    },
    "crossing": {
        "speed_kmh": ("number", _SPEED_RANGE_TEXT, ..., "km/h", "truck speed (a case may set its own)"),
        "approach": ("number", "≥ 0", 33.52, "m", "distance driven before the span entry (two 16.76 m spans)"),
        "free_vibration": ("number", "≥ 0", 3.0, "s", "time simulated after the last axle leaves"),
        "run_in": ("number", f"0 … {MAX_RUN_IN:g}", 0.0, "m", "road the truck drives alone before the approach, so that "
                   "it arrives settled as a real truck does (vbikit.solve.run_in; the profiles must reach that far "
                   "back); 0: it starts at rest"),
        "dt": ("number", "> 0", None, "s", "fixed time step; default automatic"),
    },
    "signal": {
        "lowpass_hz": ("number", "> 0", None, "Hz", "zero-phase low-pass of record and simulation; default none"),
        "drift": ("text", "quiet, model, none", "quiet", "", "how accelerometer offset and drift are removed"),
        "quiet_tail": ("number", "≥ 0", 1.0, "s", "time at the end of the record where the bridge is at rest"),
        "bands_hz": ("array of [low, high]", "0 ≤ low < high", [[0.0, 5.0], [5.0, 15.0], [15.0, 30.0], [30.0, 60.0]],
                     "Hz", "frequency bands of the PSD comparison"),
    },
    "case": {
        "name": ("text", "", None, "", "label of the loading case; default case1, case2, …"),
        "responses": ("text", "an existing file", ..., "", "response CSV, relative to the FIELD.toml"),
        "lateral_offset": ("number", "", ..., "m", "vehicle centreline from the deck centreline, positive left"),
        "sampling_rate": ("number", "> 0", None, "Hz", "checked against the file's time column (1 %)"),
        "trigger_time": ("number", "", None, "s", "time on the record's clock when the front axle reaches the span entry; required with align = trigger"),
        "align": ("text", "trigger, xcorr", "trigger", "", "time alignment of record and simulation"),
        "profile_left": ("text", "an existing file", None, "", "measured profile under the left wheel line (y > 0); default a smooth road"),
        "profile_right": ("text", "an existing file", None, "", "measured profile under the right wheel line (needs profile_left)"),
        "speed_kmh": ("number", _SPEED_RANGE_TEXT, None, "km/h", "speed of this case; default crossing.speed_kmh"),
        "channel": ("array of tables", "", ..., "", "the sensors [[case.channel]] used"),
    },
    "case.channel": {
        "name": ("text", "", ..., "", "the CSV column name"),
        "quantity": ("text", "displacement, acceleration, strain", ..., "", "what the sensor measures"),
        "girder": ("integer", "≥ 1", ..., "-", "girder (Girder 1 at the most negative y)"),
        "x": ("number", "≥ 0", ..., "m", "sensor station from the entry support"),
        "unit": ("text", "a unit of the quantity", ..., "", "must equal the unit in the CSV header"),
    },
}

#: flat keys of the earlier FIELD.toml layout → their section key (still read, with a warning)
DEPRECATED_KEYS = {"bridge": "bridge.model", "truck": "vehicle.model", "n_modes": "bridge.n_modes",
                   "damping_ratio": "bridge.damping_ratio", "stiffness_factor": "bridge.stiffness_factor",
                   "bridge_parameters": "bridge.deck", "speed_kmh": "crossing.speed_kmh",
                   "approach": "crossing.approach", "free_vibration": "crossing.free_vibration", "dt": "crossing.dt"}


def _upgrade(doc: dict[str, Any], path: Path) -> dict[str, Any]:
    """A FIELD.toml in the earlier flat layout (``bridge = "…"``, ``truck = "…"``, ``speed_kmh`` …
    at the top) rewritten into sections, with a FutureWarning naming the new keys."""
    old = [k for k in DEPRECATED_KEYS if k in doc and not (k == "bridge" and isinstance(doc[k], dict))]
    if not old:
        return doc
    new = {k: v for k, v in doc.items() if k not in old}
    for key in old:
        section, name = DEPRECATED_KEYS[key].split(".")
        table = new.setdefault(section, {})
        if not isinstance(table, dict) or name in table:
            raise FieldFileError(f"{path}: {key} and {DEPRECATED_KEYS[key]} both given; keep {DEPRECATED_KEYS[key]}")
        table[name] = doc[key]
    moved = ", ".join(f"{k} → {DEPRECATED_KEYS[k]}" for k in old)
    warnings.warn(f"{path}: the flat FIELD.toml keys are deprecated; use sections as in a scenario file ({moved})",
                  FutureWarning, stacklevel=3)
    return new


def _keys(table: dict[str, Any], section: str, where: str, path: Path) -> None:
    allowed = set(FIELD_KEYS[section]) | ({"bridge", "vehicle", "crossing", "signal", "case"} if section == "" else set())
    extra = sorted(set(table) - allowed)
    if extra:
        # (the wording of every input file's: "key: unknown key; allowed: …")
        raise FieldFileError(f"{path}: {where}{extra[0]}: unknown key; allowed: {', '.join(sorted(allowed))}")


def _default(section: str, key: str) -> Any:
    return FIELD_KEYS[section][key][2]


def _table(doc: dict[str, Any], key: str, path: Path, required: bool = True) -> dict[str, Any]:
    table = doc.get(key, {} if not required else None)
    if table is None:
        raise FieldFileError(f"{path}: missing section [{key}]")
    if not isinstance(table, dict):
        raise FieldFileError(f"{path}: [{key}] must be a table")
    return table


def _num(table: dict[str, Any], key: str, where: str, path: Path, default: Any = ..., positive: bool = False,
         nonneg: bool = False, bounds: tuple[float, float] | None = None, unit: str = "") -> Any:
    if key not in table:
        if default is ...:
            raise FieldFileError(f"{path}: missing key {where}{key}")
        return default
    # (the one check and wording of a number read from an input file: "key: expected a number in [lo, hi] [unit], got …")
    lo, hi = bounds if bounds is not None else (None, None)
    if positive or nonneg:  # (> 0 or >= 0 as well as within bounds, as the flags always meant)
        lo = 0.0 if lo is None else max(lo, 0.0)
    return number(table[key], f"{path}: {where}{key}", lo, hi, lo_open=positive and lo <= 0.0, unit=unit,
                  error=FieldFileError)


def _int(table: dict[str, Any], key: str, path: Path, default: int, lo: int, hi: int, where: str = "") -> int:
    return int(number(table.get(key, default), f"{path}: {where}{key}", lo, hi, integer=True, error=FieldFileError))


def _file(table: dict[str, Any], key: str, where: str, base: Path, path: Path, required: bool) -> Path | None:
    if key not in table:
        if required:
            raise FieldFileError(f"{path}: missing key {where}{key}")
        return None
    v = table[key]
    if not isinstance(v, str):
        raise FieldFileError(f"{path}: {where}{key} must be a file name, got {v!r}")
    p = (base / v).resolve()
    try:
        input_file(p, FieldFileError)  # (the one reader's words: not found, a folder, a device …)
    except FieldFileError as err:
        raise FieldFileError(f"{path}: {where}{key}: {err}") from None
    return p


def load_field_toml(path: str | Path) -> FieldSpec:
    """Read and check a ``FIELD.toml`` (format in docs/field.md); errors name the key."""
    path = Path(path)
    doc = read_toml(path, FieldFileError, "field file")
    base = path.parent
    doc = _upgrade(doc, path)
    _keys(doc, "", "", path)
    bridge_t, vehicle_t, crossing_t = _table(doc, "bridge", path), _table(doc, "vehicle", path), _table(doc, "crossing", path)
    _keys(bridge_t, "bridge", "bridge.", path)
    _keys(vehicle_t, "vehicle", "vehicle.", path)
    _keys(crossing_t, "crossing", "crossing.", path)
    for table, section in ((bridge_t, "bridge"), (vehicle_t, "vehicle")):
        if not isinstance(table.get("model"), str):
            raise FieldFileError(f"{path}: missing key {section}.model (a preset name)")
    sig = _table(doc, "signal", path, required=False)
    _keys(sig, "signal", "signal.", path)
    lowpass = _num(sig, "lowpass_hz", "signal.", path, _default("signal", "lowpass_hz"), positive=True)
    drift = sig.get("drift", _default("signal", "drift"))
    if drift not in ("quiet", "model", "none"):
        raise FieldFileError(f"{path}: signal.drift must be 'quiet', 'model' or 'none', got {drift!r}")
    bands_raw = sig.get("bands_hz", _default("signal", "bands_hz"))
    def _hz(v: Any) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
            raise ValueError
        return float(v)

    try:
        bands = tuple((_hz(a), _hz(b)) for a, b in bands_raw)
    except (TypeError, ValueError):
        raise FieldFileError(f"{path}: signal.bands_hz must be a list of [low, high] pairs of finite numbers [Hz]") from None
    if any(not 0 <= a < b for a, b in bands):
        raise FieldFileError(f"{path}: signal.bands_hz: every band needs 0 <= low < high, got {bands_raw!r}")
    speed = _num(crossing_t, "speed_kmh", "crossing.", path, bounds=SPEED_RANGE_KMH, unit="km/h") / 3.6
    cases_raw = doc.get("case")
    if not isinstance(cases_raw, list) or not cases_raw:
        raise FieldFileError(f"{path}: needs at least one [[case]] table")
    cases = []
    for i, c in enumerate(cases_raw, start=1):
        where = f"case[{i}]."
        if not isinstance(c, dict):
            raise FieldFileError(f"{path}: [[case]] {i} must be a table")
        _keys(c, "case", where, path)
        chans_raw = c.get("channel")
        if not isinstance(chans_raw, list) or not chans_raw:
            raise FieldFileError(f"{path}: {where}channel: needs at least one [[case.channel]] table")
        chans = []
        for j, ch in enumerate(chans_raw, start=1):
            w2 = f"{where}channel[{j}]."
            if not isinstance(ch, dict):
                raise FieldFileError(f"{path}: {w2.rstrip('.')}: [[case.channel]] entries must be tables (name, quantity, girder, x, unit)")
            _keys(ch, "case.channel", w2, path)
            for key in ("name", "quantity", "unit"):
                if not isinstance(ch.get(key), str):
                    raise FieldFileError(f"{path}: missing key {w2}{key} (a string)")
            if ch["quantity"] not in QUANTITIES:
                raise FieldFileError(f"{path}: {w2}quantity must be one of {QUANTITIES}, got {ch['quantity']!r}")
            if ch["unit"] not in UNITS or UNITS[ch["unit"]][0] != ch["quantity"]:
                ok = [u for u, (q, _) in UNITS.items() if q == ch["quantity"]]
                raise FieldFileError(f"{path}: {w2}unit [{ch['unit']}] is not a {ch['quantity']} unit; allowed: {', '.join(ok)}")
            g = int(number(ch.get("girder"), f"{path}: {w2}girder", 1, integer=True, error=FieldFileError))
            chans.append(ChannelSpec(ch["name"], ch["quantity"], g, _num(ch, "x", w2, path, nonneg=True), ch["unit"]))
        align = c.get("align", _default("case", "align"))
        if align not in ("trigger", "xcorr"):
            raise FieldFileError(f"{path}: {where}align must be 'trigger' or 'xcorr', got {align!r}")
        trigger = _num(c, "trigger_time", where, path, None)
        if align == "trigger" and trigger is None:
            raise FieldFileError(f"{path}: {where}trigger_time is required with align = 'trigger' (or use align = 'xcorr')")
        name = c.get("name", f"case{i}")
        if not isinstance(name, str):
            raise FieldFileError(f"{path}: {where}name must be a string, got {name!r}")
        try:
            check_name(name, f"{where}name")  # it names the case's output files
        except ValueError as err:
            raise FieldFileError(f"{path}: {err}") from None
        cs = CaseSpec(
            name=str(name),
            responses=_file(c, "responses", where, base, path, True),
            lateral_offset=_num(c, "lateral_offset", where, path),
            channels=tuple(chans),
            sampling_rate=_num(c, "sampling_rate", where, path, None, positive=True),
            trigger_time=trigger,
            align=align,
            profile_left=_file(c, "profile_left", where, base, path, False),
            profile_right=_file(c, "profile_right", where, base, path, False),
            speed=None if "speed_kmh" not in c else _num(c, "speed_kmh", where, path, bounds=SPEED_RANGE_KMH,
                                                           unit="km/h") / 3.6,
        )
        if cs.profile_right is not None and cs.profile_left is None:
            raise FieldFileError(f"{path}: {where}profile_right needs profile_left")
        cases.append(cs)
    bp = bridge_t.get("deck", {})
    if not isinstance(bp, dict):
        raise FieldFileError(f"{path}: [bridge.deck] must be a table")
    return FieldSpec(
        path=path,
        name=str(doc.get("name", path.stem)),
        bridge=bridge_t["model"],
        truck=vehicle_t["model"],
        speed=speed,
        approach=_num(crossing_t, "approach", "crossing.", path, _default("crossing", "approach"), nonneg=True),
        free_vibration=_num(crossing_t, "free_vibration", "crossing.", path, _default("crossing", "free_vibration"), nonneg=True),
        run_in=_num(crossing_t, "run_in", "crossing.", path, _default("crossing", "run_in"), bounds=(0.0, MAX_RUN_IN),
                    unit="m"),
        n_modes=_int(bridge_t, "n_modes", path, _default("bridge", "n_modes"), 1, 500, "bridge."),
        damping_ratio=_num(bridge_t, "damping_ratio", "bridge.", path, _default("bridge", "damping_ratio"), nonneg=True),
        stiffness_factor=_num(bridge_t, "stiffness_factor", "bridge.", path, _default("bridge", "stiffness_factor"), positive=True),
        lowpass_hz=lowpass,
        drift=drift,
        quiet_tail=_num(sig, "quiet_tail", "signal.", path, _default("signal", "quiet_tail"), nonneg=True),
        bands=bands,
        cases=tuple(cases),
        dt=_num(crossing_t, "dt", "crossing.", path, _default("crossing", "dt"), positive=True),
        bridge_overrides=dict(bp),
    )


def check_case_record(case: CaseSpec, record: MeasuredRecord, spec_path: Path, lowpass_hz: float | None = None) -> None:
    """Cross-check a case's channel table against its CSV: missing channels, unit mismatches, sampling
    rate; and the low-pass cut-off ``lowpass_hz`` [Hz] (``signal.lowpass_hz``) against the record: at
    least 1/T (T its duration: a filter whose period exceeds the record cannot be realised over it,
    and the Butterworth filter's start-up solve becomes singular far below) and below its Nyquist
    frequency fs/2."""
    for ch in case.channels:
        if ch.name not in record.channels:
            raise FieldFileError(f"{record.path}: channel {ch.name!r} (listed in {spec_path.name}, case {case.name!r}) "
                                 f"is missing; the file has: {', '.join(record.channels)}")
        if record.units[ch.name] != ch.unit:
            raise FieldFileError(f"{record.path}: channel {ch.name!r} is in [{record.units[ch.name]}] but "
                                 f"{spec_path.name} (case {case.name!r}) says [{ch.unit}]: unit mismatch")
    if case.sampling_rate is not None:
        fs = record.sampling_rate
        if abs(fs - case.sampling_rate) > TIME_TOLERANCE * case.sampling_rate:
            raise FieldFileError(f"{record.path}: sampled at {fs:.6g} Hz but {spec_path.name} case {case.name!r} "
                                 f"says sampling_rate = {case.sampling_rate:g} Hz")
    if lowpass_hz is not None:
        fs = record.sampling_rate
        duration = float(record.time[-1] - record.time[0])
        lowest = 1.0 / duration if duration > 0 else math.inf
        if not lowest <= lowpass_hz < fs / 2:
            raise FieldFileError(f"{spec_path}: signal.lowpass_hz = {lowpass_hz:g} Hz does not fit the record of case "
                                 f"{case.name!r} ({record.path.name}: {duration:.4g} s sampled at {fs:.4g} Hz): the cut-off must be "
                                 f"at least 1/duration = {lowest:.4g} Hz and below the Nyquist frequency {fs / 2:.4g} Hz; "
                                 "choose one in that range or leave the key out")
