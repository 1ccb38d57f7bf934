"""Exact static peaks (vbikit.lifetime.peaks) against a brute-force 1 mm travel grid, on cases
that defeat sampling: opposing trucks over a support (reaction), a shear line's jump, one axle,
an asymmetric continuous beam."""
import numpy as np
import pytest

from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.presets import BRIDGE_PRESETS
from vbikit.lifetime.influence import HALF_TRACK, Tabulated, effect_line, event_static
from vbikit.traffic.records import VehicleRecord

#: the brute force's travel step [m]
GRID = 1e-3


def _brute(records, tab, span, lanes=(0.0, 0.0)):
    """R(t) on a grid of GRID of travel of the fastest vehicle over the whole event, summed here
    from the records (each axle load halved on two wheels at ± HALF_TRACK about its lane's y), and the
    bound Σ P · max|g'| · GRID by which its largest value may fall short of the supremum (each load
    moves at most GRID a step; at a jump the supremum is a one-sided limit, approached from its side)."""
    t0 = min(r.time for r in records) - 1.0
    t1 = max(r.time + (span + r.length) / r.speed for r in records) + 1.0
    dt = GRID / max(r.speed for r in records)
    t = np.arange(t0, t1 + dt, dt)
    total = np.zeros(t.size)
    for r in records:
        d = np.r_[0.0, np.cumsum(r.axle_spacings)]
        for dd, p in zip(d, r.axle_loads):
            x = -dd + r.speed * (t - r.time) if r.direction == "+x" else span + dd - r.speed * (t - r.time)
            for y in (HALF_TRACK, -HALF_TRACK):
                track = int(np.argmin(np.abs(tab.tracks - (lanes[r.lane - 1] + y))))
                total += 0.5 * p * tab(x, np.full(t.size, track))
    slope = np.max(np.abs(tab.b - tab.a)) / tab.h
    # plus the table's one-sided limits, taken ε = 1e-9·L off the nodes: its cells meet with steps
    # of up to 2ε·|g'|, which the exact sweep's straight segments smooth out
    eps = 1e-9 * max(span, 1.0)
    return total, sum(sum(r.axle_loads) for r in records) * slope * (GRID + 2 * eps)


def _turning_points(x, gate):
    """Hysteresis filter (a reversal kept when larger than ``gate``), plain Python."""
    out = [x[0]]
    for v in x[1:]:
        if len(out) >= 2 and (v - out[-1]) * (out[-1] - out[-2]) >= 0:
            out[-1] = v
        elif abs(v - out[-1]) > gate:
            out.append(v)
    return np.array(out)


def _check(records, line, deck, dx=0.02, lanes=(0.0, 0.0)):
    tab = Tabulated(line, deck, sorted({y + s * HALF_TRACK for y in lanes for s in (-1, 1)}), dx)
    es = event_static(records, [tuple(range(len(records)))], [line], deck.span, lanes, tables=[tab],
                      keep_histories=True)
    got = es.peaks[0, 0]
    hist, bound = _brute(records, tab, deck.span, lanes)
    s = line.sign
    best = s * np.max(s * hist)
    scale = np.max(np.abs(hist))
    # never below a value the history takes (the exact supremum), within rounding
    assert s * got >= s * best - 1e-9 * scale
    # and within the grid's bound of the grid's best
    assert s * got - s * best <= bound + 1e-9 * scale, (got, best, bound)
    # the history's turning points (what the fatigue count reads): those of the brute force within
    # its bound, both filtered alike (reversals above 3 × the bound)
    exact = _turning_points(es.histories[0], 3 * bound)
    brute = _turning_points(hist, 3 * bound)
    assert exact.size == brute.size and np.all(np.abs(exact - brute) <= bound + 1e-9 * scale), (exact, brute)
    assert es.histories[0][0] == 0 and es.histories[0][-1] == 0  # the bridge empty before and after
    # the extreme the other way (the direction not reported), held to the same two bounds
    other, other_best = es.opposite[0, 0], -s * np.max(-s * hist)
    assert -s * other >= -s * other_best - 1e-9 * scale
    assert -s * other - (-s * other_best) <= bound + 1e-9 * scale, (other, other_best, bound)
    return got, best, bound


