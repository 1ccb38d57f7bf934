"""Rainflow counting: the ASTM E1049-85 example, and chunked counting with joined residuals equal
to the whole-history count of the ``rainflow`` package (an independent implementation)."""
from __future__ import annotations

import json

import numpy as np
import pytest
import rainflow as rainflow_pkg
from hypothesis import given, settings
from hypothesis import strategies as st

from vbikit.fatigue import FatigueError, RainflowCounter, RainflowState, finish, histogram, join, rainflow, reversals

#: ASTM E1049-85 (reapproved 2011), 5.4.4 (rainflow counting) and its worked example: the
#: reversals A…I of the example load history and the counted (range, cycles) of its table (the
#: same history and counts are quoted in the rainflow package's issue #4 and MathWorks' rainflow page)
ASTM_HISTORY = [-2, 1, -3, 5, -1, 3, -4, 4, -2]
ASTM_TABLE = [(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]


def test_astm_e1049_example():
    assert rainflow(ASTM_HISTORY) == ASTM_TABLE


def test_astm_example_with_leading_and_trailing_zeros_is_a_different_history():
    # The standard's table belongs to the history WITHOUT zeros.  With a 0 before and after, two
    # more half cycles of range 2 appear (by hand, three-point rule: 0, -2, 1 -> |1-(-2)| = 3 >= 2
    # and the range 0..-2 holds the start: half cycle 2; at the end -2, 0 is a residual half cycle 2).
    assert rainflow([0, *ASTM_HISTORY, 0]) == [(2.0, 1.0), *ASTM_TABLE]


def test_streaming_counter_gives_the_astm_table():
    c = RainflowCounter()
    c.feed(ASTM_HISTORY[:4])
    c.feed(ASTM_HISTORY[4:])
    assert c.finish() == ASTM_TABLE


def test_small_histories_by_hand():
    assert rainflow([]) == []
    assert rainflow([3.0]) == []
    assert rainflow([2.0, 2.0, 2.0]) == []              # no range, no cycle
    assert rainflow([-5.0, 4.0]) == [(9.0, 0.5)]        # one half cycle (first and last points are reversals)
    assert rainflow([0, 1, 2, 3, 1]) == [(2.0, 0.5), (3.0, 0.5)]  # monotone run 0..3 is one range
    assert reversals([0, 1, 1, 2, 3, 1, 1, 0]).tolist() == [0.0, 3.0, 0.0]


def _whole(x) -> list[tuple[float, float]]:
    """The reference: the rainflow package on the whole history (independent of the streaming code)."""
    return [(float(r), float(n)) for r, n in rainflow_pkg.count_cycles(list(map(float, x)))]


def _chunked(x: np.ndarray, cuts: list[int]) -> list[tuple[float, float]]:
    """Each chunk counted by its own counter (as on separate workers), states serialised through
    JSON and joined in order."""
    parts = np.split(x, sorted(set(cuts)))
    states = []
    for part in parts:
        c = RainflowCounter()
        c.feed(part)
        states.append(RainflowState.from_dict(json.loads(json.dumps(c.state.to_dict()))))
    state = states[0]
    for other in states[1:]:
        state = join(state, other)
    return finish(state)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=3, max_size=60), st.lists(st.integers(1, 59), max_size=8))
def test_chunked_equals_whole_history_integer_histories(values, cuts):
    # small integers: many ties and plateaus, the hard cases of rainflow counting
    x = np.array(values, dtype=float)
    cuts = [c for c in cuts if c < x.size]
    if np.unique(x).size < 2 or x.size < 3:
        return
    assert _chunked(x, cuts) == _whole(x)


@pytest.mark.parametrize("seed", range(20))
def test_chunked_equals_whole_history_random_splits(seed):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.normal(size=400)) + rng.normal(size=400)   # a wandering stress history
    cuts = rng.choice(np.arange(1, x.size), size=rng.integers(1, 15), replace=False).tolist()
    assert _chunked(x, cuts) == _whole(x)
    # the same chunks fed to one counter
    c = RainflowCounter()
    for part in np.split(x, sorted(cuts)):
        c.feed(part)
    assert c.finish() == _whole(x)


