"""Axis labels from dataset units: the CF/UDUNITS spelling of a dataset (``"km h-1"``) as a reader
writes it on a figure (``"km/h"``); the one place figures turn a unit into text."""
from __future__ import annotations

import re
from typing import Any

_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_TERM = re.compile(r"^([A-Za-zµ°]+)(-?\d+)?$")


def unit_label(cf_unit: str) -> str:
    """A unit in CF/UDUNITS spelling written for a figure: ``"km h-1"`` → ``"km/h"``, ``"m s-2"`` →
    ``"m/s²"``, ``"N m2"`` → ``"N·m²"``, ``"1"`` or ``""`` → ``"-"``; anything else unchanged."""
    text = (cf_unit or "").strip()
    if text in ("", "1"):
        return "-"
    terms = [_TERM.match(t) for t in text.split()]
    if not all(terms):
        return text
    num, den = [], []
    for m in terms:
        base, power = m.group(1), int(m.group(2) or 1)
        shown = base + (str(abs(power)).translate(_SUPERSCRIPT) if abs(power) != 1 else "")
        (den if power < 0 else num).append(shown)
    top = "·".join(num) or "1"
    if not den:
        return top
    return f"{top}/{den[0]}" if len(den) == 1 else f"{top}/({'·'.join(den)})"


def axis_label(variable: Any, name: str | None = None) -> str:
    """``"name [unit]"`` for an xarray variable or coordinate: its ``long_name`` (or ``name``) and
    its ``units`` attribute through [`unit_label`][vbikit.plot.labels.unit_label]."""
    attrs = getattr(variable, "attrs", {})
    text = name or attrs.get("long_name") or str(getattr(variable, "name", ""))
    return f"{text} [{unit_label(str(attrs.get('units', '')))}]"
