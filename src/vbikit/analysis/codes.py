"""Design-code dynamic allowances, to show beside a computed impact factor.

Each function returns the code's allowance as a fraction of the static load effect (IM, DLA,
μ — all "the dynamic increment over the static effect", comparable with vbikit's IM).  Sources
and the second source each value was checked against are listed in ``docs/bridges.md``
("Design-code allowances"); for the OHBDC curve none has been found.

* AASHTO LRFD Bridge Design Specifications, Table 3.6.2.1-1: IM = 0.33 for all limit states
  but fatigue (0.15) and deck joints (0.75), applied to the design truck or tandem.
* AASHTO Standard Specifications for Highway Bridges (17th ed., 2002), 3.8.2.1:
  I = 50 / (L + 125) ≤ 0.30 with L [ft] the loaded length (3.8.2.2: the span for sagging
  moment and shear, the mean of the two adjacent spans for hogging moment over a support).
* CSA S6 (Canadian Highway Bridge Design Code), 3.8.4.5.3 (the clause number of S6-14 and S6:19):
  DLA = 0.40 when only one axle of the CL-W truck is on the span (governs), 0.30 for two axles or
  for axles Nos. 1–3 (the steering axle and the tandem), 0.25 for any other three or more.  The
  count is of the axles that can be on the span together, not of the truck's axles
  (``axles_on_span``).  Second source: LLAnalyzer (docs/references.md), whose automatic DLA is
  40 / 30 / 25 % by the axles selected on the spans; the code's own text was not found in a public
  copy (searched 2026-12), so edition and clause rest on the primary citation.
* Ontario Highway Bridge Design Code (OHBDC), 1983: DAF from the first flexural frequency,
  0.40 for 2.5–4.5 Hz, linear to 0.20 at 1 Hz and at 6 Hz, 0.20 below 1 Hz and above 6 Hz.
* China JTG D60-2015, §4.3.2: μ = 0.05 for f < 1.5 Hz, 0.1767 ln f − 0.0157 for
  1.5 ≤ f ≤ 14 Hz, 0.45 for f > 14 Hz (f = first bending frequency [Hz]).  vbikit uses f = f1 for
  every effect, hogging moments over the piers of continuous beams included.  Open question: the
  commentary to 4.3.2 is said to take, for continuous beams, f1 for sagging moment and shear and a
  second frequency f2 for hogging-moment effects; a search for it (2026-12: stored web pages,
  documentation, source code, in Chinese and English) found neither the commentary's text nor a
  second source stating the f2 rule (only a third-party script using the commentary's f1 formula
  for a continuous beam), so the rule is left as is: μ(f1) beside a hogging moment (an entry's
  ``hogging_region``) may differ from what the commentary asks (docs/bridges.md).
* EN 1991-2:2003 6.4.5.2 (railway, shown instead of the above for railway vehicles): Φ2 =
  1.44/(√L_Φ − 0.2) + 0.82 within 1.00 … 1.67 (Eq. 6.4), Φ3 = 2.16/(√L_Φ − 0.2) + 0.73 within
  1.00 … 2.00 (Eq. 6.5); ``vbikit.rail.codes`` uses these same functions.
"""
from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

FT_PER_M = 1.0 / 0.3048


def aashto_lrfd(limit_state: str = "strength") -> float:
    """AASHTO LRFD IM [-]: "strength" (and service; all but fatigue and joints) 0.33, "fatigue" 0.15, "deck-joints" 0.75."""
    table = {"strength": 0.33, "fatigue": 0.15, "deck-joints": 0.75}
    if limit_state not in table:
        raise ValueError(f"limit_state must be one of {', '.join(table)}, got {limit_state!r}")
    return table[limit_state]


def aashto_standard(loaded_length: float) -> float:
    """AASHTO Standard Specifications I = 50 / (L + 125) ≤ 0.30 [-], L the loaded length given in [m] (converted to ft)."""
    if not (math.isfinite(loaded_length) and loaded_length > 0):
        raise ValueError(f"loaded_length must be > 0 m, got {loaded_length!r}")
    return min(50.0 / (loaded_length * FT_PER_M + 125.0), 0.30)


def csa_s6(n_axles: int, cl_w_front_axles: bool = False) -> float:
    """CSA S6 DLA [-] by the number of axles that govern: 1 → 0.40, 2 → 0.30, ≥ 3 → 0.25, except
    0.30 for three axles that are Nos. 1–3 of the CL-W truck (``cl_w_front_axles``)."""
    if int(n_axles) != n_axles or n_axles < 1:
        raise ValueError(f"n_axles must be an integer >= 1, got {n_axles!r}")
    if cl_w_front_axles and n_axles != 3:
        raise ValueError(f"cl_w_front_axles applies to three axles (Nos. 1–3 of the CL-W truck), got n_axles={n_axles!r}")
    return 0.40 if n_axles == 1 else 0.30 if n_axles == 2 or cl_w_front_axles else 0.25


#: positions closer than this [m] are one axle (``axles_on_span``): the wheels of one axle, and axles
#: of several vehicles side by side in different lanes at one offset
AXLE_POSITION_TOLERANCE = 1e-3


