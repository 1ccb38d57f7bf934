"""Palmgren–Miner damage, damage-equivalent stress ranges and remaining life."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.fatigue._checks import positive, spectrum
from vbikit.fatigue.errors import FatigueError
from vbikit.fatigue.sn_curves import SNCurve


def miner_damage(ranges: Any, counts: Any, curve: SNCurve, whole_spectrum: bool = True) -> float:
    """Palmgren–Miner damage sum D = Σ nᵢ / N(Δσᵢ) (EN 1993-1-9 A.5; AASHTO LRFD C6.6.1.2.5).

    Parameters
    ----------
    ranges : array_like
        Stress ranges Δσᵢ, Pa (e.g. from ``rainflow``).
    counts : array_like
        Cycles nᵢ at each range (half cycles 0.5).
    curve : SNCurve
        The resistance curve (``sn_curve("EN 71")``).
    whole_spectrum : bool
        True (default): the ranges are the detail's whole loading, so they do nothing when the
        largest (with a count > 0) is below the curve's constant-amplitude fatigue limit
        ``curve.threshold`` (EN 1993-1-9:2005 1.3.3.3, Δσ_D; AASHTO LRFD 6.6.1.2.5, (ΔF)_TH).
        False: they are a part of a longer loading (a day, an event, a chunk), whose damages
        add up; the limit rule is then the caller's, applied once to the whole loading.

    Returns
    -------
    float
        The damage (1.0: failure by Miner's rule); ranges below the EN cut-off Δσ_L do nothing.
    """
    if not isinstance(curve, SNCurve):
        raise FatigueError(f"curve: needs an SNCurve (e.g. sn_curve('EN 71')), got {type(curve).__name__}")
    r, n = spectrum(ranges, counts)
    live = n > 0
    if not live.any():
        return 0.0
    if whole_spectrum and r[live].max() < curve.threshold:
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
    (bilinear curves included): Δσ with N(Δσ) = n_ref / D.  Zero when the damage is zero.

    On a curve with a cut-off (EN 1993-1-9) no range does less than n_ref / N_L damage in n_ref
    cycles (N_L = 10⁸): a smaller damage raises a FatigueError naming ``n_ref``, the largest
    n_ref = D · N_L that works, and ``equivalent_stress_range`` as the single-slope alternative."""
    n_ref = positive(n_ref, "n_ref")
    d = miner_damage(ranges, counts, curve)
    if d == 0.0:
        return 0.0
    last = curve.segments[-1]
    if curve.rule == "cutoff":
        n_cut = last.n_ref * (last.stress_ref / last.stress_min) ** last.m
        if n_ref / d > n_cut:
            raise FatigueError(f"n_ref: the spectrum's damage D = {d:.4g} is below n_ref / N_L = {n_ref:g} / "
                               f"{n_cut:.4g}: no range of {curve.name} above its cut-off does that little in "
                               f"{n_ref:g} cycles; use n_ref ≤ D · N_L = {d * n_cut:.4g}, or "
                               f"equivalent_stress_range (single slope)")
    return curve.stress_range_at(n_ref / d)


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
    d = _non_negative(damage_per_year, "damage_per_year")
    d0 = _non_negative(damage_so_far, "damage_so_far")
    lim = positive(limit, "limit")
    if d0 >= lim:
        return 0.0
    return float("inf") if d == 0.0 else (lim - d0) / d


def _non_negative(value: Any, name: str) -> float:
    """``value`` as a finite float ≥ 0, or a FatigueError naming ``name``."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise FatigueError(f"{name}: needs a finite number ≥ 0, got {value!r}") from None
    if not np.isfinite(v) or v < 0:
        raise FatigueError(f"{name}: needs a finite number ≥ 0, got {value!r}")
    return v


__all__ = ["damage_equivalent_range", "equivalent_stress_range", "miner_damage", "remaining_life"]
