"""The messages of a failed pydantic validation of an input file (studies, lifetime and railway
files): one line per problem, naming the key as ``section.key``."""
from __future__ import annotations

import math
import re
import typing
from typing import Any, Optional

from pydantic import BaseModel, ValidationError

#: the largest step budget an option or key may set (--max-steps, max_steps): 1e12 steps, weeks of computing
MAX_STEPS_LIMIT = 1e12

#: a validator's message that names one of its section's keys first ("speed: must be …")
_KEY_FIRST = re.compile(r"^([A-Za-z_]+): ")


def _model_at(model: Optional[type], loc: tuple) -> Optional[type]:
    """The pydantic model reached from ``model`` along ``loc`` (field names and list indices), or None."""
    for part in loc:
        if model is None:
            return None
        if isinstance(part, int):
            continue
        field = getattr(model, "model_fields", {}).get(part)
        if field is None:
            return None
        model = _inner_model(field.annotation)
    return model


def _inner_model(annotation: Any) -> Optional[type]:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _inner_model(arg)
        if found is not None:
            return found
    return None


def allowed_keys(model: Optional[type], loc: tuple = ()) -> list[str]:
    """The keys the table at ``loc`` of the pydantic ``model`` takes (empty if unknown)."""
    inner = _model_at(model, loc)
    return list(getattr(inner, "model_fields", {})) if inner is not None else []


def validation_message(err: ValidationError, title: str, unknown_key: Optional[str] = None,
                       model: Optional[type] = None) -> str:
    """``title`` and one line per error: ``section.key: message``.  An unknown key says
    ``unknown_key`` (default "unknown key") and, given the ``model``, the keys its table takes; a
    missing one "missing required key", a wrong type what it got; a model validator's message that
    starts with a key name is put under that key."""
    lines = []
    for e in err.errors():
        loc = ".".join(str(p) for p in e["loc"])
        msg = e["msg"].removeprefix("Value error, ")
        key = _KEY_FIRST.match(msg)
        if key and e["type"] == "value_error":
            loc, msg = f"{loc}.{key.group(1)}" if loc else key.group(1), msg[key.end():]
        if e["type"] == "extra_forbidden":
            msg = unknown_key or "unknown key"
            keys = allowed_keys(model, tuple(e["loc"][:-1]))
            if keys:
                msg += f"; allowed: {', '.join(keys)}"
        elif e["type"] == "missing":
            msg = "missing required key"
        elif "input" in e and e["type"] != "value_error":
            msg = f"{msg} (got {e['input']!r})"
        lines.append(f"{loc}: {msg}" if loc else msg)
    return f"{title}:\n  " + "\n  ".join(lines) if title else "\n  ".join(lines)


def number(value: Any, key: str, lo: Optional[float] = None, hi: Optional[float] = None, *, lo_open: bool = False,
           hi_open: bool = False, integer: bool = False, unit: str = "", error: type[Exception] = ValueError) -> float:
    """``value`` as a float (an int for ``integer``), or ``error`` naming ``key`` and the allowed
    range: a number (no boolean, no string), finite, within [lo, hi] (``lo_open``/``hi_open``: the
    bound excluded).  The one strict check of a number read from an input file."""
    low = "" if lo is None else f"{'(' if lo_open else '['}{lo:g}"
    high = "" if hi is None else f"{hi:g}{')' if hi_open else ']'}"
    what = "an integer" if integer else "a number"
    rng = (f" in {low}, {high}" if lo is not None and hi is not None else
           f" {'>' if lo_open else '>='} {lo:g}" if lo is not None else
           f" {'<' if hi_open else '<='} {hi:g}" if hi is not None else "")
    expect = f"{key}: expected {what}{rng}{f' [{unit}]' if unit else ''}"
    ok_type = isinstance(value, int) if integer else isinstance(value, (int, float))
    if isinstance(value, bool) or not ok_type:
        raise error(f"{expect}, got {type(value).__name__} {_short(value)}")
    try:
        v = value if integer else float(value)
    except OverflowError:
        raise error(f"{expect}, got {_short(value)}") from None
    if (not integer and not math.isfinite(v)) or (lo is not None and (v <= lo if lo_open else v < lo)) or \
            (hi is not None and (v >= hi if hi_open else v > hi)):
        raise error(f"{expect}, got {_short(value)}")
    return int(value) if integer else v


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
