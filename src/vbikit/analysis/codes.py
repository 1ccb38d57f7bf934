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
* CSA S6 (Canadian Highway Bridge Design Code), 3.8.4.5.3: DLA = 0.40 when one axle of the
  CL-W truck governs, 0.30 for two axles or for axles Nos. 1–3 (the steering axle and the tandem),
  0.25 for any other three or more.
* Ontario Highway Bridge Design Code (OHBDC), 1983: DAF from the first flexural frequency,
  0.40 for 2.5–4.5 Hz, linear to 0.20 at 1 Hz and at 6 Hz, 0.20 below 1 Hz and above 6 Hz.
* China JTG D60-2015, §4.3.2: μ = 0.05 for f < 1.5 Hz, 0.1767 ln f − 0.0157 for
  1.5 ≤ f ≤ 14 Hz, 0.45 for f > 14 Hz (f = first bending frequency [Hz]).
"""
from __future__ import annotations

import math
from typing import Any, Optional

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
    """China JTG D60-2015 μ [-] from the first bending frequency [Hz]."""
    f = float(first_frequency)
    if not (math.isfinite(f) and f > 0):
        raise ValueError(f"first_frequency must be > 0 Hz, got {first_frequency!r}")
    if f < 1.5:
        return 0.05
    if f > 14.0:
        return 0.45
    return 0.1767 * math.log(f) - 0.0157


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
    ``first_frequency`` [Hz] (OHBDC, JTG), ``n_axles`` of the vehicle (CSA S6; None = not given)."""
    out: dict[str, Any] = {
        "aashto_lrfd": aashto_lrfd(),
        "aashto_standard": aashto_standard(loaded_length),
        "ohbdc_1983": ohbdc_1983(first_frequency),
        "jtg_d60_2015": jtg_d60_2015(first_frequency),
    }
    if n_axles:
        out["csa_s6"] = csa_s6(n_axles)
    return out
