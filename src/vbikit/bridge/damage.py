"""Local damage: a bending-stiffness reduction over a region of a beam span or of one girder.

A damaged region x ∈ [position, position + length] has EI_damaged = (1 − severity) · EI
(severity 0 = intact, 1 = no bending stiffness); the mass is unchanged.  This is the usual
"stiffness-loss" damage model of vibration-based damage detection (e.g. Doebling, Farrar &
Prime, *Shock and Vibration Digest* 30, 1998).  To first order the change of a squared
circular frequency is the Rayleigh quotient of the change, with the intact mass-normalised
mode φ (Rayleigh's perturbation result):

    Δ(ω²) ≈ −severity · ∫_region EI (∂²φ/∂x²)² dx

Regions with ``severity == 0`` are dropped before a model is built, so a zero-severity damage
gives the intact model bit for bit.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Optional

import numpy as np


@dataclass(frozen=True)
class Damage:
    """A stiffness loss over a region.

    Parameters
    ----------
    position : float
        Start of the damaged region [m from the bridge entry, x = 0].
    length : float
        Length of the region along x [m] (> 0).
    severity : float
        Relative loss of bending stiffness EI [-], 0 ≤ severity < 1.
    girder : int, optional
        Girder number (1-based) of a slab-on-girder deck; None on a beam.
    """

    position: float
    length: float
    severity: float
    girder: Optional[int] = None

    def __post_init__(self) -> None:
        for name in ("position", "length", "severity"):
            v = float(getattr(self, name))
            if not np.isfinite(v):
                raise ValueError(f"bridge.damage.{name} must be a finite number, got {v!r}")
            object.__setattr__(self, name, v)
        if self.position < 0:
            raise ValueError(f"bridge.damage.position must be >= 0 m, got {self.position}")
        if self.length <= 0:
            raise ValueError(f"bridge.damage.length must be > 0 m, got {self.length}")
        if not 0.0 <= self.severity < 1.0:
            raise ValueError(f"bridge.damage.severity must be in [0, 1), got {self.severity}")
        if self.girder is not None:
            if int(self.girder) != self.girder or self.girder < 1:
                raise ValueError(f"bridge.damage.girder must be an integer >= 1, got {self.girder!r}")
            object.__setattr__(self, "girder", int(self.girder))

    @property
    def end(self) -> float:
        return self.position + self.length

    def overlap(self, a: float, b: float) -> float:
        """Length [m] of [a, b] inside the damaged region."""
        return max(0.0, min(b, self.end) - max(a, self.position))


def active_damage(damage: Iterable[Damage]) -> tuple[Damage, ...]:
    """The damages with a non-zero severity (the others change nothing)."""
    return tuple(d for d in damage if d.severity > 0.0)


def stiffness_factor(damage: Iterable[Damage], a: float, b: float, girder: Optional[int] = None) -> float:
    """EI factor [-] of an element [a, b] [m]: 1 − Σ severity × (overlap / element length), over the
    damages on ``girder`` (all damages when ``girder`` is None and a damage has no girder).  Exact
    when the element lies wholly inside or outside each region; a smeared average otherwise."""
    factor = 1.0
    for d in damage:
        if d.severity > 0.0 and d.girder == girder:
            factor -= d.severity * d.overlap(a, b) / (b - a)
    if factor <= 0.0:
        raise ValueError("overlapping bridge.damage regions remove all bending stiffness of an element")
    return factor
