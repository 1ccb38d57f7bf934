"""Generated inputs for the fuzz tests (hypothesis strategies) and the judge of each run's outcome.

Inputs: valid small scenarios, studies and field files, mutated — keys set to values of every kind
(in range, at and past the bounds, zero, negative, huge, tiny, NaN, ±inf, strings holding numbers,
booleans, lists, tables), keys removed, unknown keys added — and, for some, the TOML text itself
damaged (truncated, random characters, deep nesting, bytes that are not UTF-8).

Outcome of a run (:func:`judge`): "ok" (exit 0, every number in the JSON output finite),
"clean" (exit 2, one ``error:`` message naming a key or the file), or a failure: "traceback",
"nan" (exit 0 with a non-finite number), "unclear" (exit 2 naming neither key nor file), "hang"
(over :data:`HANG_SECONDS`), "exit N".
"""
from __future__ import annotations

import copy
import json
import math
import re
import signal
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from hypothesis import strategies as st

#: a run over this many seconds counts as hung
HANG_SECONDS = 60
#: budgets given to fuzzed runs (every accepted input then runs in about a second)
RUN_LIMITS = ["--max-steps", "30000", "--max-memory", "300MB"]

# ------------------------------------------------------------------------------------- TOML text


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        text = repr(v)
        return text if any(c in text for c in ".e") else text + ".0"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(data: dict[str, Any], prefix: str = "") -> str:
    """TOML text of ``data``: scalars and lists inline, tables as [sections], lists of tables as [[arrays]]."""
    lines, tables = [], []
    for k, v in data.items():
        key = json.dumps(k)
        if isinstance(v, dict):
            tables.append((k, v))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            tables.append((k, v))
        else:
            lines.append(f"{key} = {_value(v)}")
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in tables:
        name = f"{prefix}{json.dumps(k)}"
        if isinstance(v, dict):
            out += f"\n[{name}]\n" + to_toml(v, name + ".")
        else:
            for item in v:
                scalars = {a: b for a, b in item.items() if not isinstance(b, dict)}
                out += f"\n[[{name}]]\n" + to_toml(scalars, name + ".")
    return out


# ------------------------------------------------------------------------------------- values

NUMBERS = st.one_of(
    st.sampled_from([0, 1, -1, 2, 0.0, 0.5, 1e-9, 1e-300, 1e9, 1e300, -1e9, 10, 100, 1000, 1e6, 1e7]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-10**12, max_value=10**12),
)
WEIRD = st.one_of(
    st.sampled_from(["12", "", "nan", "inf", "C", "beam", "point", "../../etc/passwd", "/etc/passwd", "x" * 300,
                     "x/../../../escaped", "rk4", "newmark"]),
    st.booleans(), st.just([]), st.lists(st.integers(0, 5), max_size=3), st.just({}), st.just({"a": 1}),
)
ANY_VALUE = st.one_of(NUMBERS, NUMBERS, WEIRD)

