"""Where a population's events start their vehicles: the attributes a traffic stream's dataset and
lifetime.nc state it with, their words, and the ``start_from_rest`` and ``start_unsettled`` flags judged on
them — one definition for both (docs/traffic.md, "Start from rest and the approach").

Every event starts its vehicles ``crossing.approach`` before the bridge; with a run-in
(``crossing.run_in``, ``vbikit.solve.run_in``) they first drive that much of the road alone and start
settled.  A population's run-in is fitted to the road per event (a short road holds less of it), so an
event records the run-in it got (NaN for one of moving forces, which has nothing to settle), and the
dataset states the population's run-in, the shortest an event got and how many the road cut short.  Each
event also records the largest share of its start transient a sprung vehicle kept at the bridge
(``vbikit.solve.run_in.start_transient_left``), and the dataset how many events kept more than the trucks the
settled start was checked with (``SETTLED_TRANSIENT_LEFT``).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from vbikit._words import counted
from vbikit.analysis.checks import BASE_SCENARIO, Flag, start_from_rest_flags, start_unsettled_flags
from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT, lengthened_run_in

#: the attributes (name -> (units, meaning)) a population dataset states its start with (``start_attrs``)
START_ATTRIBUTES: dict[str, tuple[str, str]] = {
    "approach_m": ("m", "crossing.approach: the events start their vehicles this far before the bridge"),
    "run_in_m": ("m", "crossing.run_in of the population: the road each event's vehicles first drive alone "
                      "(vbikit.solve.run_in; 0: they start at rest)"),
    "run_in_min_m": ("m", "the shortest run-in an event with sprung vehicles got (less than run_in_m where the road "
                          "was too short for the whole of it, more where every event's vehicles needed more: "
                          "run_in_adaptive); absent when no event has sprung vehicles"),
    "run_in_max_m": ("m", "the longest run-in an event with sprung vehicles got (more than run_in_m where its "
                          "vehicles needed more to settle: run_in_adaptive); absent when no event has sprung vehicles"),
    "run_in_adaptive": ("1", "1 if the population lengthened an event's run-in to what its vehicles need to keep at "
                             "most SETTLED_TRANSIENT_LEFT of their start transient (its own run-in, on a rough road: "
                             "vbikit.traffic.study.EventContext.settled_run_in); 0 for a run-in the base scenario "
                             "gives (absent: a dataset written before 2026-12-07, 0)"),
    "run_in_shortened_events": ("1", "events whose run-in the road cut short (of what the population gives them)"),
    "run_in_least_approach_m": ("m", "the approach a run-in needs: every contact point off the deck at the start"),
    "start_transient_left_max": ("1", "the largest share of its start transient (its slowest mode the road excites) "
                                      "a sprung vehicle kept when it reached the bridge, exp(−σ_min t) "
                                      "(vbikit.solve.run_in.start_transient_left); absent when no event has sprung "
                                      "vehicles"),
    "start_unsettled_events": ("1", "events with a sprung vehicle that kept more than SETTLED_TRANSIENT_LEFT of its "
                                    "start transient (the start_unsettled flag)"),
    "start_settling_run_in_m": ("m", "the crossing.run_in with which every sprung vehicle of every event would keep at "
                                     "most SETTLED_TRANSIENT_LEFT of its start transient, the approach as it is "
                                     "(vbikit.solve.run_in.start_settling; events with a vehicle with an undamped mode "
                                     "left out); absent when no event has sprung vehicles, or every event has such a "
                                     "vehicle"),
}

#: the integers among ``START_ATTRIBUTES``, counts and the one yes/no (a lifetime summary gives None for one its
#: dataset does not state)
START_COUNTS = ("run_in_adaptive", "run_in_shortened_events", "start_unsettled_events")


def start_attrs(approach: float, run_in: float, got: ArrayLike, least_approach: float,
                left: ArrayLike = (), settling: ArrayLike = (), adaptive: bool = False) -> dict[str, Any]:
    """``START_ATTRIBUTES`` of a population whose events start ``approach`` [m] before the bridge after the
    population's ``run_in`` [m]; ``got``: the run-in each event got (NaN for one of moving forces);
    ``least_approach`` [m]: the approach a run-in needs; ``left``, ``settling``: the share of its start transient
    each event's sprung vehicles kept at the bridge at most and the run-in that would settle them
    (``vbikit.solve.run_in.start_settling``; NaN for moving forces, inf for an undamped mode; per event, as ``got``);
    ``adaptive``: the population lengthened each event's run-in to its vehicles' settling run-in
    (``vbikit.traffic.study.EventContext.lengthens``; ``lengthened_run_in``), which is then what an event was given and
    may have been cut short of."""
    got = np.asarray(got, float)
    need = np.asarray(settling, float)
    given = np.full(got.shape, float(run_in))
    if adaptive and need.shape == got.shape:  # (the population's rule: vbikit.solve.run_in.lengthened_run_in)
        given = np.array([lengthened_run_in(run_in, n) for n in need], float).reshape(got.shape)
    sprung = np.isfinite(got)
    got, given = got[sprung], given[sprung]
    left = np.asarray(left, float)
    left = left[np.isfinite(left)]
    settling = need[np.isfinite(need)]
    return {"approach_m": float(approach), "run_in_m": float(run_in),
            **({"run_in_min_m": float(got.min()), "run_in_max_m": float(got.max())} if got.size else {}),
            "run_in_adaptive": int(bool(adaptive)),
            "run_in_shortened_events": int(np.sum(got < given - 1e-9)),
            "run_in_least_approach_m": float(least_approach),
            **({"start_transient_left_max": float(left.max()),
                "start_unsettled_events": int(np.sum(left > SETTLED_TRANSIENT_LEFT))} if left.size else {}),
            **({"start_settling_run_in_m": float(settling.max())} if settling.size else {})}


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
    lengthened = int(attrs.get("run_in_adaptive", 0)) and float(attrs.get("run_in_max_m", 0.0)) > 0.0
    if run_in <= 0.0 and not lengthened:
        return f"{vehicles} start at rest {approach:g} m before the bridge (crossing.run_in = 0)"
    short = _shortened(attrs)
    less = ("" if not short else f"; the road held less than their vehicles needed on {counted(short, 'event')}"
            if int(attrs.get("run_in_adaptive", 0)) else f"; the road held less on {counted(short, 'event')}, "
            f"{shortest:g} m the shortest")
    unsettled = int(attrs.get("start_unsettled_events", 0))
    still = (f"; on {counted(unsettled, 'event')} a vehicle had not settled (start_unsettled)") if unsettled else ""
    longest = float(attrs.get("run_in_max_m", run_in))
    longer = (f", longer where the vehicles needed more to settle, up to {longest:g} m"
              if int(attrs.get("run_in_adaptive", 0)) and longest > run_in + 1e-9 else "")
    return (f"{vehicles} start{'' if unsettled else ' settled,'} {approach:g} m before the bridge after driving "
            f"{run_in:g} m of the road alone (crossing.run_in{longer}{less}){still}")


def start_flags(attrs: Mapping[str, Any], output: str = "impact_factor", subject: str = "crossing.approach",
                sprung: bool = False, total: int = 0, where: str = BASE_SCENARIO) -> list[Flag]:
    """``start_from_rest`` (``vbikit.analysis.checks.start_from_rest_flags``) judged on a dataset's
    ``START_ATTRIBUTES``: its approach plus the shortest run-in an event got; none when no event has sprung
    vehicles (no ``run_in_min_m``, unless ``sprung`` says the population's vehicles are: a dataset written before
    the shortest was stored, judged on its ``run_in_m``, 0 when absent) or for one written before the start was;
    or else (the vehicles driven ``SETTLED_APPROACH`` in all) ``start_unsettled``
    (``vbikit.analysis.checks.start_unsettled_flags``) on its ``start_unsettled_events`` of ``total`` events: a
    vehicle lighter damped than the trucks that distance was checked with (none for a dataset written before
    2026-12-07, which did not count them)."""
    if "approach_m" not in attrs or not ("run_in_min_m" in attrs or sprung):
        return []
    driven = float(attrs["approach_m"]) + _shortest(attrs)
    from_rest = start_from_rest_flags(driven, output=output, subject=subject, shortened=_shortened(attrs),
                                      least_approach=float(attrs.get("run_in_least_approach_m", 0.0)), where=where)
    return from_rest or start_unsettled_flags(int(attrs.get("start_unsettled_events", 0)),
                                              float(attrs.get("start_transient_left_max", 0.0)),
                                              float(attrs.get("start_settling_run_in_m", math.nan)), total,
                                              output=output, subject=subject,
                                              run_in=float(attrs.get("run_in_m", math.nan)), shortened=_shortened(attrs),
                                              where=where, adaptive=bool(int(attrs.get("run_in_adaptive", 0))))


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
