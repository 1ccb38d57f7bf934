"""Reading input files and writing output files: the one place for the rules every reader and
writer follows.

* **Atomic outputs** (``atomic_write``, ``write_text``, ``save_figure``): every output
  is written to a temporary file in the destination's folder and renamed over the destination
  (``os.replace``, atomic on POSIX and Windows).  A killed process, a full disk or any other
  failure leaves the previous file (or none) in place, never a partial one; the temporary file
  is removed.  A failure raises ``OutputError`` (an ``OSError``) naming the file.
* **Safe names** (``inside``): a file name taken from an input file (a field case name, …)
  may not leave the output folder.
* **Outputs readable as the umask says** (``atomic_write``): the temporary file is created
  with mode ``0o666`` less the process umask, as ``open`` would create the destination itself
  (folders: ``0o777`` less the umask), not the ``0o600`` of ``tempfile.mkstemp``.
* **User files** (``read_bytes``, ``read_text``): only a regular file is opened (a folder, FIFO,
  device or socket is refused before opening it: no hang on a FIFO without a writer, no endless
  read of ``/dev/zero``), of at most ``max_input_bytes()`` (``VBIKIT_MAX_INPUT_MB``, default
  ``DEFAULT_MAX_INPUT_MB``), checked before reading and again while reading (``/proc`` files
  report size 0).  Text is decoded as UTF-8; a file that is not text (NUL bytes, invalid UTF-8)
  is refused.  Every message names the file and never echoes its content.
* **CSV rows** (``csv_rows``): the lines of a CSV text as cells, a line longer than
  ``MAX_CSV_LINE`` characters refused before the ``csv`` module sees it (its field-size limit
  would raise a bare ``csv.Error``); a malformed line is refused naming its number only.
"""
from __future__ import annotations

import errno
import os
import re
import secrets
import stat
from pathlib import Path
from typing import Any, Callable


class OutputError(OSError):
    """An output file that could not be written (full disk, no permission, …); names the file."""

    def __str__(self) -> str:  # the message alone, without OSError's "[Errno 21] " before it
        return self.strerror if self.strerror and len(self.args) == 2 and self.filename is None else super().__str__()


def _describe(err: OSError) -> str:
    if err.errno == errno.ENOSPC:
        return "no space left on the device"
    if err.errno == errno.EDQUOT:
        return "disk quota exceeded"
    return err.strerror or str(err)