# keys a mutation may set: scenario path -> values more likely to get past the schema
SCENARIO_KEYS: dict[tuple[str, ...], Any] = {
    ("bridge", "model"): st.sampled_from(["beam", "paper-bridge-2-beam", "paper-bridge-1-beam", "paper-bridge-1",
                                          "slab-on-girder", "modes-file", "nope"]),
    ("bridge", "span"): NUMBERS, ("bridge", "EI"): NUMBERS, ("bridge", "mass_per_length"): NUMBERS,
    ("bridge", "damping_ratio"): st.one_of(st.floats(0, 1), NUMBERS), ("bridge", "n_modes"): st.integers(-2, 600),
    ("bridge", "neutral_axis_depth"): NUMBERS, ("bridge", "modes_file"): WEIRD,
    ("bridge", "deck"): st.fixed_dictionaries({}, optional={"n_elements": st.integers(-1, 10**10),
                                                            "span": NUMBERS, "n_girders": st.integers(-1, 100),
                                                            "girder": st.sampled_from(["II", "IX", 3]),
                                                            "diaphragms": st.lists(NUMBERS, max_size=3)}),
    ("vehicle", "model"): st.sampled_from(["hs20-44", "sprung-mass", "moving-force", "two-axle", "quarter-car", "xx"]),
    ("vehicle", "mass"): NUMBERS, ("vehicle", "force"): NUMBERS, ("vehicle", "stiffness"): NUMBERS,
    ("tire", "model"): st.sampled_from(["point", "multipoint", "disk", "rigid-disk", "other"]),
    ("tire", "n_points"): st.integers(-1, 200), ("tire", "contact_length"): NUMBERS, ("tire", "radius"): NUMBERS,
    ("tire", "disk_spacing"): st.one_of(st.floats(1e-6, 0.2), NUMBERS), ("tire", "layout"): WEIRD,
    ("tire", "loss_of_contact"): st.one_of(st.booleans(), WEIRD),
    ("road", "class"): st.sampled_from(["none", "A", "C", "H", "good", "psd", "Z", "average"]),
    ("road", "seed"): st.one_of(st.integers(-5, 2**64), NUMBERS), ("road", "spacing"): NUMBERS,
    ("road", "n_min"): NUMBERS, ("road", "n_max"): NUMBERS, ("road", "phi0"): NUMBERS, ("road", "n0"): NUMBERS,
    ("road", "exponent"): NUMBERS, ("road", "length"): NUMBERS, ("road", "right_coherence"): NUMBERS,
    ("road", "profile_file"): WEIRD,
    ("road", "defects"): st.lists(st.fixed_dictionaries(
        {"kind": st.sampled_from(["depression", "bump", "step", "pothole", "crack"])},
        optional={"position": NUMBERS, "depth": NUMBERS, "height": NUMBERS, "length": NUMBERS, "ramp": NUMBERS,
                  "shape": st.sampled_from(["trapezoid", "cosine", "step", "zigzag"])}), max_size=2),
    ("crossing", "speed"): NUMBERS, ("crossing", "speed_kmh"): st.one_of(st.floats(0.001, 400), NUMBERS),
    ("crossing", "acceleration"): NUMBERS, ("crossing", "approach"): NUMBERS, ("crossing", "run_in"): NUMBERS,
    ("crossing", "free_vibration"): NUMBERS, ("crossing", "dt"): st.one_of(st.floats(1e-6, 0.1), NUMBERS),
    ("crossing", "integrator"): st.sampled_from(["rk4", "newmark", "euler"]), ("crossing", "lateral_offset"): NUMBERS,
    ("response", "x"): NUMBERS, ("response", "y"): NUMBERS, ("response", "girder"): st.integers(-1, 9),
    ("name",): WEIRD,
    ("bridge", "spans"): st.lists(st.one_of(st.floats(1, 60), NUMBERS), max_size=4),
    ("vehicles",): st.lists(st.fixed_dictionaries(
        {"model": st.sampled_from(["sprung-mass", "moving-force", "two-axle", "axles", "zz"])},
        optional={"speed": NUMBERS, "speed_kmh": st.one_of(st.floats(1, 200), NUMBERS),
                  "direction": st.sampled_from(["+x", "-x", "up"]), "entry_time": NUMBERS,
                  "lateral_offset": NUMBERS, "acceleration": NUMBERS}), max_size=3),
}

BASE_SCENARIOS = [
    {"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 5000.0, "n_modes": 3},
     "vehicle": {"model": "sprung-mass"}, "crossing": {"speed": 20.0, "approach": 0.0, "free_vibration": 0.05}},
    {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "two-axle"},
     "tire": {"model": "multipoint", "n_points": 3}, "road": {"class": "C", "seed": 1, "length": 200},
     "crossing": {"speed_kmh": 80, "approach": 2.0, "free_vibration": 0.05}},
    {"bridge": {"model": "paper-bridge-1", "n_modes": 4}, "vehicle": {"model": "hs20-44"},
     "crossing": {"speed_kmh": 60, "approach": 1.0, "free_vibration": 0.05}, "response": {"girder": 4}},
    {"bridge": {"model": "continuous-beam", "spans": [10.0, 12.0], "EI": 5e9, "mass_per_length": 5000.0, "n_modes": 4},
     "crossing": {"approach": 1.0, "free_vibration": 0.05},
     "vehicles": [{"model": "sprung-mass", "speed": 20.0},
                  {"model": "moving-force", "speed_kmh": 50.0, "direction": "-x", "entry_time": 0.1}]},
]


