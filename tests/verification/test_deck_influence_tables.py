"""The grillage's wheel-line influence tables (``vbikit.bridge.deck_effects.DeckInfluence``):
vᵀF along a line y is a cubic in t on each element, so the tabulated values equal the direct
``load_weights`` evaluation up to round-off, on a straight and on a skew deck, for an asymmetric
two-vehicle crossing (different trucks, opposite directions, different lateral offsets); the tables
belong to one bridge's effect and one wheel line."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.effects import contact_influences, contact_positions
from vbikit.bridge import paper_deck
from vbikit.solve import Crossing, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import hs20_44, semitrailer_3s2

EFFECTS = (("moment", dict(x=7.3, girder=4)), ("shear", dict(x=3.1, girder=2)),
           ("reaction", dict(support=0, girder=3)), ("moment", dict(x=8.38, girder=4)))


@pytest.fixture(scope="module", params=[0.0, 20.0], ids=["straight", "skew 20°"])
def event(request):
    deck = paper_deck(2, n_modes=4, use_cache=False, n_elements=14, skew=request.param)
    c = Crossing(deck, vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=2.1),
                                 VehicleMotion(hs20_44(), 19.0, direction="-x", entry_time=0.25,
                                               lateral_offset=-1.7)), free_vibration=0.05, dt=2e-3)
    return deck, simulate(c)


def test_tables_equal_the_direct_evaluation(event):
    deck, result = event
    effects = [deck.load_effect(k, **kw) for k, kw in EFFECTS]
    tabulated = contact_influences(result, effects)
    x, y = contact_positions(result)
    xi = deck.span_coordinate(x, y)
    on = (xi >= 0.0) & (xi <= deck.span)
    assert on.sum() > 1000 and np.unique(y).size >= 4
    for k, effect in enumerate(effects):
        direct = np.zeros(x.shape)
        direct[on] = effect.influence.direct(x[on], y[on])
        scale = np.abs(direct).max()
        assert scale > 0
        if effect.kind != "reaction":  # the section's own element (its kinked terms) is crossed
            e = np.searchsorted(deck.dof_map.stations, xi[on], side="right") - 1
            assert np.count_nonzero(e == effect.influence.element) > 100
        # round-off of the cubic through four values: measured ≤ 2.6e-15 of the largest value
        assert np.abs(tabulated[k] - direct).max() <= 1e-13 * scale, effects[k].label


def test_tables_are_per_bridge_and_per_wheel_line():
    a = paper_deck(2, n_modes=4, use_cache=False, n_elements=14)
    b = paper_deck(2, n_modes=4, use_cache=False, n_elements=14, skew=10.0)
    ia = a.load_effect("moment", x=7.3, girder=4).influence
    ib = b.load_effect("moment", x=7.3, girder=4).influence
    x = np.linspace(0.5, 16.0, 50)
    first = ia(x, np.full(x.size, 2.1))
    other_line = ia(x, np.full(x.size, -1.7))  # the same effect, another wheel line
    other_bridge = ib(x, np.full(x.size, 2.1))  # another bridge, the same line
    assert np.abs(first - other_line).max() > 1e-3 * np.abs(first).max()
    assert np.abs(first - other_bridge).max() > 1e-3 * np.abs(first).max()
    # and each still matches its own direct evaluation after the other was tabulated
    np.testing.assert_allclose(ia(x, np.full(x.size, 2.1)), ia.direct(x, np.full(x.size, 2.1)),
                               rtol=0, atol=1e-11 * np.abs(first).max())
    np.testing.assert_allclose(other_bridge, ib.direct(x, np.full(x.size, 2.1)), rtol=0,
                               atol=1e-11 * np.abs(first).max())
    assert {y for y, _ in ia._line_tables.items()} == {2.1, -1.7} and {y for y, _ in ib._line_tables.items()} == {2.1}
