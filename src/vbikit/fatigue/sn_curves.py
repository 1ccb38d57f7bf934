"""S-N (fatigue resistance) curves as data, and one mechanism to evaluate them.

A curve is a list of power-law segments ``N = N_ref · (Δσ_ref / Δσ)^m``, each valid down to a
lower stress range, a constant-amplitude fatigue limit and a rule for small ranges.  Both codes
give a spectrum whose *largest* range is below the constant-amplitude fatigue limit no damage
(EN 1993-1-9:2005, 1.3.3.3: "under variable amplitude conditions all stress ranges have to be
below this limit for no fatigue damage to occur", Δσ_D; AASHTO LRFD 6.6.1.2.5, (ΔF)_TH).  When a
range reaches the limit, every range counts on the curve, except:

- ``"cutoff"`` (EN 1993-1-9): ranges below the last segment's lower bound (the cut-off limit
  Δσ_L) do no damage;
- ``"max-range"`` (AASHTO LRFD 6.6.1.2.5): the straight line N = A·Δf^−3 holds for every range.

Stresses are in Pa throughout; the registry names give the detail category in MPa (EN) or the
AASHTO letter.  Sources and numbers: ``en1993_curve`` and ``AASHTO_CATEGORIES``.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from vbikit.fatigue._checks import positive, series_1d
from vbikit.fatigue.errors import FatigueError

MPA = 1.0e6
#: 1 ksi in Pa (1000 lbf/in² = 1000 · 4.4482216152605 N / 0.0254² m²)
KSI = 1000.0 * 4.4482216152605 / 0.0254**2

#: the EN 1993-1-9 S-N diagram (Fig. 7.1): N_C, N_D, N_L and the slopes
EN_N_C, EN_N_D, EN_N_L = 2.0e6, 5.0e6, 1.0e8
#: detail categories of EN 1993-1-9 Fig. 7.1 / Tables 8.1–8.10, Δσ_C in MPa
EN_CATEGORIES = (160, 140, 125, 112, 100, 90, 80, 71, 63, 56, 50, 45, 40, 36)

#: AASHTO LRFD (9th ed.) Table 6.6.1.2.5-1, detail category constant A (× 10^8 ksi³) and
#: Table 6.6.1.2.5-3, constant-amplitude fatigue threshold (ΔF)_TH (ksi)
AASHTO_CATEGORIES: dict[str, tuple[float, float]] = {
    "A": (250.0, 24.0),
    "B": (120.0, 16.0),
    "B'": (61.0, 12.0),
    "C": (44.0, 10.0),
    "C'": (44.0, 12.0),
    "D": (22.0, 7.0),
    "E": (11.0, 4.5),
    "E'": (3.9, 2.6),
}


@dataclass(frozen=True)
class SNSegment:
    """One power-law piece ``N = n_ref · (stress_ref / Δσ)^m``, valid for Δσ ≥ ``stress_min``.

    Attributes
    ----------
    stress_min : float
        Lowest stress range of this piece, Pa (the next piece, or the small-range rule, below it).
    stress_ref : float
        Reference stress range, Pa.
    n_ref : float
        Cycles to failure at ``stress_ref``.
    m : float
        Inverse slope of the log–log line.
    """

    stress_min: float
    stress_ref: float
    n_ref: float
    m: float


@dataclass(frozen=True)
class SNCurve:
    """A fatigue resistance curve: power-law segments (highest stresses first) and a small-range rule.

    Attributes
    ----------
    name : str
        Registry name (``"EN 71"``, ``"AASHTO C'"``).
    segments : tuple of SNSegment
        Ordered from high to low stress ranges.
    rule : str
        ``"cutoff"``: ranges below the last segment's ``stress_min`` do no damage (EN 1993-1-9);
        ``"max-range"``: the last segment extends to zero (AASHTO LRFD 6.6.1.2.5).
    threshold : float
        Constant-amplitude fatigue limit, Pa (EN: Δσ_D; AASHTO: (ΔF)_TH): no damage at all if the
        largest range of a spectrum is below it (``miner_damage``).
    source : str
        Standard and clause.
    """

    name: str
    segments: tuple[SNSegment, ...]
    rule: str
    threshold: float
    source: str

    def cycles_to_failure(self, ranges: Any) -> np.ndarray:
        """Cycles to failure N(Δσ) of each stress range (Pa), vectorised.

        ``inf`` below the cut-off (rule ``"cutoff"``) and at Δσ = 0.  The constant-amplitude
        fatigue limit (``threshold``) is a property of a whole spectrum and is applied in
        ``miner_damage``, not here.
        """
        r = series_1d(np.atleast_1d(ranges), "ranges")
        if (r < 0).any():
            raise FatigueError("ranges: stress ranges are ≥ 0 (Pa)")
        out = np.full(r.shape, np.inf)
        upper = np.full(r.shape, True)
        last = len(self.segments) - 1
        for i, seg in enumerate(self.segments):
            low = 0.0 if (i == last and self.rule == "max-range") else seg.stress_min
            sel = upper & (r >= low) & (r > 0)
            with np.errstate(divide="ignore"):
                out[sel] = seg.n_ref * (seg.stress_ref / r[sel]) ** seg.m
            upper &= ~sel
        return out

    def stress_range_at(self, cycles: float) -> float:
        """The stress range (Pa) with ``cycles`` cycles to failure (inverse of the curve).

        Raises FatigueError beyond the cut-off (no finite range has that many cycles)."""
        n = positive(cycles, "cycles")
        for i, seg in enumerate(self.segments):
            s = seg.stress_ref * (seg.n_ref / n) ** (1.0 / seg.m)
            is_last = i == len(self.segments) - 1
            if s >= seg.stress_min or (is_last and self.rule == "max-range"):
                return float(s)
        raise FatigueError(f"cycles: {cycles:g} is beyond the cut-off of {self.name} (no damage there)")


def en1993_curve(category_mpa: float, gamma_mf: float = 1.0) -> SNCurve:
    """The EN 1993-1-9 direct-stress S-N curve of a detail category.

    Fatigue strength (EN 1993-1-9:2005, 7.1 and Fig. 7.1, Eq. 7.2):

    - Δσ ≥ Δσ_D:         N = 2·10⁶ · (Δσ_C / Δσ)³
    - Δσ_L ≤ Δσ < Δσ_D:  N = 5·10⁶ · (Δσ_D / Δσ)⁵
    - Δσ < Δσ_L:         no damage (cut-off)

    and no damage at all when every range of a spectrum is below Δσ_D (1.3.3.3, the
    constant-amplitude fatigue limit; applied by ``miner_damage``).

    with Δσ_D = (2/5)^(1/3) Δσ_C (constant-amplitude fatigue limit, N_D = 5·10⁶) and
    Δσ_L = (5/100)^(1/5) Δσ_D (cut-off limit, N_L = 10⁸).  With the partial factor γ_Mf
    (EN 1993-1-9 Table 3.1) every stress of the curve is divided by γ_Mf.

    Parameters
    ----------
    category_mpa : float
        Detail category Δσ_C, MPa (the reference value at 2·10⁶ cycles).
    gamma_mf : float, optional
        Partial factor for fatigue strength γ_Mf (1.0: the characteristic curve).
    """
    category, gamma = positive(category_mpa, "category_mpa"), positive(gamma_mf, "gamma_mf")
    dc = category * MPA / gamma
    dd = (EN_N_C / EN_N_D) ** (1.0 / 3.0) * dc
    dl = (EN_N_D / EN_N_L) ** (1.0 / 5.0) * dd
    name = f"EN {category:g}" + (f" (γMf={gamma:g})" if gamma != 1.0 else "")
    return SNCurve(name, (SNSegment(dd, dc, EN_N_C, 3.0), SNSegment(dl, dd, EN_N_D, 5.0)), "cutoff", dd,
                   "EN 1993-1-9:2005, 7.1 and Fig. 7.1 (direct stress ranges)")


def aashto_curve(category: str) -> SNCurve:
    """The AASHTO LRFD nominal fatigue resistance of a detail category (6.6.1.2.5).

    N = A · Δf^−3 (Eq. 6.6.1.2.5-2, finite life), with A from Table 6.6.1.2.5-1 and the
    constant-amplitude fatigue threshold (ΔF)_TH from Table 6.6.1.2.5-3 (constants in
    ``AASHTO_CATEGORIES``, US units, converted exactly: 1 ksi = 6.894757 MPa).  Infinite life
    when the largest stress range is below (ΔF)_TH (Fatigue I limit state, 6.6.1.2.5); otherwise
    the straight line holds for all ranges (rule ``"max-range"``).  The specification checks the
    Fatigue I *factored* range against (ΔF)_TH; ``miner_damage`` applies the rule to the ranges
    it is given, so scale them first if that check is meant.

    Parameters
    ----------
    category : str
        A, B, B', C, C', D, E or E' (a prime may be written ′ or ').
    """
    key = str(category).strip().upper().replace("′", "'").replace("’", "'")
    if key not in AASHTO_CATEGORIES:
        raise FatigueError(f"category: unknown AASHTO detail category {category!r}; "
                           f"known: {', '.join(AASHTO_CATEGORIES)}")
    a_ksi3, th_ksi = AASHTO_CATEGORIES[key]
    a = a_ksi3 * 1.0e8 * KSI**3  # Pa³
    th = th_ksi * KSI
    # written as a segment with N_ref = A / th³ at stress_ref = th (the same line N = A/Δf³)
    return SNCurve(f"AASHTO {key}", (SNSegment(th, th, a / th**3, 3.0),), "max-range", th,
                   "AASHTO LRFD Bridge Design Specifications, 6.6.1.2.5, Tables 6.6.1.2.5-1 and -3")


#: every named curve: ``"EN 71"`` (Δσ_C in MPa), ``"AASHTO C'"``
SN_CURVES: dict[str, SNCurve] = {
    **{f"EN {c}": en1993_curve(c) for c in EN_CATEGORIES},
    **{f"AASHTO {c}": aashto_curve(c) for c in AASHTO_CATEGORIES},
}


def _allowed_names() -> str:
    return (f"EN {', '.join(str(c) for c in EN_CATEGORIES)} (EN 1993-1-9, Δσ_C in MPa) or "
            f"AASHTO {', '.join(AASHTO_CATEGORIES)}")


def curve_name(name: str) -> str:
    """The registry name (a key of ``SN_CURVES``) of the S-N curve ``name``: ``"EN <Δσ_C>"`` with
    Δσ_C one of the detail categories of EN 1993-1-9 (``EN_CATEGORIES``; ``"en71"``, ``"EN 71.0"``
    → ``"EN 71"``) or ``"AASHTO <category>"`` of ``AASHTO_CATEGORIES`` (``"aashto c′"`` →
    ``"AASHTO C'"``); case and spacing free.  Anything else — a number the standard does not list
    (``"EN 37"``, a typo of 36), another family — raises FatigueError with the allowed names.
    The one check of a curve's name: ``sn_curve`` and the lifetime file's ``category`` use it."""
    text = " ".join(str(name).replace("′", "'").replace("’", "'").split())
    m = re.fullmatch(r"(?i)(EN|AASHTO)\s*(.+)", text)
    if m is not None and m.group(1).upper() == "AASHTO":
        key = f"AASHTO {m.group(2).strip().upper()}"
    elif m is not None:
        number = re.fullmatch(r"[0-9]+(?:\.[0-9]*)?", m.group(2).strip())  # no sign, no exponent
        value = float(number.group()) if number else math.nan
        key = f"EN {int(value)}" if value in EN_CATEGORIES else ""
    else:
        key = ""
    if key not in SN_CURVES:
        near = ""
        if m is not None and m.group(1).upper() == "EN" and math.isfinite(value) and value > 0:
            near = f" (the nearest EN category is {min(EN_CATEGORIES, key=lambda c: abs(c - value))})"
        raise FatigueError(f"curve: {name!r} is not a detail category{near}; allowed: {_allowed_names()}")
    return key


def sn_curve(name: str, gamma_mf: float = 1.0) -> SNCurve:
    """A curve of the registry by name: ``"EN 71"`` … or ``"AASHTO C'"`` (case and spacing free;
    ``curve_name``: a category neither standard lists is refused).

    ``gamma_mf`` (EN curves only) divides the curve's stresses by the partial factor γ_Mf.  A
    Δσ_C the standard does not list (a category reduced for size, EN 1993-1-9 Table 8.x k_s) is
    built by ``en1993_curve`` directly.
    """
    key = curve_name(name)
    if key.startswith("AASHTO"):
        if gamma_mf != 1.0:
            raise FatigueError("gamma_mf: applies to EN 1993-1-9 curves only")
        return SN_CURVES[key]
    return SN_CURVES[key] if gamma_mf == 1.0 else en1993_curve(float(key.split()[1]), gamma_mf)


__all__ = ["AASHTO_CATEGORIES", "EN_CATEGORIES", "KSI", "SNCurve", "SNSegment", "SN_CURVES",
           "aashto_curve", "curve_name", "en1993_curve", "sn_curve"]
