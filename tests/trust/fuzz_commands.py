"""Generated inputs for the lifetime, drive-by and railway commands, each with the verdict it must get.

Small valid files of each command (``BASES``) mutated: keys set to values of every kind (in range,
at and past the bounds, zero, negative, tiny, huge, NaN, ±inf, booleans, strings, lists, tables),
keys removed, unknown keys added; and for lifetime and rail their CSV inputs (records, train tables)
damaged.  Each input carries ``must_refuse``: True when it holds a value no file of the command may
accept (the classes the issue found silently accepted):

* a NaN or an infinity anywhere;
* a boolean or a string where the valid file has a number;
* a number of magnitude 1e300 or more, or a tiny positive (0 < |v| ≤ 1e-300) for a key that is a
  length, speed, stiffness, bin or count (``TINY_REFUSED``);
* an unknown key.

``outcome`` judges one run of ``vbikit validate`` (the same checks as the command, no computation):
"ok" (exit 0), "clean" (exit 2, one ``error:`` line, no content of any input file), or a failure:
"traceback", "hang" (over ``HANG_SECONDS``), "silent acceptance" (exit 0 for an input that must be
refused), "echo" (a secret line of an input file in the message), "exit N".
"""
from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

from fuzzing import ANY_VALUE, NUMBERS, WEIRD, Hang, to_toml
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

HANG_SECONDS = 30
#: a line planted in damaged CSV inputs: it must never appear in a message
SECRET = "SECRET-do-not-echo"
ROOT = Path(__file__).resolve().parents[2]

RECORDS = (ROOT / "examples" / "lifetime" / "wim.csv").read_text().splitlines()[:400]

BASES: dict[str, dict[str, Any]] = {
    "lifetime": {
        "days": 5, "seed": 1, "amplification": 0.5, "return_periods": [75.0, 100.0],
        "traffic": {"records": "records.csv", "mode": "fitted", "trucks_per_day": 2000.0},
        "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
        "load_effects": [{"kind": "moment", "x": 4.0, "name": "M"}, {"kind": "reaction", "support": 0, "name": "R"}],
        "fatigue": {"dynamic_sample": 0.05, "histogram_bin": 1e6, "damage_so_far": 0.1,
                    "details": [{"name": "d", "effect": "M", "section_modulus": 0.01, "category": "EN 71"}]},
    },
    "driveby": {
        "seed": 1, "batch_size": 2, "max_steps": 2e7,
        "bridge": {"model": "continuous-beam", "spans": [25.0], "EI": 2.4e10, "mass_per_length": 4800.0, "n_modes": 4},
        "vehicle": {"model": "test-cart", "mass": 120.0, "frequency_hz": 3.2},
        "road": {"class": "none"}, "crossing": {"speed": 8.0, "approach": 5.0},
        "sampling": {"rate": 200.0, "filter_order": 8, "cutoff": 0.4},
        "sensors": [{"name": "acc", "body": "body", "position": 0.0, "lateral": 0.0, "noise_rms": 0.01}],
        "identification": {"method": "contact", "band": [1.0, 20.0], "gap": 4.0},
        "sweep": {"speed": [5.0, 8.0], "damage_position": [11.25], "damage_length": 2.5,
                  "damage_severity": [0.0, 0.3], "noise_rms": [0.0, 0.01]},
    },
    "rail": {
        "bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0, "damping": 0.01},
        "trains": {"presets": ["hslm-a1"], "tables": ["train.csv"]},
        "speeds": {"min": 100.0, "max": 200.0, "step": 10.0},
        "coupled": {"enabled": False, "contact": 1e9},
        "run": {"workers": 1, "steps_per_period": 20, "points": 3},
    },
}