def _create_temporary(path: Path) -> str:
    """A new empty file ``.<name>.<random>.tmp`` beside ``path``, created exclusively (``O_EXCL``,
    not following links) with mode ``0o666`` less the umask: the mode ``path`` would get if written
    directly (``tempfile.mkstemp`` would give ``0o600`` whatever the umask)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        tmp = str(path.parent / f".{path.name}.{secrets.token_hex(4)}.tmp")
        try:
            os.close(os.open(tmp, flags, 0o666))
        except FileExistsError:
            continue
        return tmp
    raise FileExistsError(errno.EEXIST, f"no free temporary name beside {path}")


def atomic_write(path: str | Path, write: Callable[[Path], None]) -> Path:
    """Call ``write(tmp)`` to write a temporary file next to ``path``, then rename it to ``path``.

    The destination folder is created if needed.  On any failure the temporary file is
    removed, ``path`` is untouched, and an ``OSError`` becomes ``OutputError`` naming ``path``.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = _create_temporary(path)
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
    ``figure_format``), then close ``fig`` (also when writing fails), so that a library that
    draws many figures does not keep them open in pyplot."""
    try:
        fmt = figure_format(path)
        return atomic_write(Path(path), lambda tmp: fig.savefig(tmp, format=fmt, **kwargs))
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)


_SAFE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._ +=-]*")  # whole name (fullmatch: no trailing newline)


def check_name(name: str, key: str) -> str:
    """``name`` if it can be used as a file name inside an output folder (letters, digits,
    ``. _ - + = space``, not starting with a dot or a separator), else ``ValueError`` naming ``key``."""
    if not isinstance(name, str) or not _SAFE_NAME.fullmatch(name) or ".." in name or len(name) > 120:
        raise ValueError(f"{key} = {name!r} cannot be used in a file name: use letters, digits and . _ - + = "
                         "(no path separators, no '..', at most 120 characters)")
    return name


def shared_name(path: str | Path) -> str:
    """An input file's name as a dataset records it for others: a relative path as the user gave it
    (``sub/records.csv``), an absolute one by its name only (``/home/ann/wim/records.csv`` →
    ``records.csv``): a dataset shared with others does not carry the folders of the machine it ran on."""
    return Path(path).name if Path(path).is_absolute() else str(path)


#: the keys of a specification whose string values name files besides those containing "file" or "path"
#: (``shared_spec``): a lifetime file's ``traffic.records`` and ``base``, a rail ``bridge.scenario`` and
#: ``trains.tables``
FILE_KEYS = ("records", "base", "scenario", "tables")


def names_file(key: str) -> bool:
    """Whether a specification key names a file: ``modes_file``, ``profile_file``, ``*path*``, ``FILE_KEYS``."""
    return "file" in key or "path" in key or key in FILE_KEYS


def shared_spec(value: Any, key: str = "") -> Any:
    """A specification (parsed TOML or JSON: tables, arrays, strings, numbers) as a dataset or summary
    records it for others: a copy in which a string under a key naming a file (``names_file``: a lifetime
    file's ``traffic.records`` and ``base``, a ``modes_file``, a ``profile_file``, …; ``key``: that of
    ``value`` itself) that is an absolute path is reduced to its file name (``shared_name``:
    ``"/home/ann/wim/r.csv"`` → ``"r.csv"``), every other value as it is.  What a run read from those
    files is identified by their content (``file_sha256``), not by where they were."""
    if isinstance(value, dict):
        return {k: shared_spec(v, str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [shared_spec(v, key) for v in value]
    if isinstance(value, str) and names_file(key):
        return shared_name(value)
    return value


def file_sha256(path: str | Path) -> str:
    """The SHA-256 of the file ``path``'s bytes (read in blocks): an input file's identity in a resume
    check, independent of the folder it is in."""
    import hashlib

    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def input_digests(files: dict[str, str | Path]) -> dict[str, str]:
    """``file_sha256`` of each of ``files`` (key → path; e.g. ``{"bridge.modes_file": …}``), by the same
    keys; a file that cannot be read is recorded as ``"unreadable"`` (the run that needs it says why)."""
    out = {}
    for key, path in files.items():
        try:
            out[key] = file_sha256(path)
        except OSError:
            out[key] = "unreadable"
    return out


def inside(directory: str | Path, name: str) -> Path:
    """``directory / name``, refused (``ValueError``) if it would lie outside ``directory``
    (absolute names, ``..`` components, symbolic links pointing out)."""
    directory = Path(directory)
    base, full = os.path.realpath(directory), os.path.realpath(directory / name)
    if Path(name).is_absolute() or full == base or os.path.commonpath([base, full]) != base:
        raise ValueError(f"output name {name!r} leaves the output folder {directory}")
    return directory / name


#: folders no output folder may lie in (device files and the kernel's views, not storage)
_SYSTEM_DIRS = ("/dev", "/proc", "/sys")


def _system_dir(path: str | Path) -> str | None:
    """The system folder of ``_SYSTEM_DIRS`` that ``path`` lies in (also through a symbolic link), or None."""
    real = os.path.realpath(path)
    return next((d for d in _SYSTEM_DIRS if real == d or real.startswith(d + os.sep)), None)


def output_dir(path: str | Path, key: str = "--out-dir", create: bool = True) -> Path:
    """The output folder ``path``, created with its parents (``create``; else only checked: its
    nearest existing ancestor must be a writable folder); ``OutputError`` naming ``key`` when it
    names a file (or anything else that is not a folder), lies in ``/dev``, ``/proc`` or ``/sys``
    (also through a symbolic link), or cannot be created — checked before any computation."""
    path = Path(path)
    system = _system_dir(path)
    if system is not None:
        raise OutputError(f"{key} {path}: lies in {system}, a system folder; give a folder for the output files")
    if os.path.lexists(path) and not os.path.isdir(path):
        raise OutputError(f"{key} {path}: exists and is not a folder; give a folder for the output files")
    if not create:
        ancestor = Path(os.path.abspath(path))
        while not os.path.lexists(ancestor):
            ancestor = ancestor.parent
        if not os.path.isdir(ancestor):
            raise OutputError(f"{key} {path}: {ancestor} is not a folder; give a folder for the output files")
        if not os.access(ancestor, os.W_OK | os.X_OK):
            if ancestor == Path(os.path.abspath(path)):  # (the folder exists: writing into it is refused)
                raise OutputError(f"{key} {path}: the folder is not writable")
            raise OutputError(f"{key} {path}: cannot create the folder in {ancestor} (not writable)")
        return path
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise OutputError(f"{key} {path}: cannot create the folder: {_describe(err)}") from None
    if not os.access(path, os.W_OK | os.X_OK):
        raise OutputError(f"{key} {path}: the folder is not writable")
    return path


def output_names(out_dir: str | Path, files: tuple[str, ...] = (), folders: tuple[str, ...] = (),
                 key: str = "--out-dir") -> Path:
    """The output folder ``out_dir`` of a command that writes fixed ``files`` there and keeps its
    finished work (resumed by the next run) in ``folders`` there, checked before any computation:
    ``OutputError`` naming ``key`` and the path when one of ``files`` exists as a folder (or anything
    but a file or link), or one of ``folders`` as a file (was: the whole run, then ``[Errno 21] cannot
    write out/rail.nc: Is a directory``, or a bare ``[Errno 17] File exists``).  Nothing is created."""
    out_dir = Path(out_dir)
    for name in files:
        path = out_dir / name
        if os.path.lexists(path) and not os.path.isfile(path) and not os.path.islink(path):
            raise OutputError(f"{key} {out_dir}: {path} exists and is not a file; the run writes its {name} there: "
                              f"remove it or choose another {key}")
    for name in folders:
        path = out_dir / name
        if os.path.lexists(path) and not os.path.isdir(path):
            raise OutputError(f"{key} {out_dir}: {path} exists and is not a folder; the run keeps its finished work "
                              f"in the folder {name} there: remove it or choose another {key}")
    return out_dir


_FILE_ALLOWED = "give the path of a file in a writable folder (missing folders are created)"


def output_file(path: str | Path, key: str) -> Path:
    """The output file ``path``, checked before any computation (nothing is created; an existing
    file or symbolic link is replaced by the writers, ``atomic_write``); ``OutputError`` naming ``key``
    when it names a folder (or anything else that is not a regular file or a link), lies in ``/dev``, ``/proc`` or ``/sys``
    (also through a symbolic link), or its folder cannot hold it: the checks of ``output_dir`` on
    the parent folder (not a file, writable), which the writers create."""
    path = Path(path)
    system = _system_dir(path)
    if system is not None:
        raise OutputError(f"{key} {path}: lies in {system}, a system folder; {_FILE_ALLOWED}")
    if os.path.isdir(path):
        raise OutputError(f"{key} {path}: is a folder, not a file; {_FILE_ALLOWED}")
    if os.path.lexists(path) and not os.path.isfile(path) and not os.path.islink(path):
        # (a symbolic link, even a dangling one, is replaced by the writers like a file: os.replace)
        raise OutputError(f"{key} {path}: exists and is not a regular file; {_FILE_ALLOWED}")
    output_dir(path.parent, key=f"{key} {path}: its folder", create=False)
    return path


def not_an_input(path: str | Path, key: str, inputs: list[Any]) -> Path:
    """The output file ``path`` (of the option ``key``) unless it is one of the input files ``inputs``
    (the same file, also under another name or through a link): then ``OutputError`` naming both,
    checked before any computation — the output would replace the input (``vbikit run s.toml --out
    s.toml`` wrote the histories over the scenario)."""
    for given in inputs:
        try:
            same = os.path.samefile(path, given)
        except OSError:  # either does not exist (yet): not the same file
            same = False
        if same:
            raise OutputError(f"{key} {path}: is the input file {given}; writing it would replace the input: "
                              "give another path for the output")
    return Path(path)


def distinct_outputs(paths: dict[str, Any]) -> None:
    """``paths`` (option -> output file, None: not written) name different files, else ``OutputError``
    naming both options, before any computation: the second written would replace the first."""
    seen: dict[str, str] = {}
    for key, path in paths.items():
        if path is None:
            continue
        real = os.path.realpath(path)
        if real in seen:
            raise OutputError(f"{key} {path}: is also {seen[real]}'s file; give each output its own path")
        seen[real] = key


#: the largest input file read by default [MiB]; the environment variable ``MAX_INPUT_ENV`` sets another
DEFAULT_MAX_INPUT_MB = 256
MAX_INPUT_ENV = "VBIKIT_MAX_INPUT_MB"

_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))


def max_input_bytes(error: type[Exception] = ValueError) -> int:
    """The size limit of an input file [bytes]: ``VBIKIT_MAX_INPUT_MB`` MiB if set (a number > 0,
    else ``error``), else ``DEFAULT_MAX_INPUT_MB`` MiB."""
    import math

    text = os.environ.get(MAX_INPUT_ENV, "").strip()
    if not text:
        return DEFAULT_MAX_INPUT_MB * 2**20
    try:
        mb = float(text)
    except ValueError:
        mb = math.nan
    if not (math.isfinite(mb) and 0 < mb <= 2**40):
        raise error(f"{MAX_INPUT_ENV} must be a size in MiB > 0 (e.g. 1024), got {text!r}")
    return int(mb * 2**20)


def _size(n: int) -> str:
    return f"{n:,} bytes" if n < 2**20 else f"{n / 2**20:.1f} MiB"


def _too_large(path: Path, what: str, limit: int, size: str) -> str:
    return (f"{path}: the {what} is {size}, more than the {_size(limit)} allowed for an input file; "
            f"set the environment variable {MAX_INPUT_ENV} (in MiB) to read larger files")


def input_file(path: str | Path, error: type[Exception], what: str = "file") -> os.stat_result:
    """The ``os.stat`` of the user file ``path``, or ``error`` naming it when it is missing, cannot be
    examined or is not a regular file (a folder, FIFO, device or socket): the checks ``read_bytes``
    makes before opening a file, for a reader that only needs the file to exist."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        where = "" if os.path.isabs(path) else f" (looked for {os.path.abspath(path)})"  # (a relative path: from where)
        raise error(f"{what} not found: {path}{where}") from None
    except OSError as err:
        raise error(f"{path}: cannot read {what}: {err.strerror}") from None
    kind = next((name for test, name in _KINDS if test(st.st_mode)), None if stat.S_ISREG(st.st_mode) else "not a file")
    if kind is not None:
        raise error(f"{path} is {kind}, not a regular file; give the {what} as a file")
    return st


