"""What a traffic stream's headline numbers are worth in time steps: its governing events run again.

A stream's statistics name two governing events (``vbikit.traffic.study.stream_statistics``): the
one with the largest static effect and the one with the largest dynamic effect at the first
response point, whose dynamic amplifications are the stream's design-facing numbers.  Each is run
again at half its automatic time step (the step check of a single run, ``vbikit.scenario.step_check``,
and the lifetime's governing events, ``vbikit.lifetime.governing``, do the same); the change of its
displacement impact factor, IM_half − IM_run, says how much of that number is the step.  A change
above ``STEP_TOLERANCE`` (the single run's step check tolerance on an IM, 5e-3) is flagged
(``stream_step_sensitive``).  On random roads with point tires the implicit integrators' IM moves
by up to a few 1e-3 with the step (docs/verification.md, "The road's stations and the tire
dashpots"): the change is the stream's own measure of that.
"""
from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

from vbikit.analysis.checks import Flag
from vbikit.analysis.effect_step import STEP_TOLERANCE

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.traffic.study import TrafficStudy

#: the governing events a stream's statistics name (``stream_statistics``' ``governing_<which>_event``)
GOVERNING = ("static", "dynamic")
#: the step of the re-run, times the event's automatic step
HALF_STEP = 0.5


def half_step_impact_factor(job: "TrafficStudy", event: int) -> float:
    """The displacement impact factor of ``event`` at the first response point, run at half its
    automatic step (the event's crossing and road, ``TrafficStudy.crossing``)."""
    from vbikit.analysis.response import reduce_crossing
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    crossing = job.crossing(event)
    result = simulate(dataclasses.replace(crossing, dt=HALF_STEP * plan_run(crossing).dt))
    points, _ = reduce_crossing(result, job.context().plan, names=("impact_factor",))
    return float(points[0]["impact_factor"])


def governing_step_check(job: "TrafficStudy", attrs: dict[str, Any], im: Any) -> tuple[dict[str, float], list[Flag]]:
    """The governing events of a stream (``attrs``: its statistics) at half the step: the dataset
    attributes ``governing_<which>_half_step_im_change`` (IM_half − IM_run, ``im`` the events' IMs at
    the first point) and ``half_step_tolerance``, and a ``stream_step_sensitive`` flag per event whose
    change is above ``STEP_TOLERANCE``."""
    out: dict[str, float] = {"half_step_tolerance": STEP_TOLERANCE}
    flags: list[Flag] = []
    done: dict[int, float] = {}
    for which in GOVERNING:
        event = int(attrs[f"governing_{which}_event"])
        if event not in done:
            done[event] = half_step_impact_factor(job, event) - float(im[event])
        change = done[event]
        out[f"governing_{which}_half_step_im_change"] = change
        if abs(change) > STEP_TOLERANCE:
            flags.append(Flag("stream_step_sensitive",
                              f"the governing {which} event ({event}): its impact factor changes by {change:+.2e} at "
                              f"half the time step (tolerance {STEP_TOLERANCE:g}) — the stream's amplifications carry "
                              "that much step error; run it with a shorter crossing.dt or integrator = \"rk4\"",
                              output="impact_factor", subject=f"event {event}", value=change, threshold=STEP_TOLERANCE))
    return out, flags
