"""Where a population's events start their vehicles: the attributes a traffic stream's dataset and
lifetime.nc state it with, their words, and the ``start_from_rest`` flag judged on them — one
definition for both (docs/traffic.md, "Start from rest and the approach").

Every event starts its vehicles ``crossing.approach`` before the bridge; with a run-in
(``crossing.run_in``, ``vbikit.solve.run_in``) they first drive that much of the road alone and start
settled.  A population's run-in is fitted to the road per event (a short road holds less of it), so an
event records the run-in it got (NaN for one of moving forces, which has nothing to settle), and the
dataset states the population's run-in, the shortest an event got and how many the road cut short.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from vbikit._words import counted
from vbikit.analysis.checks import Flag, start_from_rest_flags

#: the attributes (name -> (units, meaning)) a population dataset states its start with (``start_attrs``)
START_ATTRIBUTES: dict[str, tuple[str, str]] = {
    "approach_m": ("m", "crossing.approach: the events start their vehicles this far before the bridge"),
    "run_in_m": ("m", "crossing.run_in of the population: the road each event's vehicles first drive alone "
                      "(vbikit.solve.run_in; 0: they start at rest)"),
    "run_in_min_m": ("m", "the shortest run-in an event with sprung vehicles got (less than run_in_m where the road "
                          "was too short for the whole of it); absent when no event has sprung vehicles"),
    "run_in_shortened_events": ("1", "events whose run-in the road cut short"),
    "run_in_least_approach_m": ("m", "the approach a run-in needs: every contact point off the deck at the start"),
}


def start_attrs(approach: float, run_in: float, got: ArrayLike, least_approach: float) -> dict[str, Any]:
    """``START_ATTRIBUTES`` of a population whose events start ``approach`` [m] before the bridge after the
    population's ``run_in`` [m]; ``got``: the run-in each event got (NaN for one of moving forces);
    ``least_approach`` [m]: the approach a run-in needs."""
    got = np.asarray(got, float)
    got = got[np.isfinite(got)]
    return {"approach_m": float(approach), "run_in_m": float(run_in),
            **({"run_in_min_m": float(got.min())} if got.size else {}),
            "run_in_shortened_events": int(np.sum(got < run_in - 1e-9)),
            "run_in_least_approach_m": float(least_approach)}


def start_words(attrs: Mapping[str, Any], vehicles: str = "sprung vehicles") -> str:
    """How a population's ``vehicles`` started, in words, from its dataset's ``START_ATTRIBUTES`` (what
    ``vbikit traffic`` prints and the lifetime report says).  A ``run_in_m`` of NaN: the population's run-in
    not known (a dataset that stored only the shortest), said as "at least" the shortest."""
    if "approach_m" not in attrs:
        return f"{vehicles} start at rest crossing.approach before the bridge (a dataset written before the start was stored)"
    approach, run_in = float(attrs["approach_m"]), float(attrs.get("run_in_m", 0.0))
    shortest = _shortest(attrs)
    if not math.isfinite(run_in):
        return (f"{vehicles} start settled, {approach:g} m before the bridge after driving at least {shortest:g} m of the "
                "road alone (crossing.run_in)") if shortest > 0.0 else \
            f"{vehicles} start at rest {approach:g} m before the bridge on some events (the road held none of crossing.run_in)"
    if run_in <= 0.0:
        return f"{vehicles} start at rest {approach:g} m before the bridge (crossing.run_in = 0)"
    short = _shortened(attrs)
    less = f"; the road held less on {counted(short, 'event')}, {shortest:g} m the shortest" if short else ""
    return (f"{vehicles} start settled, {approach:g} m before the bridge after driving {run_in:g} m of the road alone "
            f"(crossing.run_in{less})")


def start_flags(attrs: Mapping[str, Any], output: str = "impact_factor", subject: str = "crossing.approach",
                sprung: bool = False) -> list[Flag]:
    """``start_from_rest`` (``vbikit.analysis.checks.start_from_rest_flags``) judged on a dataset's
    ``START_ATTRIBUTES``: its approach plus the shortest run-in an event got; none when no event has sprung
    vehicles (no ``run_in_min_m``, unless ``sprung`` says the population's vehicles are: a dataset written before
    the shortest was stored, judged on its ``run_in_m``, 0 when absent) or for one written before the start was."""
    if "approach_m" not in attrs or not ("run_in_min_m" in attrs or sprung):
        return []
    return start_from_rest_flags(float(attrs["approach_m"]) + _shortest(attrs), output=output, subject=subject,
                                 shortened=_shortened(attrs),
                                 least_approach=float(attrs.get("run_in_least_approach_m", 0.0)))


def _shortest(attrs: Mapping[str, Any]) -> float:
    """The shortest run-in an event got (the population's when none is stated)."""
    value = float(attrs.get("run_in_min_m", attrs.get("run_in_m", 0.0)))
    return value if math.isfinite(value) else 0.0


def _shortened(attrs: Mapping[str, Any]) -> int:
    """The events whose run-in the road cut short (a dataset that does not say: at least one when its
    shortest is below the population's run-in)."""
    if "run_in_shortened_events" in attrs:
        return int(attrs["run_in_shortened_events"])
    run_in = float(attrs.get("run_in_m", 0.0))
    return int(math.isfinite(run_in) and _shortest(attrs) < run_in - 1e-9)
