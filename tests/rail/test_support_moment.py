"""The moment envelope's stations include the supports (``vbikit.rail.envelope.moment_sections``):
over the middle support of a continuous girder, or a restrained end, the hogging moment can govern,
and the stations L/16 … 15L/16 alone missed it."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge.continuous import ContinuousBeam
from vbikit.rail.envelope import moment_sections, static_envelope
from vbikit.rail.run import MOMENT_SECTIONS
from vbikit.rail.sweep import SweepSetup, sweep_moving_forces
from vbikit.solve.moving_loads import default_dx
from vbikit.vehicle.trains import Train

L1, L2 = 12.0, 10.0  # the middle support at 12 m = 8.73 L/16: not one of the stations j L/16
L = L1 + L2
P = 1e5
AXLES = np.arange(30) * 1.0  # 30 axles of 100 kN at 1 m: nearly a distributed load over both spans


def hogging_over_middle_support(xi):
    """Three-moment equation (Clapeyron) of a two-span beam on pinned supports, constant EI: the
    moment over the middle support under a unit load at ξ, −ξ (L1² − ξ²) / (2 L1 (L1 + L2)) in span 1
    and −b (L2² − b²) / (2 L2 (L1 + L2)), b = L − ξ, in span 2 (e.g. Timoshenko & Young, Theory of
    Structures, continuous beams); 0 off the girder."""
    xi = np.asarray(xi, float)
    b = L - xi
    return np.where((xi >= 0) & (xi <= L1), -xi * (L1**2 - xi**2) / (2 * L1 * L),
                    np.where((xi > L1) & (xi <= L), -b * (L2**2 - b**2) / (2 * L2 * L), 0.0))


def test_hogging_over_the_middle_support_of_a_two_span_girder_governs_the_envelope():
    """Static envelope at the middle support against the three-moment equation (brute force over
    the train's positions every 1 mm: 1556 kN m hogging), and the largest of every station; the
    old stations (interior j L/16) reach under 90 % of it (measured 86.6 %).  The dynamic envelope (moving forces at
    5 m/s, mode acceleration) also has its largest value there, within 0.5 % of the static one
    (speed parameter v / (2 f1 L) = 0.006: quasi-static; measured +0.085 %)."""
    bridge = ContinuousBeam((L1, L2), 2.5e10, 12000.0, 0.02, n_modes=4)
    sections = moment_sections(bridge.span, MOMENT_SECTIONS, bridge.support_x)
    assert np.any(np.isclose(sections, L1)) and sections[0] == pytest.approx(0.0, abs=1e-6 * L) and sections[-1] == L
    j = int(np.argmin(np.abs(sections - L1)))
    s = np.arange(0.0, L + AXLES[-1] + 1e-3, 1e-3)
    closed = float(np.abs(hogging_over_middle_support(s[:, None] - AXLES[None, :]).sum(axis=1) * P).max())
    static = static_envelope(bridge, "moment", sections, AXLES, np.full(AXLES.size, P))
    assert static[j] == pytest.approx(closed, rel=1e-6)
    assert int(np.argmax(static)) == j
    old = (sections > 0) & (sections < L) & ~np.isclose(sections, L1)  # the stations j L/16, 0 < j < 16
    assert static[old].max() < 0.9 * closed
    v = np.array([5.0])
    setup = SweepSetup(bridge, np.array([0.5 * L1]), tuple(("moment", float(x)) for x in sections),
                       default_dx(bridge, 5.0, 20), 1.0 / float(bridge.frequencies_hz[0]), 1e12)
    env, _ = sweep_moving_forces(setup, [Train("uniform", AXLES, np.full(AXLES.size, P))], v)[0]
    dyn = env.max_effect[0]
    assert int(np.argmax(dyn)) == j
    assert dyn[j] == pytest.approx(closed, rel=5e-3)


def test_restrained_span_hogging_at_both_ends_governs(tmp_path):
    """A 20 m span with rotational end springs 5e10 N m/rad (EI 7.9e10 N m², the restrained span of
    tests/rail/test_trust.py) under HSLM-A3, whose axles are symmetric: the static envelope is
    symmetric about midspan, so the entry station (just right of the support: the bridge model
    gives 0 at x = 0 exactly, left of the end's couple) equals the exit one, and both exceed every
    interior station (hogging governs: 1489 against 1190 kN m at midspan)."""
    from vbikit.rail.run import build_bridge
    from vbikit.rail.spec import parse_rail_spec
    from vbikit.vehicle.trains import hslm_a

    (tmp_path / "bridge.toml").write_text('[bridge]\nmodel = "continuous-beam"\nspans = [20.0]\nEI = 7.9e10\n'
                                          'mass_per_length = 25000.0\nrotational_stiffness = [5e10, 5e10]\n')
    data = {"bridge": {"scenario": str(tmp_path / "bridge.toml")}, "trains": {"presets": ["hslm-a3"]},
            "speeds": {"min": 100.0, "max": 120.0, "step": 20.0}}
    bridge = build_bridge(parse_rail_spec(data), tmp_path)[0]
    t = hslm_a(3)
    xs = moment_sections(20.0, MOMENT_SECTIONS, bridge.support_x)
    env = static_envelope(bridge, "moment", xs, t.axle_positions, t.axle_loads)
    # a curved line is sampled every L/400 of travel (within 1e-3 below the brute force, tests/rail/test_trust.py)
    np.testing.assert_allclose(env, env[::-1], rtol=1e-3)
    assert env[0] == env.max() or env[-1] == env.max()
    assert min(env[0], env[-1]) > 1.2 * env[1:-1].max()


def test_shear_envelope_takes_both_sides_of_the_jump_against_brute_force():
    """The breakpoint sweep (``vbikit.analysis.breakpoints``) on a simply supported span's shear line,
    which jumps by 1 at its section: V_x(ξ) = ξ/L (ξ < x), −(1 − ξ/L) (ξ > x), brute force over the
    train (HSLM-A5's first 10 axles) every 1 mm (a lower bound within Σ P · 1 mm / L).  The
    axles-on-breakpoints enumeration it replaced read the line on one side of the jump only
    (x = 7 m: 50 % low, x = 2.5 m: 37 %, x = 10 m: 8 %)."""
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.vehicle.trains import hslm_a

    span = 20.0
    bridge = EulerBernoulliBeam(span, 2.5e10, 12000.0, 0.02, n_modes=3)
    axles, loads = hslm_a(5).axle_positions[:10], hslm_a(5).axle_loads[:10]
    xs = np.array([2.5, 7.0, 10.0, 15.0])
    got = static_envelope(bridge, "shear", xs, axles, loads)
    s = np.arange(0.0, span + axles[-1] + 1e-3, 1e-3)
    xi = s[:, None] - axles[None, :]
    for x, g in zip(xs, got):
        v = np.where(xi < x, xi / span, -(1 - xi / span)) * ((xi >= 0) & (xi <= span))
        brute = float(np.abs(v @ loads).max())
        assert brute <= g * (1 + 1e-9) and g <= brute + float(np.sum(loads)) * 1e-3 / span