def read_bytes(path: str | Path, error: type[Exception], what: str = "file", max_bytes: int | None = None) -> bytes:
    """The bytes of the user file ``path``, refused with ``error`` naming the file (never its
    content) when it is missing, not a regular file (a folder, FIFO, device or socket: checked
    before opening it), or larger than ``max_bytes`` (default ``max_input_bytes()``; checked before
    reading and while reading)."""
    path = Path(path)
    limit = max_input_bytes(error) if max_bytes is None else int(max_bytes)
    st = input_file(path, error, what)
    if st.st_size > limit:
        raise error(_too_large(path, what, limit, _size(st.st_size)))
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)  # O_NONBLOCK: a FIFO put there since the check cannot block the open
    except OSError as err:
        raise error(f"{path}: cannot read {what}: {err.strerror}") from None
    with os.fdopen(fd, "rb") as fh:
        st = os.fstat(fh.fileno())
        if not stat.S_ISREG(st.st_mode):
            raise error(f"{path} is not a regular file; give the {what} as a file")
        blocks, total = [], 0
        try:  # in blocks: a file may grow while read, and /proc files report size 0
            while total <= limit:
                block = fh.read(min(max(st.st_size + 1, 1 << 16), limit + 1 - total))
                if not block:
                    break
                blocks.append(block)
                total += len(block)
        except OSError as err:
            raise error(f"{path}: cannot read {what}: {err.strerror}") from None
        data = b"".join(blocks)
    if len(data) > limit:
        raise error(_too_large(path, what, limit, "larger"))
    return data


