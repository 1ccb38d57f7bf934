"""The error fatigue functions raise on bad input."""
from __future__ import annotations

from vbikit.errors import VbikitError


class FatigueError(VbikitError):
    """Bad input to a fatigue function: the message starts with the argument it is about
    (``ranges: …``, ``curve: …``) and says what is allowed."""

    message_names_key = True


__all__ = ["FatigueError"]
