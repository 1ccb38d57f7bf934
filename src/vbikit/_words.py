"""Small helpers for the words of messages and reports."""
from __future__ import annotations

import re
from typing import Optional


def raise_budget(key: str, option: str, most: float) -> str:
    """The one advice of a refused budget that the input file and the command line both set (``vbikit driveby``,
    ``rail``, ``lifetime``): "raise KEY in the input file or OPTION on the command line (at most MOST)"."""
    return f"raise {key} in the input file or {option} on the command line (at most {most:g})"


def duration_words(hours: float) -> str:
    """A run-time estimate [h] in words: seconds, minutes or hours ("40 s", "12 min", "3.5 h")."""
    return f"{hours * 3600:.0f} s" if hours < 1 / 60 else f"{hours * 60:.0f} min" if hours < 2 else f"{hours:.1f} h"


def counted(n: int, noun: str, plural: Optional[str] = None, thousands: bool = False) -> str:
    """``n`` and ``noun``, singular for exactly one: ``counted(1, "exceedance")`` → "1 exceedance",
    ``counted(3, "exceedance")`` → "3 exceedances"; ``plural`` where adding "s" is wrong;
    ``thousands``: the count with thousands separators ("12,209 events")."""
    number = f"{n:,}" if thousands else f"{n}"
    return f"{number} {noun if n == 1 else (plural or noun + 's')}"


#: a unit in brackets at the end of a description ("span length [m]")
_UNIT = re.compile(r"\[([^\[\]]+)\]\s*$")
#: the words a unit in a description is made of (anything else in brackets is not a unit)
_UNIT_WORDS = {"m", "kg", "s", "N", "Pa", "Hz", "rad", "km", "h", "cycle", "mm", "kN", "GPa"}


def _is_unit(text: str) -> bool:
    words = re.findall(r"[A-Za-z]+", text)
    return text == "-" or (bool(words) and all(w in _UNIT_WORDS for w in words))


def split_unit(description: str) -> tuple[str, str]:
    """(meaning, unit) of a schema field's description with its SI unit in brackets — the one place a
    key's unit is written (``Field(description="bending stiffness [N m^2]")``): at the end (then
    removed from the meaning) or, failing that, the first bracket that is a unit (kept in place);
    "" for a dimensionless ("[-]") or unitless key; ``^2`` / ``^3`` as ² / ³.  The key references
    of docs/reference and ``vbikit presets`` read units through it."""
    m = _UNIT.search(description)
    if m and _is_unit(m.group(1)):
        unit, meaning = m.group(1), description[: m.start()].rstrip(" ;,")
    else:
        inner = [u for u in re.findall(r"(?<!\[)\[([^\[\]]+)\](?!\])", description) if _is_unit(u)]
        if not inner:
            return description, ""
        unit, meaning = inner[0], description
    return meaning, ("" if unit == "-" else unit.replace("^2", "²").replace("^3", "³"))


__all__ = ["counted", "split_unit"]
