"""How a lifetime dynamic round is cut into batches (``DynamicJob.batches``): by day when the
workers must draw the day's traffic, in equal batches across days when every event's records are
stored (so that a short run's round keeps every worker busy)."""
from __future__ import annotations

from vbikit.lifetime.jobs import EVENT_STRIDE, MIN_DYNAMIC_BATCHES, DynamicJob


def _job(items, stored: bool, batch_size: int = 32) -> DynamicJob:
    records = tuple(("record",) for _ in items) if stored else ()
    return DynamicJob(None, "setup", 1, tuple(items), (), batch_size, event_records=records)


def test_stored_records_give_equal_batches_across_days():
    # 7 days of 19 events: by day 7 batches of 19 (4 + 3 on 2 workers); stored: 16 of 8 or 9
    items = [d * EVENT_STRIDE + k for d in range(7) for k in range(19)]
    by_day = _job(items, stored=False).batches()
    assert [len(b) for b in by_day] == [19] * 7 and all(len({g // EVENT_STRIDE for g in b}) == 1 for b in by_day)
    even = _job(items, stored=True).batches()
    assert MIN_DYNAMIC_BATCHES == 16 and len(even) == 16
    assert sorted(len(b) for b in even) == [8] * 11 + [9] * 5  # 133 = 5·9 + 11·8
    assert [g for b in even for g in b] == items  # every event once, in order
    # many events: batches of at most batch_size
    many = [d * EVENT_STRIDE + k for d in range(3) for k in range(400)]
    cut = _job(many, stored=True).batches()
    assert len(cut) == 38 and max(map(len, cut)) <= 32 and [g for b in cut for g in b] == many
    # fewer events than MIN_DYNAMIC_BATCHES: one a batch; one record missing: by day again
    assert _job(items[:5], stored=True).batches() == [(g,) for g in items[:5]]
    partial = DynamicJob(None, "setup", 1, tuple(items), (), 32, event_records=(None,) + (("r",),) * (len(items) - 1))
    assert partial.batches() == by_day
