"""What every worker of a lifetime run shares: the bridge and its crossing template, the
influence lines of the requested load effects (tabulated along the wheel tracks), the tire's
contact pattern and the lane centres — built once per process from a JSON-able description."""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any, Optional, Sequence

import numpy as np

from vbikit.bridge.base import GirderDeck
from vbikit.lifetime.influence import HALF_TRACK, InfluenceLine, Tabulated, TirePattern, deflection_line, effect_line


@dataclass
class Setup:
    """Built from ``(base, base_dir, effects, lanes, n_lanes, dx)`` (see ``build_setup``)."""

    context: Any  # vbikit.traffic.study.EventContext
    bridge: Any
    lines: list[InfluenceLine]
    tables: list[Tabulated]
    pattern: TirePattern
    lanes: tuple[float, ...]

    @property
    def span(self) -> float:
        return float(self.bridge.span)


_SETUPS: dict[str, Setup] = {}


def lane_centres(bridge, n_lanes: int, lanes: Optional[Sequence[float]]) -> tuple[float, ...]:
    """Lane centres y [m]: given, else the traffic default (two lanes at ∓ width/4 on a deck), a
    beam's every lane on its axis y = 0."""
    if lanes is not None:
        return tuple(float(y) for y in lanes)
    if not isinstance(bridge, GirderDeck):
        return (0.0,) * max(n_lanes, 1)
    from vbikit.traffic.study import default_lanes

    return tuple(default_lanes(bridge))


def _line(bridge, e: dict[str, Any]) -> InfluenceLine:
    kind, girder, name = e["kind"], e.get("girder"), e.get("name") or ""
    direction = e.get("direction") or "auto"
    if kind == "deflection":
        if girder is not None:
            if not isinstance(bridge, GirderDeck):
                raise ValueError("girder: the bridge has no girders")
            y = float(bridge.girder_y[bridge.girder_index(girder)])
        else:
            y = float(bridge.default_response_y) if e.get("y") is None else float(e["y"])
        x = float(bridge.default_x_at(y)) if e.get("x") is None else float(e["x"])
        if not 0.0 <= float(bridge.span_coordinate(x, y)) <= bridge.span:
            raise ValueError(f"x = {x:g} m is off the span 0 … {bridge.span:g} m")
        return deflection_line(bridge, x, y, name, direction)
    kw = {} if girder is None else {"girder": girder}
    if kind == "reaction":
        effect = bridge.load_effect("reaction", support=int(e["support"]), **kw)
    else:
        x = float(bridge.span) / 2 if e.get("x") is None else float(e["x"])
        effect = bridge.load_effect(kind, x=x, **kw)
    y = float(bridge.girder_y[bridge.girder_index(girder)]) if girder is not None else 0.0
    return effect_line(bridge, effect, name, y, direction)


def build_setup(key: str) -> Setup:
    """The ``Setup`` of a JSON description (cached per process)."""
    if key in _SETUPS:
        return _SETUPS[key]
    from vbikit.bridge.base import HasLoadEffects
    from vbikit.solve.crossing import require_every_result
    from vbikit.traffic.study import EventContext

    d = json.loads(key)
    base = {k: v for k, v in d["base"].items()}
    ctx = EventContext.of(base, d["base_dir"])
    require_every_result(ctx.template.crossing.resolve, "a lifetime's load effects need the step for every result",
                         where=" of the base scenario")
    bridge = ctx.template.crossing.bridge
    lines = []
    for i, e in enumerate(d["effects"]):
        if e["kind"] != "deflection" and not isinstance(bridge, HasLoadEffects):
            raise ValueError(f"load_effects[{i + 1}].kind: the bridge model offers no {e['kind']}")
        try:
            lines.append(_line(bridge, e))
        except ValueError as err:
            raise ValueError(f"load_effects[{i + 1}]: {err}") from None
    names = [ln.name for ln in lines]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"load_effects: two effects named {', '.join(dup)}; give each a name")
    lanes = lane_centres(bridge, d["n_lanes"], d["lanes"])
    pattern = TirePattern.of_crossing(ctx.template)
    tracks = sorted({y + s * HALF_TRACK for y in lanes for s in (-1.0, 1.0)})
    tables = [Tabulated(line, bridge, tracks, d["dx"]) for line in lines]
    setup = Setup(ctx, bridge, lines, tables, pattern, lanes)
    _SETUPS.clear()
    _SETUPS[key] = setup
    return setup


def setup_key(base: dict, base_dir: str, effects: list[dict], lanes: Optional[Sequence[float]], n_lanes: int,
              dx: float) -> str:
    """The canonical JSON description of a setup."""
    return json.dumps({"base": base, "base_dir": str(base_dir), "effects": effects,
                       "lanes": None if lanes is None else [float(y) for y in lanes], "n_lanes": int(n_lanes),
                       "dx": float(dx)}, sort_keys=True)


def day_events(setup: Setup, records) -> list[tuple[int, ...]]:
    """The events (vehicle indices) of one day's records (``vbikit.traffic.partition``; lengths
    from the axle spacings and the tire's reach)."""
    from vbikit.traffic.events import partition

    if not records:
        return []
    reach = setup.bridge.deck_overhang + setup.pattern.reach
    lengths = [r.length for r in records]
    return [e.vehicles for e in partition([r.time for r in records], [r.speed for r in records], lengths,
                                          setup.span, reach)]


def check_lanes(setup: Setup, lanes_used: Sequence[int]) -> None:
    """ValueError if a lane of the traffic has no centre, or its wheels leave the deck."""
    for lane in lanes_used:
        if not 1 <= lane <= len(setup.lanes):
            raise ValueError(f"lane {lane} of the records has no centre (lanes at y = "
                             f"{', '.join(f'{y:g}' for y in setup.lanes)} m; give traffic.lanes)")
    width = getattr(setup.bridge, "deck_width", None)  # a grillage's, a mode file's; a beam has none
    if width is not None and np.isfinite(width):
        for lane in lanes_used:
            y = setup.lanes[lane - 1]
            if abs(y) + HALF_TRACK > width / 2:
                raise ValueError(f"lane {lane} at y = {y:g} m puts wheels off the {width:g} m wide deck")


def tracks_of(setup: Setup) -> np.ndarray:
    return np.asarray(setup.tables[0].tracks) if setup.tables else np.zeros(0)
