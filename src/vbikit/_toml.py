"""Reading TOML input files (scenarios, studies, field tests) with errors of the caller's type."""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def parse_toml(text: str, source: str, error: type[Exception]) -> dict[str, Any]:
    """Parse TOML ``text``; a syntax error raises ``error("<source>: not valid TOML: …")``."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise error(f"{source}: not valid TOML: {err}") from None


def read_toml(path: str | Path, error: type[Exception], what: str = "file") -> dict[str, Any]:
    """Read and parse a TOML file; a missing file raises ``error("<what> not found: <path>")``."""
    path = Path(path)
    if not path.is_file():
        raise error(f"{what} not found: {path}")
    return parse_toml(path.read_text(), str(path), error)
