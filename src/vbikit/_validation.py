"""The messages of a failed pydantic validation of an input file (studies, lifetime and railway
files): one line per problem, naming the key as ``section.key`` and a list's item as ``name[k]``
(k from 1, as every other message of vbikit counts items: ``key_name``)."""
from __future__ import annotations

import math
import re
import typing
from typing import Any, Optional

from pydantic import BaseModel, ValidationError

#: the largest step budget an option or key may set (--max-steps, max_steps): 1e12 steps, weeks of computing
MAX_STEPS_LIMIT = 1e12
#: the most local worker processes a file may ask for (a railway file's run.workers); ``--workers`` takes
#: up to ``workers_limit()``.  More processes than cores only wait for one (each holds its own copy of the
#: models; 100,000 asked for forked until the machine ran out of memory); a Dask cluster (--scheduler) for more
MAX_WORKERS = 64


def workers_limit() -> int:
    """The most local worker processes ``--workers`` takes: ``MAX_WORKERS``, or the machine's cores if more."""
    import os

    return max(MAX_WORKERS, os.cpu_count() or 1)


def checked_workers(value: Any, key: str = "workers", error: type[Exception] = ValueError) -> Optional[int]:
    """Local worker processes as given: None (the default: the input file's setting, else ``default_workers``) or an
    integer in [1, ``workers_limit()``], else ``error`` naming ``key`` and the range — the one check of the command
    line's ``--workers`` and of the Python entry points' ``workers`` (``run_study``, ``run_lifetime``, ``run_driveby``,
    ``run_rail``: a trial's ``run_study(…, workers=0)`` ran, ``workers=-3`` too, where the CLI refused 0)."""
    return None if value is None else int(number(value, key, 1, workers_limit(), integer=True, error=error))


def default_workers() -> int:
    """The local worker processes of a run whose command line (``--workers``) and input file leave them open: all
    cores — the one default of every command with local workers (``vbikit.cli.guard.WORKERS_HELP``)."""
    import os

    return os.cpu_count() or 1

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


def key_name(loc: tuple) -> str:
    """The key of a pydantic location as the messages name it: names joined by dots, a list's item
    ``k`` (0-based in ``loc``) as ``[k + 1]`` after its list's name: ``("trains", "hslm_b", 0, "d")``
    -> ``trains.hslm_b[1].d`` (pydantic's ``__root__`` left out).  The one place a location
    becomes a key name (of the scenario files too: ``vbikit.scenario.schema.error_path``)."""
    out = ""
    for part in loc:
        if part == "__root__":
            continue
        if isinstance(part, int) and not isinstance(part, bool):
            out += f"[{part + 1}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def validation_message(err: ValidationError, title: str, unknown_key: Optional[str] = None,
                       model: Optional[type] = None) -> str:
    """``title`` and one line per error: ``section.key: message``.  An unknown key says
    ``unknown_key`` (default "unknown key") and, given the ``model``, the keys its table takes; a
    missing one "missing required key", a wrong type what it got; a model validator's message that
    starts with a key name is put under that key."""
    lines = []
    for e in err.errors():
        loc = key_name(tuple(e["loc"]))
        msg = short_quotes(e["msg"].removeprefix("Value error, "))
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
        elif e["type"] in _BOUND_ERRORS + _INTEGER_ERRORS + _NUMBER_ERRORS:
            msg = bound_message(e, _field_at(model, tuple(e["loc"])))
        elif "input" in e and e["type"] != "value_error":
            msg = f"{msg} (got {short_value(e['input'])})"
        lines.append(f"{loc}: {msg}" if loc else msg)
    return f"{title}:\n  " + "\n  ".join(lines) if title else "\n  ".join(lines)


def _field_at(model: Optional[type], loc: tuple) -> Any:
    """The pydantic field (``FieldInfo``) of the key at ``loc`` of ``model`` (a list item: its
    list's field), None if unknown."""
    names = [p for p in loc if isinstance(p, str)]
    if not names:
        return None
    parent = _model_at(model, loc[:len(loc) - 1 - loc[::-1].index(names[-1])])
    return getattr(parent, "model_fields", {}).get(names[-1]) if parent is not None else None


