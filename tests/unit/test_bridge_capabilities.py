"""The bridge models' optional capabilities (protocols in bridge/base.py), the base-class defaults every
bridge answers, the grillage's DOF map and the mode cache's key."""
from __future__ import annotations

import pickle

import numpy as np

from vbikit.bridge import (
    ContinuousBeam,
    DescribesModes,
    EulerBernoulliBeam,
    GirderDeck,
    HasLoadEffects,
    SlabOnGirderBridge,
)
from vbikit.bridge.modefile import ImportedModalBridge
from vbikit.bridge.nodal import DofMap, NodalModes
from vbikit.bridge.presets import BRIDGE_PRESETS, paper_deck
from vbikit.bridge.series import GirderSpanSeries, SpanSeries


def _beam(span: float = 10.0) -> EulerBernoulliBeam:
    return EulerBernoulliBeam(span=span, EI=1e9, mass_per_length=1000.0, n_modes=3)


def _imported() -> ImportedModalBridge:
    deck = SlabOnGirderBridge(span=9.0, n_girders=3, n_modes=3, n_elements=6, use_cache=False)
    return ImportedModalBridge(deck.nodal_modes, deck.omega, deck.damping_ratios, deck.strain_lever_arm)


def test_protocols_tell_the_models_apart():
    deck = SlabOnGirderBridge(span=9.0, n_girders=3, n_modes=3, n_elements=6, use_cache=False)
    beam = _beam()
    cont = ContinuousBeam(spans=(8.0, 10.0), EI=1e9, mass_per_length=1000.0, n_modes=3)
    imported = _imported()
    assert isinstance(deck, GirderDeck) and isinstance(deck, HasLoadEffects) and isinstance(deck, DescribesModes)
    assert not isinstance(beam, GirderDeck) and isinstance(beam, HasLoadEffects) and not isinstance(beam, DescribesModes)
    assert not isinstance(cont, GirderDeck) and isinstance(cont, HasLoadEffects)
    assert isinstance(imported, GirderDeck) and not isinstance(imported, HasLoadEffects)


def test_every_bridge_answers_the_base_defaults():
    beam = _beam(12.0)
    assert (beam.skew, beam.default_lateral_offset, beam.default_response_y, beam.name) == (0.0, 0.0, 0.0, "")
    assert beam.default_response_x == 6.0 and beam.default_x_at(1.0) == 6.0
    assert beam.span_lengths == (12.0,) and list(beam.support_x) == [0.0, 12.0] and beam.span_index(11.0) == 0
    cont = ContinuousBeam(spans=(8.0, 10.0), EI=1e9, mass_per_length=1000.0, n_modes=3)
    assert cont.span_lengths == (8.0, 10.0) and cont.span_index(8.0) == 1 and cont.span_index(7.9) == 0
    deck = SlabOnGirderBridge(span=30.0, spans=(12.0, 18.0), n_modes=3, skew=10.0, use_cache=False)
    assert deck.span_lengths == (12.0, 18.0) and deck.skew == 10.0
    assert SlabOnGirderBridge(span=30.0, use_cache=False).span_lengths == (30.0,)


def test_a_series_is_a_girder_deck_only_with_a_girder_deck_instrumented():
    deck = BRIDGE_PRESETS["cypress-bayou-3span"].build(n_modes=3)
    assert type(deck) is GirderSpanSeries and isinstance(deck, GirderDeck)
    main = deck.spans[deck.instrumented]
    assert np.array_equal(deck.girder_y, main.girder_y) and deck.default_girder == main.default_girder
    again = pickle.loads(pickle.dumps(deck))  # studies send bridges to worker processes
    assert type(again) is GirderSpanSeries and again.n_girders == main.n_girders
    beams = SpanSeries((_beam(), None), lengths=(10.0, 5.0), instrumented=0)
    assert type(beams) is SpanSeries and not isinstance(beams, GirderDeck)
    assert beams.span_lengths == (10.0, 5.0) and beams.span_index(12.0) == 1
    assert isinstance(beams, HasLoadEffects) and beams.load_effect("moment", 5.0).x == 5.0


def test_dof_map_numbers_the_grid_and_round_trips_nodal_modes():
    deck = SlabOnGirderBridge(span=9.0, n_girders=3, n_modes=4, n_elements=6, skew=15.0, use_cache=False)
    dofs = deck.dof_map
    assert dofs.n_dof == 3 * 3 * 7 == deck.assemble()[0].shape[0]
    assert dofs.dof(2, 6, 2) == dofs.n_dof - 1 and dofs.dof(1, 0, 1) == 3 * 7 + 1
    assert np.array_equal(dofs.dof(np.array([0, 1]), np.array([3, 3]), 0), [9, 30])
    modes = deck.nodal_modes
    again = dofs.nodal(dofs.vector(modes))
    for name in ("w", "wx", "wy"):
        assert np.array_equal(getattr(again, name), getattr(modes, name))
    assert isinstance(again, NodalModes) and again.skew_tan == modes.skew_tan == deck.skew_tan
    assert DofMap(deck.stations, deck.girder_y, deck.skew_tan).dof(1, 2, 0) == dofs.dof(1, 2, 0) == 27


def test_mode_cache_key_is_unchanged():
    """The key names the cached modes on disk: a change would orphan every user's cache."""
    assert paper_deck(2, n_modes=10).cache_key() == "c32c5c6ad8607f682c1b2de704d20e2f"
    assert SlabOnGirderBridge(span=9.16, n_modes=6).cache_key() == "c4746c56a1922153a3def20e2b5c355f"
    assert paper_deck(2, n_modes=6, skew=10.0).cache_key() == "07ca294181b4e28a831b2eb76e14b176"
