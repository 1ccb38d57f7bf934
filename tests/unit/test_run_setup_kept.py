"""Set-up of a run kept between traffic events (issue 33): the lean kernels' wheel entries per wheel rows,
the exact modal step's step-free terms per mode set, the wheel tracks per points' y, the line tables of
the compiled load-effect sums per influences and wheel lines, and the response points' deck check; and
what one run hands on instead of computing it again (the results' travel from the time grid, the
divergence check reading the deferred q̈'s sums, histories not zeroed before the kernel fills them).

Each kept value is compared with the same value made afresh or with an independent closed form, and each
key with inputs that differ in one part of it, where a key too wide would hand back the other's value."""
from __future__ import annotations

import dataclasses
import importlib

import numpy as np
import pytest

from vbikit.analysis import line_sums
from vbikit.analysis.response import point_shapes
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.effects import UniformLineInfluence
from vbikit.solve import Crossing, simulate
from vbikit.solve.modal_step import exact_step
from vbikit.solve.result import DeferredAccelerations, DivergenceError, check_finite
from vbikit.solve.system import wheel_tracks
from vbikit.vehicle import sprung_mass

lean = importlib.import_module("vbikit.solve.kernels.lean")  # (the package's ``lean`` is the kernel)


def _chopra_free(omega, zeta, h):
    """The free part of the exact step of an under-damped mode (Chopra 2017, Eq. 5.2.5 with the
    decaying sine and cosine): a11, a12, a21, a22."""
    r = np.sqrt(1.0 - zeta**2)
    wd, e = omega * r, np.exp(-zeta * omega * h)
    sn, cs = np.sin(wd * h), np.cos(wd * h)
    return e * (cs + zeta / r * sn), e * sn / wd, -e * omega / r * sn, e * (cs - zeta / r * sn)


def test_exact_step_terms_are_kept_per_mode_set():
    """Two mode sets with the same ω and another ζ, stepped alternately at steps where ωh < 0.5 (the
    exponential branch whose step-free terms are kept): each equals its own closed form."""
    omega = np.array([20.0, 75.0, 160.0])
    for h in (1.1e-3, 1.7e-3, 1.1e-3):
        for zeta in (np.array([0.02, 0.05, 0.0]), np.array([0.3, 0.6, 0.9])):
            step = exact_step(omega, zeta, h)
            for got, want in zip((step.a11, step.a12, step.a21, step.a22), _chopra_free(omega, zeta, h)):
                np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)


def test_wheel_entries_are_kept_per_rows():
    rows = np.array([[1.0, -2.0, 0.0], [0.0, 1.0, 3.0]])
    other = rows.copy()
    other[1, 2] = 4.0  # the same pattern, one value else
    first = lean.wheel_entries(rows)
    assert lean.wheel_entries(rows.copy()) is first  # kept (the same bytes)
    dof, h = lean.wheel_entries(other)
    assert h[1].tolist() == [1.0, 4.0] and dof[1].tolist() == [1, 2]
    assert first[1][1].tolist() == [1.0, 3.0]
    fresh = lean._wheel_entries(other)
    assert np.array_equal(dof, fresh[0]) and np.array_equal(h, fresh[1])
    assert dof.flags.writeable  # (numba compiles another kernel for read-only arrays)


def test_wheel_tracks_are_kept_per_y_and_handed_out_as_copies():
    y = np.array([0.9, -0.9, 0.9, -0.9])
    tracks, index = wheel_tracks(y)
    assert tracks.tolist() == [-0.9, 0.9] and index.tolist() == [1, 0, 1, 0]
    tracks[:] = 7.0  # the caller owns its copy
    again, _ = wheel_tracks(y)
    assert again.tolist() == [-0.9, 0.9]
    moved, moved_index = wheel_tracks(np.array([0.9, -1.1, 0.9, -1.1]))
    assert moved.tolist() == [-1.1, 0.9] and moved_index.tolist() == [1, 0, 1, 0]


