"""What to read from a crossing: the response points and the load effects (a response plan).

A [`ResponsePlan`][vbikit.analysis.ResponsePlan] is the part of a scenario that says where and what to report, kept
apart from the crossing (the physics): ``[response]`` / ``[[response.points]]`` in a scenario
file, or built directly from Python and passed to [`vbikit.run`][vbikit.scenario.run] beside a crossing.
"""
from __future__ import annotations

from dataclasses import dataclass

from vbikit.bridge.effects import LoadEffect

#: how moments, shears and reactions are computed (vbikit.analysis.effects)
DEFAULT_LOAD_EFFECT_METHOD = "mode-acceleration"


@dataclass(frozen=True)
class ResponsePoint:
    """One deck point responses are read at.

    Parameters
    ----------
    x : float or None
        Distance [m] from the entry support; None: the bridge's default section on the line y
        (midspan of the first span; on a skew deck that line's own).
    y : float or None
        Distance [m] from the deck centreline, positive left; None: the bridge's response line.
    girder : int, optional
        1-based girder (bridges with girders): the point is on its line (y, if also given, must be
        that line's).
    name : str
        Label of the point in reports, CSV columns and datasets (default ``p1``, ``p2``, … by position).
    """

    x: float | None = None
    y: float | None = None
    girder: int | None = None
    name: str = ""


def point_name(position: int, name: str | None = None) -> str:
    """A response point's name: its own, else ``p{position}`` (1-based) — the one naming rule of
    scenarios, reports, CSV columns and datasets."""
    return name or f"p{position}"


@dataclass(frozen=True)
class ResponsePlan:
    """Response points (at least one; the first is the headline point) and load effects.

    Parameters
    ----------
    points : tuple of ResponsePoint
        The response points, at least one, names unique; the first is the headline point
        (default: the bridge's default point).
    load_effects : tuple of LoadEffect
        Moments, shears and reactions to report (default none).
    load_effect_method : str
        How load effects are computed from the modes (``vbikit.analysis.effects``):
        ``"mode-acceleration"`` (default) or ``"mode-superposition"``.
    """

    points: tuple[ResponsePoint, ...] = (ResponsePoint(),)
    load_effects: tuple[LoadEffect, ...] = ()
    load_effect_method: str = DEFAULT_LOAD_EFFECT_METHOD

    def __post_init__(self) -> None:
        if not self.points:
            raise ValueError("a response plan needs at least one response point")
        names = self.point_names
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"response point names must be unique; repeated: {', '.join(dup)}")

    @property
    def point_names(self) -> list[str]:
        """Every point's name (``p{i}`` for an unnamed i-th point)."""
        return [point_name(i, p.name) for i, p in enumerate(self.points, start=1)]

    @property
    def first(self) -> ResponsePoint:
        return self.points[0]

    @property
    def first_effects(self) -> dict[str, LoadEffect]:
        """The first requested load effect of each kind present (``"moment"``, ``"shear"``,
        ``"reaction"``): the ones the per-crossing outputs of the catalogue report."""
        out: dict[str, LoadEffect] = {}
        for e in self.load_effects:
            out.setdefault(e.kind, e)
        return out