def _set(data: dict, path: tuple[str, ...], value: Any) -> None:
    node = data
    for p in path[:-1]:
        if not isinstance(node.get(p), dict):
            node[p] = {}
        node = node[p]
    node[path[-1]] = value


def _delete(data: dict, path: tuple[str, ...]) -> None:
    node = data
    for p in path[:-1]:
        node = node.get(p)
        if not isinstance(node, dict):
            return
    node.pop(path[-1], None)


@st.composite
def mutated(draw, bases: list[dict], keys: dict[tuple[str, ...], Any]) -> dict:
    data = copy.deepcopy(draw(st.sampled_from(bases)))
    for _ in range(draw(st.integers(0, 3))):
        action = draw(st.sampled_from(["set", "set", "set", "any", "delete", "unknown"]))
        path = draw(st.sampled_from(sorted(keys)))
        if action == "set":
            _set(data, path, draw(keys[path]))
        elif action == "any":
            _set(data, path, draw(ANY_VALUE))
        elif action == "delete":
            _delete(data, path)
        else:
            _set(data, path[:-1] + (draw(st.sampled_from(["spead", "x_y", "Class", "unknown"])),), draw(ANY_VALUE))
    return data


@st.composite
def damaged_text(draw, text: str) -> bytes:
    """``text`` as bytes, sometimes damaged (most inputs are left intact)."""
    kind = draw(st.sampled_from(["intact"] * 15 + ["truncate", "insert", "nest", "bytes", "duplicate"]))
    raw = text.encode()
    if kind == "truncate":
        return raw[: draw(st.integers(0, max(0, len(raw) - 1)))]
    if kind == "insert":
        at = draw(st.integers(0, len(raw)))
        return raw[:at] + draw(st.text(min_size=1, max_size=5)).encode() + raw[at:]
    if kind == "nest":
        depth = draw(st.integers(100, 3000))
        return raw + b"\nzz = " + b"[" * depth + b"]" * depth + b"\n"
    if kind == "bytes":
        at = draw(st.integers(0, len(raw)))
        return raw[:at] + draw(st.binary(min_size=1, max_size=4)) + raw[at:]
    if kind == "duplicate":
        return raw + b"\n" + raw
    return raw


def scenarios() -> st.SearchStrategy[bytes]:
    return mutated(BASE_SCENARIOS, SCENARIO_KEYS).map(to_toml).flatmap(damaged_text)


# ------------------------------------------------------------------------------------- surfaces added since the paper
# [[vehicles]] (every key, axle trucks, per-vehicle tires), [bridge.deck], [[bridge.damage]], continuous-beam
# keys, load-effect sections, and mode files (a file written by the project's writer, its headers and rows
# damaged).  Each generated input also says whether it must be refused (``must_refuse``): it holds a NaN, or an
# infinity outside the keys where inf means rigid (support and rotational springs).

SPRING_KEYS = ("support_stiffness", "rotational_stiffness")
SPEEDS_KMH = st.one_of(st.floats(1, 400), NUMBERS)
def _plausible(good: Any) -> Any:
    """Mostly ``good`` values, sometimes any number."""
    return st.one_of(good, good, good, NUMBERS)


@st.composite
def axle_trucks(draw) -> dict:
    """An [[vehicles]] table of model "axles": loads and spacings mostly of matching lengths."""
    n = draw(st.one_of(st.integers(1, 8), st.sampled_from([60, 2000])))
    out: dict[str, Any] = {"model": "axles",
                           "axle_loads": draw(st.lists(_plausible(st.floats(2e4, 2e5)), min_size=n, max_size=n)),
                           "axle_spacings": draw(st.lists(_plausible(st.floats(1.0, 8.0)), min_size=n - 1, max_size=n - 1))}
    if draw(st.integers(0, 4)) == 0:
        out[draw(st.sampled_from(["axle_loads", "axle_spacings"]))] = draw(st.one_of(WEIRD, st.lists(NUMBERS, max_size=3)))
    for key, good in (("half_track", st.floats(0.5, 1.5)), ("tire_deflection", st.floats(0.005, 0.05)),
                      ("suspension_deflection", st.floats(0.01, 0.2)), ("suspension_damping_ratio", st.floats(0, 0.9)),
                      ("tire_damping_ratio", st.floats(0, 0.9)), ("tractor_groups", st.integers(-1, 4)),
                      ("unsprung_masses", st.lists(_plausible(st.floats(300, 1500)), min_size=n, max_size=n))):
        if draw(st.integers(0, 5)) == 0:
            out[key] = draw(_plausible(good))
    return out