#: keys (paths) a mutation may set, per command
KEYS: dict[str, list[tuple]] = {
    "lifetime": [("days",), ("seed",), ("amplification",), ("return_periods",), ("characteristic_period",), ("ds",),
                 ("dx",), ("budget_hours",), ("batch_size",), ("years",), ("days_per_year",), ("ci",),
                 ("traffic", "trucks_per_day"), ("traffic", "lanes"), ("traffic", "speed_kmh"), ("traffic", "components"),
                 ("traffic", "mode"), ("load_effects", 0, "x"), ("load_effects", 0, "kind"), ("load_effects", 1, "support"),
                 ("load_effects", 0, "y"), ("fatigue", "dynamic_sample"), ("fatigue", "histogram_bin"),
                 ("fatigue", "damage_so_far"), ("fatigue", "details", 0, "section_modulus"),
                 ("fatigue", "details", 0, "category"), ("fatigue", "details", 0, "gamma_mf"), ("bridge", "n_modes")],
    "driveby": [("seed",), ("batch_size",), ("max_steps",), ("vehicle", "mass"), ("vehicle", "frequency_hz"),
                ("vehicle", "damping_ratio"), ("sampling", "rate"), ("sampling", "filter_order"), ("sampling", "cutoff"),
                ("sensors", 0, "position"), ("sensors", 0, "lateral"), ("sensors", 0, "noise_rms"),
                ("sensors", 0, "quantity"), ("sensors", 0, "body"), ("identification", "gap"),
                ("identification", "band"), ("identification", "window"), ("identification", "method"),
                ("sweep", "speed"), ("sweep", "damage_position"), ("sweep", "damage_length"),
                ("sweep", "damage_severity"), ("sweep", "noise_rms"), ("sweep", "road_seed"), ("crossing", "speed"),
                ("bridge", "spans")],
    "rail": [("bridge", "span"), ("bridge", "EI"), ("bridge", "mass_per_length"), ("bridge", "damping"),
             ("bridge", "n_modes"), ("bridge", "classification_factor"), ("bridge", "deck"), ("trains", "presets"),
             ("trains", "sleeper_spacing"), ("speeds", "min"), ("speeds", "max"), ("speeds", "step"),
             ("speeds", "fine_step"), ("speeds", "fine_width"), ("coupled", "contact"), ("coupled", "max_steps"),
             ("coupled", "seed"), ("run", "workers"), ("run", "steps_per_period"), ("run", "budget"), ("run", "points")],
}

#: keys whose tiny positive value (0 < v ≤ 1e-300) must be refused: lengths, speeds, stiffnesses, bins, counts
TINY_REFUSED = {"ds", "dx", "histogram_bin", "section_modulus", "trucks_per_day", "speed_kmh", "span", "EI",
                "mass_per_length", "mass", "frequency_hz", "rate", "step", "fine_step", "contact", "speed",
                "damage_length", "gap", "budget", "max_steps", "budget_hours", "amplification", "x"}

TINY = st.sampled_from([5e-324, 1e-310, 1e-300])
HUGE = st.sampled_from([1e300, -1e300, 1.7e308, 10**400])
VALUES = st.one_of(NUMBERS, WEIRD, TINY, HUGE, st.sampled_from([True, False, "fast", "1", [], {}, [0], [1e300]]))


def _get(data: Any, path: tuple) -> Any:
    for p in path:
        try:
            data = data[p]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _set(data: dict, path: tuple, value: Any) -> bool:
    node = data
    for p in path[:-1]:
        try:
            node = node[p]
        except (KeyError, IndexError, TypeError):
            return False
    if isinstance(node, dict) or (isinstance(node, list) and isinstance(path[-1], int) and path[-1] < len(node)):
        node[path[-1]] = value
        return True
    return False


def _non_finite(value: Any) -> bool:
    if isinstance(value, float):
        return not math.isfinite(value)
    if isinstance(value, list):
        return any(_non_finite(v) for v in value)
    if isinstance(value, dict):
        return any(_non_finite(v) for v in value.values())
    return False


