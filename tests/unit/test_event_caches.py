"""Set-up kept between crossings and events (issue 33): the mode-shape tables and the ``Modes`` bundle per
bridge and set of tracks, the load-effect step check's deck quantities per bridge and set of wheel lines,
a crossing's exit time and top speed, and the step check deferred to first use in population runs.

Every cached path is compared bit for bit with the same quantity computed afresh (caches emptied), and
each cache key is tested with inputs that differ in exactly one part of the key (another bridge with the
same span, other tracks, another speed), where a wrong key would return the other's stale value."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit._kept import forget_kept
from vbikit.analysis import effect_step
from vbikit.analysis.effects import load_effect_responses
from vbikit.bridge import paper_beam
from vbikit.bridge.presets import paper_deck
from vbikit.solve import Crossing, VehicleMotion, simulate, tabulate
from vbikit.solve.system import kernel_data
from vbikit.vehicle.presets import hs20_44


@pytest.fixture(scope="module")
def deck():
    return paper_deck(1, n_modes=4, use_cache=False, n_elements=12)


def _fresh():
    forget_kept()


def test_track_table_is_kept_per_bridge_and_track_set_and_equals_a_fresh_one(deck):
    _fresh()
    fresh = tabulate._tabulate(deck, np.array([0.0, 0.9]), 100)
    first = tabulate.tabulate_tracks(deck, np.array([0.0, 0.9]))
    assert tabulate.tabulate_tracks(deck, np.array([0.0, 0.9])) is first  # kept
    for name in ("start", "end", "values", "slopes"):
        assert np.array_equal(getattr(first, name), getattr(fresh, name))
    # another track set on the same deck: its own table (a key without the tracks would return the first)
    other = tabulate.tabulate_tracks(deck, np.array([0.0, 0.5]))
    assert other is not first and not np.array_equal(other.values[1], first.values[1])
    assert np.array_equal(other.values[1], tabulate._tabulate(deck, np.array([0.5]), 100).values[0])
    # another bridge with the same span and modes but other stiffness (Bridge 1's section): its own table
    beam1, beam2 = paper_beam(16.76, "I", n_modes=6), paper_beam(16.76, "II", n_modes=6)
    t2 = tabulate.tabulate_tracks(beam2, np.array([0.0]))
    assert not np.array_equal(tabulate.tabulate_tracks(beam1, np.array([0.0])).values, t2.values)


def test_modes_bundle_is_kept_with_its_table_and_follows_the_bridge():
    beam = paper_beam(16.76, "II", n_modes=6)
    c1 = Crossing(beam, hs20_44(), speed=20.0)
    c2 = Crossing(beam, hs20_44(), speed=25.0)
    d1, d2 = kernel_data(c1), kernel_data(c2)
    assert d2.modes is d1.modes  # same bridge and tracks: one bundle
    _fresh()
    d3 = kernel_data(c1)
    for a, b in zip(d1.modes, d3.modes):
        assert np.array_equal(a, b)
    # the same beam with other damping: a different bridge object, its own bundle and ζ
    damped = paper_beam(16.76, "II", n_modes=6, damping_ratio=0.05)
    d4 = kernel_data(Crossing(damped, hs20_44(), speed=20.0))
    assert np.allclose(d4.modes.zeta, 0.05) and np.allclose(d1.modes.zeta, beam.damping_ratios)


def test_exit_time_and_top_speed_are_those_of_the_crossing_they_belong_to(deck):
    c = Crossing(deck, hs20_44(), speed=20.0)
    exit_20, top_20 = c.exit_time(), c.max_speed
    assert c.with_road(None).exit_time() == exit_20  # a copy on another road keeps its vehicles
    faster = dataclasses.replace(c, speed=25.0)  # a wrong cache would keep the 20 m/s values
    # closed form: the last axle (setback = the vehicle's length) leaves x = span; t = (span + approach + L) / v
    length = float(max(w.offset for w in hs20_44().wheels) - min(w.offset for w in hs20_44().wheels))
    assert faster.exit_time() == pytest.approx((deck.span + c.approach + length) / 25.0, rel=1e-12)
    assert exit_20 == pytest.approx((deck.span + c.approach + length) / 20.0, rel=1e-12)
    assert faster.max_speed == 25.0 and top_20 == 20.0
    # the road range: from the last axle's start (−approach − L) to where the front axle is at the end
    lo, hi = faster.road_extent()
    assert lo == pytest.approx(-c.approach - length, rel=1e-12)
    assert hi == pytest.approx(-c.approach + 25.0 * faster.duration, rel=1e-12)
    assert c.road_extent()[1] == pytest.approx(-c.approach + 20.0 * c.duration, rel=1e-12)


def test_step_check_deck_quantities_are_kept_per_wheel_lines_and_equal_fresh_ones(deck):
    effect = deck.default_load_effects()[0]
    near = Crossing(deck, hs20_44(), speed=20.0, lateral_offset=-1.0)
    far = Crossing(deck, hs20_44(), speed=20.0, lateral_offset=1.0)
    _fresh()
    fresh_near = effect_step.load_effect_step(near, [effect])
    fresh_far = effect_step.load_effect_step(dataclasses.replace(far), [effect])
    assert fresh_near != fresh_far  # the lines matter: a key without them would mix the two up
    # warm: the other offset's lines in the cache first, then each again (another crossing object)
    assert effect_step.load_effect_step(dataclasses.replace(near), [effect]) == fresh_near
    assert effect_step.load_effect_step(far, [effect]) == fresh_far
    # the step itself is kept per top speed: a faster crossing on the same lines gets its own
    fast = dataclasses.replace(near, speed=35.0)
    warm_fast = effect_step.load_effect_step(fast, [effect])
    _fresh()
    assert effect_step.load_effect_step(dataclasses.replace(fast), [effect]) == warm_fast != fresh_near
    x, y = effect_step._deck_points(near)
    shapes, _, _ = effect_step._deck_modes(near)
    assert np.array_equal(shapes, deck.mode_shapes(x, y))


def test_deferred_step_check_equals_the_immediate_one(deck):
    result = simulate(Crossing(deck, hs20_44(), speed=30.0, dt=4e-3))  # a long step: a warning to compare
    effects = deck.default_load_effects()
    now = load_effect_responses(result, effects)
    later = load_effect_responses(result, effects, check_step=False)
    assert any(r.step_warning for r in now)
    for a, b in zip(now, later):
        assert callable(b.step_check)  # not made yet
        assert np.array_equal(a.dynamic, b.dynamic) and np.array_equal(a.static, b.static)
        assert (b.step_warning, b.recommended_dt) == (a.step_warning, a.recommended_dt)
        assert not callable(b.step_check)  # made once, kept


def test_events_on_warm_caches_equal_events_on_empty_ones():
    """Two events of a stream: the second run after the first (tables, deck quantities kept) equals the
    second run alone on emptied caches, bit for bit."""
    from vbikit.traffic import LaneTraffic, synthetic_stream
    from vbikit.traffic.study import traffic_study

    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "B", "length": 200.0},
            "crossing": {"approach": 5.0, "free_vibration": 0.1}}
    lanes = [LaneTraffic(1, "+x", 900, 80, 5), LaneTraffic(2, "-x", 900, 70, 5)]
    job = traffic_study(synthetic_stream(lanes, 6, seed=2), base, lanes=[-1.8, 1.8], seed=5, batch_size=2)
    _fresh()
    alone = job.run_event(1)
    job.run_event(0)
    warm = job.run_event(1)
    assert alone[1] == warm[1]
    for a, b in zip(alone[0][0], warm[0][0]):
        assert a.keys() == b.keys() and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)
    assert alone[0][1] == warm[0][1]


def test_vehicle_motion_crossing_has_its_own_exit_time(deck):
    """Several-vehicle crossings (events): the exit time is that of its own vehicles."""
    truck = hs20_44()
    one = Crossing(deck, vehicles=(VehicleMotion(truck, 20.0),))
    two = Crossing(deck, vehicles=(VehicleMotion(truck, 20.0), VehicleMotion(truck, 20.0, entry_time=1.5)))
    assert two.exit_time() == pytest.approx(one.exit_time() + 1.5, rel=1e-12)


def test_road_spacing_is_that_of_its_own_stations():
    from vbikit.road import RoadProfile

    road = RoadProfile(np.array([0.0, 0.5, 0.7, 2.0]), np.array([0.0, 1e-3, 0.0, 2e-3]))
    assert road.spacing == pytest.approx(0.2, rel=1e-12)
    assert road.spacing == float(np.min(np.diff(road.x)))  # again: the kept value
    finer = dataclasses.replace(road, x=np.array([0.0, 0.5, 0.55, 2.0]))  # a wrong cache would keep 0.2
    assert finer.spacing == pytest.approx(0.05, rel=1e-12)
    assert dataclasses.replace(road, resolution=0.3).spacing == 0.3


def test_passing_instants_position_tables_are_kept_per_wheel_lines(deck):
    """The load effects' jump and kink instants (``effects._passing_instants``) read a table of their
    positions kept per bridge, effects and wheel lines: a crossing in one lane after another lane's
    crossing warmed the store equals the same crossing on an emptied store, bit for bit; and the table
    of a wheel line on a girder (y = 0: its moment's line kinks at the section only) is not that of a
    line between girders (which breaks at every station): a key without the lines would give the
    second line the first's table."""
    from vbikit.analysis.effects import _passing_instants, _position_table

    effects = [deck.load_effect("moment", 9.0, girder=2), deck.load_effect("shear", 4.0, girder=3),
               deck.load_effect("reaction", support=0, girder=1)]
    runs = [simulate(Crossing(deck, vehicles=(VehicleMotion(hs20_44(), 20.0, lateral_offset=y),), dt=2e-3))
            for y in (-1.3, 0.7)]
    _fresh()
    alone = _passing_instants(runs[1], effects, "jump", "kink")
    _fresh()
    _passing_instants(runs[0], effects, "kink", "jump")
    first = _passing_instants(runs[0], effects, "jump", "kink")
    warm = _passing_instants(runs[1], effects, "jump", "kink")
    for a, b in zip(alone, warm):
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)
    on_girder, between = _position_table(deck, tuple(effects), np.array([0.0]), ("kink",)), \
        _position_table(deck, tuple(effects), np.array([0.7]), ("kink",))
    _fresh()
    fresh = _position_table(deck, tuple(effects), np.array([0.7]), ("kink",))
    np.testing.assert_array_equal(between[0], fresh[0])
    assert on_girder[1][0][1] < between[1][0][1]  # the moment's block: 3 positions on the girder, 14 between