def number(value: Any, key: str, lo: Optional[float] = None, hi: Optional[float] = None, *, lo_open: bool = False,
           hi_open: bool = False, integer: bool = False, unit: str = "", error: type[Exception] = ValueError) -> float:
    """``value`` as a float (an int for ``integer``), or ``error`` naming ``key`` and the allowed
    range: a number (no boolean, no string), finite, within [lo, hi] (``lo_open``/``hi_open``: the
    bound excluded).  The one strict check of a number read from an input file."""
    expect = f"{key}: {expected(lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit)}"
    ok_type = isinstance(value, int) if integer else isinstance(value, (int, float))
    if isinstance(value, bool) or not ok_type:
        raise error(f"{expect}, got {type(value).__name__} {short_value(value)}")
    try:
        v = value if integer else float(value)
    except OverflowError:
        raise error(f"{expect}, got {short_value(value)}") from None
    if (not integer and not math.isfinite(v)) or (lo is not None and (v <= lo if lo_open else v < lo)) or \
            (hi is not None and (v >= hi if hi_open else v > hi)):
        raise error(f"{expect}, got {short_value(value)}")
    return int(value) if integer else v


#: units that say "no unit" (a dimensionless number): not printed after a range
DIMENSIONLESS = ("1", "-")


def expected(lo: Optional[float] = None, hi: Optional[float] = None, *, lo_open: bool = False, hi_open: bool = False,
             integer: bool = False, unit: str = "", finite: bool = False) -> str:
    """``expected a number in [lo, hi] [unit]`` (or ``>= lo``, ``< hi`` …; ``lo_open``/``hi_open``:
    the bound excluded): the one wording of an allowed range, of ``number`` and of the bound errors
    of the input files' pydantic validations (``bound_message``)."""
    low = "" if lo is None else f"{'(' if lo_open else '['}{lo:g}"
    high = "" if hi is None else f"{hi:g}{')' if hi_open else ']'}"
    what = "an integer" if integer else "a finite number" if finite else "a number"
    rng = (f" in {low}, {high}" if lo is not None and hi is not None else
           f" {'>' if lo_open else '>='} {lo:g}" if lo is not None else
           f" {'<' if hi_open else '<='} {hi:g}" if hi is not None else "")
    return f"expected {what}{rng}{f' [{unit}]' if unit and unit not in DIMENSIONLESS else ''}"


#: pydantic's error types of a violated bound (``Field(ge=, gt=, le=, lt=)``)
_BOUND_ERRORS = ("greater_than", "greater_than_equal", "less_than", "less_than_equal")
#: pydantic's error types of a value that is not an integer where one is expected (20.5, "20")
_INTEGER_ERRORS = ("int_from_float", "int_parsing", "int_type")
#: pydantic's error types of a value that is not a finite number where one is expected ("30", true, inf)
_NUMBER_ERRORS = ("float_type", "float_parsing", "finite_number")
#: the unit at the end of a field's description: "speed at t = 0 [km/h]" -> km/h ("[-]": none)
_UNIT = re.compile(r"\[([A-Za-z0-9²³µ°/^·. -]{1,12})\]\s*$")


def _constraints(field: Any) -> list[Any]:
    """The bound objects (``annotated_types.Ge`` …) of a pydantic field, or of the items of a list
    field (``list[Annotated[float, Field(ge=…)]]``)."""
    found = list(getattr(field, "metadata", None) or [])
    todo = list(typing.get_args(getattr(field, "annotation", None)))
    while todo and not found:
        arg = todo.pop(0)
        for item in getattr(arg, "__metadata__", ()):  # Annotated[float, Field(ge=…)] or Annotated[float, Ge(…)]
            found += list(getattr(item, "metadata", None) or [item])
        todo += list(typing.get_args(arg))
    return found


