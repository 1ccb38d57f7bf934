"""The ``[bridge.deck]`` table of a scenario: the keys it may set, their documentation and its
translation into keyword arguments of [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge].

The keys are the model's dataclass fields (less those set elsewhere in a scenario or not
physical); their descriptions and units are read from the model's numpy-style docstring.
"""
from __future__ import annotations

import re
from dataclasses import fields

import numpy as np

from vbikit.bridge.girder_deck import SlabOnGirderBridge
from vbikit.bridge.sections import AASHTO_GIRDERS, GirderSection

#: model fields a ``[bridge.deck]`` table does not set: ``[bridge]`` keys (n_modes, damping_ratio,
#: damage), labels and cache settings
NOT_DECK_KEYS = ("n_modes", "damping_ratio", "use_cache", "cache_dir", "name", "damage")

#: the parameters a scenario may set in ``[bridge.deck]`` (n_modes and damping_ratio are ``[bridge]`` keys)
SCENARIO_PARAMETERS: tuple[str, ...] = tuple(f.name for f in fields(SlabOnGirderBridge) if f.name not in NOT_DECK_KEYS)


def deck_parameter_docs() -> dict[str, tuple[str, str]]:
    """``name -> (description, unit)`` of the [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge] parameters, read from its
    numpy-style docstring (``a, b : type`` lines; the unit is the description's bracketed text,
    the i-th one for the i-th name of a shared line, "" when dimensionless or not given)."""
    text: dict[str, str] = {}
    position: dict[str, int] = {}
    names: list[str] = []
    for line in (SlabOnGirderBridge.__doc__ or "").splitlines():
        m = re.match(r"^    (\w[\w, ]*?)\s*:\s*.+$", line) or re.match(r"^    (\w[\w, ]*)$", line)
        if m and not line.startswith("     "):
            names = [n.strip() for n in m.group(1).split(",")]
            for i, n in enumerate(names):
                text[n], position[n] = "", i
        elif line.startswith("        ") and names:
            for n in names:
                text[n] = (text[n] + " " + line.strip()).strip()
    out = {}
    for n, t in text.items():
        units = re.findall(r"\[([^\[\]]+)\]", t)
        unit = units[position[n]] if position[n] < len(units) else (units[0] if units else "")
        out[n] = (t, "" if unit == "-" else unit)
    return out


def deck_parameters(table: dict[str, object]) -> dict[str, object]:
    """Keyword arguments of [`SlabOnGirderBridge`][vbikit.bridge.SlabOnGirderBridge] from a scenario's ``[bridge.deck]`` table:
    ``girder`` is an AASHTO type ("I" … "VI") or a table {area, inertia, y_bottom, depth} [m², m⁴, m, m];
    ``diaphragms`` a list of x [m]; numbers as given (the constructor checks their ranges)."""
    def number(v: object, where: str) -> float:  # strict: no "12", no true, finite
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
            raise ValueError(f"bridge.deck.{where}: must be a finite number, got {v!r}")
        return float(v)

    out: dict[str, object] = {}
    for key, value in table.items():
        if key not in SCENARIO_PARAMETERS:
            raise ValueError(f"unknown [bridge.deck] key {key!r}; allowed: {', '.join(SCENARIO_PARAMETERS)}")
        if key == "girder" and not isinstance(value, (dict, str)) or key == "girder" and isinstance(value, str) \
                and value not in AASHTO_GIRDERS:
            raise ValueError(f"bridge.deck.girder: unknown girder type {value!r}; allowed: an AASHTO type "
                             f"({', '.join(AASHTO_GIRDERS)}) or a table {{area, inertia, y_bottom, depth}}")
        if key == "girder" and isinstance(value, dict):
            need = ("area", "inertia", "y_bottom", "depth")
            if sorted(value) != sorted(need):
                raise ValueError(f"bridge.deck.girder: a custom section needs exactly {', '.join(need)} [m², m⁴, m, m]")
            value = GirderSection(**{k: number(v, f"girder.{k}") for k, v in value.items()})
        elif key == "spans":
            if not isinstance(value, (list, tuple)) or not value:
                raise ValueError(f"bridge.deck.spans: must be a list of span lengths > 0 [m], got {value!r}")
            value = tuple(number(v, "spans") for v in value)
            if any(v <= 0 for v in value):
                raise ValueError(f"bridge.deck.spans: every span must be > 0 m, got {list(value)}")
        elif key == "diaphragms":
            if not isinstance(value, (list, tuple)):
                raise ValueError("bridge.deck.diaphragms: a list of x positions [m]")
            value = tuple(number(v, "diaphragms") for v in value)
        elif key not in ("girder", "name"):
            value = number(value, key) if not isinstance(value, int) or isinstance(value, bool) else value
            if key in ("n_girders", "n_elements", "default_girder") and not isinstance(value, int):
                raise ValueError(f"bridge.deck.{key}: must be an integer, got {value!r}")
        out[key] = value
    if "spans" in out and "span" not in out:  # the total length follows from the spans
        out["span"] = float(sum(out["spans"]))  # type: ignore[arg-type]
    return out
