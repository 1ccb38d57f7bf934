"""Reading input files and writing output files: the one place for the rules every reader and
writer follows.

* **Atomic outputs** (``atomic_write``, ``write_text``, ``save_figure``): every output
  is written to a temporary file in the destination's folder and renamed over the destination
  (``os.replace``, atomic on POSIX and Windows).  A killed process, a full disk or any other
  failure leaves the previous file (or none) in place, never a partial one; the temporary file
  is removed.  A failure raises ``OutputError`` (an ``OSError``) naming the file.
* **Safe names** (``inside``): a file name taken from an input file (a field case name, …)
  may not leave the output folder.
* **Text inputs** (``read_text``): decoded as UTF-8; a file that is not text is refused
  with its name and without echoing its content.
"""
from __future__ import annotations

import errno
import os
import re
import tempfile
from pathlib import Path
from typing import Any, Callable


class OutputError(OSError):
    """An output file that could not be written (full disk, no permission, …); names the file."""


def _describe(err: OSError) -> str:
    if err.errno == errno.ENOSPC:
        return "no space left on the device"
    if err.errno == errno.EDQUOT:
        return "disk quota exceeded"
    return err.strerror or str(err)


def atomic_write(path: str | Path, write: Callable[[Path], None]) -> Path:
    """Call ``write(tmp)`` to write a temporary file next to ``path``, then rename it to ``path``.

    The destination folder is created if needed.  On any failure the temporary file is
    removed, ``path`` is untouched, and an ``OSError`` becomes ``OutputError`` naming ``path``.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
        os.close(fd)
    except OSError as err:
        raise OutputError(err.errno, f"cannot write {path}: {_describe(err)}") from None
    try:
        write(Path(tmp))
        os.replace(tmp, path)
    except OSError as err:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(err, OutputError):
            raise
        raise OutputError(err.errno, f"cannot write {path}: {_describe(err)}") from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    def write(tmp: Path) -> None:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())

    return atomic_write(path, write)


def figure_format(path: str | Path) -> str:
    """The figure format of ``path`` by its suffix (PNG without one); an
    [`OptionError`][vbikit.errors.OptionError] naming the file and the formats matplotlib writes when it
    has another suffix (checked before any computation by the commands that draw)."""
    from matplotlib.backend_bases import FigureCanvasBase

    from vbikit.errors import OptionError

    fmt = Path(path).suffix.lstrip(".").lower() or "png"
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise OptionError(f"{path}: figures are written as {', '.join(sorted(supported))} (by the file's suffix), "
                          f"not {fmt!r}")
    return fmt


def save_figure(fig: Any, path: str | Path, **kwargs: Any) -> Path:
    """``fig.savefig`` to ``path`` atomically (the format follows the file suffix, PNG without one;
    ``figure_format``)."""
    fmt = figure_format(path)
    return atomic_write(Path(path), lambda tmp: fig.savefig(tmp, format=fmt, **kwargs))


_SAFE_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._ +=-]*$")


def check_name(name: str, key: str) -> str:
    """``name`` if it can be used as a file name inside an output folder (letters, digits,
    ``. _ - + = space``, not starting with a dot or a separator), else ``ValueError`` naming ``key``."""
    if not _SAFE_NAME.match(name) or ".." in name or len(name) > 120:
        raise ValueError(f"{key} = {name!r} cannot be used in a file name: use letters, digits and . _ - + = "
                         "(no path separators, no '..', at most 120 characters)")
    return name


def inside(directory: str | Path, name: str) -> Path:
    """``directory / name``, refused (``ValueError``) if it would lie outside ``directory``
    (absolute names, ``..`` components, symbolic links pointing out)."""
    directory = Path(directory)
    base, full = os.path.realpath(directory), os.path.realpath(directory / name)
    if Path(name).is_absolute() or full == base or os.path.commonpath([base, full]) != base:
        raise ValueError(f"output name {name!r} leaves the output folder {directory}")
    return directory / name


def read_text(path: str | Path, error: type[Exception], what: str = "file") -> str:
    """The UTF-8 text of ``path``; a missing file, a folder or a file that is not UTF-8 text raises
    ``error`` naming the file (never its content)."""
    path = Path(path)
    if not path.is_file():
        raise error(f"{what} not found: {path}")
    try:
        data = path.read_bytes()
    except OSError as err:
        raise error(f"{path}: cannot read {what}: {err.strerror}") from None
    if b"\x00" in data:
        raise error(f"{path}: not a text file (binary content); expected a {what}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise error(f"{path}: not UTF-8 text (invalid byte at offset {err.start}); save the {what} as UTF-8") from None
    return text.removeprefix("\ufeff")


def json_safe(obj: Any, where: str = "") -> tuple[Any, list[str]]:
    """``obj`` (dicts, lists, numbers, numpy values) with every NaN or ±inf replaced by None, and
    the dotted keys that were replaced: JSON outputs never hold NaN or Infinity."""
    import math

    import numpy as np

    bad: list[str] = []

    def clean(value: Any, key: str) -> Any:
        if isinstance(value, np.ndarray):
            value = value.tolist()
        elif isinstance(value, np.generic):
            value = value.item()
        if isinstance(value, dict):
            return {k: clean(v, f"{key}.{k}" if key else str(k)) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [clean(v, f"{key}[{i}]") for i, v in enumerate(value)]
        if isinstance(value, float) and not math.isfinite(value):
            bad.append(key)
            return None
        if isinstance(value, Path):
            return str(value)
        return value

    return clean(obj, where), bad


def json_text(obj: Any, indent: int | None = None) -> str:
    """Strict JSON of ``obj`` (NaN/inf become null, see ``json_safe``)."""
    import json

    return json.dumps(json_safe(obj)[0], indent=indent, allow_nan=False)
