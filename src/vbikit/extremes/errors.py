"""The error extreme-value functions raise on bad input."""
from __future__ import annotations

from vbikit.errors import VbikitError


class ExtremesError(VbikitError):
    """Bad input to an extreme-value function: the message starts with the argument it is about
    (``maxima: …``, ``threshold: …``) and says what is allowed."""

    message_names_key = True


__all__ = ["ExtremesError"]
