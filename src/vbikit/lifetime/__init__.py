"""Lifetime load effects with dynamics: years of traffic from a records file, every event's static
peak by influence lines, coupled dynamics for the events that can govern (the screening rule),
extreme-value characteristic values and the assessment dynamic ratio, and fatigue damage.

``run_lifetime(spec, out_dir)`` (``vbikit lifetime FILE --out-dir DIR``) writes ``lifetime.nc``
(see docs/lifetime.md).
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.lifetime.influence import (InfluenceLine, Tabulated, TirePattern, deflection_line, effect_line,
                                           event_static, point_loads)
    from vbikit.lifetime.run import Prepared, prepare, run_lifetime, screen
    from vbikit.lifetime.screening import candidates, top_events
    from vbikit.lifetime.spec import LifetimeError, LifetimeFile, parse_lifetime, read_lifetime
    from vbikit.lifetime.traffic import NormalMixture, TrafficModel, fit_mixture, fit_traffic

__all__ = [
    "InfluenceLine",
    "LifetimeError",
    "LifetimeFile",
    "NormalMixture",
    "Prepared",
    "Tabulated",
    "TirePattern",
    "TrafficModel",
    "candidates",
    "deflection_line",
    "effect_line",
    "event_static",
    "fit_mixture",
    "fit_traffic",
    "parse_lifetime",
    "point_loads",
    "prepare",
    "read_lifetime",
    "run_lifetime",
    "screen",
    "top_events",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.lifetime.influence": ["InfluenceLine", "Tabulated", "TirePattern", "deflection_line", "effect_line",
                                  "event_static", "point_loads"],
    "vbikit.lifetime.run": ["Prepared", "prepare", "run_lifetime", "screen"],
    "vbikit.lifetime.screening": ["candidates", "top_events"],
    "vbikit.lifetime.spec": ["LifetimeError", "LifetimeFile", "parse_lifetime", "read_lifetime"],
    "vbikit.lifetime.traffic": ["NormalMixture", "TrafficModel", "fit_mixture", "fit_traffic"],
})
