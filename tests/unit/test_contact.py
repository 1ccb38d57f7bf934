"""Unit tests for vbikit.contact: tire layouts, the road-averaging transfer function, contact points."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.contact import AASHTO_CONTACT_LENGTH, MultiPointTire, PointTire, contact_points
from vbikit.vehicle import hs20_44, moving_force

A = AASHTO_CONTACT_LENGTH


def test_aashto_contact_length():
    assert A == pytest.approx(0.254)  # 10 in


@pytest.mark.parametrize("n", [2, 3, 6, 9])
def test_ends_layout(n):
    offsets, weights = MultiPointTire(n_points=n, layout_rule="ends").layout()
    assert offsets.size == weights.size == n
    assert offsets[0] == pytest.approx(-A / 2) and offsets[-1] == pytest.approx(A / 2)
    np.testing.assert_allclose(np.diff(offsets), A / (n - 1), rtol=1e-12)
    assert MultiPointTire(n_points=n, layout_rule="ends").spacing() == pytest.approx(A / (n - 1))


@pytest.mark.parametrize("n", [2, 3, 6, 9])
def test_cells_layout(n):
    offsets, weights = MultiPointTire(n_points=n, layout_rule="cells").layout()
    assert offsets.size == weights.size == n
    np.testing.assert_allclose(np.diff(offsets), A / n, rtol=1e-12)
    assert offsets[0] == pytest.approx(-A / 2 + A / (2 * n))  # centre of the first cell
    assert offsets.mean() == pytest.approx(0.0, abs=1e-15)  # patch centred on the wheel
    assert MultiPointTire(n_points=n, layout_rule="cells").spacing() == pytest.approx(A / n)


@pytest.mark.parametrize("rule", ["ends", "cells"])
@pytest.mark.parametrize("n", [1, 2, 5, 6, 8])
def test_weights_equal_and_sum_to_one(rule, n):
    _, weights = MultiPointTire(n_points=n, layout_rule=rule).layout()
    np.testing.assert_allclose(weights, 1.0 / n)
    assert weights.sum() == pytest.approx(1.0, rel=1e-15)


@pytest.mark.parametrize("rule", ["ends", "cells"])
def test_single_point_is_the_point_tire(rule):
    multi = MultiPointTire(n_points=1, layout_rule=rule)
    for got, expected in zip(multi.layout(), PointTire().layout()):
        np.testing.assert_array_equal(got, expected)
    assert multi.point_count == PointTire().point_count == 1
    assert multi.point_count == 1
    assert multi.spacing() == 0.0
    np.testing.assert_array_equal(multi.transfer(np.array([0.5, 3.0])), 1.0)


def test_contact_length_is_settable():
    offsets, _ = MultiPointTire(n_points=4, contact_length=0.4).layout()
    np.testing.assert_allclose(offsets, [-0.2, -0.2 / 3, 0.2 / 3, 0.2])


def _direct_transfer(tire: MultiPointTire, nu: np.ndarray) -> np.ndarray:
    """|Σ β_p exp(2πi ν ξ_p)|: the averaging of a road harmonic by the actual contact points."""
    offsets, weights = tire.layout()
    return np.abs(np.exp(2j * np.pi * np.outer(nu, offsets)) @ weights)


@pytest.mark.parametrize("rule", ["ends", "cells"])
@pytest.mark.parametrize("n", [2, 3, 6, 9])
def test_transfer_equals_discrete_average_of_the_layout(rule, n):
    tire = MultiPointTire(n_points=n, layout_rule=rule)
    nu = np.linspace(0.0, 10.0, 401)
    np.testing.assert_allclose(tire.transfer(nu), _direct_transfer(tire, nu), atol=1e-12)


def test_cells_transfer_tends_to_sinc():
    # model data §3 [computed]: |sinc(νa)| = 0.97, 0.90, 0.63, 0.28 at ν = 0.5, 1, 2, 3 cycle/m
    nu = np.array([0.5, 1.0, 2.0, 3.0])
    h = MultiPointTire(n_points=400, layout_rule="cells").transfer(nu)
    np.testing.assert_allclose(h, np.abs(np.sinc(nu * A)), atol=1e-4)
    np.testing.assert_allclose(h, [0.97, 0.90, 0.63, 0.28], atol=0.005)


def test_ends_transfer_six_points_at_three_cycles_per_metre():
    # model data §3 [computed]: end-to-end layout, n = 6, s = 0.0508 m: H(3 cycle/m) = 0.10
    h = float(MultiPointTire(n_points=6, layout_rule="ends").transfer(3.0))
    assert h == pytest.approx(0.10, abs=0.005)
    s = A / 5
    assert h == pytest.approx(abs(np.sin(np.pi * 3 * s * 6) / (6 * np.sin(np.pi * 3 * s))), rel=1e-12)


def test_transfer_at_zero_wavenumber_is_one():
    for rule in ("ends", "cells"):
        assert float(MultiPointTire(n_points=6, layout_rule=rule).transfer(0.0)) == pytest.approx(1.0)


@pytest.mark.parametrize("tire", [PointTire(), MultiPointTire(n_points=6), MultiPointTire(n_points=4, layout_rule="cells")])
def test_contact_points_share_each_wheel(tire):
    v = hs20_44()
    cp = contact_points(v, tire)
    n = tire.point_count
    assert cp.n == n * len(v.wheels)
    assert cp.rows.shape == (cp.n, v.n_dof)
    k_sum = cp.wheel_sum(cp.stiffness, len(v.wheels))
    c_sum = cp.wheel_sum(cp.damping, len(v.wheels))
    np.testing.assert_allclose(k_sum, [w.stiffness for w in v.wheels], rtol=1e-14)
    np.testing.assert_allclose(c_sum, [w.damping for w in v.wheels], rtol=1e-14)
    np.testing.assert_allclose(cp.wheel_sum(cp.weight, len(v.wheels)), 1.0, rtol=1e-14)
    offsets, _ = tire.layout()
    for i, w in enumerate(v.wheels):
        sel = cp.wheel == i
        # positive offset = ahead of the wheel = smaller setback behind the front axle
        np.testing.assert_allclose(cp.setback[sel], w.offset - offsets, atol=1e-15)
        np.testing.assert_allclose(cp.lateral[sel], w.lateral)
        np.testing.assert_array_equal(cp.rows[sel], np.broadcast_to(w.row, (n, v.n_dof)))


def test_contact_points_of_a_moving_force_carry_the_fixed_load():
    cp = contact_points(moving_force(80e3), MultiPointTire(n_points=5))
    assert cp.rows.shape == (5, 0)
    assert cp.fixed_load.sum() == pytest.approx(80e3)
    np.testing.assert_allclose(cp.fixed_load, 16e3)


@pytest.mark.parametrize("n", [0, -1, 2.5])
def test_invalid_number_of_points_raises(n):
    with pytest.raises(ValueError, match="n_points"):
        MultiPointTire(n_points=n)


def test_invalid_contact_length_and_rule_raise():
    with pytest.raises(ValueError, match="contact_length"):
        MultiPointTire(n_points=6, contact_length=0.0)
    with pytest.raises(ValueError, match="layout_rule"):
        MultiPointTire(n_points=6, layout_rule="middle")
