"""The drive-by file (DRIVEBY.toml): an instrumented vehicle over a bridge, swept.

    name = "drive-by example"
    seed = 1                    # noise seeds derive from it and the case index
    batch_size = 4              # cases per stored batch (study runner)
    max_steps = 2e7             # budget: integration steps of the whole sweep (raise to run more)

    [bridge] / [tire] / [road] / [crossing]      # scenario tables (docs/scenario.md)
    [vehicle]                   # a vehicle preset, or "test-cart" / "two-axle-car" (vbikit.driveby.vehicles)
    model = "test-cart"

    [sampling]
    rate = 200                  # sensor rate [Hz]; filter_order, cutoff (fraction of the rate)

    [[fleet]]                   # instead of [vehicle]: several instrumented vehicles, each a [vehicle] table with a name
    name = "light-cart"         # (variability.fleet: "draw" one per pass, "all" every one on every pass)
    model = "test-cart"

    [dataset]                   # the stored dataset (vbikit.driveby.study.dataset)
    format = "netcdf"           # "zarr" also writes driveby.zarr (needs the zarr package)
    chunk_passes = 64           # passes per chunk of the per-pass records (1: a chunk per pass)
    spectra = true              # amplitude spectra of the on-bridge records (sensor_spectrum, contact_spectrum)

    [[sensors]]                 # name, body or axle, position [m], lateral [m], quantity, noise_rms / noise_snr_db
    name = "cart_acc"
    body = "body"

    [identification]
    method = "contact"          # "contact": contact-point acceleration (single-axle vehicle); "sensor": the sensor's own;
                                # "residual": contact minus that of an identical vehicle following at gap [m]
    gap = 4.0                   # method "residual": distance of the follower behind the vehicle [m]
    exclude_vehicle = true      # skip ± 2 / T around the vehicle's own frequencies
    sensor = "cart_acc"         # default the first sensor
    band = [1.0, 20.0]          # search band [Hz]; default [4 v / L, 20 Hz]
    spectrum = "periodogram"    # or "welch"; window = "hann"

    [sweep]                     # lists; every combination is one case
    speed = [5.0, 8.0, 10.0]            # [m/s]
    road_class = ["none", "A"]
    road_seed = [1, 2]
    damage_position = [10.0]            # start of the damaged region [m] (bridge model "continuous-beam")
    damage_length = 2.5                 # one number [m]
    damage_severity = [0.0, 0.3]        # 0 = healthy
    noise_rms = [0.0, 0.01]             # replaces every sensor's noise_rms [units of the quantity]

Every case is validated as a scenario before anything runs (``vbikit.driveby.study.check_cases``); errors name the key
(``sweep.speed``, ``sensors.cart_acc.body``, ``bridge.EI``).
"""
from __future__ import annotations

import copy
import itertools
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional

from vbikit._validation import MAX_STEPS_LIMIT, number, short_quotes
from vbikit.driveby.sensors import MAX_NOISE_RMS, Sampling, Sensor
from vbikit.driveby.variability import (COUPLING_CHECK_EVERY, DAMAGE_KEYS, Variability, expand_cases, parse_coupling,
                                        parse_variability)
from vbikit.driveby.vehicles import DRIVEBY_VEHICLES
from vbikit.errors import VbikitError
from vbikit.scenario.schema import MAX_SPEED, MIN_SPEED

#: top-level keys of a drive-by file
TOP_KEYS = ("name", "seed", "batch_size", "max_steps", "bridge", "tire", "road", "crossing", "vehicle", "sampling",
            "sensors", "identification", "sweep", "coupling", "coupling_check_every", "variability", "fleet", "dataset")
#: [dataset] keys -> (default, description)
DATASET_KEYS: dict[str, tuple[Any, str]] = {
    "format": ("netcdf", "\"netcdf\" (driveby.nc) or \"zarr\" (driveby.nc and driveby.zarr; needs the zarr package)"),
    "chunk_passes": (64, "passes per chunk of the per-pass records, an integer in [1, 100000]"),
    "spectra": (True, "true or false: amplitude spectra of the on-bridge records"),
}
#: dataset formats: name -> the Python package it needs (None: always there)
DATASET_FORMATS: dict[str, Optional[str]] = {"netcdf": None, "zarr": "zarr"}
#: sweep keys -> (kind, unit)
SWEEP_KEYS: dict[str, tuple[str, str]] = {
    "speed": ("numbers", "m/s"), "road_class": ("names", ""), "road_seed": ("integers", ""),
    "damage_position": ("numbers", "m"), "damage_severity": ("numbers", "1"), "noise_rms": ("numbers", "sensor unit"),
}
#: identification methods
METHODS = {"contact": "spectrum of the contact-point acceleration back-calculated from the sensor (single-axle vehicle)",
           "residual": "spectrum of the residual of the contact-point accelerations of the vehicle and an identical one "
                       "following it at identification.gap (roughness cancellation)",
           "sensor": "spectrum of the sensor's own record"}
