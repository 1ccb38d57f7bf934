"""What a traffic stream's headline numbers are worth in time steps: its governing events run again.

A stream's statistics name two governing events (``vbikit.traffic.study.stream_statistics``): the
one with the largest static effect and the one with the largest dynamic effect at the first
response point, whose dynamic amplifications are the stream's design-facing numbers.  Each is run
again at half the step its event ran with (as a single run's step check, ``vbikit.scenario.step_check``,
and the lifetime's governing events, ``vbikit.lifetime.governing``, do); the change of its
displacement impact factor, IM_half − IM_run, is the number to read for the step's share of it.
A change above ``STEP_TOLERANCE`` (the single run's step check tolerance on an IM, 5e-3) is flagged
(``stream_step_sensitive``): a gross step error.  Smaller ones matter too: on random roads with
point tires the implicit integrators' IM moves by up to a few 1e-3 with the step (docs/verification.md,
"The road's stations and the tire dashpots"), which the printed change shows but the flag does not.
"""
from __future__ import annotations

import dataclasses
import logging
import math
from typing import Any

from vbikit.analysis.checks import Flag
from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.solve.budget import BudgetError

log = logging.getLogger(__name__)

#: the governing events a stream's statistics name (``stream_statistics``' ``governing_<which>_event``)
GOVERNING = ("static", "dynamic")
#: the step of the re-run, times the step the event ran with
HALF_STEP = 0.5


def half_step_impact_factor(job: Any, event: int) -> float:
    """The displacement impact factor at the first response point of ``event`` of the stream ``job``
    (a ``vbikit.traffic.study.TrafficStudy``), run at half the step its event ran with (the event's
    crossing and road, ``TrafficStudy.crossing``); NaN when that run is above the budget."""
    from vbikit.analysis.response import reduce_crossing
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    crossing = job.crossing(event)
    try:
        result = simulate(dataclasses.replace(crossing, dt=HALF_STEP * plan_run(crossing).dt))
    except BudgetError as err:
        log.warning("the governing event %d was not run again at half the step: %s", event, err)
        return math.nan
    points, _ = reduce_crossing(result, job.context().plan, names=("impact_factor",))
    return float(points[0]["impact_factor"])


def governing_step_check(job: Any, attrs: dict[str, Any], im: Any) -> tuple[dict[str, float], list[Flag]]:
    """The governing events of the stream ``job`` (``attrs``: its statistics) at half the step: the
    dataset attributes ``governing_<which>_half_step_im_change`` (IM_half − IM_run, ``im`` the events'
    IMs at the first point; NaN: not checked) and ``half_step_tolerance``, and one
    ``stream_step_sensitive`` flag per event whose change is above ``STEP_TOLERANCE``."""
    out: dict[str, float] = {"half_step_tolerance": STEP_TOLERANCE}
    roles: dict[int, list[str]] = {}
    for which in GOVERNING:
        roles.setdefault(int(attrs[f"governing_{which}_event"]), []).append(which)
    flags: list[Flag] = []
    for event, which in roles.items():
        change = half_step_impact_factor(job, event) - float(im[event])
        for w in which:
            out[f"governing_{w}_half_step_im_change"] = change
        if math.isfinite(change) and abs(change) > STEP_TOLERANCE:
            flags.append(Flag("stream_step_sensitive",
                              f"the governing {' and '.join(which)} event ({event}): its impact factor changes by "
                              f"{change:+.2e} at half the time step (tolerance {STEP_TOLERANCE:g}) — the stream's "
                              "amplifications carry that much step error; check them with integrator = \"rk4\" "
                              "(docs/verification.md, \"The road's stations and the tire dashpots\")",
                              output="impact_factor", subject=f"event {event}", value=change, threshold=STEP_TOLERANCE))
    return out, flags
