"""Unit tests for vbikit.bridge: the simply supported Euler–Bernoulli beam and the paper presets."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS, EulerBernoulliBeam, paper_beam

L, EI, M = 20.0, 3.2e10, 8000.0  # span [m], bending stiffness [N m²], mass per length [kg/m]


@pytest.fixture
def beam() -> EulerBernoulliBeam:
    return EulerBernoulliBeam(span=L, EI=EI, mass_per_length=M, damping_ratio=0.02, n_modes=12, neutral_axis_depth=0.6)


def test_frequencies_closed_form(beam):
    n = np.arange(1, 13)
    expected = (n * np.pi / L) ** 2 * np.sqrt(EI / M)
    np.testing.assert_allclose(beam.omega, expected, rtol=1e-13)
    np.testing.assert_allclose(beam.frequencies_hz, expected / (2 * np.pi), rtol=1e-13)
    np.testing.assert_allclose(beam.damping_ratios, 0.02)


def test_mass_normalisation_by_quadrature(beam):
    # Gauss–Legendre with 200 nodes integrates sin(iπx/L) sin(jπx/L), i, j ≤ 12, to round-off
    t, w = np.polynomial.legendre.leggauss(200)
    x = 0.5 * L * (t + 1.0)
    phi = beam.mode_shapes(x)
    gram = (phi * (M * 0.5 * L * w)[:, None]).T @ phi  # ∫ m φᵢ φⱼ dx
    np.testing.assert_allclose(gram, np.eye(12), atol=1e-12)


def test_slopes_match_finite_differences(beam):
    x = np.linspace(0.37, L - 0.37, 41)
    h = 1e-5
    fd = (beam.mode_shapes(x + h) - beam.mode_shapes(x - h)) / (2 * h)
    slope_amplitude = np.sqrt(2 / (M * L)) * beam.wavenumbers
    np.testing.assert_allclose(beam.mode_slopes(x) / slope_amplitude, fd / slope_amplitude, atol=1e-8)


def test_strain_shapes_are_curvature_times_lever_arm(beam):
    x = np.linspace(0.5, L - 0.5, 17)
    h = 1e-3
    curvature = (beam.mode_shapes(x + h) - 2 * beam.mode_shapes(x) + beam.mode_shapes(x - h)) / h**2
    scale = np.sqrt(2 / (M * L)) * beam.wavenumbers**2 * 0.6
    np.testing.assert_allclose(beam.strain_shapes(x) / scale, 0.6 * curvature / scale, atol=1e-5)


def test_central_downward_load_sags_with_positive_bottom_strain():
    b = EulerBernoulliBeam(span=L, EI=EI, mass_per_length=M, n_modes=50, neutral_axis_depth=0.6)
    P = 100e3
    xi = b.static_modal_coordinates([L / 2], [0.0], [-P])  # downward force (z up)
    assert xi.shape == (50,)
    assert xi[0] < 0.0
    w_mid = float(b.mode_shapes([L / 2])[0] @ xi)
    eps_mid = float(b.strain_shapes([L / 2])[0] @ xi)
    assert w_mid < 0.0  # deflects downward
    assert eps_mid > 0.0  # bottom fibre in tension
    # deflection series converges as n⁻⁴: exact PL³/48EI to 1e-5
    assert -w_mid == pytest.approx(b.static_midspan_deflection(P), rel=1e-5)
    # curvature series converges as n⁻² (odd modes ≤ 50 miss ≈ 0.8 %): ε = (PL/4) c / EI
    assert eps_mid == pytest.approx(P * L / 4 * 0.6 / EI, rel=0.015)
    assert eps_mid < P * L / 4 * 0.6 / EI  # truncated from below


def test_static_modal_coordinates_broadcast_over_leading_axes(beam):
    x = np.array([[2.0, 5.0], [8.0, 11.0], [14.0, 30.0]])  # (3 instants, 2 loads); 30 m is off the span
    f = np.array([-1e3, -2e3])
    xi = beam.static_modal_coordinates(x, 0.0, f)
    assert xi.shape == (3, 12)
    for i in range(3):
        expected = (beam.mode_shapes(x[i]).T @ f) / beam.omega**2
        np.testing.assert_allclose(xi[i], expected, rtol=1e-13)


@pytest.mark.parametrize("x", [-1.0, -1e-9, L + 1e-9, L + 3.0])
def test_zero_outside_the_span(beam, x):
    assert not np.any(beam.mode_shapes([x]))
    assert not np.any(beam.mode_slopes([x]))
    assert not np.any(beam.strain_shapes([x]))


def test_mode_shapes_vanish_at_supports(beam):
    np.testing.assert_allclose(beam.mode_shapes([0.0, L]), 0.0, atol=1e-15)


@pytest.mark.parametrize(
    ("span", "girder", "f1"),
    [(9.16, "II", 24.6), (16.76, "II", 7.3), (39.62, "VI", 2.7)],  # model data §1 [computed]
)
def test_paper_beam_first_frequency(span, girder, f1):
    assert paper_beam(span, girder).frequencies_hz[0] == pytest.approx(f1, rel=0.03)


@pytest.mark.parametrize("name", sorted(BRIDGE_PRESETS))
def test_every_bridge_preset_builds(name):
    beam = BRIDGE_PRESETS[name].build(n_modes=4)
    # a series of spans has n_modes per span; identical spans share their frequencies
    spans = getattr(beam, "n_vibrating_spans", 1)
    assert beam.n_modes == 4 * spans
    assert np.all(np.diff(beam.omega) > 0) if spans == 1 else np.all(np.diff(beam.omega) >= 0)
    assert beam.damping_ratios[0] == pytest.approx(0.02)  # documented default


def test_paper_beam_presets_match_domain_frequencies():
    f1 = [BRIDGE_PRESETS[f"paper-bridge-{i}-beam"].build().frequencies_hz[0] for i in (1, 2, 3)]
    np.testing.assert_allclose(f1, [24.6, 7.3, 2.7], rtol=0.03)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("span", 0.0),
        ("span", -5.0),
        ("span", np.inf),
        ("EI", -1.0),
        ("EI", np.nan),
        ("mass_per_length", 0.0),
        ("neutral_axis_depth", -0.1),
        ("damping_ratio", -0.01),
        ("damping_ratio", 1.0),
        ("n_modes", 0),
        ("n_modes", 2.5),
    ],
)
def test_invalid_parameters_raise_naming_the_field(field, value):
    kwargs = dict(span=L, EI=EI, mass_per_length=M, damping_ratio=0.02, n_modes=5, neutral_axis_depth=0.5)
    kwargs[field] = value
    with pytest.raises(ValueError, match=field):
        EulerBernoulliBeam(**kwargs)