AXLE_TRUCK = axle_trucks()
LISTED_VEHICLE = st.one_of(
    st.fixed_dictionaries(
        {"model": st.sampled_from(["sprung-mass", "moving-force", "two-axle", "hs20-44", "quarter-car", "3s2", "zz"])},
        optional={"speed": NUMBERS, "speed_kmh": SPEEDS_KMH, "direction": st.sampled_from(["+x", "-x", "up"]),
                  "entry_time": st.one_of(st.floats(0, 3), NUMBERS), "lateral_offset": st.one_of(st.floats(-6, 6), NUMBERS),
                  "acceleration": st.one_of(st.floats(-3, 3), NUMBERS), "mass": NUMBERS, "stiffness": NUMBERS,
                  "force": NUMBERS, "tire": st.fixed_dictionaries({"model": st.sampled_from(["point", "multipoint", "disk"])},
                                                                   optional={"n_points": st.integers(-1, 40)})}),
    AXLE_TRUCK,
)
DECK_TABLE = st.fixed_dictionaries({}, optional={
    "spans": st.one_of(st.lists(st.one_of(st.floats(5, 40), NUMBERS, WEIRD), max_size=4), WEIRD,
                       st.just([10.0] * 40)),
    "n_elements": st.integers(-1, 10**6), "n_girders": st.integers(-1, 30), "span": NUMBERS,
    "girder_spacing": NUMBERS, "default_girder": st.one_of(st.integers(-1, 12), NUMBERS), "skew": NUMBERS,
    "girder": st.one_of(st.sampled_from(["II", "IX"]), st.fixed_dictionaries(
        {"area": NUMBERS, "inertia": NUMBERS, "y_bottom": NUMBERS, "depth": NUMBERS})),
})
DAMAGE = st.lists(st.fixed_dictionaries({}, optional={
    "position": st.one_of(st.floats(0, 30), NUMBERS), "length": st.one_of(st.floats(0.1, 10), NUMBERS),
    "severity": st.one_of(st.floats(0, 0.99), NUMBERS), "girder": st.one_of(st.integers(-1, 8), WEIRD)}), max_size=3)
SECTIONS = st.one_of(st.lists(st.one_of(st.floats(0, 30), NUMBERS), max_size=4), WEIRD)

NEW_SURFACE_KEYS: dict[tuple[str, ...], Any] = {
    ("vehicles",): st.lists(LISTED_VEHICLE, min_size=0, max_size=4),
    ("vehicles", "more"): st.sampled_from([60, 200]),  # replaced by that many sprung masses (see new_surface_inputs)
    ("bridge", "model"): st.sampled_from(["continuous-beam", "slab-on-girder", "paper-bridge-2", "paper-bridge-2-beam",
                                          "beam"]),
    ("bridge", "spans"): st.one_of(st.lists(st.one_of(st.floats(2, 60), NUMBERS), max_size=5), WEIRD,
                                   st.sampled_from([[10.0] * 25, [10.0] * 3000])),
    ("bridge", "EI"): st.one_of(NUMBERS, st.lists(NUMBERS, max_size=3)),
    ("bridge", "mass_per_length"): st.one_of(NUMBERS, st.lists(NUMBERS, max_size=3)),
    ("bridge", "support_stiffness"): st.one_of(NUMBERS, st.lists(st.one_of(st.sampled_from([0.0, 1e6, 1e12]), NUMBERS),
                                                                 max_size=4)),
    ("bridge", "rotational_stiffness"): st.lists(NUMBERS, max_size=3),
    ("bridge", "elements_per_span"): st.one_of(st.integers(-1, 1200), WEIRD),
    ("bridge", "neutral_axis_depth"): NUMBERS, ("bridge", "damping_ratio"): NUMBERS,
    ("bridge", "n_modes"): st.integers(-1, 30),
    ("bridge", "deck"): DECK_TABLE,
    ("bridge", "damage"): DAMAGE,
    ("response", "moment"): SECTIONS, ("response", "shear"): SECTIONS,
    ("response", "reaction"): st.one_of(st.lists(st.integers(-1, 6), max_size=4), WEIRD),
    ("response", "load_effect_method"): st.sampled_from(["mode-acceleration", "mode-superposition", "other"]),
    ("crossing", "speed_kmh"): SPEEDS_KMH,
}

