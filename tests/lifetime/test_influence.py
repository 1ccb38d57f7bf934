"""Influence lines and static peaks by convolution against the coupled run's static reference."""
import numpy as np
import pytest

from vbikit.analysis.effects import load_effect_response
from vbikit.analysis.response import point_response
from vbikit.lifetime.influence import (Tabulated, TirePattern, deflection_line, effect_line, event_static,
                                       point_loads)
from vbikit.solve import simulate
from vbikit.traffic.records import VehicleRecord
from vbikit.traffic.study import traffic_study


def _records():
    # unequal loads, spacings, speeds and both directions, so a swapped axle, sign or index shows
    return [
        VehicleRecord(0.0, "+x", 22.0, (50e3, 110e3, 95e3), (4.3, 1.25), lane=1, id="a"),
        VehicleRecord(0.35, "-x", 17.0, (40e3, 70e3), (5.1,), lane=2, id="b"),
        VehicleRecord(9.0, "+x", 25.0, (60e3, 80e3, 75e3, 72e3, 61e3), (5.4, 1.3, 9.6, 1.2), lane=1, id="c"),
    ]


@pytest.mark.parametrize("bridge, tire, lanes", [("paper-bridge-1-beam", "point", (0.0, 0.0)),
                                                 ("paper-bridge-1", "multipoint", None)])
def test_static_peak_equals_coupled_static_reference(bridge, tire, lanes):
    """Every event's static history by convolution, evaluated at the coupled run's time steps,
    equals the run's static reference (vbikit.analysis: mode-acceleration static part and the
    static modal deflection) to 1e-9 relative — several-vehicle event, both directions."""
    base = {"bridge": {"model": bridge, "n_modes": 4}, "tire": {"model": tire}, "road": {"class": "none"},
            "response": {"moment": [3.7], "shear": [2.1]}}
    study = traffic_study(_records(), base, lanes=lanes)
    ctx = study.context()
    deck = ctx.template.crossing.bridge
    lines = [deflection_line(deck, 5.2, study.lanes[0])] + [effect_line(deck, e) for e in ctx.plan.load_effects]
    pattern = TirePattern.of_crossing(ctx.template)
    assert study.size == 2 and len(study.events[0]) == 2
    for e in range(study.size):
        result = simulate(study.crossing(e))
        got = event_static(study.records, [study.events[e]], lines, deck.span, study.lanes, pattern,
                           times=[result.time + study.event_start[e]], keep_histories=True)
        refs = [point_response(result, 5.2, study.lanes[0]).static_displacement]
        refs += [load_effect_response(result, eff).static for eff in ctx.plan.load_effects]
        for j, (line, ref) in enumerate(zip(lines, refs)):
            scale = np.max(np.abs(ref))
            assert np.max(np.abs(got.histories[j] - ref)) <= 1e-9 * scale, line.name
            assert got.peaks[0, j] == pytest.approx(ref[np.argmax(line.sign * ref)], rel=1e-9)


def test_moment_line_closed_form_and_tabulation():
    """Simply supported beam: moment at a under a unit downward load at x is x(L−a)/L (x ≤ a),
    a(L−x)/L (x ≥ a) (statics); the tabulated line, with its kink on a grid node, reproduces it to
    rounding; the shear just right of a, −x/L (x < a) and 1 − x/L (x > a), keeps its jump."""
    from vbikit.bridge.presets import BRIDGE_PRESETS

    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    L, a = deck.span, 6.1
    line = effect_line(deck, deck.load_effect("moment", x=a))
    x = np.linspace(0, L, 1001)
    expected = np.where(x <= a, x * (L - a) / L, a * (L - x) / L)
    assert np.allclose(line.evaluate(x, np.zeros_like(x)), expected, rtol=0, atol=1e-12 * L)
    assert line.sign == 1.0
    dx = 0.05
    tab = Tabulated(line, deck, [0.0], dx)
    err = np.abs(tab(x, np.zeros(x.size, np.int64)) - expected)
    inner = (x > dx) & (x < L - dx)
    assert np.max(err[inner]) <= 1e-7  # the kink at the section is a node: exact but for the ε of the one-sided limits
    assert np.max(err[~inner]) <= dx * max(a, L - a) / L / 2  # the support kinks inside a cell: ≤ h·|g'|/2
    shear = effect_line(deck, deck.load_effect("shear", x=a))
    tab = Tabulated(shear, deck, [0.0], dx)
    xs = np.array([a - 1e-6, a + 1e-6, a - 0.37, a + 0.41])
    expected = np.where(xs < a, -xs / L, 1 - xs / L)
    assert np.allclose(tab(xs, np.zeros(4, np.int64)), expected, rtol=0, atol=1e-5)


def test_single_axle_peak_closed_form():
    """One 100 kN axle crossing a simply supported beam: the peak midspan moment is PL/4 (statics);
    sampled with ds = L/400 on the tabulated line, within ds/2·P/2 of it (the line's slope is 1/2)."""
    from vbikit.bridge.presets import BRIDGE_PRESETS

    deck = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=3)
    L = deck.span
    line = effect_line(deck, deck.load_effect("moment", x=L / 2))
    rec = [VehicleRecord(3.0, "+x", 20.0, (100e3, 1e-6), (30.0,), lane=1)]  # second axle negligible
    ds = L / 400
    tab = Tabulated(line, deck, np.unique(point_loads(rec, (0.0,)).y), 0.01)
    got = event_static(rec, [(0,)], [line], L, (0.0,), ds=ds, tables=[tab]).peaks[0, 0]
    assert abs(got - 100e3 * L / 4) <= ds / 2 * 100e3 / 2 + 100e3 * 0.01 / 4
