"""Fatigue: rainflow counting (ASTM E1049-85), also chunk by chunk with exact residual joining;
S-N curves of EN 1993-1-9 and AASHTO LRFD; Palmgren–Miner damage, equivalent ranges, remaining life.

Pure numerics (numpy, the ``rainflow`` package).  Stresses in Pa; curve names give the EN detail
category in MPa (``"EN 71"``) or the AASHTO letter (``"AASHTO C'"``).
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.fatigue.counting import rainflow, reversals
    from vbikit.fatigue.damage import damage_equivalent_range, equivalent_stress_range, miner_damage, remaining_life
    from vbikit.fatigue.errors import FatigueError
    from vbikit.fatigue.sn_curves import (AASHTO_CATEGORIES, EN_CATEGORIES, SN_CURVES, SNCurve, SNSegment, aashto_curve,
                                          curve_name, en1993_curve, sn_curve)
    from vbikit.fatigue.streaming import RainflowCounter, RainflowState, finish, histogram, join

__all__ = [
    "AASHTO_CATEGORIES",
    "EN_CATEGORIES",
    "FatigueError",
    "RainflowCounter",
    "RainflowState",
    "SNCurve",
    "SNSegment",
    "SN_CURVES",
    "aashto_curve",
    "curve_name",
    "damage_equivalent_range",
    "en1993_curve",
    "equivalent_stress_range",
    "finish",
    "histogram",
    "join",
    "miner_damage",
    "rainflow",
    "remaining_life",
    "reversals",
    "sn_curve",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.fatigue.counting": ["rainflow", "reversals"],
    "vbikit.fatigue.damage": ["damage_equivalent_range", "equivalent_stress_range", "miner_damage", "remaining_life"],
    "vbikit.fatigue.errors": ["FatigueError"],
    "vbikit.fatigue.sn_curves": ["AASHTO_CATEGORIES", "EN_CATEGORIES", "SN_CURVES", "SNCurve", "SNSegment",
                                 "aashto_curve", "curve_name", "en1993_curve", "sn_curve"],
    "vbikit.fatigue.streaming": ["RainflowCounter", "RainflowState", "finish", "histogram", "join"],
})