NEW_SURFACE_BASES = [
    {"bridge": {"model": "continuous-beam", "spans": [10.0, 12.0], "EI": 5e9, "mass_per_length": 5000.0, "n_modes": 3},
     "crossing": {"approach": 1.0, "free_vibration": 0.05},
     "vehicles": [{"model": "sprung-mass", "speed": 20.0},
                  {"model": "two-axle", "speed_kmh": 60.0, "direction": "-x", "entry_time": 0.1}]},
    {"bridge": {"model": "paper-bridge-2", "n_modes": 3, "deck": {"n_elements": 10}},
     "crossing": {"approach": 1.0, "free_vibration": 0.05, "speed_kmh": 70.0},
     "vehicles": [{"model": "hs20-44", "lateral_offset": -1.8}, {"model": "hs20-44", "lateral_offset": 1.8}]},
    {"bridge": {"model": "continuous-beam", "spans": [8.0, 10.0, 8.0], "EI": [4e9, 6e9, 4e9], "mass_per_length": 4000.0,
                "n_modes": 3, "support_stiffness": [1e12, 1e9, 1e9, 1e12],
                "damage": [{"position": 3.0, "length": 1.5, "severity": 0.3}]},
     "vehicle": {"model": "axles", "axle_loads": [40e3, 80e3, 80e3], "axle_spacings": [4.0, 1.3]},
     "crossing": {"speed_kmh": 60.0, "approach": 1.0, "free_vibration": 0.05},
     "response": {"moment": [4.0, 8.0], "shear": [1.0], "reaction": [0, 1]}},
    {"bridge": {"model": "paper-bridge-2", "n_modes": 3, "deck": {"n_elements": 10},
                "damage": [{"position": 5.0, "length": 2.0, "severity": 0.2, "girder": 2}]},
     "vehicle": {"model": "hs20-44"}, "crossing": {"speed_kmh": 60.0, "approach": 1.0, "free_vibration": 0.05},
     "response": {"moment": [8.38], "reaction": [0, 1]}},
]


def must_refuse(data: Any, key: str = "") -> bool:
    """True when ``data`` holds a value no scenario may accept: a NaN anywhere, an infinity outside the
    spring keys (where inf means rigid)."""
    if isinstance(data, dict):
        return any(must_refuse(v, k) for k, v in data.items())
    if isinstance(data, list):
        return any(must_refuse(v, key) for v in data)
    if isinstance(data, float):
        return math.isnan(data) or (math.isinf(data) and key not in SPRING_KEYS)
    return False


def _expand(data: dict) -> dict:
    """``vehicles.more = N``: N sprung masses one after another (a budget above 50 vehicles)."""
    more = data.get("vehicles", {}).pop("more", None) if isinstance(data.get("vehicles"), dict) else None
    if isinstance(more, int) and not isinstance(more, bool) and 0 < more <= 500:
        data["vehicles"] = [{"model": "sprung-mass", "speed": 20.0, "entry_time": 1.0 * i} for i in range(more)]
        data.pop("vehicle", None)
    return data


@st.composite
def new_surface_inputs(draw) -> tuple[bytes, bool]:
    """(scenario TOML, must_refuse) over the surfaces added since the paper."""
    data = _expand(draw(mutated(NEW_SURFACE_BASES, NEW_SURFACE_KEYS)))
    return draw(damaged_text(to_toml(data))), must_refuse(data)


def _mode_file_text() -> str:
    """A mode file written by the project's writer (a three-line grillage, three modes)."""
    import tempfile

    from vbikit.bridge.modefile import write_modes
    from vbikit.bridge.presets import BRIDGE_PRESETS

    with tempfile.TemporaryDirectory() as tmp:
        bridge = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=3, n_elements=6)
        return write_modes(bridge, Path(tmp) / "m.csv").read_text()


