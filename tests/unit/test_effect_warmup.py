"""`vbikit compile` also compiles the load-effect kernel of the grillage decks and beams
(``vbikit.analysis.warmup.compile_effect_kernels``): its tiny call has the argument types of a real
run, so a deck crossing's load effects afterwards add no second compiled variant of
``vbikit.analysis.line_sums.line_sums`` (a float passed as an int, or a non-contiguous array,
would add one)."""
from __future__ import annotations

from vbikit.analysis.effects import load_effect_responses
from vbikit.analysis.line_sums import line_sums
from vbikit.analysis.warmup import compile_effect_kernels
from vbikit.bridge import paper_deck
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44


def test_the_warm_up_compiles_the_variant_a_deck_run_uses():
    compile_effect_kernels()
    warmed = set(line_sums.signatures)
    assert len(warmed) == 1
    deck = paper_deck(2, n_modes=4, use_cache=False, n_elements=14)
    result = simulate(Crossing(deck, hs20_44(), speed=20.0, approach=1.0, free_vibration=0.0, dt=4e-3))
    load_effect_responses(result, [deck.load_effect("moment", x=7.3, girder=4), deck.load_effect("reaction", support=0, girder=3)])
    assert set(line_sums.signatures) == warmed


def test_a_beam_run_uses_the_same_variant():
    """The beam's load effects (wheel-line tables on [0, L], ``UniformLineInfluence``) take the same
    compiled pass with the same argument types: still the one variant ``vbikit compile`` made."""
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.contact import MultiPointTire

    compile_effect_kernels()
    warmed = set(line_sums.signatures)
    beam = EulerBernoulliBeam(span=16.76, EI=1.0e10, mass_per_length=7500.0, n_modes=4)
    result = simulate(Crossing(beam, hs20_44(), MultiPointTire(n_points=2), speed=20.0, approach=1.0,
                               free_vibration=0.0, dt=4e-3))
    load_effect_responses(result, beam.default_load_effects())
    assert set(line_sums.signatures) == warmed