def bound_message(error: dict, field: Any = None) -> Optional[str]:
    """The message of a pydantic bound error (``Input should be greater than or equal to 0.0036``), or
    of a value that is not an integer where one is expected (``Input should be a valid integer``), as
    ``expected`` words it, with both bounds of ``field`` (its pydantic ``FieldInfo``; None: the
    violated bound only) and the unit its description ends with; None for another error."""
    if error.get("type") not in _BOUND_ERRORS + _INTEGER_ERRORS + _NUMBER_ERRORS:
        return None
    bounds: dict[str, Any] = {"ge": None, "gt": None, "le": None, "lt": None}
    for item in _constraints(field):
        for name in bounds:
            if getattr(item, name, None) is not None:
                bounds[name] = getattr(item, name)
    bounds.update({k: v for k, v in (error.get("ctx") or {}).items() if k in bounds})
    lo_open, hi_open = bounds["gt"] is not None, bounds["lt"] is not None
    lo = bounds["gt"] if lo_open else bounds["ge"]
    hi = bounds["lt"] if hi_open else bounds["le"]
    annotation = getattr(field, "annotation", None)
    kinds = {annotation, *typing.get_args(annotation)}
    description = getattr(field, "description", None) or ""
    found = _UNIT.search(description)
    if found is not None:
        unit = found.group(1) if found.group(1).strip() != "-" else ""
    else:  # (a unit in brackets inside the description: "stress = effect / section_modulus [m³] (…)")
        from vbikit._words import split_unit

        unit = split_unit(description)[1]
    text = expected(None if lo is None else float(lo), None if hi is None else float(hi), lo_open=lo_open,
                    hi_open=hi_open, integer=(int in kinds and float not in kinds) or error["type"] in _INTEGER_ERRORS,
                    unit=unit,
                    finite=error["type"] == "finite_number")
    if "input" not in error:
        return text
    value = error["input"]
    quoted = " (a number is written without quotes)" if isinstance(value, str) else ""
    return f"{text}, got {short_value(value)}{quoted}"


#: the most characters of an input value a message quotes (``short_value``, ``short_quotes``): a message names the key
#: and the allowed values, and shows a value only as far as it tells which one was given, never a file's content
QUOTED_CHARACTERS = 40


def short_value(value: Any) -> str:
    """An input value as a message quotes it: its repr (TOML's true, false for a bool), cut to ``QUOTED_CHARACTERS``
    with "..."."""
    if isinstance(value, bool):  # (as the file writes it: TOML's true, false)
        return "true" if value else "false"
    text = repr(value)
    return text if len(text) <= QUOTED_CHARACTERS else text[:QUOTED_CHARACTERS - 3] + "..."


#: a quoted value as ``repr`` writes one: its opening quote after no letter or quote (not the prime of AASHTO's "C'"),
#: its first character no space (not the text between two quoted values), then ``QUOTED_CHARACTERS`` − 2 more
_LONG_QUOTE = re.compile(r"(?<![\w'\"])'[^'\s][^'\n]{%d,}'|(?<![\w'\"])\"[^\"\s][^\"\n]{%d,}\""
                         % (QUOTED_CHARACTERS - 2, QUOTED_CHARACTERS - 2))


def short_quotes(message: str) -> str:
    """``message`` with every quoted value longer than ``QUOTED_CHARACTERS`` cut as ``short_value`` cuts it
    (``unknown bridge model 'XXXX…'`` of a 5,000-character value: its first 37 characters and "..."): what a
    validator's own message quotes of the input (``{value!r}``) as the formatters here pass it on."""
    def cut(m: re.Match) -> str:
        return m.group(0)[:QUOTED_CHARACTERS - 3] + "..."

    return _cut_brackets(_LONG_QUOTE.sub(cut, message))


_OPENING = {"[": "]", "{": "}", "(": ")"}


def _cut_brackets(message: str) -> str:
    """``message`` with every list, table or tuple quoted after "got " (``got [0.1, 0.2, …]``, a validator's
    ``{value!r}``) longer than ``QUOTED_CHARACTERS`` cut as ``short_value`` cuts it (to its matching bracket)."""
    out, at = [], 0
    while (start := message.find("got ", at)) >= 0:
        begin = start + 4
        if begin >= len(message) or message[begin] not in _OPENING:
            out.append(message[at:begin])
            at = begin
            continue
        depth, end = 0, begin
        for end in range(begin, len(message)):
            depth += message[end] in _OPENING
            depth -= message[end] in _OPENING.values()
            if depth == 0:
                break
        value = message[begin:end + 1]
        out.append(message[at:begin] + (value if len(value) <= QUOTED_CHARACTERS
                                        else value[:QUOTED_CHARACTERS - 3] + "..."))
        at = end + 1
    return "".join(out) + message[at:]
