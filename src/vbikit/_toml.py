"""Reading TOML input files (scenarios, studies, field tests) with errors of the caller's type."""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from vbikit._files import read_text

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def parse_toml(text: str, source: str, error: type[Exception]) -> dict[str, Any]:
    """Parse TOML ``text``; any problem (syntax, nesting too deep) raises ``error("<source>: not valid TOML: …")``."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise error(f"{source}: not valid TOML: {err}") from None
    except RecursionError:
        raise error(f"{source}: not valid TOML: tables or arrays nested too deeply") from None


def read_toml(path: str | Path, error: type[Exception], what: str = "file") -> dict[str, Any]:
    """Read and parse a TOML file; a missing or non-text file raises ``error`` naming the file."""
    return parse_toml(read_text(path, error, what), str(path), error)