def axles_on_span(positions: Any, span: float) -> int:
    """The largest number of axles that can be on a span of length ``span`` [m] at once (CSA S6
    3.8.4.5.3 counts the axles on the span): distinct axle positions along the deck [m] (wheels
    within ``AXLE_POSITION_TOLERANCE`` are one axle) within any window of length ``span``, an axle
    exactly ``span`` behind another not counted with it (on the far support it loads no span).
    ``positions``: one configuration (1-D: e.g. a vehicle's wheel offsets) or several (2-D, one
    row per instant: the axles of several vehicles as placed, every row counted on its own)."""
    L = float(span)
    if not (math.isfinite(L) and L > 0):
        raise ValueError(f"span must be > 0 m, got {span!r}")
    x = np.atleast_2d(np.asarray(positions, float))
    if x.size == 0:
        raise ValueError("axles_on_span needs at least one axle position")
    best = 0
    rows = np.unique(np.round(x - np.nanmin(x, axis=1, keepdims=True), 3), axis=0)  # configurations (shifts alike)
    for row in rows:
        u = np.unique(np.round(row[np.isfinite(row)] / AXLE_POSITION_TOLERANCE)) * AXLE_POSITION_TOLERANCE
        if u.size:
            ends = np.searchsorted(u, u + L - 0.5 * AXLE_POSITION_TOLERANCE, side="left")
            best = max(best, int(np.max(ends - np.arange(u.size))))
    return best


def ohbdc_1983(first_frequency: float) -> float:
    """OHBDC (1983) DAF [-] from the first flexural frequency [Hz] (plateau 0.40 on 2.5–4.5 Hz)."""
    f = float(first_frequency)
    if not (math.isfinite(f) and f > 0):
        raise ValueError(f"first_frequency must be > 0 Hz, got {first_frequency!r}")
    if f <= 1.0 or f >= 6.0:
        return 0.20
    if f < 2.5:
        return 0.20 + 0.20 * (f - 1.0) / 1.5
    if f <= 4.5:
        return 0.40
    return 0.40 - 0.20 * (f - 4.5) / 1.5


def jtg_d60_2015(first_frequency: float) -> float:
    """China JTG D60-2015 μ [-] from the first bending frequency [Hz] (every effect; for hogging
    moments of continuous beams see the open question on f2 in the module docstring)."""
    f = float(first_frequency)
    if not (math.isfinite(f) and f > 0):
        raise ValueError(f"first_frequency must be > 0 Hz, got {first_frequency!r}")
    if f < 1.5:
        return 0.05
    if f > 14.0:
        return 0.45
    return 0.1767 * math.log(f) - 0.0157


def phi2(determinant_length: float) -> float:
    """Φ2 (carefully maintained track), EN 1991-2 6.4.5.2 Eq. 6.4: 1.44/(√L_Φ − 0.2) + 0.82 within
    1.00 … 1.67, L_Φ the determinant length [m] (a simply supported girder: its span, Table 6.2).
    A dynamic factor (1 + increment) of the static load models LM71/SW, not of a real train."""
    return float(np.clip(1.44 / (math.sqrt(determinant_length) - 0.2) + 0.82, 1.0, 1.67))


def phi3(determinant_length: float) -> float:
    """Φ3 (standard maintenance), EN 1991-2 6.4.5.2 Eq. 6.5: 2.16/(√L_Φ − 0.2) + 0.73 within 1.00 … 2.00."""
    return float(np.clip(2.16 / (math.sqrt(determinant_length) - 0.2) + 0.73, 1.0, 2.0))


#: the railway dynamic factors shown for a railway vehicle instead of the highway codes, key → label
RAILWAY_FACTORS: dict[str, str] = {
    "en1991_2_phi2": "EN 1991-2 6.4.5.2 Φ2 (carefully maintained track), L_Φ = the loaded length",
    "en1991_2_phi3": "EN 1991-2 6.4.5.2 Φ3 (standard maintenance), L_Φ = the loaded length",
}


def railway_allowances(determinant_length: float) -> dict[str, Any]:
    """For a railway vehicle, in place of the highway codes (which do not apply to trains): EN 1991-2
    Φ2 and Φ3 for L_Φ = ``determinant_length`` [m] (the loaded length: exact for a simply supported
    span; EN 1991-2 Table 6.2 gives other L_Φ for continuous decks), with ``railway`` = True.  They
    are factors 1 + φ of LM71, not the increment of this train: a train's own check is ``vbikit rail``
    (EN 1991-2 6.4.6)."""
    if not (math.isfinite(determinant_length) and determinant_length > 0):
        raise ValueError(f"determinant_length must be > 0 m, got {determinant_length!r}")
    return {"railway": True, "en1991_2_phi2": phi2(determinant_length), "en1991_2_phi3": phi3(determinant_length)}


#: the codes by key, with a short label
CODES: dict[str, str] = {
    "aashto_lrfd": "AASHTO LRFD 3.6.2.1 (0.33)",
    "aashto_standard": "AASHTO Standard 3.8.2 (50/(L+125) <= 0.30, L in ft)",
    "csa_s6": "CSA S6 3.8.4.5.3 (by number of axles)",
    "ohbdc_1983": "OHBDC 1983 (by first flexural frequency)",
    "jtg_d60_2015": "JTG D60-2015 4.3.2 (by first frequency)",
}


def code_allowances(loaded_length: float, first_frequency: float, n_axles: Optional[int]) -> dict[str, Any]:
    """Every code's value for one load effect: ``loaded_length`` [m] (AASHTO Standard),
    ``first_frequency`` [Hz] (OHBDC, JTG), ``n_axles`` on the span at once (CSA S6, ``axles_on_span``;
    None = not given)."""
    out: dict[str, Any] = {
        "aashto_lrfd": aashto_lrfd(),
        "aashto_standard": aashto_standard(loaded_length),
        "ohbdc_1983": ohbdc_1983(first_frequency),
        "jtg_d60_2015": jtg_d60_2015(first_frequency),
    }
    if n_axles:
        out["csa_s6"] = csa_s6(n_axles)
    return out
