"""The one base class of user errors.

Every error that bad input causes — a scenario, study, field or records file, a mode or road
file, a budget or a time step the run refuses — is a [`VbikitError`][vbikit.errors.VbikitError]: the command line
prints its message on one line and exits with code 2.  Any other exception is a programming
error and shows its traceback.  ``VbikitError`` is a ``ValueError``, so code that caught the
specific errors as ``ValueError`` keeps working.
"""
from __future__ import annotations

import re
from typing import Any

#: a message that starts with the key it is about: ``bridge.deck.span: …``, ``road.defects[2].depth = …``,
#: or after a heading line (``invalid scenario:\n  crossing.speed: …``)
_LEADING_KEY = re.compile(r"^(?:[^\n]*:\n\s*)?([A-Za-z_][\w\-]*(?:\[\d+\])*(?:\.[\w\-]+(?:\[\d+\])*)*)(?::\s| = )")
#: a leading ``name.toml: …`` is the file, not a key
_FILE_SUFFIXES = {"toml", "csv", "json", "nc", "txt"}


class VbikitError(ValueError):
    """An error caused by the user's input; the message says what to change.

    Parameters
    ----------
    *args : str
        The message: one self-contained sentence (or a heading and indented lines) naming the input.
    key : str, optional
        The scenario (or study, field-file) key the error concerns, e.g. ``"crossing.speed"``;
        None where the error is not about one key.  Classes whose messages start with their key
        (``message_names_key``) read it from the message when it is not given.
    """

    #: the message starts with the key it concerns (``key: …`` or ``key = …``)
    message_names_key = False

    def __init__(self, *args: Any, key: str | None = None) -> None:
        super().__init__(*args)
        if key is None and self.message_names_key and args and isinstance(args[0], str):
            match = _LEADING_KEY.match(args[0])
            key = match.group(1) if match and match.group(1).rsplit(".", 1)[-1] not in _FILE_SUFFIXES else None
        self.key = key

    def __reduce__(self) -> tuple[Any, ...]:  # keep ``key`` through pickling (study worker processes)
        return (_rebuild, (type(self), self.args, self.key))


def _rebuild(cls: type[VbikitError], args: tuple[Any, ...], key: str | None) -> VbikitError:
    err = cls.__new__(cls)
    ValueError.__init__(err, *args)
    err.key = key
    return err


#: a message's heading line of schema errors: ``invalid scenario:`` (the key lines follow, indented)
_HEADING = re.compile(r"^(invalid [^\n:]+):\n")


def naming_file(message: str, path: Any) -> str:
    """``message``, of an error about the input file ``path``, with the file named in its first line:
    ``invalid scenario:`` / key lines become ``invalid scenario bad.toml:`` / key lines, any other
    message ``bad.toml: message``.  A first line that already names ``path`` (the readers' own errors:
    ``bad.toml: not valid TOML …``, ``records.csv:3: …``) is kept as it is, as is a message about a
    command-line option (``--scheduler …: cannot connect``).  ``path`` is written as given
    (``str(path)``), never the file's content."""
    name = str(path)
    first = message.split("\n", 1)[0]
    if first.startswith("--") or re.search(rf"(?<![\w./\\-]){re.escape(name)}(?!\w|\.\w)", first):
        return message
    heading = _HEADING.match(message)
    if heading:
        return f"{heading.group(1)} {name}:\n{message[heading.end():]}"
    return f"{name}: {message}"


class OptionError(VbikitError):
    """A command-line option value that cannot be used (``--max-memory 4XB``, ``--tires foo``)."""

    message_names_key = True


__all__ = ["OptionError", "VbikitError", "naming_file"]
