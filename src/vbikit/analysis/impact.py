"""Static reference and impact factor.

The static reference is the same bridge model (same modes) under the vehicle's static wheel
loads moved along the same path: at each time t the contact points carry their static
share β_p·P_w of the wheel load P_w (from the vehicle's equilibrium on flat rigid ground)
and ξ_st(t) = −Σ_p φ(x_p(t)) β_p P_w / ω² (downward loads, z up).

Impact factor (paper, §3):  IM = (R_dyn,max − R_st,max) / R_st,max, where R is the response
measured in the direction of the static peak (downward for deflection, tension for
bottom-fibre strain), so R_max = max_t(s·R(t)) with s the sign of the static peak.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.solve import system
from vbikit.solve.result import CrossingResult


def static_modal_history(result: CrossingResult) -> NDArray[np.float64]:
    """ξ_st(t) (n_t, n_modes): static modal coordinates under the moving static wheel loads."""
    return system.static_modal_history(result.crossing, result.travel)


@dataclass(frozen=True)
class ImpactFactor:
    """Peak dynamic and static responses (signed, largest magnitude in the load direction) and IM."""

    dynamic_peak: float
    static_peak: float
    impact_factor: float
    time_dynamic_peak: float
    time_static_peak: float


def impact_factor(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64]) -> ImpactFactor:
    """IM = (R_dyn,max − R_st,max)/R_st,max with peaks taken in the static peak's direction."""
    i_st = int(np.argmax(np.abs(static)))
    sign = np.sign(static[i_st]) or 1.0
    if static[i_st] == 0.0:
        raise ValueError("the static response is zero everywhere: no impact factor at this response point")
    i_dyn = int(np.argmax(sign * dynamic))
    r_dyn, r_st = float(dynamic[i_dyn]), float(static[i_st])
    return ImpactFactor(r_dyn, r_st, (sign * r_dyn - sign * r_st) / (sign * r_st), float(time[i_dyn]), float(time[i_st]))
