"""Unit tests for the mode-shape tabulation (vbikit.solve.tabulate) and its Hermite evaluation (kernels.shapes_at)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam, paper_beam
from vbikit.solve import kernels
from vbikit.solve.system import modes_data
from vbikit.solve.tabulate import tabulate_tracks


def _evaluate(beam, table, x, track=0):
    """φ, φ' and the on-deck flags from the compiled kernel at deck stations x."""
    n_m = beam.omega.size
    phi = np.zeros((x.size, n_m))
    dphi = np.zeros_like(phi)
    on = np.zeros(x.size, np.bool_)
    modes = modes_data(beam, table)
    kernels.shapes_at(np.ascontiguousarray(x, float), np.full(x.size, track, np.int64), modes, phi, dphi, on)
    return phi, dphi, on


def _stations(span, seed=0, n=3000):
    rng = np.random.default_rng(seed)
    return np.concatenate([[0.0, span, span / 2, 1e-12, span - 1e-12], rng.uniform(0.0, span, n)])


@pytest.mark.parametrize("n_modes", [20, 50])
def test_hermite_tables_reproduce_beam_modes(n_modes):
    beam = paper_beam(16.76, "II", n_modes=n_modes)
    table = tabulate_tracks(beam, np.array([0.0]))
    x = _stations(beam.span)
    phi, dphi, on = _evaluate(beam, table, x)
    assert on.all()
    amp = np.sqrt(2.0 / (beam.mass_per_length * beam.span))  # mode amplitude [kg^-1/2]
    k = beam.wavenumbers
    err_values = np.abs(phi - beam.mode_shapes(x)).max(axis=0) / amp
    err_slopes = np.abs(dphi - beam.mode_slopes(x)).max(axis=0) / (amp * k)  # relative to the slope amplitude kA
    # values: cubic Hermite error ≤ (kh)⁴/384 ≈ 2.5e-9 at 100 grid points per retained mode (kh ≤ π/100)
    assert err_values.max() <= 1e-8
    # slopes: the derivative of a cubic Hermite interpolant has error ≤ (√3/216) h³ max|f⁗| = (√3/216)(kh)³ kA,
    # ≈ 2.49e-7 kA for the highest mode.  (Not ≤ 1e-7: that would need ≥ 136 grid points per mode.)
    kh = k * table.spacing
    bound = np.sqrt(3.0) / 216.0 * kh**3
    assert np.all(err_slopes <= 1.01 * bound + 1e-12)
    assert err_slopes.max() <= 2.6e-7


def test_table_grid_and_exact_nodes():
    beam = paper_beam(16.76, "II", n_modes=20)
    table = tabulate_tracks(beam, np.array([-1.1, 1.1]))
    assert table.values.shape == table.slopes.shape == (2, 2001, 20)
    assert table.spacing == pytest.approx(beam.span / 2000)
    # at grid nodes the interpolant returns the tabulated (exact) values
    x = table.spacing * np.array([0, 1, 7, 1000, 1999, 2000], float)
    phi, dphi, _ = _evaluate(beam, table, x, track=1)
    np.testing.assert_allclose(phi, beam.mode_shapes(x), rtol=0, atol=1e-15)
    np.testing.assert_allclose(dphi, beam.mode_slopes(x), rtol=1e-12, atol=1e-15)


def test_small_models_get_at_least_200_intervals():
    beam = EulerBernoulliBeam(span=10.0, EI=1e9, mass_per_length=1000.0, n_modes=1)
    assert tabulate_tracks(beam, np.array([0.0])).values.shape[1] == 201


def test_points_off_the_deck_are_flagged():
    beam = paper_beam(9.16, "II", n_modes=5)
    table = tabulate_tracks(beam, np.array([0.0]))
    x = np.array([-0.5, -1e-9, 0.0, 4.0, beam.span, beam.span + 1e-9, 20.0])
    _, _, on = _evaluate(beam, table, x)
    np.testing.assert_array_equal(on, [False, False, True, True, True, False, False])
