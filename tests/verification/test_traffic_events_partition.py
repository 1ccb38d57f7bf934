# Traffic events against an independent grouping: vehicle i is on the bridge from t_i until its last
# axle leaves, t_i + (span + length_i)/v_i (docs/traffic.md); events are the connected components of
# the "on the bridge together" relation, found here by union–find over every pair of vehicles.
from __future__ import annotations

import numpy as np
import pytest

from vbikit.traffic.events import on_bridge_intervals, partition


def _components(t, v, lengths, span):
    n = len(t)
    start = np.asarray(t, float)
    end = start + (span + np.asarray(lengths, float)) / np.asarray(v, float)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for j in range(i + 1, n):
            if start[i] < end[j] and start[j] < end[i]:  # open intervals overlap
                parent[find(i)] = find(j)
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(find(i), []).append(i)
    return sorted(tuple(sorted(g)) for g in groups.values()), start, end


@pytest.mark.parametrize("seed", range(6))
def test_events_are_the_connected_components(seed):
    rng = np.random.default_rng(seed)
    n, span = 60, 30.0
    t = np.sort(rng.uniform(0.0, 120.0, n))
    v = rng.uniform(8.0, 33.0, n)  # fast short cars overtake slow long trucks
    lengths = np.where(rng.random(n) < 0.5, rng.uniform(3.0, 6.0, n), rng.uniform(12.0, 22.0, n))
    expected, start, end = _components(t, v, lengths, span)
    events = partition(t, v, lengths, span)
    assert sorted(tuple(sorted(e.vehicles)) for e in events) == expected
    for e in events:
        members = list(e.vehicles)
        assert e.start == pytest.approx(start[members].min(), rel=1e-14)
        assert e.end == pytest.approx(end[members].max(), rel=1e-14)  # the last to leave, not the latest to enter
    s, en = on_bridge_intervals(t, v, lengths, span)
    np.testing.assert_allclose(en - s, (span + lengths) / v, rtol=1e-14)


def test_a_long_slow_truck_holds_an_event_open():
    # truck: on the bridge 0 … (30 + 20)/10 = 5 s; a car enters at 1 s and leaves at 1 + 34/34 = 2 s;
    # a second car enters at 4 s, while the truck is still on: one event of three
    events = partition([0.0, 1.0, 4.0], [10.0, 34.0, 34.0], [20.0, 4.0, 4.0], 30.0)
    assert [e.vehicles for e in events] == [(0, 1, 2)]
    assert events[0].end == pytest.approx(max(5.0, 4.0 + 34.0 / 34.0))
    # without the truck's length (exit at 3 s) the last car would be alone: the length matters
    events = partition([0.0, 1.0, 4.0], [10.0, 34.0, 34.0], [5.0, 4.0, 4.0], 30.0)
    assert [e.vehicles for e in events] == [(0, 1), (2,)]