MODE_FILE_TEXT: list[str] = []
MODE_HEADERS = ["span", "frequencies_hz", "omega", "damping_ratios", "girder_y", "strain_lever_arm",
                "default_lateral_offset", "default_girder", "deck_width", "skew", "skew_tan"]
HEADER_VALUES = st.one_of(
    st.lists(st.floats(-5, 50), min_size=1, max_size=5).map(lambda v: ", ".join(map(repr, v))),
    st.lists(st.floats(-5, 50), min_size=1, max_size=5).map(lambda v: ", ".join(map(repr, sorted(v)))),
    st.lists(st.one_of(st.floats(-5, 50), NUMBERS), min_size=0, max_size=6).map(lambda v: ", ".join(map(repr, v))),
    st.sampled_from(["", "10 20", "nan", "inf", "-inf", "x", "1,,2", "0", "-1", "1e300", "2.5", "5", "0.5", "1", "4"]),
)
TAME_VEHICLE = st.fixed_dictionaries({"model": st.sampled_from(["hs20-44", "sprung-mass", "two-axle"])},
                                     optional={"lateral_offset": st.floats(-4.5, 4.5), "entry_time": st.floats(0, 1),
                                               "direction": st.sampled_from(["+x", "-x"])})


@st.composite
def mode_file_inputs(draw) -> tuple[bytes, bytes, bool]:
    """(scenario TOML, mode file, must_refuse): a scenario reading fuzz.modes.csv, the file's headers
    replaced, removed or added, its rows damaged."""
    if not MODE_FILE_TEXT:
        MODE_FILE_TEXT.append(_mode_file_text())
    lines = MODE_FILE_TEXT[0].splitlines()
    refuse = False
    for _ in range(draw(st.integers(0, 2))):
        key = draw(st.sampled_from(MODE_HEADERS))
        at = [i for i, line in enumerate(lines) if line.startswith(f"# {key} =")]
        action = draw(st.sampled_from(["set", "set", "set", "delete"]))
        if action == "delete":
            lines = [line for i, line in enumerate(lines) if i not in at]
            continue
        value = draw(HEADER_VALUES)
        if key in ("frequencies_hz", "omega", "span") and any(w in value.split(", ") for w in ("nan", "inf", "-inf")):
            refuse = True
        if at:
            lines[at[0]] = f"# {key} = {value}"
        else:
            lines.insert(1, f"# {key} = {value}")
    rows = draw(st.sampled_from(["intact"] * 12 + ["drop", "nan", "text", "truncate"]))
    first = next(i for i, line in enumerate(lines) if line and not line.startswith("#")) + 1
    if rows == "drop" and len(lines) > first + 1:
        del lines[draw(st.integers(first, len(lines) - 1))]
    elif rows in ("nan", "text") and len(lines) > first:
        i = draw(st.integers(first, len(lines) - 1))
        cells = lines[i].split(",")
        cells[draw(st.integers(0, len(cells) - 1))] = "nan" if rows == "nan" else "zz"
        lines[i] = ",".join(cells)
        refuse = True
    elif rows == "truncate":
        lines = lines[: draw(st.integers(0, len(lines)))]
    bridge: dict[str, Any] = {"model": "modes-file", "modes_file": "fuzz.modes.csv"}
    for key, values in (("n_modes", st.one_of(st.integers(1, 4), st.integers(-1, 6))),
                        ("damping_ratio", st.one_of(st.sampled_from([0.02, 0.05]), st.floats(0, 0.99), NUMBERS))):
        if draw(st.integers(0, 3)) == 0:
            bridge[key] = draw(values)
    data = {"bridge": bridge, "crossing": {"speed_kmh": 60.0, "approach": 1.0, "free_vibration": 0.05}}
    if draw(st.booleans()):
        data["vehicle"] = {"model": "hs20-44"}
    else:
        data["vehicles"] = draw(st.lists(st.one_of(TAME_VEHICLE, TAME_VEHICLE, LISTED_VEHICLE), min_size=1, max_size=2))
    if draw(st.booleans()):
        data["response"] = {"girder": draw(st.integers(-1, 6))}
    refuse = refuse or must_refuse(data)
    return to_toml(data).encode(), ("\n".join(lines) + "\n").encode(), refuse