def read_text(path: str | Path, error: type[Exception], what: str = "file", max_bytes: int | None = None) -> str:
    """The UTF-8 text of the user file ``path`` (``read_bytes``); a file that is not UTF-8 text
    (NUL bytes, invalid UTF-8) raises ``error`` naming the file (never its content)."""
    path = Path(path)
    data = read_bytes(path, error, what, max_bytes)
    nul = data.find(b"\x00")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise error(f"{path}:{line}: a NUL byte: not a text file (binary content); "
                    f"expected {'an' if what[:1] in 'aeiou' else 'a'} {what}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise error(f"{path}: not UTF-8 text (invalid byte at offset {err.start}); save the {what} as UTF-8") from None
    return text.removeprefix("\ufeff")


#: the longest line of a CSV input [characters]: 64 KiB (a table row of a few hundred numbers)
MAX_CSV_LINE = 1 << 16


def csv_rows(text: str, error: type[Exception], source: str, max_line: int = MAX_CSV_LINE,
             what: str = "CSV", max_rows: int | None = None,
             too_many: Callable[[int], str] | None = None) -> list[tuple[int, list[str]]]:
    """(line number, cells stripped of blanks) of every line of the CSV ``text`` that is neither
    blank nor a ``#`` comment.  A line longer than ``max_line`` characters, or one the ``csv``
    module cannot read (an unclosed quote, …), raises ``error`` naming ``source`` and the line
    number, never the line's content (``what``: the kind of file, for the message).  With
    ``max_rows``, more rows than that are refused (``error(too_many(rows))``) from a count of the
    lines before any is parsed."""
    import csv

    lines = text.split("\n")
    if max_rows is not None:
        n = sum(1 for line in lines if line.strip() and not line.lstrip().startswith("#"))
        if n > max_rows:
            raise error(too_many(n) if too_many else f"{source}: {n:,} rows, more than the {max_rows:,} allowed")
    out = []
    for no, line in enumerate(lines, start=1):
        if len(line) > max_line:
            raise error(f"{source}:{no}: a line of {len(line):,} characters; a {what} line holds at most {max_line:,}")
        line = line.rstrip("\r")
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            cells = next(csv.reader([line], strict=True))
        except (csv.Error, StopIteration):
            raise error(f"{source}:{no}: not a CSV line (a quote left open or misplaced)") from None
        out.append((no, [c.strip() for c in cells]))
    return out


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
