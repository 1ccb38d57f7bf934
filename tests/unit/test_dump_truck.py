"""Dump truck of the field test: static axle loads [paper] and the load-equalising walking beam."""
import numpy as np
import pytest

from vbikit.vehicle.builder import VehicleBuilder
from vbikit.vehicle.model import GRAVITY
from vbikit.vehicle.presets import VEHICLE_PRESETS, dump_truck


def test_static_axle_loads_match_paper():
    v = dump_truck()
    loads = v.static_wheel_loads()
    axle = loads[0::2] + loads[1::2]
    # paper §4.2: 80.0 / 95.6 / 95.6 kN
    np.testing.assert_allclose(axle, [80.0e3, 95.6e3, 95.6e3], rtol=0, atol=1e-6 * 95.6e3)
    np.testing.assert_allclose(loads[0::2], loads[1::2], rtol=1e-12)  # left = right
    assert [w.offset for w in v.wheels[::2]] == pytest.approx([0.0, 6.25, 7.45])  # spacings 6.25 / 1.2 m
    assert v.n_dof == 11
    assert np.all(v.natural_frequencies() > 0.5)  # no mechanism


def test_registered_preset():
    assert VEHICLE_PRESETS["dump-truck"].build().name == "dump-truck"


def test_pivoted_beam_equalises_unequal_springs():
    """Two axles on a walking beam carry equal static loads even with very different springs
    (moment balance about the pin), whereas the same axles on the body directly do not."""
    def build(walking: bool):
        vb = VehicleBuilder("t")
        body = vb.body("body", 10_000.0, 3.0, pitch_inertia=1e4, pitch=True)
        a1 = vb.body("a1", 500.0, 0.0)
        vb.spring(body.point(0.0), a1.heave, 3e5)
        vb.wheel("w1", a1.heave, 0.0, 0.0, 1e6, 0.0)
        carrier = vb.pivoted_beam("beam", body, 5.0, mass=200.0, pitch_inertia=20.0) if walking else body
        for name, s, k in (("a2", 4.5, 2e6), ("a3", 5.5, 0.5e6)):
            a = vb.body(name, 800.0, s)
            vb.spring(carrier.point(s), a.heave, k)
            vb.wheel(name, a.heave, s, 0.0, 1.5e6, 0.0)
        return vb.build().static_wheel_loads()

    eq = build(True)
    assert eq[1] == pytest.approx(eq[2], rel=1e-12)
    # independent reference: statics of the body on two supports (front spring, pivot at 5 m)
    w_body = 10_000.0 * GRAVITY
    r_pivot = w_body * 3.0 / 5.0
    assert eq[0] == pytest.approx(w_body - r_pivot + 500.0 * GRAVITY, rel=1e-10)
    assert eq[1] == pytest.approx((r_pivot + 200.0 * GRAVITY) / 2 + 800.0 * GRAVITY, rel=1e-10)
    plain = build(False)
    assert abs(plain[1] - plain[2]) > 1e3


def test_pivoted_beam_needs_mass():
    vb = VehicleBuilder("t")
    body = vb.body("body", 1.0, 0.0)
    with pytest.raises(ValueError, match="pitch_inertia"):
        vb.pivoted_beam("beam", body, 1.0, mass=1.0, pitch_inertia=0.0)
