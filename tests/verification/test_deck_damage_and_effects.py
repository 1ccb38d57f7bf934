"""Local damage of one girder and girder load effects on the slab-on-girder deck.

Independent numbers: first-order perturbation (Rayleigh's quotient with the intact mode,
Δ(ω²) = φᵀ ΔK φ with ΔK the lost girder bending stiffness, evaluated here by Gauss quadrature of
EI (∂²φ/∂x²)² over the damaged elements); equilibrium (the bearing reactions of all girders carry
the load); statics of the girder recovered from element forces must equal the full-stiffness value.
The OpenSees comparison of girder moments and reactions is in ``test_opensees_deck_effects.py``.
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import paper_deck
from vbikit.bridge.damage import Damage


def test_zero_severity_is_the_intact_deck_bit_for_bit():
    intact = paper_deck(2, n_modes=6, use_cache=False)
    zero = paper_deck(2, n_modes=6, use_cache=False, damage=(Damage(6.0, 2.0, 0.0, girder=4),))
    assert zero.cache_key() == intact.cache_key()
    assert np.array_equal(zero.omega, intact.omega)
    assert np.array_equal(zero.nodal_modes.w, intact.nodal_modes.w)
    damaged = paper_deck(2, n_modes=6, use_cache=False, damage=(Damage(6.0, 2.0, 0.1, girder=4),))
    assert damaged.cache_key() != intact.cache_key()


def test_girder_damage_lowers_f1_as_rayleigh_predicts():
    intact = paper_deck(2, n_modes=1, use_cache=False)
    xs = intact.stations
    start, end = xs[10], xs[14]  # four whole elements of Girder 4
    s = 0.01
    damaged = paper_deck(2, n_modes=1, use_cache=False, damage=(Damage(start, end - start, s, girder=4),))
    EI = intact.line_properties["EI"][3]
    gauss = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]) + 1) / 2, np.array([5, 8, 5]) / 18
    integral = 0.0
    for a, b in zip(xs[10:14], xs[11:15]):
        xq = a + (b - a) * gauss[0]
        k = intact.nodal_modes.curvatures(xq, 3)[:, 0]
        integral += (b - a) * gauss[1] @ (EI * k**2)
    predicted = -s * integral / (2 * intact.omega[0] ** 2)
    measured = damaged.omega[0] / intact.omega[0] - 1
    assert measured < 0
    # measured: the drop exceeds the first-order value by 0.9 % at s = 0.01 (1.8 % at 0.02, 4.6 % at
    # 0.05, 9.6 % at 0.1: the second-order remainder, ∝ s, of the right sign — Rayleigh's quotient
    # with the intact mode is an upper bound on the damaged ω²)
    assert measured == pytest.approx(predicted, rel=0.015)


def test_bearing_reactions_carry_the_load_and_moments_match_statics():
    deck = paper_deck(2, n_modes=6, use_cache=False)
    rng = np.random.default_rng(3)
    x = rng.uniform(0.0, deck.span, 40)
    y = rng.uniform(-4.8, 4.8, 40)  # overhangs included
    total = sum(deck.load_effect("reaction", support=s, girder=g).influence(x, y)
                for g in range(1, 6) for s in (0, 1))
    np.testing.assert_allclose(total, -1.0, atol=1e-9)
    # moment of Girder 3 at a node from the influence function = EI ∂²w/∂x² of the static solution
    # just right of the node (the element recovery; the slab's torsion puts a small couple into the
    # girder at every node, so the moment jumps there and the element on the right is the one used)
    node = deck.stations[12]
    far = np.abs(x - node) > 2 * (deck.stations[1] - deck.stations[0])
    m = deck.load_effect("moment", x=float(node), girder=3).influence(x[far], y[far])
    EI = deck.line_properties["EI"][2]
    for xi, yi, mi in zip(x[far][:5], y[far][:5], m[:5]):
        sol = deck.static_solution([xi], [yi], [1.0])
        right = EI * sol.line_values(np.array([node + 1e-9]), 2)[2, 0, 0]
        assert mi == pytest.approx(right, rel=1e-6, abs=1e-9)