def test_chunked_equals_whole_at_reversals_inside_monotone_runs_and_length_one_chunks():
    x = np.array([0.0, 2.0, 5.0, 1.0, 1.0, 3.0, -4.0, -1.0, -2.0, 6.0, 6.0, 0.5, 2.5, -3.0])
    whole = _whole(x)
    at_reversal = [2, 3, 6, 9]           # chunks end exactly at a peak or valley
    in_monotone = [1, 7, 10]             # chunk boundaries inside a rising or falling run / plateau
    singles = list(range(1, x.size))     # every chunk of length 1
    for cuts in (at_reversal, in_monotone, singles):
        assert _chunked(x, cuts) == whole
    c = RainflowCounter()
    for v in x:
        c.feed([v])
    assert c.finish() == whole


def test_residual_stays_small_for_a_long_history():
    # memory bounded by the residual: 200 000 points of noise leave a short residual
    rng = np.random.default_rng(3)
    c = RainflowCounter(bin_width=0.1)
    for _ in range(20):
        c.feed(rng.normal(size=10_000))
    state = c.state
    assert state.residual.size < 40
    assert state.ranges.size < 200        # bins, not cycles
    assert state.counts.sum() > 50_000    # the closed full cycles are all there


def test_binned_counter_equals_binned_whole_count():
    rng = np.random.default_rng(7)
    x = rng.normal(size=3000)
    whole = _whole(x)
    width = 0.25
    c = RainflowCounter(bin_width=width)
    for part in np.array_split(x, 9):
        c.feed(part)
    got = c.finish()
    # the same binned counting on separate workers, states joined
    states = []
    for part in np.array_split(x, 5):
        w = RainflowCounter(bin_width=width)
        w.feed(part)
        states.append(w.state)
    joined = states[0]
    for other in states[1:]:
        joined = join(joined, other)
    assert finish(joined) == got
    edges, totals = histogram([r for r, _ in whole], [n for _, n in whole], width)
    expected = [(k * width, t) for k, t in enumerate(totals) if t > 0]
    assert [(round(r / width), n) for r, n in got] == [(round(r / width), n) for r, n in expected]


def test_histogram_by_hand():
    edges, totals = histogram([0.1, 0.9, 1.0, 2.5], [1.0, 0.5, 2.0, 0.5], bin_width=1.0)
    assert edges.tolist() == [0.0, 1.0, 2.0, 3.0]
    assert totals.tolist() == [1.5, 2.0, 0.5]      # [0,1): 1 + 0.5; [1,2): 2; [2,3): 0.5


def test_bad_input_names_the_argument():
    with pytest.raises(FatigueError) as err:
        rainflow([0.0, np.nan, 1.0])
    assert err.value.key == "series"
    with pytest.raises(FatigueError) as err:
        RainflowCounter().feed([[1.0, 2.0]])
    assert err.value.key == "chunk"
    with pytest.raises(FatigueError) as err:
        join(RainflowCounter(bin_width=1.0).state, RainflowCounter().state)
    assert err.value.key == "state_b"
    with pytest.raises(FatigueError) as err:
        histogram([1.0], [1.0], bin_width=0.0)
    assert err.value.key == "bin_width"
    # a stored state read back (e.g. a worker's JSON) is checked before counting continues
    good = {"ranges": [1.0], "counts": [2.0], "residual": [0.0, 3.0], "bin_width": None}
    for bad in ({"residual": [0.0, float("nan")]}, {"counts": [-1.0]}, {"ranges": [float("inf")]},
                {"bin_width": 0.0}):
        with pytest.raises(FatigueError) as err:
            RainflowState.from_dict({**good, **bad})
        assert err.value.key in ("state", "bin_width"), bad


def test_counting_the_reversals_alone_gives_the_same_cycles():
    """The lifetime runner counts ``rainflow(reversals(h))`` (``vbikit.lifetime.jobs``): the same
    (range, count) pairs as the whole history, here random walks with plateaus and the zero ends
    of an event's history (the bridge empty before and after)."""
    rng = np.random.default_rng(11)
    for _ in range(50):
        h = np.round(np.cumsum(rng.normal(size=rng.integers(3, 400))), 1)  # rounding makes plateaus
        h = np.concatenate([[0.0, 0.0], h, [0.0, 0.0]])
        assert rainflow(reversals(h)) == rainflow(h)
