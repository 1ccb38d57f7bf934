"""Named return periods of characteristic load effects (a small registry)."""
from __future__ import annotations

from dataclasses import dataclass

from vbikit.extremes._checks import open_unit, positive
from vbikit.extremes.errors import ExtremesError


@dataclass(frozen=True)
class ReturnPeriod:
    """A return period used for characteristic values, with its source.

    Attributes
    ----------
    name : str
        Registry key.
    years : float
        Return period T, years.
    description : str
        What the code or practice means by it.
    source : str
        Clause or document.
    """

    name: str
    years: float
    description: str
    source: str


def exceedance_return_period(probability: float, years: float) -> float:
    """Return period whose level is exceeded with ``probability`` in ``years`` years:
    T = 1 / (1 − (1 − p)^(1/years)) (independent years).  10 % in 100 years → 949.6 years."""
    p = open_unit(probability, "probability", "a probability")
    n_years = positive(years, "years")
    return 1.0 / (1.0 - (1.0 - p) ** (1.0 / n_years))


#: Return periods by name
RETURN_PERIODS: dict[str, ReturnPeriod] = {r.name: r for r in (
    ReturnPeriod("aashto-75", 75.0,
                 "AASHTO LRFD live load calibrated to the maximum load effect expected in the 75-year design life",
                 "AASHTO LRFD Bridge Design Specifications, 1.2 (design life 75 years) and 3.6.1.2 (HL-93); "
                 "calibration: Nowak (1999), NCHRP Report 368"),
    ReturnPeriod("100-year", 100.0,
                 "the level exceeded on average once in 100 years (a 100-year design working life, EN 1990 "
                 "Table 2.1, category 5: bridges)",
                 "EN 1990:2002, Table 2.1"),
    ReturnPeriod("eurocode-1000", 1000.0,
                 "Eurocode characteristic road traffic values (Load Model 1): a return period of about 1000 years, "
                 "quoted as a 10 % probability of exceedance in 100 years (exactly 949.6 years) or 5 % in 50 years "
                 "(975.3 years), both rounded to 1000",
                 "EN 1991-2:2003, 4.3.2 (Load Model 1, characteristic values) and the background documents of its "
                 "calibration"),
)}


def return_period(name: str) -> float:
    """The years of a named return period (``"aashto-75"``, ``"100-year"``, ``"eurocode-1000"``)."""
    try:
        return RETURN_PERIODS[name].years
    except (KeyError, TypeError):
        raise ExtremesError(f"name: unknown return period {name!r}; known: {', '.join(RETURN_PERIODS)}") from None


__all__ = ["RETURN_PERIODS", "ReturnPeriod", "exceedance_return_period", "return_period"]