# ------------------------------------------------------------------------------------- studies

STUDY_BASE = {"name": "fuzz", "seed": 1, "batch_size": 2, "base": BASE_SCENARIOS[1],
              "axes": {"tire.n_points": [1, 3], "road.seed": {"samples": 2}}}
STUDY_KEYS: dict[tuple[str, ...], Any] = {
    ("seed",): st.one_of(st.integers(-3, 2**40), WEIRD), ("batch_size",): st.one_of(st.integers(-1, 20000), WEIRD),
    ("histories",): st.one_of(st.booleans(), WEIRD), ("name",): WEIRD,
    ("axes", "crossing.speed_kmh"): st.lists(st.one_of(st.floats(1, 200), NUMBERS, WEIRD), max_size=4),
    ("axes", "tire.n_points"): st.lists(st.one_of(st.integers(-1, 12), WEIRD), max_size=4),
    ("axes", "road.class"): st.lists(st.sampled_from(["A", "B", "C", "Q", "none", "psd"]), max_size=3),
    ("axes", "road.seed"): st.one_of(st.fixed_dictionaries({"samples": st.one_of(st.integers(-1, 4), WEIRD)}),
                                     st.lists(st.integers(-1, 9), max_size=3)),
    ("axes", "bridge.n_modes"): st.lists(st.integers(-1, 40), max_size=3),
    ("axes", "nope.key"): st.lists(st.integers(0, 3), max_size=2),
    ("axes", "crossing.dt"): st.lists(st.one_of(st.floats(1e-5, 0.05), NUMBERS), max_size=2),
    **{("base",) + k: v for k, v in SCENARIO_KEYS.items() if k[0] in ("crossing", "road", "tire")},
}


def studies() -> st.SearchStrategy[bytes]:
    return mutated([STUDY_BASE], STUDY_KEYS).map(to_toml).flatmap(damaged_text)


# ------------------------------------------------------------------------------------- field files

FIELD_BASE = {
    "name": "fuzz field", "bridge": "paper-bridge-2-beam", "truck": "two-axle", "speed_kmh": 60.0, "approach": 2.0,
    "free_vibration": 0.2, "n_modes": 3, "damping_ratio": 0.02,
    "signal": {"lowpass_hz": 40.0, "drift": "quiet", "quiet_tail": 0.05},
    "case": [{"name": "c1", "responses": "resp.csv", "lateral_offset": 0.0, "trigger_time": 0.1, "align": "trigger",
              "channel": [{"name": "D", "quantity": "displacement", "girder": 1, "x": 8.38, "unit": "mm"}]}],
}
FIELD_KEYS: dict[tuple[str, ...], Any] = {
    ("bridge",): st.sampled_from(["paper-bridge-2-beam", "cypress-bayou", "nope", 3]),
    ("truck",): st.sampled_from(["two-axle", "dump-truck", "nope"]), ("speed_kmh",): NUMBERS,
    ("approach",): NUMBERS, ("free_vibration",): NUMBERS, ("n_modes",): st.one_of(st.integers(-1, 600), WEIRD),
    ("damping_ratio",): NUMBERS, ("stiffness_factor",): NUMBERS, ("dt",): st.one_of(st.floats(1e-5, 0.1), NUMBERS),
    ("bridge_parameters",): st.one_of(WEIRD, st.fixed_dictionaries({}, optional={"n_elements": st.integers(-1, 10**9),
                                                                               "bogus": NUMBERS})),
    ("signal", "lowpass_hz"): NUMBERS, ("signal", "drift"): WEIRD, ("signal", "quiet_tail"): NUMBERS,
    ("signal", "bands_hz"): st.one_of(WEIRD, st.lists(st.lists(NUMBERS, min_size=2, max_size=2), max_size=2)),
    ("crossing", "run_in"): NUMBERS, ("unknown",): ANY_VALUE,
}
CASE_KEYS = {"name": WEIRD, "responses": WEIRD, "lateral_offset": NUMBERS, "sampling_rate": NUMBERS,
             "trigger_time": NUMBERS, "align": WEIRD, "speed_kmh": NUMBERS, "channel": st.just([])}
