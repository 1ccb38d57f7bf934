"""Small helpers for the words of messages and reports."""
from __future__ import annotations

from typing import Optional


def counted(n: int, noun: str, plural: Optional[str] = None, thousands: bool = False) -> str:
    """``n`` and ``noun``, singular for exactly one: ``counted(1, "exceedance")`` → "1 exceedance",
    ``counted(3, "exceedance")`` → "3 exceedances"; ``plural`` where adding "s" is wrong;
    ``thousands``: the count with thousands separators ("12,209 events")."""
    number = f"{n:,}" if thousands else f"{n}"
    return f"{number} {noun if n == 1 else (plural or noun + 's')}"


__all__ = ["counted"]
