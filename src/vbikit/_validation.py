"""The messages of a failed pydantic validation of an input file (studies, lifetime and railway
files): one line per problem, naming the key as ``section.key``."""
from __future__ import annotations

import re
from typing import Optional

from pydantic import ValidationError

#: a validator's message that names one of its section's keys first ("speed: must be …")
_KEY_FIRST = re.compile(r"^([A-Za-z_]+): ")


def validation_message(err: ValidationError, title: str, unknown_key: Optional[str] = None) -> str:
    """``title`` and one line per error: ``section.key: message``.  An unknown key says
    ``unknown_key`` (default "unknown key"), a missing one "missing required key", a wrong type
    what it got; a model validator's message that starts with a key name is put under that key."""
    lines = []
    for e in err.errors():
        loc = ".".join(str(p) for p in e["loc"])
        msg = e["msg"].removeprefix("Value error, ")
        key = _KEY_FIRST.match(msg)
        if key and e["type"] == "value_error":
            loc, msg = f"{loc}.{key.group(1)}" if loc else key.group(1), msg[key.end():]
        if e["type"] == "extra_forbidden":
            msg = unknown_key or "unknown key"
        elif e["type"] == "missing":
            msg = "missing required key"
        elif "input" in e and e["type"] != "value_error":
            msg = f"{msg} (got {e['input']!r})"
        lines.append(f"{loc}: {msg}" if loc else msg)
    return f"{title}:\n  " + "\n  ".join(lines) if title else "\n  ".join(lines)
