"""Where a running study keeps its work: the output's lock file and the finished-batch files.

* **Lock** (``lock_output``): ``<out>.lock``, held with ``filelock`` while a study writes to
  ``out``.  It must be a regular file of the output folder: a symbolic link there (dangling or
  not), a folder, a FIFO or a device is refused with a message instead of being followed (the
  file is created with ``O_NOFOLLOW``, never through a link).
* **Parts** (``save_part``, ``load_part``): every finished batch is one ``batch-NNNNNN.npz`` in
  ``<out>.parts/``, written atomically; the SHA-256 of its bytes is recorded in
  ``<out>.parts/SHA256SUMS`` (the format of ``sha256sum``, one line a part, appended before the
  part is renamed into place; the last line of a part counts).  A part whose bytes differ from
  the recorded checksum — rewritten after it was written, even as a valid file with other values
  — or that has no recorded checksum is not used: on resume it is moved aside and recomputed
  (``vbikit.study.run``), when the parts are assembled it is refused (``PartChangedError``).
  Recomputing is safe because every batch's result depends only on the study, so the dataset
  stays identical to that of an unbroken run.
"""
from __future__ import annotations

import errno
import hashlib
import io
import os
import re
import stat
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, Optional

import numpy as np

from vbikit._files import OutputError, atomic_write, read_bytes
from vbikit.study.spec import StudyError

#: the file of the parts' checksums, in the parts directory
CHECKSUMS = "SHA256SUMS"
_LINE = re.compile(r"^([0-9a-f]{64})  (batch-[0-9]{6}\.npz)$")


class PartChangedError(StudyError):
    """A finished part whose bytes are not those recorded when it was written."""


def parts_dir(out: Path) -> Path:
    """Directory of the finished-batch files of the study written to ``out``."""
    return out.with_name(out.name + ".parts")


def part_path(parts: Path, k: int) -> Path:
    """The file of finished batch ``k`` in the parts directory ``parts``."""
    return parts / f"batch-{k:06d}.npz"


def part_checksums(parts: Path) -> dict[str, str]:
    """The recorded SHA-256 of each part (file name → hex digest; the last line of a name counts;
    a malformed line, e.g. one cut short by a killed run, is skipped)."""
    try:
        text = (parts / CHECKSUMS).read_text(encoding="ascii", errors="replace")
    except FileNotFoundError:
        return {}
    sums = {}
    for line in text.splitlines():
        m = _LINE.match(line)
        if m:
            sums[m[2]] = m[1]
    return sums


def _record_checksum(parts: Path, name: str, digest: str) -> None:
    fd = os.open(parts / CHECKSUMS, os.O_WRONLY | os.O_APPEND | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o666)
    try:
        line = f"{digest}  {name}\n".encode()
        if os.write(fd, line) != len(line):
            raise OSError(errno.ENOSPC, "short write")
    finally:
        os.close(fd)


def save_part(parts: Path, k: int, arrays: dict, checksum: str) -> None:
    """Write the arrays of finished batch ``k`` (with its index and the study's ``checksum``) and
    record the SHA-256 of the file's bytes; atomic (``OutputError`` naming the file on failure)."""
    path = part_path(parts, k)

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays, batch_index=np.int64(k), spec_checksum=np.str_(checksum))
        _record_checksum(parts, path.name, hashlib.sha256(tmp.read_bytes()).hexdigest())

    atomic_write(path, write)


def part_bytes(parts: Path, k: int, sums: Optional[dict[str, str]] = None) -> tuple[bytes, Optional[str]]:
    """The bytes of part ``k`` and why they cannot be trusted (None if they match the recorded
    checksum); ``sums``: ``part_checksums(parts)`` if already read."""
    path = part_path(parts, k)
    data = read_bytes(path, StudyError, "study part", max_bytes=1 << 62)  # a regular file (no FIFO), any size
    recorded = (part_checksums(parts) if sums is None else sums).get(path.name)
    if recorded is None:
        return data, (f"no checksum of it is recorded in {CHECKSUMS} (written by an older vbikit version, or the run "
                      "stopped before recording it)")
    if hashlib.sha256(data).hexdigest() != recorded:
        return data, f"its contents changed after it was written (the SHA-256 differs from the one in {CHECKSUMS})"
    return data, None


def load_part(parts: Path, k: int, sums: Optional[dict[str, str]] = None) -> dict[str, np.ndarray]:
    """The arrays of the finished batch ``k`` in the parts directory ``parts``, verified against
    its recorded checksum (``PartChangedError`` if they differ; ``sums``: ``part_checksums(parts)``
    if already read)."""
    path = part_path(parts, k)
    if not path.is_file():
        raise StudyError(f"batch {k} has not finished ({path} missing)")
    data, problem = part_bytes(parts, k, sums)
    if problem:
        raise PartChangedError(f"study part {path} is not used: {problem}; run the same command again to recompute it")
    with np.load(io.BytesIO(data), allow_pickle=False) as part:
        return {name: part[name] for name in part.files}


def _not_a_file(path: Path, st: os.stat_result) -> Optional[str]:
    if stat.S_ISLNK(st.st_mode):
        return "a symbolic link"
    if stat.S_ISDIR(st.st_mode):
        return "a folder"
    return None if stat.S_ISREG(st.st_mode) else "not a regular file"


@contextmanager
def lock_output(out: Path) -> Iterator[None]:
    """Hold ``<out>.lock`` while the block runs (one writer per output; the OS releases the lock
    when its process ends, even by SIGKILL); the lock file is removed at the end.  A second
    holder gets ``StudyError``; a lock path that is a symbolic link or not a regular file gets
    ``StudyError`` naming it; an output folder where no file can be created gets ``OutputError``."""
    from filelock import FileLock, Timeout

    path = Path(str(out) + ".lock")
    refuse = (f"{path} is {{}}; a study's lock file must be a regular file in the output folder: remove it "
              "or write to another path")
    try:
        kind = _not_a_file(path, os.lstat(path))
    except FileNotFoundError:
        kind = None
    except OSError as err:
        raise OutputError(err.errno, f"--out {out}: cannot create files in {out.parent}: {err.strerror}") from None
    if kind:
        raise StudyError(refuse.format(kind))
    flags = os.O_WRONLY | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0) \
        | getattr(os, "O_CLOEXEC", 0)
    try:  # a folder where no file can be created (read-only, /proc) is not "locked by another study"
        fd = os.open(path, flags, 0o666)
    except OSError as err:
        if err.errno in (errno.ELOOP, errno.EISDIR, errno.ENXIO):  # a link, folder or FIFO put there since
            raise StudyError(refuse.format("not a regular file")) from None
        raise OutputError(err.errno, f"--out {out}: cannot create files in {out.parent}: {err.strerror}") from None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise StudyError(refuse.format("not a regular file"))
    finally:
        os.close(fd)
    lock = FileLock(str(path))
    try:
        lock.acquire(timeout=0)
    except Timeout:
        raise StudyError(f"another vbikit study is writing to {out} (lock {path}); wait for it to "
                         "finish or write to another path") from None
    try:
        if os.path.islink(path):  # replaced by a link between the check and the lock
            raise StudyError(refuse.format("a symbolic link"))
        yield
    finally:
        # no lock file beside a finished (or stopped) dataset: removed while still held, so a run
        # waiting on the old file cannot take it over; only a killed run leaves one (and the OS
        # has released it, so the next run simply takes it)
        if not os.path.islink(path):
            path.unlink(missing_ok=True)
        lock.release()
