"""What a traffic stream's headline numbers are worth in time steps: its governing events run again.

A stream's statistics name two governing events (``vbikit.traffic.study.stream_statistics``): the
one with the largest static effect and the one with the largest dynamic effect at the first
response point, whose dynamic amplifications are the stream's design-facing numbers.  Each is run
again at half the step its event ran with (as a single run's step check, ``vbikit.scenario.step_check``,
and the lifetime's governing events, ``vbikit.lifetime.governing``, do); the change of its
displacement impact factor, IM_half − IM_run, is the number to read for the step's share of it.
A change above ``STEP_TOLERANCE`` (the single run's step check tolerance on an IM, 5e-3) is flagged
(``stream_step_sensitive``): a gross step error.  Smaller ones matter too: on random roads with
point tires the implicit integrators' IM at the automatic step is low by up to 7e-4 (class C), an
error of the second order, of which the printed change is about three quarters (docs/verification.md,
"The road's stations and the tire dashpots").
"""
from __future__ import annotations

import dataclasses
import json
import logging
import math
from typing import Any, Mapping, Sequence

from vbikit.analysis.checks import Flag
from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.solve.budget import BudgetError

log = logging.getLogger(__name__)

#: the governing events a stream's statistics name (``stream_statistics``' ``governing_<which>_event``)
GOVERNING = ("static", "dynamic")
#: the step of the re-run, times the step the event ran with
HALF_STEP = 0.5


def half_step_impact_factors(job: Any, event: int, names: Sequence[str]) -> dict[str, float]:
    """The impact factors ``names`` (catalogue outputs: the point ones at the first response point)
    of ``event`` of the stream ``job`` (a ``vbikit.traffic.study.TrafficStudy``), run at half the step
    its event ran with (the event's crossing and road, ``TrafficStudy.crossing``); NaN when that run
    is above the budget."""
    from vbikit.analysis.response import reduce_crossing
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    crossing = job.crossing(event)
    try:
        result = simulate(dataclasses.replace(crossing, dt=HALF_STEP * plan_run(crossing).dt))
    except BudgetError as err:
        log.warning("the governing event %d was not run again at half the step: %s", event, err)
        return {name: math.nan for name in names}
    points, row = reduce_crossing(result, job.context().plan, names=tuple(names))
    values = {**points[0], **row}
    return {name: float(values[name]) if values.get(name) is not None else math.nan for name in names}


def governing_step_check(job: Any, attrs: dict[str, Any],
                         stored: Mapping[str, Any]) -> tuple[dict[str, Any], list[Flag]]:
    """The governing events of the stream ``job`` (``attrs``: its statistics) at half the step.
    ``stored``: the stream's impact factors by output name (``impact_factor``, the strain's, the load
    effects'), each per event (at the first point).  Returns the dataset attributes
    ``governing_<which>_half_step_im_change`` (the deflection IM's IM_half − IM_run; NaN: not checked),
    ``governing_<which>_half_step_changes`` (JSON: every stored impact factor's change) and
    ``half_step_tolerance``, and one ``stream_step_sensitive`` flag per event with an impact factor
    whose change is above ``STEP_TOLERANCE``."""
    out: dict[str, Any] = {"half_step_tolerance": STEP_TOLERANCE}
    roles: dict[int, list[str]] = {}
    for which in GOVERNING:
        roles.setdefault(int(attrs[f"governing_{which}_event"]), []).append(which)
    flags: list[Flag] = []
    for event, which in roles.items():
        half = half_step_impact_factors(job, event, list(stored))
        changes = {name: half[name] - float(stored[name][event]) for name in stored}
        for w in which:
            out[f"governing_{w}_half_step_im_change"] = changes.get("impact_factor", math.nan)
            out[f"governing_{w}_half_step_changes"] = json.dumps(changes)
        moved = {name: c for name, c in changes.items() if math.isfinite(c) and abs(c) > STEP_TOLERANCE}
        if moved:
            worst = max(moved, key=lambda name: abs(moved[name]))
            flags.append(Flag("stream_step_sensitive",
                              f"the governing {' and '.join(which)} event ({event}): at half the time step "
                              + ", ".join(f"{name} changes by {c:+.2e}" for name, c in moved.items())
                              + f" (tolerance {STEP_TOLERANCE:g}) — the stream's values of these carry that much step "
                              "error; run the stream with a shorter crossing.dt in the base scenario until they settle "
                              "(as a single run's step check does for load effects), and check a deflection IM on a "
                              "rough road with integrator = \"rk4\" (docs/verification.md, \"The road's stations and "
                              "the tire dashpots\")",
                              output=worst, subject=f"event {event}", value=moved[worst], threshold=STEP_TOLERANCE))
    return out, flags
