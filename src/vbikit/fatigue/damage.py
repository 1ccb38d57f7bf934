"""Palmgren–Miner damage, damage-equivalent stress ranges and remaining life."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.fatigue._checks import positive, spectrum
from vbikit.fatigue.errors import FatigueError
from vbikit.fatigue.sn_curves import SNCurve


def miner_damage(ranges: Any, counts: Any, curve: SNCurve) -> float:
    """Palmgren–Miner damage sum D = Σ nᵢ / N(Δσᵢ) (EN 1993-1-9 A.5; AASHTO LRFD C6.6.1.2.5).

    Parameters
    ----------
    ranges : array_like
        Stress ranges Δσᵢ, Pa (e.g. from ``rainflow``).
    counts : array_like
        Cycles nᵢ at each range (half cycles 0.5).
    curve : SNCurve
        The resistance curve (``sn_curve("EN 71")``).

    Returns
    -------
    float
        The damage (1.0: failure by Miner's rule).  Ranges below the EN cut-off do nothing; with
        an AASHTO curve the whole spectrum does nothing when its largest range (with a count > 0)
        is below (ΔF)_TH.
    """
    if not isinstance(curve, SNCurve):
        raise FatigueError(f"curve: needs an SNCurve (e.g. sn_curve('EN 71')), got {type(curve).__name__}")
    r, n = spectrum(ranges, counts)
    live = n > 0
    if not live.any():
        return 0.0
    if curve.rule == "max-range" and r[live].max() < curve.threshold:
        return 0.0
    big_n = curve.cycles_to_failure(r[live])
    return float(np.sum(n[live] / big_n))


def equivalent_stress_range(ranges: Any, counts: Any, m: float = 3.0, n_ref: float = 2.0e6) -> float:
    """The constant stress range that does, in ``n_ref`` cycles, the damage of the spectrum on a
    single-slope curve of inverse slope m: Δσ_eq = (Σ nᵢ Δσᵢ^m / n_ref)^(1/m).

    (EN 1993-1-9 Δσ_E,2 with n_ref = 2·10⁶ and m = 3; AASHTO LRFD's effective stress range
    (Δf)_eff = (Σ γᵢ Δfᵢ³)^(1/3) is this with n_ref = Σ nᵢ, C6.6.1.2.5.)

    Parameters
    ----------
    ranges, counts : array_like
        The spectrum (Pa, cycles).
    m : float
        Inverse slope.
    n_ref : float
        Reference number of cycles.

    Returns
    -------
    float
        Δσ_eq, Pa.
    """
    r, n = spectrum(ranges, counts)
    m = positive(m, "m")
    n_ref = positive(n_ref, "n_ref")
    return float((np.sum(n * r**m) / n_ref) ** (1.0 / m))


def damage_equivalent_range(ranges: Any, counts: Any, curve: SNCurve, n_ref: float = 2.0e6) -> float:
    """The constant stress range whose ``n_ref`` cycles do the spectrum's Miner damage on ``curve``
    (bilinear curves included): Δσ with N(Δσ) = n_ref / D.  Zero when the damage is zero."""
    d = miner_damage(ranges, counts, curve)
    if d == 0.0:
        return 0.0
    return curve.stress_range_at(positive(n_ref, "n_ref") / d)


def remaining_life(damage_per_year: float, damage_so_far: float = 0.0, limit: float = 1.0) -> float:
    """Years until the Miner sum reaches ``limit`` at a constant yearly damage: (limit − D₀) / d.

    Parameters
    ----------
    damage_per_year : float
        Damage per year (≥ 0); 0 gives ``inf``.
    damage_so_far : float
        Damage already accumulated D₀ (≥ 0).
    limit : float
        Damage at failure (1.0 by Miner's rule).

    Returns
    -------
    float
        Years; 0 when the limit is already reached.
    """
    d = float(damage_per_year)
    d0 = float(damage_so_far)
    if not np.isfinite(d) or d < 0:
        raise FatigueError(f"damage_per_year: needs a finite number ≥ 0, got {damage_per_year!r}")
    if not np.isfinite(d0) or d0 < 0:
        raise FatigueError(f"damage_so_far: needs a finite number ≥ 0, got {damage_so_far!r}")
    lim = positive(limit, "limit")
    if d0 >= lim:
        return 0.0
    return float("inf") if d == 0.0 else (lim - d0) / d


__all__ = ["damage_equivalent_range", "equivalent_stress_range", "miner_damage", "remaining_life"]
