"""The traffic budget check plans the stream's longest run (``TrafficStudy.check_budget``).

Was: the longest event was chosen by a formula of its own, each vehicle's record time plus (approach +
span + axle spacings) / speed, which counts the approach after every vehicle's entry rather than once
before the run and ignores the deck's skew reach: on streams with mixed speeds it planned a shorter
event than the longest in 3 of the 12 streams below (a slow vehicle whose approach starts the run earlier than the first
vehicle's).  The longest run is now read from ``partition``'s ends and the run's start as
``Crossing.start_time`` defines it.  Checked against brute force: every event's crossing built (without
its road) and its ``duration`` compared."""
from __future__ import annotations

import pytest

import vbikit.solve.plan
from vbikit.traffic import LaneTraffic, synthetic_stream
from vbikit.traffic.study import traffic_study


@pytest.mark.parametrize("deck", [{}, {"deck": {"skew": 20.0}}], ids=["straight", "skew 20°"])
@pytest.mark.parametrize("seed", range(6))
def test_the_budget_check_plans_the_longest_run(monkeypatch, deck, seed):
    records = synthetic_stream([LaneTraffic(1, "+x", 400, 40, 30), LaneTraffic(2, "-x", 400, 30, 25)], 60, seed=seed)
    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 4, **deck}, "tire": {"model": "point"},
            "road": {"class": "none"}, "crossing": {"approach": 30.0}}
    planned = []
    monkeypatch.setattr(vbikit.solve.plan, "plan_run", lambda crossing, limits=None: planned.append(crossing))
    job = traffic_study(records, base, batch_size=16)  # (checks its budget: the one crossing planned)
    template = job.context().template
    durations = [template.with_vehicles(tuple(job.crossing(e).vehicles), None, None).duration for e in range(job.size)]
    assert len(planned) == 1 and job.size > 20 and max(len(v) for v in job.events) > 1
    assert planned[0].duration == pytest.approx(max(durations), rel=1e-12)