def _huge(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return abs(value) >= 1e300
    if isinstance(value, list):
        return any(_huge(v) for v in value)
    return False


def _tiny(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return 0 < value <= 1e-300
    if isinstance(value, list):
        return any(_tiny(v) for v in value)
    return False


def refused_value(old: Any, new: Any, key: Any) -> bool:
    """Whether setting a key whose valid value is ``old`` to ``new`` must be refused (module docstring)."""
    if _non_finite(new) or _huge(new):
        return True
    numeric = isinstance(old, (int, float)) and not isinstance(old, bool)
    if numeric and (isinstance(new, (bool, str, dict)) or (isinstance(new, list))):
        return True
    numeric_list = isinstance(old, list) and old and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                         for v in old)
    if numeric_list and isinstance(new, list) and any(isinstance(v, (bool, str)) for v in new):
        return True
    return key in TINY_REFUSED and _tiny(new)


@st.composite
def command_inputs(draw, kind: str) -> tuple[dict, bool, dict[str, str]]:
    """(file as a dict, must_refuse, further files name -> text) for ``kind``; the files' damage is
    named in ``data["_damage"]`` (removed before writing)."""
    data = copy.deepcopy(BASES[kind])
    refused: dict[tuple, bool] = {}  # path -> its value must be refused (a later change of the path decides)

    def forget(path: tuple) -> None:  # the path and everything under it replaced or removed
        for p in [p for p in refused if p[:len(path)] == path]:
            del refused[p]

    for _ in range(draw(st.integers(0, 3))):
        action = draw(st.sampled_from(["set", "set", "set", "any", "delete", "unknown"]))
        path = draw(st.sampled_from(KEYS[kind]))
        old = _get(BASES[kind], path)
        if action == "delete":
            node = _get(data, path[:-1])
            if isinstance(node, dict) and path[-1] in node:
                del node[path[-1]]
                forget(path)
            continue
        if action == "unknown":
            name = (draw(st.sampled_from(["spead", "colour", "x_y"])),)
            value = draw(ANY_VALUE)
            if isinstance(value, dict) and any(isinstance(p, int) for p in path):
                continue  # a table inside an [[array]] table: to_toml cannot write it
            if _set(data, path[:-1] + name, value):
                refused[path[:-1] + name] = True
            continue
        value = draw(VALUES if action == "set" else ANY_VALUE)
        if isinstance(value, dict) and any(isinstance(p, int) for p in path):
            continue  # a table inside an [[array]] table: to_toml cannot write it
        if _set(data, path, value):
            forget(path)
            refused[path] = refused_value(old, value, path[-1])
    refuse = any(refused.values())
    files: dict[str, str] = {}
    if kind in ("lifetime", "rail"):
        lines = RECORDS if kind == "lifetime" else ["position_m,load_kN", "0,170", "3,170", "14,170", "17,170"]
        damage = draw(st.sampled_from(["intact"] * 8 + list(CSV_DAMAGE)))
        files["records.csv" if kind == "lifetime" else "train.csv"] = damaged_csv(lines, damage, draw(st.integers(0, 3)))
        refuse = refuse or damage in CSV_REFUSED or (kind == "rail" and damage == "same-time")
        files["_damage"] = damage
    return data, refuse, files


#: damages of a CSV input: a secret line planted, a header only, a 300,000-character field, a line repeated
#: (two records at one time; a train's axle twice), a time (or a load) of 1e300, an empty file, a NaN
CSV_DAMAGE = ("secret", "header-only", "huge-field", "same-time", "late", "empty", "nan")
#: the damages every command must refuse
CSV_REFUSED = ("header-only", "huge-field", "late", "empty", "nan")


def damaged_csv(lines: list[str], kind: str, at: int = 0) -> str:
    """The CSV ``lines`` with the damage ``kind`` (``CSV_DAMAGE``)."""
    lines = list(lines)
    if kind == "secret":
        lines.insert(min(at, len(lines)), f"{SECRET},{SECRET}")
    elif kind == "header-only":
        lines = lines[:1]
    elif kind == "huge-field":
        lines.insert(1, "9" * 300_000 + ",1")
    elif kind == "same-time":
        lines[2] = lines[1]
    elif kind == "late":
        cells = lines[2].split(",")
        cells[1] = "1e300"
        lines[2] = ",".join(cells)
    elif kind == "empty":
        lines = []
    elif kind == "nan":
        cells = lines[2].split(",")
        cells[-1 if len(cells) == 2 else 1] = "nan"
        lines[2] = ",".join(cells)
    return "\n".join(lines) + "\n"


def fuzz_settings(n: int, slow: bool):
    """Hypothesis settings of the command fuzz tests: ``n`` examples, derandomised unless ``slow``."""
    return settings(max_examples=n, deadline=None, database=None, derandomize=not slow,
                    suppress_health_check=list(HealthCheck), print_blob=True)


FILE_NAMES = {"lifetime": "LIFETIME.toml", "driveby": "DRIVEBY.toml", "rail": "RAIL.toml"}


def write_input(tmp: Path, kind: str, data: dict, files: dict[str, str]) -> Path:
    path = tmp / FILE_NAMES[kind]
    path.write_text(to_toml(data))
    for name, text in files.items():
        if not name.startswith("_"):
            (tmp / name).write_text(text)
    return path


def outcome(result: Any, refuse: bool) -> str:
    """The verdict of one ``vbikit validate`` run (module docstring)."""
    if result is None or isinstance(result.exception, Hang):
        return "hang"
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return "traceback"
    if SECRET in result.output:
        return "echo"
    if result.exit_code == 0:
        return "silent acceptance" if refuse else "ok"
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    if result.exit_code == 2 and len(errors) == 1 and "Traceback" not in result.output:
        return "clean"
    return f"exit {result.exit_code}"