#: default budget: integration steps of the whole sweep
MAX_STEPS = 2e7
#: the files ``vbikit driveby`` (``run_driveby``) writes into its folder
DATASET_FILE, ZARR_FILE, REPORT_FILE, SUMMARY_FILE = ("driveby.nc", "driveby.zarr", "driveby-report.txt",
                                                      "driveby-summary.json")
#: the shortest identification.gap [m]: the follower of method "residual" half a metre behind the vehicle
MIN_GAP = 0.5
#: the most cases of one sweep (each is estimated, one by one, before anything runs)
MAX_CASES = 100_000
#: the numeric sweep keys' ranges: key -> (lowest, highest, highest excluded, unit); speeds those of a scenario
SWEEP_RANGES: dict[str, tuple[float, float, bool, str]] = {
    "speed": (MIN_SPEED, MAX_SPEED, False, "m/s"), "damage_position": (0.0, 1000.0, False, "m"),
    "damage_severity": (0.0, 1.0, True, "1"), "noise_rms": (0.0, MAX_NOISE_RMS, False, "units of the quantity"),
}
#: the parameters of the drive-by vehicles that take any: model -> key -> (lowest, highest, unit)
VEHICLE_PARAMETERS: dict[str, dict[str, tuple[float, float, str]]] = {
    "test-cart": {"mass": (1.0, 1e5, "kg"), "frequency_hz": (0.1, 100.0, "Hz"), "damping_ratio": (0.0, 0.99, "1")},
    "two-axle-car": {},
}
#: default search band's upper end [Hz]
BAND_MAX_HZ = 20.0


class DriveByError(VbikitError):
    """An invalid drive-by file; the message names the key."""

    message_names_key = True


