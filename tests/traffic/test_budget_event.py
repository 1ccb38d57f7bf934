"""The traffic budget check plans the stream's longest run (``TrafficStudy.check_budget``).

Was: the longest event was chosen by a formula of its own, each vehicle's record time plus (approach +
span + axle spacings) / speed, which counts the approach after every vehicle's entry rather than once
before the run and ignores the deck's skew reach: on streams with mixed speeds it planned a shorter
event than the longest in 3 of the 12 streams below (a slow vehicle whose approach starts the run earlier than the first
vehicle's).  The longest run is now read from ``partition``'s ends and the run's start as
``Crossing.start_time`` defines it, and planned first, with the events largest by top speed and by the
vehicles' size (memory).  Checked against brute force: every event's crossing built (without
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
    assert 1 <= len(planned) <= 12 and job.size > 20 and max(len(v) for v in job.events) > 1
    assert planned[0].duration == pytest.approx(max(durations), rel=1e-12)  # the longest first


def test_the_budget_check_finds_the_event_of_most_memory_though_not_the_longest(monkeypatch):
    """The review's case: in the straight deck's stream of seed 0 the longest event (4 trucks) needs 39.6 MB,
    a shorter one of 6 trucks 42.7 MB (``estimate_run``: memory grows with the vehicles' DOFs and wheels).
    With a 41 MB budget the check planned only the longest and passed; that event then stopped the stream
    mid-run.  Now the check refuses before any event runs — and brute force over every event agrees."""
    from vbikit.solve.budget import Limits, estimate_run
    from vbikit.solve.plan import plan_run
    from vbikit.study.spec import StudyError

    records = synthetic_stream([LaneTraffic(1, "+x", 400, 40, 30), LaneTraffic(2, "-x", 400, 30, 25)], 60, seed=0)
    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 4}, "tire": {"model": "point"}, "road": {"class": "none"},
            "crossing": {"approach": 30.0}}
    job = traffic_study(records, base, batch_size=16)  # (the default budget: passes)
    memory = [estimate_run(c, plan_run(c).dt).memory for c in (job.crossing(e) for e in range(job.size))]
    longest = max(range(job.size), key=lambda e: job.crossing(e).duration)
    assert memory[longest] < 41e6 < max(memory)  # the case: the longest event is not the largest
    with pytest.raises(StudyError, match="above the budget of one event"):
        traffic_study(records, base, batch_size=16, limits=Limits(max_memory=41e6))
    traffic_study(records, base, batch_size=16, limits=Limits(max_memory=max(memory) * 1.001))  # just above: passes