def test_opposing_trucks_over_the_entry_support():
    """Reaction at the entry support of the example's 16.76 m beam, the example week's day-0 event
    of issue 32 (a +x five-axle and a −x three-axle truck): the peak, with the +x truck's last
    axle just on and the −x truck's front axle not yet off the support, lasts ≈ 0.6 ms of
    travel.  The sampled pass gave 298.1 kN against the brute force's 368.7 kN."""
    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    line = effect_line(deck, deck.load_effect("reaction", support=0))
    recs = [VehicleRecord(61232.187, "+x", 22.15430291449719,
                          (61164.03953091272, 71188.60661061645, 78604.15011003624, 78866.63141865704,
                           70817.42306065423), (5.446414256508372, 1.3082720205289682, 9.444354667607124,
                                                1.3171943268598336), lane=1),
            VehicleRecord(61232.289, "-x", 24.316008728629054, (75835.81384757446, 73147.49414423549,
                                                               80365.48955433207),
                          (5.011286660421838, 1.277080637534855), lane=2)]
    _, best, _ = _check(recs, line, deck)
    assert best == pytest.approx(368.66e3, rel=1e-4)  # the brute force's value (issue 32: 368.7 kN)


def test_shear_jump_under_a_truck():
    """Shear just right of x = 6.1 m of the 16.76 m beam (a jump of 1 in the line) under a
    three-axle truck: the peak is a one-sided limit at an axle's crossing of the section."""
    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    line = effect_line(deck, deck.load_effect("shear", x=6.1))
    recs = [VehicleRecord(0.37, "+x", 23.7, (45e3, 120e3, 80e3), (3.9, 1.25), lane=1)]
    _check(recs, line, deck)


def test_single_axle_closed_form():
    """One 100 kN axle (a negligible second one 30 m behind): moment at a = 5.3 m of the beam,
    peak P·a(L − a)/L (statics) exactly, not within a sampling step."""
    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    L, a = deck.span, 5.3
    line = effect_line(deck, deck.load_effect("moment", x=a))
    recs = [VehicleRecord(0.123, "-x", 19.3, (100e3, 1e-6), (30.0,), lane=1)]
    got, _, _ = _check(recs, line, deck)
    assert got == pytest.approx(100e3 * a * (L - a) / L, rel=1e-8)


@pytest.mark.parametrize("kind, where", [("moment", {"x": 14.0}), ("reaction", {"support": 1})])
def test_asymmetric_continuous_beam(kind, where):
    """Two-span continuous beam (12 m + 20 m, curved influence lines: a knot at every node), two
    trucks in opposite directions at different speeds."""
    deck = ContinuousBeam(spans=(12.0, 20.0), EI=(5e9, 8e9), mass_per_length=8e3, n_modes=4)
    line = effect_line(deck, deck.load_effect(kind, **where))
    recs = [VehicleRecord(0.0, "+x", 21.0, (60e3, 130e3, 110e3), (3.6, 1.3), lane=1),
            VehicleRecord(0.41, "-x", 16.5, (55e3, 95e3, 90e3, 85e3), (3.2, 6.1, 1.3), lane=2)]
    _check(recs, line, deck, dx=0.05)


def test_grillage_deck_wheels_on_four_tracks():
    """Slab-on-girder deck (paper-bridge-1): the line differs from wheel track to wheel track (four
    table rows), two trucks in opposite lanes and directions; Girder 2's moment at 4.1 m."""
    deck = BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=4)
    line = effect_line(deck, deck.load_effect("moment", x=4.1, girder=2), y=float(deck.girder_y[1]))
    recs = [VehicleRecord(0.0, "+x", 21.0, (60e3, 130e3, 110e3), (3.6, 1.3), lane=1),
            VehicleRecord(0.21, "-x", 16.5, (55e3, 95e3), (4.2,), lane=2)]
    _check(recs, line, deck, lanes=(-1.8, 1.8))


def test_no_traffic():
    """A day without trucks: no events, no peaks, empty histories."""
    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    line = effect_line(deck, deck.load_effect("moment", x=5.0))
    tab = Tabulated(line, deck, [-HALF_TRACK, HALF_TRACK], 0.02)
    es = event_static([], [], [line], deck.span, (0.0,), tables=[tab], keep_histories=True)
    assert es.peaks.shape == (0, 1) and es.histories[0].size == 0 and list(es.offsets[0]) == [0]