@dataclass(frozen=True)
class DriveBy:
    """A parsed drive-by file (module docstring); ``cases`` the sweep's combinations (dicts of
    the sweep keys), in order (the last key varies fastest)."""

    name: str
    seed: int
    batch_size: int
    max_steps: float
    scenario: dict
    vehicle: dict
    sampling: Sampling
    sensors: tuple[Sensor, ...]
    method: str
    sensor: str
    band: Optional[tuple[float, float]]
    spectrum: str
    window: str
    gap: float
    exclude_vehicle: bool
    sweep: dict
    damage_length: float
    base_dir: str = "."
    cases: tuple = field(default=(), repr=False)
    # dataset keys (vbikit.driveby.variability): coupling mode, its check interval, the random passes
    coupling: str = "coupled"
    coupling_check_every: int = COUPLING_CHECK_EVERY
    variability: Variability = field(default_factory=Variability)
    #: the instrumented vehicles of [[fleet]]: (name, vehicle table) each; () with one [vehicle]
    fleet: tuple = ()
    #: the [dataset] table, every key of ``DATASET_KEYS`` set
    output: dict = field(default_factory=lambda: {k: v for k, (v, _) in DATASET_KEYS.items()})

    def vehicle_table(self, k: Optional[int]) -> dict:
        """The vehicle table of fleet vehicle ``k`` (the file's [vehicle] without a fleet or ``k`` None)."""
        return self.vehicle if k is None or not self.fleet else self.fleet[k][1]

    def input_sha256(self) -> dict[str, str]:
        """The SHA-256 of each file the scenario reads (a bridge's ``modes_file``, a measured road:
        ``vbikit.scenario.schema.INPUT_FILE_KEYS``), by key; read once per spec."""
        kept = self.__dict__.get("_input_sha256")
        if kept is None:
            from vbikit._files import input_digests
            from vbikit.scenario.schema import input_paths

            kept = input_digests(input_paths(self.scenario, self.base_dir))
            object.__setattr__(self, "_input_sha256", kept)  # (the spec is immutable: its files read once)
        return kept

    def to_json(self) -> str:
        """Canonical text of the drive-by run (the resume check and the dataset's ``study`` attribute): no
        folder — the files the scenario reads by their content (``input_sha256``; absent when it reads
        none), an absolute path in it by its file name (``vbikit._files.shared_spec``) — so a moved project
        folder resumes, a changed modes or profile file does not, and a shared dataset names no folder."""
        return self._identity(earlier=False)

    def earlier_json(self) -> tuple[str, ...]:
        """The identity as a dataset written before 2026-12-06 holds it (the folder, ``base_dir``, in place
        of the files' content): such a finished dataset is still recognised (``vbikit.study.run``)."""
        return (self._identity(earlier=True),)

    def _identity(self, earlier: bool) -> str:
        from vbikit._files import shared_spec

        digests = {} if earlier else self.input_sha256()
        return json.dumps({"kind": "vbikit driveby", "name": self.name, "seed": self.seed, "batch_size": self.batch_size,
                           "scenario": self.scenario if earlier else shared_spec(self.scenario), "vehicle": self.vehicle,
                           **({"base_dir": self.base_dir} if earlier else {}),
                           **({"input_sha256": digests} if digests else {}),
                           "sampling": [self.sampling.rate, self.sampling.filter_order, self.sampling.cutoff],
                           "sensors": [s.__dict__ for s in self.sensors], "method": self.method, "sensor": self.sensor,
                           "band": self.band, "spectrum": self.spectrum, "window": self.window, "gap": self.gap,
                           "exclude_vehicle": self.exclude_vehicle, "sweep": self.sweep,
                           "damage_length": self.damage_length,
                           **({"coupling": self.coupling, "coupling_check_every": self.coupling_check_every,
                               "variability": self.variability.__dict__} if self.variability.active
                              or self.coupling != "coupled" else {}),
                           **({"fleet": self.fleet} if self.fleet else {}),
                           **({"dataset": self.output} if self.output != DriveBy.__dataclass_fields__["output"].default_factory()
                              else {})}, sort_keys=True, default=str)


def _numbers(key: str, value: Any, kind: str) -> list:
    values = value if isinstance(value, list) else [value]
    if not values:
        raise DriveByError(f"sweep.{key}: give at least one value")
    for v in values:
        if kind == "names" and not isinstance(v, str):
            raise DriveByError(f"sweep.{key}: expected road class names (strings), got {v!r}")
        if kind == "integers":
            number(v, f"sweep.{key}", 0, 2**63 - 1, integer=True, error=DriveByError)
        if kind == "numbers":
            lo, hi, hi_open, unit = SWEEP_RANGES.get(key, (None, None, False, ""))
            number(v, f"sweep.{key}", lo, hi, hi_open=hi_open, unit=unit, error=DriveByError)
    if len(set(map(str, values))) != len(values):
        raise DriveByError(f"sweep.{key}: repeated values in {values}")
    return [float(v) if kind == "numbers" else v for v in values]


