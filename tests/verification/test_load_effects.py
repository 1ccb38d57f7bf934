# Load effects of a crossing: equilibrium of the static reference, the mode-acceleration method's
# convergence with few modes, and the simply supported closed forms.
#
# Independent numbers: equilibrium (the static support reactions carry exactly the static wheel
# loads on the bridge: Σ_j R_j(t) = Σ_w P_w [wheel on the deck]); the simply supported beam's
# influence lines in closed form (M(L/2) = P L / 4 at midspan); and, for the convergence, the same
# crossing with 48 modes, where both methods agree.
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.effects import load_effect_response, load_effect_responses
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.solve import Crossing, simulate
from vbikit.vehicle.presets import hs20_44

SPANS = [20.0, 25.0, 20.0]
EI, MASS = 1.286e10, 7537.0  # Bridge 2's whole cross-section (docs/bridges.md)


@pytest.fixture(scope="module")
def runs():
    out = {}
    for n in (6, 48):
        beam = ContinuousBeam(SPANS, EI, MASS, n_modes=n, damping_ratio=0.02)
        out[n] = simulate(Crossing(beam, hs20_44(), speed=75 / 3.6, dt=2e-4))
    return out


def test_static_reactions_carry_the_static_wheel_loads(runs):
    res = runs[6]
    beam = res.crossing.bridge
    reactions = load_effect_responses(res, [beam.load_effect("reaction", support=j) for j in range(4)])
    total = sum(r.static for r in reactions)
    wheels = res.crossing.vehicle.wheels
    x = res.front_position[:, :1] - np.array([w.offset for w in wheels])[None, :]
    on = (x >= 0.0) & (x <= beam.span)
    expected = (on * res.crossing.vehicle.static_wheel_loads()[None, :]).sum(axis=1)
    np.testing.assert_allclose(total, expected, atol=1e-6 * expected.max())


EFFECTS = [("moment", {"x": 10.0}), ("moment", {"x": 20.0}), ("shear", {"x": 20.0}), ("reaction", {"support": 1})]


@pytest.mark.parametrize("kind, kw", EFFECTS)
def test_mode_acceleration_converges_with_few_modes(runs, kind, kw):
    # measured dynamic peaks against mode acceleration with 48 modes (the reference):
    #   mode acceleration,  6 modes: +1.0e-4, +2.5e-5, −1.8e-5, −2.2e-4
    #   mode superposition, 6 modes: −5.4 %, +6.4 %, −16 %, −14 %
    #   mode superposition, 48 modes: −2.0 %, +0.16 %, +3.1 %, +8.2 %  (still converging)
    peaks = {}
    for n, res in runs.items():
        e = res.crossing.bridge.load_effect(kind, **kw)
        for method in ("mode-acceleration", "mode-superposition"):
            peaks[n, method] = load_effect_response(res, e, method).impact.dynamic_peak
    ref = peaks[48, "mode-acceleration"]
    assert peaks[6, "mode-acceleration"] == pytest.approx(ref, rel=5e-4)
    assert abs(peaks[6, "mode-superposition"] / ref - 1) > 0.04
    assert abs(peaks[48, "mode-superposition"] / ref - 1) < abs(peaks[6, "mode-superposition"] / ref - 1)


def test_simply_supported_closed_forms():
    L = 16.0
    beam = EulerBernoulliBeam(L, 1e10, 8000.0, n_modes=200)
    x = np.linspace(0.0, L, 81)
    m = beam.load_effect("moment", x=L / 2)
    np.testing.assert_allclose(-m.influence(x), np.where(x < L / 2, x / 2, (L - x) / 2), atol=1e-12)
    np.testing.assert_allclose(-beam.load_effect("reaction", support=1).influence(x), x / L, atol=1e-12)
    # modal values: with 200 modes the series reaches the exact static value at midspan (P L / 4)
    series = (beam.mode_shapes([L / 2]) / beam.omega**2) @ m.modal
    assert -series[0] == pytest.approx(L / 4, rel=3e-3)  # measured 2.0e-3: the tail falls only as 1/n (slow convergence)


def test_two_vehicles_in_opposite_directions_keep_equilibrium():
    # static reactions of a two-span beam under two trucks driving towards each other carry the
    # static wheel loads on the deck at every instant (each truck on its own path)
    from vbikit.scenario import build, scenario_from_toml

    text = """
[bridge]
model = "continuous-beam"
spans = [20.0, 25.0]
EI = 1.286e10
mass_per_length = 7537.0
n_modes = 6
[[vehicles]]
model = "hs20-44"
speed_kmh = 60
[[vehicles]]
model = "two-axle"
direction = "-x"
speed_kmh = 50
entry_time = 0.3
[crossing]
approach = 5
"""
    built = build(scenario_from_toml(text))
    res = simulate(built.crossing)
    beam = res.crossing.bridge
    total = sum(r.static for r in load_effect_responses(res, [beam.load_effect("reaction", support=j) for j in range(3)]))
    x = res.wheel_positions()
    on = (x >= 0.0) & (x <= beam.span)
    expected = (on * res.crossing.vehicle.static_wheel_loads()[None, :]).sum(axis=1)
    assert expected.max() > 1.2 * res.crossing.vehicle.static_wheel_loads()[:6].sum()  # both trucks on the deck at once
    np.testing.assert_allclose(total, expected, atol=1e-6 * expected.max())