CHANNEL_KEYS = {"name": WEIRD, "quantity": WEIRD, "girder": st.one_of(st.integers(-1, 9), WEIRD), "x": NUMBERS,
                "unit": st.sampled_from(["mm", "m", "g", "furlong"])}


@st.composite
def field_files(draw) -> tuple[bytes, bytes]:
    """(FIELD.toml, resp.csv) — both possibly mutated."""
    data = draw(mutated([FIELD_BASE], FIELD_KEYS))
    if draw(st.booleans()):
        case = data["case"][0]
        table, keys = (case, CASE_KEYS) if draw(st.booleans()) else (case["channel"][0] if case.get("channel") else case,
                                                                    CHANNEL_KEYS)
        key = draw(st.sampled_from(sorted(keys)))
        table[key] = draw(st.one_of(keys[key], ANY_VALUE))
    n = draw(st.sampled_from([200, 200, 200, 3]))
    rate = 200.0
    rows = [f"{i / rate:.4f},{-1.0 * math.sin(math.pi * i / max(n, 1)):.5f}" for i in range(n)]
    csv_text = "time [s], D [mm]\n" + "\n".join(rows) + "\n"
    if draw(st.integers(0, 4)) == 0:
        csv_text = draw(st.sampled_from(["", "time [s], D [mm]\n0,nan\n", "a,b\n1,2\n", "time [s], D [mm]\n" +
                                         "".join(f"{i / rate},0\n" for i in range(50))]))
    return draw(damaged_text(to_toml(data))), csv_text.encode()


# ------------------------------------------------------------------------------------- judging

_KEY = re.compile(r"\b[a-z_]+(\.[A-Za-z0-9_\"\-]+)+\b|\b(bridge|vehicle|tire|road|crossing|response|axes|base|seed|"
                  r"batch_size|name|case|signal|n_modes|speed_kmh|approach|free_vibration|damping_ratio|dt|"
                  r"stiffness_factor|truck|histories|vehicles)\b")


class Hang(Exception):
    pass


@contextmanager
def time_limit(seconds: int = HANG_SECONDS):
    def handler(signum, frame):
        raise Hang

    old = signal.signal(signal.SIGALRM, handler)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def _strict_json(text: str) -> Any:
    def refuse(name: str) -> Any:
        raise ValueError(f"non-finite JSON constant {name}")

    return json.loads(text, parse_constant=refuse)


def _finite(obj: Any) -> bool:
    if isinstance(obj, dict):
        return all(_finite(v) for v in obj.values())
    if isinstance(obj, list):
        return all(_finite(v) for v in obj)
    if isinstance(obj, float):
        return math.isfinite(obj)
    return True


def judge(result: Any, file_names: tuple[str, ...], outputs: tuple[Path, ...] = ()) -> str:
    """Outcome of one CliRunner result (module docstring); ``outputs``: JSON files the run wrote."""
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return "hang" if isinstance(result.exception, Hang) else "traceback"
    if result.exit_code == 0:
        try:
            for text in [result.stdout] + [p.read_text() for p in outputs if p.exists()]:
                if text.strip().startswith(("{", "[")):
                    if not _finite(_strict_json(text)):
                        return "nan"
        except ValueError:
            return "nan"
        if "nan" in result.stdout.lower().split():
            return "nan"
        return "ok"
    if result.exit_code == 2:
        message = result.output
        if "Traceback" in message:
            return "traceback"
        if "error" not in message.lower():
            return "unclear"
        if any(name in message for name in file_names) or _KEY.search(message):
            return "clean"
        return "unclear"
    return f"exit {result.exit_code}"


def cli_refused(res: Any, *parts: str) -> str:
    """The stderr of a CliRunner result that is a clean refusal: exit 2, no exception but the exit, one
    ``error:`` line, no traceback, every one of ``parts`` in it."""
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)
    assert res.exit_code == 2, res.output
    errors = [line for line in res.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and "Traceback" not in res.output, res.output
    for part in parts:
        assert part in res.stderr, res.stderr
    return res.stderr
