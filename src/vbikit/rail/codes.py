"""EN 1991-2 / EN 1990 rules of the dynamic analysis of railway bridges.

Edition: EN 1991-2:2003 with its corrigenda (AC) and EN 1990:2002/A1:2005 Annex A2.  The clause,
table and equation numbers below are those of that edition (ENV 1991-3:1995, quoted by some
secondary sources, numbers them differently: there LM71 is Figure 6.2 and Table 6.6 is the groups
of loads).  Checked against a second source: the HSLM-A trains (6.4.6.1.1, Figure 6.12, Table 6.3;
Annex E, E.1 refers to them so) and HSLM's limits of validity (Annex E, Table E.1); the others are
as given by one transcription of the standard and SincBridgeDynamics.jl (Table 6.6) and are marked
so in docs/railway.md.

* Damping (EN 1991-2:2003 6.4.6, Table 6.6): lower limits of ζ [%] for span L [m]:
  steel and composite 0.5 + 0.125 (20 − L) for L < 20 m, 0.5 above; prestressed concrete
  1.0 + 0.07 (20 − L) / 1.0; filler beam and reinforced concrete 1.5 + 0.07 (20 − L) / 1.5
  (the same rule in SincBridgeDynamics.jl, ``ec1damping``).
* Additional damping for spans below 30 m (EN 1991-2 Eq. 6.13, Figure 6.15), allowing for
  vehicle–bridge interaction in a moving-force analysis:
  Δζ = (0.0187 L − 0.00064 L²) / (1 − 0.0441 L − 0.0044 L² + 0.000255 L³) [%].
* Frequency range (EN 1990 A2.4.4.2.1(4) and EN 1991-2 6.4.6): modes up to the greater of
  30 Hz, 1.5 n0 and n3.
* Peak deck acceleration limits (EN 1990 A2.4.4.2.1(4)): 3.5 m/s² ballasted track, 5 m/s²
  direct fastening.
* Resonance speeds (EN 1991-2:2003 6.4.6): v_i = n0 λ_i, λ_i = D / i (D: coach length, or for any
  train its dominant repeated axle spacing, ``vbikit.rail.signature``).
* Dynamic factors of the static load models (EN 1991-2 6.4.5.2): Φ2 = 1.44/(√L_Φ − 0.2) + 0.82
  within 1.00 … 1.67 (carefully maintained track), Φ3 = 2.16/(√L_Φ − 0.2) + 0.73 within 1.00 … 2.00
  (standard maintenance), L_Φ the determinant length [m] (the span of a simply supported girder).
* Track irregularities of real trains (EN 1991-2 Annex C): φ'' = α/100 [56 e^{−(L_Φ/10)²} +
  50 (L_Φ n0/80 − 1) e^{−(L_Φ/20)²}] ≥ 0, α = v/22 for v ≤ 22 m/s, else 1.
* Range of application of HSLM (EN 1991-2:2003 6.4.6.1.1(5) and Annex E): HSLM-B for simply
  supported spans L < 7 m, HSLM-A otherwise (``HSLM_B_MAX_SPAN``, ``hslm_range_flags``).
* Load Model 71 (EN 1991-2 6.3.2, Figure 6.1): four 250 kN axles 1.6 m apart and 80 kN/m on both
  sides from 0.8 m beyond the outer axles, times the classification factor α.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import NDArray

# Φ2 and Φ3 live with the other codes' allowances (the run report shows them for railway vehicles)
from vbikit.analysis.codes import phi2, phi3

#: EN 1991-2:2003 6.4.6.1.1(5), Annex E: HSLM-B applies to simply supported spans below this [m], HSLM-A otherwise
HSLM_B_MAX_SPAN = 7.0


#: the trains of the HSLM-A family (EN 1991-2:2003 Annex E, Table E.1: HSLM-A1 … A10)
HSLM_A_COUNT = 10


def hslm_range_flags(span: float, names: list[str]) -> list:
    """The ``hslm_range`` flags (``vbikit.analysis.checks.Flag``) of a sweep whose HSLM trains
    (``names``: the trains' names) lie outside their range of application (EN 1991-2:2003
    6.4.6.1.1(5), Annex E): HSLM-B on a simply supported span ``span`` [m] of 7 m or more (its check
    is then not the standard's one: HSLM-A is), HSLM-A on a span below 7 m (HSLM-B is); value: the
    span [m], threshold: ``HSLM_B_MAX_SPAN`` [m]; and ``hslm_incomplete`` when HSLM-A runs on such a span with
    fewer than its ten trains (value: how many, threshold: ``HSLM_A_COUNT``).  Flags, not errors: a user may run
    either outside its range, or a few trains, on purpose (research, comparison)."""
    from vbikit.analysis.checks import Flag
    from vbikit.vehicle.trains import HSLM_B_NAME

    out = []
    b_trains = [n for n in names if n.startswith(HSLM_B_NAME)]
    a_trains = [n for n in names if n.startswith("HSLM-A")]
    if b_trains and span >= HSLM_B_MAX_SPAN:
        out.append(Flag("hslm_range", f"HSLM-B outside its range of application: EN 1991-2:2003 6.4.6.1.1(5) and Annex E "
                        f"apply HSLM-B to simply supported spans below {HSLM_B_MAX_SPAN:g} m only, this span is {span:g} m, "
                        f"so the check of {', '.join(b_trains)} is not the EN 1991-2 one; use HSLM-A (trains.presets = "
                        f"[\"hslm-a\"])" + ("" if a_trains else ", which this sweep does not run"),
                        subject=", ".join(b_trains), value=float(span), threshold=HSLM_B_MAX_SPAN))
    if a_trains and span >= HSLM_B_MAX_SPAN and len(set(a_trains)) < HSLM_A_COUNT:
        out.append(Flag("hslm_incomplete", f"HSLM-A incomplete: the sweep runs {', '.join(a_trains)}, "
                        f"{len(set(a_trains))} of the {HSLM_A_COUNT} trains HSLM-A1 … A{HSLM_A_COUNT} with which EN 1991-2:2003 "
                        "6.4.6.1.1 and Annex E check a span of 7 m or more: a PASS covers only these trains, not the "
                        "standard's check; run all ten (trains.presets = [\"hslm-a\"])",
                        subject=", ".join(a_trains), value=float(len(set(a_trains))), threshold=float(HSLM_A_COUNT)))
    if a_trains and span < HSLM_B_MAX_SPAN:
        out.append(Flag("hslm_range", f"HSLM-A outside its range of application: span {span:g} m < {HSLM_B_MAX_SPAN:g} m, "
                        "for which EN 1991-2:2003 6.4.6.1.1(5) uses HSLM-B (trains.hslm_b, N and d from the standard's "
                        "figure)", subject=", ".join(a_trains), value=float(span), threshold=HSLM_B_MAX_SPAN))
    return out


def hslm_range_warnings(span: float, names: list[str]) -> list[str]:
    """The messages of ``hslm_range_flags`` (the dataset's ``code_warnings``, the log)."""
    return [f.message for f in hslm_range_flags(span, names)]


@dataclass(frozen=True)
class DeckDamping:
    """Table 6.6 row: ζ = base + slope (20 − L) [%] for L < 20 m, base for L ≥ 20 m."""

    name: str
    base: float
    slope: float
    description: str

    def ratio(self, span: float) -> float:
        """ζ [-] (a ratio, not %) for span L [m]."""
        pct = self.base + self.slope * (20.0 - span) if span < 20.0 else self.base
        return pct / 100.0


#: EN 1991-2:2003 Table 6.6 by deck type
DECK_DAMPING: dict[str, DeckDamping] = {
    "steel": DeckDamping("steel", 0.5, 0.125, "steel and composite"),
    "composite": DeckDamping("composite", 0.5, 0.125, "steel and composite"),
    "prestressed-concrete": DeckDamping("prestressed-concrete", 1.0, 0.07, "prestressed concrete"),
    "reinforced-concrete": DeckDamping("reinforced-concrete", 1.5, 0.07, "filler beam and reinforced concrete"),
    "filler-beam": DeckDamping("filler-beam", 1.5, 0.07, "filler beam and reinforced concrete"),
}

#: EN 1990 A2.4.4.2.1(4): peak deck acceleration limits [m/s²] by track type
ACCELERATION_LIMITS: dict[str, float] = {"ballasted": 3.5, "direct": 5.0}

#: EN 1991-2 6.3.2(3): the classification factors α allowed
CLASSIFICATION_FACTORS = (0.75, 0.83, 0.91, 1.00, 1.10, 1.21, 1.33, 1.46)


def additional_damping(span: float) -> float:
    """Δζ [-] (ratio) of EN 1991-2 Eq. 6.13 for span L [m] < 30 m; 0 for L ≥ 30 m."""
    if span >= 30.0:
        return 0.0
    L = float(span)
    pct = (0.0187 * L - 0.00064 * L**2) / (1.0 - 0.0441 * L - 0.0044 * L**2 + 0.000255 * L**3)
    return pct / 100.0


def code_damping(deck: str, span: float, extra: bool = True) -> float:
    """ζ [-] of Table 6.6 for ``deck`` and span L [m], plus Δζ (Eq. 6.13) when ``extra``."""
    if deck not in DECK_DAMPING:
        raise ValueError(f"deck type must be one of {', '.join(DECK_DAMPING)}, got {deck!r}")
    return DECK_DAMPING[deck].ratio(span) + (additional_damping(span) if extra else 0.0)


def frequency_limit(frequencies_hz: NDArray[np.float64]) -> float:
    """max(30 Hz, 1.5 n0, n3) [Hz] (n3 the third frequency; the highest given if fewer)."""
    f = np.sort(np.asarray(frequencies_hz, float))
    n3 = float(f[2]) if f.size >= 3 else float(f[-1])
    return max(30.0, 1.5 * float(f[0]), n3)


def resonance_speeds(n0: float, wavelength: float, v_max: float = math.inf, orders: int = 4) -> NDArray[np.float64]:
    """v_i = n0 D / i [m/s], i = 1 … ``orders``, those ≤ ``v_max`` (default: all ``orders``, so that
    entry i − 1 is order i)."""
    v = n0 * wavelength / np.arange(1, orders + 1)
    return v[v <= v_max]


DYNAMIC_FACTORS: dict[str, Callable[[float], float]] = {"careful": phi2, "standard": phi3}


def phi_irregularity(speed: float, determinant_length: float, n0: float) -> float:
    """φ'' of EN 1991-2 Annex C for speed v [m/s], L_Φ [m] and first frequency n0 [Hz]."""
    alpha = speed / 22.0 if speed <= 22.0 else 1.0
    L = determinant_length
    value = alpha / 100.0 * (56.0 * math.exp(-(L / 10.0) ** 2) + 50.0 * (L * n0 / 80.0 - 1.0) * math.exp(-(L / 20.0) ** 2))
    return max(value, 0.0)


def lm71_loads(alpha: float = 1.0) -> tuple[NDArray[np.float64], float, float]:
    """LM71: axle positions [m] about the group centre, axle load [N], distributed load [N/m] (× α)."""
    return np.array([-2.4, -0.8, 0.8, 2.4]), 250e3 * alpha, 80e3 * alpha


def lm71_peak(influence: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]], span: float,
              alpha: float = 1.0, step: float = 0.02, y: float = 0.0) -> float:
    """Largest |R| of LM71 on a span with the static influence line I(x) [per N of upward force]:
    the axle group at every position (``step`` [m]), the distributed load wherever it adds to the
    effect (EN 1991-2 6.3.2(2)) outside the group's 6.4 m; |R| of the worse sign."""
    axles, q_axle, q_line = lm71_loads(alpha)
    x = np.arange(0.0, span + 0.5 * step, step)
    inside = x.copy()  # the end values as limits from inside the span (an axle on a support carries no shear)
    inside[0], inside[-1] = 1e-9 * span, span * (1 - 1e-9)
    eta = -np.asarray(influence(inside, np.full_like(x, y)), float)  # effect of a unit *downward* force on the line y
    # every position that puts an axle or an end of the distributed-load gap on a grid point
    centres = np.unique(np.concatenate([x - a for a in axles] + [x - 3.2, x + 3.2]))
    xa = centres[:, None] + axles[None, :]
    on = (xa >= -1e-9) & (xa <= span + 1e-9)
    best = 0.0
    for sign in (1.0, -1.0):
        part = np.clip(sign * eta, 0.0, None)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (part[1:] + part[:-1]) * step)])
        conc = np.sum(np.where(on, np.interp(np.clip(xa, 0, span), x, sign * eta), 0.0), axis=1) * q_axle
        lo, hi = np.clip(centres - 3.2, 0, span), np.clip(centres + 3.2, 0, span)
        udl = (cum[-1] - (np.interp(hi, x, cum) - np.interp(lo, x, cum))) * q_line
        best = max(best, float(np.max(conc + udl)))
    return best
