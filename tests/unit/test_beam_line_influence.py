"""The simply supported beam's load effects as wheel-line tables (``UniformLineInfluence``) and their
compiled reduction (``vbikit.analysis.line_sums``), and what a kept bridge keeps between runs.

Independent numbers: the textbook influence lines of a simply supported beam of span L under a
unit downward point load at a (e.g. Hibbeler, *Structural Analysis*, 8th ed., 2012, §6.1):
R_A = (L − a)/L, R_B = a/L, M(s) = a (L − s)/L for a ≤ s and s (L − a)/L for a ≥ s,
V(s⁺) = −a/L for a ≤ s and (L − a)/L for a > s — written here directly, not through vbikit; the
library's sign convention (``vbikit.bridge.effects``) is that of a unit *upward* force, the negative.
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.effects import contact_positions, load_effect_responses, tabulated_together
from vbikit.analysis.impact import static_modal_history
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.effects import UniformLineInfluence
from vbikit.contact import MultiPointTire
from vbikit.solve import Crossing, simulate, system
from vbikit.vehicle import hs20_44

L = 16.76


def textbook(kind: str, a: np.ndarray, s: float = 0.0, support: int = 0) -> np.ndarray:
    """The influence line of a unit downward load at a (module docstring), 0 off the span."""
    on = (a >= 0.0) & (a <= L)
    if kind == "reaction":
        value = (L - a) / L if support == 0 else a / L
    elif kind == "moment":
        value = np.where(a <= s, a * (L - s) / L, s * (L - a) / L)
    else:
        value = np.where(a <= s, -a / L, (L - a) / L)
    return np.where(on, value, 0.0)


CASES = [("moment", {"x": L / 2}, {"s": L / 2}), ("moment", {"x": 3.1}, {"s": 3.1}), ("shear", {"x": 0.0}, {"s": 0.0}),
         ("shear", {"x": 11.0}, {"s": 11.0}), ("reaction", {"support": 0}, {"support": 0}),
         ("reaction", {"support": 1}, {"support": 1})]


@pytest.mark.parametrize("kind, kw, ref", CASES)
def test_the_tables_are_the_textbook_influence_lines(kind, kw, ref):
    beam = EulerBernoulliBeam(span=L, EI=1.0e10, mass_per_length=7500.0, n_modes=4)
    effect = beam.load_effect(kind, **kw)
    assert isinstance(effect.influence, UniformLineInfluence)
    a = np.concatenate([np.linspace(-1.0, L + 1.0, 2001), [0.0, L, kw.get("x", 0.0)]])
    np.testing.assert_allclose(-effect.influence(a, np.zeros_like(a)), textbook(kind, a, **ref), rtol=0, atol=1e-13 * L)


@pytest.fixture(scope="module")
def beam_run():
    beam = EulerBernoulliBeam(span=L, EI=1.0e10, mass_per_length=7500.0, n_modes=6)
    return simulate(Crossing(beam, hs20_44(), MultiPointTire(n_points=3), speed=20.0, approach=2.0,
                             free_vibration=0.1, dt=2e-3))


def test_the_compiled_pass_sums_the_textbook_lines_over_the_moving_points(beam_run):
    """Static and dynamic histories of mode acceleration: −Σ_p I(x_p(t)) β_p P_w and
    −Σ_p I(x_p(t)) β_p f_w(t) − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i)/ω_i², I the textbook lines."""
    res = beam_run
    beam, cp = res.crossing.bridge, res.crossing.contact
    effects = [beam.load_effect(kind, **kw) for kind, kw, _ in CASES]
    assert tabulated_together(effects)  # the beam's effects take the compiled pass
    out = load_effect_responses(res, effects)
    x, _ = contact_positions(res)
    static_loads = cp.weight * res.crossing.vehicle.static_wheel_loads()[cp.wheel]
    forces = res.wheel_forces[:, cp.wheel] * cp.weight[None, :]
    rates = res.xi_ddot + res.xi_dot * (2.0 * beam.damping_ratios * beam.omega)
    assert (x < 0).any() and (x > L).any()  # points off the deck on both sides
    for (kind, _, ref), e, r in zip(CASES, effects, out):
        influence = -textbook(kind, x, **ref)  # per unit upward force
        static = -(influence @ static_loads)
        dynamic = -(influence * forces).sum(axis=1) - rates @ (e.modal / beam.omega**2)
        scale = np.abs(static).max()
        np.testing.assert_allclose(r.static, static, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(r.dynamic, dynamic, rtol=0, atol=1e-9 * scale)


def test_a_kept_bridge_keeps_its_effects_and_static_reference(beam_run):
    res = beam_run
    beam = res.crossing.bridge
    assert beam.load_effect("moment", x=4.0) is beam.load_effect("moment", x=4.0)
    with pytest.raises(ValueError, match="support must be 0 or 1"):
        beam.load_effect("reaction", support=1.5)  # never kept under support 1
    first = static_modal_history(res)
    assert static_modal_history(res) is first and not first.flags.writeable
    fresh = system.static_modal_history(res.crossing, res.travel, res.kernel_data)
    np.testing.assert_array_equal(first, fresh)


def test_bad_tables_are_refused():
    with pytest.raises(ValueError, match=r"poly must have shape \(4, 1\)"):
        UniformLineInfluence(np.array([0.0, 1.0]), np.zeros((3, 1)))
    with pytest.raises(ValueError, match="stations"):
        UniformLineInfluence(np.array([1.0, 0.0]), np.zeros((4, 1)))
    with pytest.raises(ValueError, match="element"):
        UniformLineInfluence(np.array([0.0, 1.0]), np.zeros((4, 1)), "moment", 3, 0.5)