def _table(data: dict, key: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise DriveByError(f"{key}: expected a table [{key}], got {type(value).__name__}")
    return value


class _Errors:
    """The input errors of one drive-by file, gathered: every key's check runs (``check``), its error kept, so that
    the file's errors are reported together (``raise_all``), as a study, lifetime or railway file's are (pydantic:
    ``vbikit._validation.validation_message``)."""

    def __init__(self) -> None:
        self.messages: list[str] = []

    def check(self, work: Any, default: Any = None) -> Any:
        """``work()``, or ``default`` after keeping its error's message (a ``VbikitError``: it names the key)."""
        try:
            return work()
        except VbikitError as err:
            text = short_quotes(str(err))
            heading = _HEADED.match(text)  # (a part's own list of errors: its lines, under this file's heading)
            self.messages.extend(line.strip() for line in text[heading.end():].splitlines() if line.strip()) \
                if heading else self.messages.append(text)
            return default

    def add(self, message: str) -> None:
        self.messages.append(short_quotes(message))

    def raise_all(self) -> None:
        """``DriveByError``: ``invalid drive-by file:`` and one line a key, when any check failed."""
        if self.messages:
            raise DriveByError("invalid drive-by file:\n  " + "\n  ".join(dict.fromkeys(self.messages)))


#: a message that is already a list of key lines under a heading (``invalid …:``)
_HEADED = re.compile(r"^invalid [^\n:]+:\n")


def parse_driveby(data: dict[str, Any], base_dir: str | Path = ".") -> DriveBy:
    """Validate a drive-by file's tables (raises ``DriveByError`` naming every bad key, one a line under
    ``invalid drive-by file:``: all of the file's errors at once); every case of its sweep is validated as a
    scenario, and the budget checked, by ``vbikit.driveby.study.check_cases`` (which ``run_driveby`` and the command
    line call before anything runs)."""
    errors = _Errors()
    for key in (k for k in data if k not in TOP_KEYS):
        errors.add(f"{key}: unknown key of a drive-by file; allowed: {', '.join(TOP_KEYS)}")
    if "bridge" not in data:
        errors.add("bridge: a drive-by file needs a [bridge] table (scenario keys)")
    name = data.get("name", "")
    if not isinstance(name, str) or len(name) > 200:
        errors.add("name: expected a text of at most 200 characters")
    seed = errors.check(lambda: number(data.get("seed", 0), "seed", 0, 2**63 - 1, integer=True, error=DriveByError), 0)
    batch = errors.check(lambda: number(data.get("batch_size", 4), "batch_size", 1, 1000, integer=True,
                                        error=DriveByError), 4)
    max_steps = errors.check(lambda: number(data.get("max_steps", MAX_STEPS), "max_steps", 1, MAX_STEPS_LIMIT,
                                            error=DriveByError), MAX_STEPS)
    fleet = errors.check(lambda: _fleet(data), ())
    vehicle = fleet[0][1] if fleet else errors.check(
        lambda: _vehicle_table(dict(_table(data, "vehicle")) or {"model": "test-cart"}, "vehicle"), {})
    output = errors.check(lambda: _dataset_table(_table(data, "dataset")), {})
    sampling = errors.check(lambda: _sampling(_table(data, "sampling")))
    sensors = errors.check(lambda: _sensors(data.get("sensors", [])))
    names = [s.name for s in sensors] if sensors else None
    ident = errors.check(lambda: _identification(_table(data, "identification"), names, sampling))
    sweep_t = errors.check(lambda: dict(_table(data, "sweep")), {})
    damage_length = errors.check(lambda: number(sweep_t.pop("damage_length", 0.1 * 25.0), "sweep.damage_length", 1e-3,
                                                1000.0, unit="m", error=DriveByError), 2.5)
    sweep: dict[str, list] = {}
    for key, value in sweep_t.items():
        if key not in SWEEP_KEYS:
            errors.add(f"sweep.{key}: unknown key; allowed: {', '.join(SWEEP_KEYS)}, damage_length")
            continue
        values = errors.check(lambda: _numbers(key, value, SWEEP_KEYS[key][0]))
        if values is not None:
            sweep[key] = values
    if any(not isinstance(v, str) or len(v) > 40 for v in sweep.get("road_class", [])):
        errors.add("sweep.road_class: expected road class names (e.g. none, A … H)")
    n_cases = math.prod(len(v) for v in sweep.values()) if sweep else 1
    if n_cases > MAX_CASES:
        errors.add(f"sweep: {n_cases:,} cases, more than the {MAX_CASES:,} a sweep may hold; sweep fewer values")
    if "damage_severity" in sweep_t and "damage_position" not in sweep_t:
        errors.add("sweep.damage_position: damage_severity needs damage_position (start of the damaged region [m])")
    coupling_every = errors.check(lambda: parse_coupling(data))
    variability = errors.check(lambda: parse_variability(data.get("variability")))
    if variability is not None and any(k in DAMAGE_KEYS for k, _ in variability.drawn) and "damage_position" in sweep_t:
        errors.add("variability.damage_position: the damage is drawn per pass or swept (sweep.damage_position), not both")
    errors.raise_all()  # (the file's every error, before the cases are built from it)
    method, sensor, band, spectrum, window, gap, exclude_vehicle = ident
    coupling, check_every = coupling_every
    scenario = {k: copy.deepcopy(data[k]) for k in ("bridge", "tire", "road", "crossing") if k in data}
    keys = list(sweep)
    cases = tuple(dict(zip(keys, combo)) for combo in itertools.product(*(sweep[k] for k in keys)))
    cases = expand_cases(cases, variability, len(fleet))
    return DriveBy(name, seed, batch, float(max_steps), scenario, vehicle, sampling, tuple(sensors), method, sensor, band,
                   spectrum, window, float(gap), exclude_vehicle, sweep, float(damage_length), str(base_dir), cases,
                   coupling, check_every, variability, fleet, output)


def _sampling(table: dict) -> Sampling:
    """The [sampling] table as a ``Sampling`` (an error naming the key)."""
    bad = [k for k in table if k not in ("rate", "filter_order", "cutoff")]
    if bad:
        raise DriveByError(f"sampling.{bad[0]}: unknown key; allowed: rate, filter_order, cutoff")
    return Sampling(**{k: table[k] for k in table})


#: the keys of a [[sensors]] table
SENSOR_KEYS = ("name", "body", "axle", "position", "lateral", "quantity", "noise_rms", "noise_snr_db", "vehicle")


def _sensors(tables: Any) -> list[Sensor]:
    """The [[sensors]] tables as ``Sensor``s (every sensor's error, one a line)."""
    if not isinstance(tables, list) or not tables:
        raise DriveByError("sensors: give at least one [[sensors]] table (name, body or axle, quantity, ...)")
    errors, sensors = _Errors(), []
    for i, t in enumerate(tables):
        if not isinstance(t, dict) or "name" not in t:
            errors.add(f"sensors[{i + 1}].name: every [[sensors]] table needs a name")
            continue
        extra = [k for k in t if k not in SENSOR_KEYS]
        if extra:
            errors.add(f"sensors.{t['name']}.{extra[0]}: unknown key; allowed: {', '.join(SENSOR_KEYS)}")
            continue
        sensor = errors.check(lambda: Sensor(**t))
        if sensor is not None:
            sensors.append(sensor)
    names = [s.name for s in sensors]
    if len(set(names)) != len(names):
        errors.add(f"sensors.name: each sensor needs its own name, got {names}")
    errors.raise_all()
    return sensors


#: the keys of the [identification] table
IDENTIFICATION_KEYS = ("method", "sensor", "band", "spectrum", "window", "gap", "exclude_vehicle")


def _identification(ident: dict, names: Optional[list[str]], sampling: Optional[Sampling]) -> tuple:
    """(method, sensor, band, spectrum, window, gap, exclude_vehicle) of the [identification] table; the sensor
    checked against ``names`` and the band against ``sampling`` (not when those failed: their errors are reported)."""
    errors = _Errors()
    extra = [k for k in ident if k not in IDENTIFICATION_KEYS]
    if extra:
        errors.add(f"identification.{extra[0]}: unknown key; allowed: {', '.join(IDENTIFICATION_KEYS)}")
    gap = errors.check(lambda: number(ident.get("gap", 4.0), "identification.gap", MIN_GAP, 1000.0, unit="m",
                                      error=DriveByError))
    exclude_vehicle = ident.get("exclude_vehicle", True)
    if not isinstance(exclude_vehicle, bool):
        errors.add(f"identification.exclude_vehicle: expected true or false, got {exclude_vehicle!r}")
    method = ident.get("method", "contact")
    if not isinstance(method, str) or method not in METHODS:
        errors.add(f"identification.method: {method!r}; allowed: {', '.join(METHODS)}")
    sensor = ident.get("sensor", names[0] if names else None)
    if names is not None and (not isinstance(sensor, str) or sensor not in names):
        errors.add(f"identification.sensor: {sensor!r} is not a sensor; sensors: {', '.join(names)}")
    band = ident.get("band")
    if band is not None and sampling is not None:
        if not (isinstance(band, list) and len(band) == 2
                and all(isinstance(b, (int, float)) and not isinstance(b, bool) for b in band)
                and 0 < band[0] < band[1] < 0.5 * sampling.rate):
            errors.add(f"identification.band: expected [f_lo, f_hi] with 0 < f_lo < f_hi < rate / 2 = "
                       f"{0.5 * sampling.rate:g} Hz, got {band!r}")
        else:
            band = (float(band[0]), float(band[1]))
    spectrum = ident.get("spectrum", "periodogram")
    if not isinstance(spectrum, str) or spectrum not in ("periodogram", "welch"):
        errors.add(f"identification.spectrum: {spectrum!r}; allowed: periodogram, welch")
    window = ident.get("window", "hann")
    if not isinstance(window, str) or len(window) > 40:
        errors.add("identification.window: expected a scipy window name (hann, hamming, boxcar, ...)")
    else:
        try:
            from scipy.signal import get_window

            get_window(window, 16)
        except (ValueError, TypeError):
            errors.add(f"identification.window: {window!r} is not a scipy window (hann, hamming, boxcar, ...)")
    errors.raise_all()
    return method, sensor, band, spectrum, window, gap, exclude_vehicle


def _vehicle_table(vehicle: dict, where: str) -> dict:
    """A validated [vehicle] table (or one of [[fleet]], ``where`` = ``fleet.<name>``)."""
    if "model" not in vehicle:
        raise DriveByError(f"{where}.model: missing; a vehicle preset or one of {', '.join(DRIVEBY_VEHICLES)}")
    if not isinstance(vehicle["model"], str):
        raise DriveByError(f"{where}.model: expected a name (a vehicle preset or one of {', '.join(DRIVEBY_VEHICLES)})")
    if vehicle["model"] in VEHICLE_PARAMETERS:
        allowed_v = VEHICLE_PARAMETERS[vehicle["model"]]
        for k, v in vehicle.items():
            if k == "model":
                continue
            if k not in allowed_v:
                raise DriveByError(f"{where}.{k}: unknown key of the {vehicle['model']}; allowed: "
                                   f"{', '.join(['model', *allowed_v]) if allowed_v else 'model'}")
            lo, hi, unit = allowed_v[k]
            number(v, f"{where}.{k}", lo, hi, unit=unit, error=DriveByError)
    return vehicle


#: the most vehicles of one [[fleet]]
MAX_FLEET = 100


def _fleet(data: dict) -> tuple:
    """The [[fleet]] tables as ((name, vehicle table), ...); () without a fleet."""
    tables = data.get("fleet")
    if tables is None:
        return ()
    if "vehicle" in data:
        raise DriveByError("fleet: give either [vehicle] (one vehicle) or [[fleet]] tables (several), not both")
    if not isinstance(tables, list) or not 1 <= len(tables) <= MAX_FLEET or not all(isinstance(t, dict) for t in tables):
        raise DriveByError(f"fleet: expected 1 … {MAX_FLEET} [[fleet]] tables (name, model and the model's keys)")
    out = []
    for i, t in enumerate(tables):
        name = t.get("name")
        if not isinstance(name, str) or not name or len(name) > 80:
            raise DriveByError(f"fleet[{i + 1}].name: every [[fleet]] table needs a name (a text of 1 … 80 characters)")
        out.append((name, _vehicle_table({k: v for k, v in t.items() if k != "name"}, f"fleet.{name}")))
    names = [n for n, _ in out]
    if len(set(names)) != len(names):
        raise DriveByError(f"fleet.name: each vehicle of the fleet needs its own name, got {names}")
    return tuple(out)


def _dataset_table(table: dict) -> dict:
    """The [dataset] table, validated, every key of ``DATASET_KEYS`` set (its default where not given)."""
    extra = [k for k in table if k not in DATASET_KEYS]
    if extra:
        raise DriveByError(f"dataset.{extra[0]}: unknown key; allowed: {', '.join(DATASET_KEYS)}")
    out = {k: table.get(k, v) for k, (v, _) in DATASET_KEYS.items()}
    if out["format"] not in DATASET_FORMATS:
        raise DriveByError(f"dataset.format: {out['format']!r}; allowed: {', '.join(DATASET_FORMATS)}")
    number(out["chunk_passes"], "dataset.chunk_passes", 1, 100_000, integer=True, error=DriveByError)
    if not isinstance(out["spectra"], bool):
        raise DriveByError(f"dataset.spectra: expected true or false, got {out['spectra']!r}")
    return out


def check_dataset_format(spec: DriveBy) -> None:
    """Raise ``DriveByError`` when the [dataset] format needs a package that is not installed."""
    import importlib.util

    package = DATASET_FORMATS[spec.output["format"]]
    if package is not None and importlib.util.find_spec(package) is None:
        raise DriveByError(f"dataset.format: \"{spec.output['format']}\" needs the optional package {package!r}, which is "
                           f"not installed (pip install {package}); or use format = \"netcdf\"")


def load_driveby(path: str | Path) -> DriveBy:
    """Read and validate a drive-by file."""
    from vbikit._toml import read_toml

    path = Path(path)
    data = read_toml(path, DriveByError, "drive-by file")
    return parse_driveby(data, path.parent)