def _influence(slope: float) -> UniformLineInfluence:
    poly = np.zeros((4, 2))
    poly[1] = slope  # I = slope · t on each of the two elements
    return UniformLineInfluence(np.array([0.0, 5.0, 10.0]), poly)


def test_line_tables_are_kept_per_influences_and_wheel_lines():
    f, g = _influence(1.0), _influence(2.0)
    y1, y2 = np.array([0.5, -0.5]), np.array([0.5, 0.5])
    for influences, y in (([f], y1), ([g], y1), ([f], y2), ([f, g], y1), ([g, f], y1)):
        got = line_sums.line_tables(influences, y)
        fresh = line_sums._line_tables(influences, y)
        assert all(np.array_equal(a, b) for a, b in zip(got, fresh))
    assert line_sums.line_tables([f], y1)[0].tolist() == [1, 0] and line_sums.line_tables([f], y2)[0].tolist() == [0, 0]
    assert line_sums.line_tables([g], y1)[1][0, 0, 1] == 2.0 and line_sums.line_tables([f], y1)[1][0, 0, 1] == 1.0


def _beam():
    return EulerBernoulliBeam(25.0, 2.87e9 * 2.9, 2303.0, 0.02, n_modes=4)


def test_off_deck_response_point_is_refused_every_time():
    beam = _beam()
    for _ in range(2):  # (a refused point is not kept)
        with pytest.raises(ValueError, match="response.x"):
            point_shapes(beam, 30.0, 0.0, checked=True)
    phi, eps = point_shapes(beam, 12.5, 0.0, checked=True)
    assert np.array_equal(phi, point_shapes(beam, 12.5, 0.0)[0]) and np.array_equal(eps, point_shapes(beam, 12.5, 0.0)[1])
    with pytest.raises(ValueError, match="response.x"):
        point_shapes(beam, 12.5, float("nan"), checked=True)


@pytest.fixture(scope="module")
def run():
    crossing = Crossing(_beam(), vehicle=sprung_mass(5750.0, 1595e3, 2e3), speed=25.0, approach=5.0, free_vibration=0.2)
    return simulate(crossing)


def test_a_run_hands_on_the_time_grids_travel_and_starts_at_rest(run):
    assert np.array_equal(run.travel, run.crossing.travel(run.time))  # the same numbers as computed afresh
    assert not np.any(run.xi_dot[0]) and not np.any(run.q_dot[0]) and np.all(np.isfinite(run.q_ddot))


def test_fresh_divergence_check_reads_the_deferred_sums(run):
    bad = run.q.copy()
    bad[3, 0] = np.nan
    deferred = DeferredAccelerations(run.kernel_data.vehicles, bad, run.q_dot, run.wheel_forces, np.empty_like(bad))
    changed = dataclasses.replace(run, q=bad, q_ddot=deferred)
    for fresh in (False, True):
        with pytest.raises(DivergenceError, match="step 3 "):
            check_finite(changed, fresh=fresh)
    assert check_finite(run, fresh=True) is run


def test_expm_each_scales_each_matrix_on_its_own():
    """Blocks of several vehicles exponentiated as one stack: each equals ``expm`` of it alone (bit for
    bit) and scipy's exponential (Al-Mohy & Higham 2009, another algorithm) to round-off, with norms
    that need 0, 3 and 7 squarings in one stack."""
    from scipy.linalg import expm as scipy_expm

    from vbikit.solve.modal_step import expm, expm_each

    rng = np.random.default_rng(7)
    stack = rng.normal(size=(3, 9, 9)) * np.array([0.01, 0.5, 12.0])[:, None, None]
    each = expm_each(stack)
    for a, e in zip(stack, each):
        assert np.array_equal(e, expm(a))
        np.testing.assert_allclose(e, scipy_expm(a), rtol=1e-10, atol=1e-12 * np.abs(e).max())
