# The planar rail car's statics, frequencies and Hertz contact, each against a hand computation
# written out below (statics of a body on two supports; decoupled one-body oscillators; the Hertz
# law P = (δ/G)^(3/2) and the classical Hertz compliance of two steel cylinders).
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit.vehicle import RAIL_CAR_PRESETS, RailCarParameters, hertz_constant, hertz_stiffness, rail_car

G = 9.81


def _car(**kw) -> RailCarParameters:
    base = dict(body_mass=40_000.0, body_pitch_inertia=1.9e6, bogie_mass=3_000.0, bogie_pitch_inertia=1_800.0,
                wheelset_mass=1_700.0, primary_stiffness=2.4e6, primary_damping=2e4, secondary_stiffness=0.7e6,
                secondary_damping=4e4, bogie_half_distance=8.75, axle_half_spacing=1.25)
    base.update(kw)
    return RailCarParameters(**base)


@pytest.mark.parametrize("contact", ["hertz", "rigid", 3.0e9])
def test_static_axle_loads_with_offset_body(contact):
    """Body CG e = 1.5 m behind the mid-point: the rear bogie carries more (a swapped index shows).

    Hand statics: body on two secondary supports at a + e ahead / a − e behind its CG, so the front
    support carries W_c (a − e)/(2a); each bogie splits its load equally over its two axles.
    """
    a, e = 8.75, 1.5
    car = _car(body_cg_offset=e, contact=contact)
    wc, wt, ww = 40_000.0 * G, 3_000.0 * G, 1_700.0 * G
    front = ww + (wt + wc * (a - e) / (2 * a)) / 2      # 81 016.03… N
    rear = ww + (wt + wc * (a + e) / (2 * a)) / 2       # 114 646.03… N
    loads = rail_car(car).static_wheel_loads()
    np.testing.assert_allclose(loads, [front, front, rear, rear], rtol=1e-10)
    assert loads[2] - loads[0] == pytest.approx(wc * e / (2 * a), rel=1e-9)


def test_axle_loads_set_body_mass_and_offset():
    """Given axle loads 70/70/90/90 kN the car carries exactly them; body mass from the total."""
    p = [70e3, 70e3, 90e3, 90e3]
    car = _car()
    v = rail_car(car, axle_loads=p)
    np.testing.assert_allclose(v.static_wheel_loads(), p, rtol=1e-10)
    # body mass = total / g − 2 M_t − 4 M_w (hand): 320 kN / 9.81 − 6000 − 6800
    assert v.parameters["body_mass"] == pytest.approx(320e3 / G - 6000.0 - 6800.0, rel=1e-12)
    # body CG offset: secondary loads S_f = 140 kN − (3000 + 3400) g, S_r = 180 kN − (3000 + 3400) g
    s_f, s_r = 140e3 - 6400 * G, 180e3 - 6400 * G
    assert v.parameters["body_cg_offset"] == pytest.approx(8.75 * (s_r - s_f) / (s_r + s_f), rel=1e-12)
    with pytest.raises(ValueError, match="must be equal"):
        rail_car(car, axle_loads=[70e3, 71e3, 90e3, 90e3])


def test_wheel_order_and_positions():
    """Wheels w1…w4 front to rear at s = 0, 2b, 2a, 2a + 2b, one wheel line (y = 0)."""
    v = rail_car(_car(bogie_half_distance=9.0, axle_half_spacing=1.4))
    assert [w.name for w in v.wheels] == ["w1", "w2", "w3", "w4"]
    np.testing.assert_allclose([w.offset for w in v.wheels], [0.0, 2.8, 18.0, 20.8])
    assert all(w.lateral == 0.0 for w in v.wheels)
    assert v.n_dof == 10 and rail_car(_car(contact="rigid")).n_dof == 6


def test_decoupled_frequencies_match_hand_formulas():
    """Natural frequencies in the decoupled limits (one body on its own springs, the others held):

    body bounce √(2k_s/M_c)/2π, body pitch √(2k_s a²/J_c)/2π — primary and contact 1e6× stiffer;
    bogie bounce √((k_s + 2k_p)/M_t)/2π, bogie pitch √(2k_p b²/J_t)/2π — body 1e6× heavier, contact
    1e6× stiffer; wheelset bounce √((k_p + k_H)/M_w)/2π — body and bogies 1e6× heavier.
    The neglected coupling is O(1e-6); measured relative errors ≤ 2e-6.
    """
    ks, kp, kh, a, b = 0.7e6, 2.4e6, 2.0e9, 8.75, 1.25
    mc, jc, mt, jt, mw = 40_000.0, 1.9e6, 3_000.0, 1_800.0, 1_700.0
    tol = 1e-5
    f = lambda k, m: np.sqrt(k / m) / (2 * np.pi)  # noqa: E731

    body = rail_car(_car(primary_stiffness=kp * 1e6, contact=kh * 1e6)).natural_frequencies()
    np.testing.assert_allclose(body[:2], sorted([f(2 * ks, mc), f(2 * ks * a**2, jc)]), rtol=tol)

    bogie = rail_car(_car(body_mass=mc * 1e6, body_pitch_inertia=jc * 1e6, contact=kh * 1e6)).natural_frequencies()
    expected = sorted([f(ks + 2 * kp, mt)] * 2 + [f(2 * kp * b**2, jt)] * 2)
    np.testing.assert_allclose(bogie[2:6], expected, rtol=tol)

    ws = rail_car(_car(body_mass=mc * 1e6, body_pitch_inertia=jc * 1e6, bogie_mass=mt * 1e6,
                       bogie_pitch_inertia=jt * 1e6, contact=kh)).natural_frequencies()
    np.testing.assert_allclose(ws[-4:], [f(kp + kh, mw)] * 4, rtol=tol)


def test_hertz_stiffness_hand_values():
    """k_H = 3/(2G) P₀^(1/3), G = 4.57 R^−0.149 × 1e-8 (conical) / 3.86 R^−0.115 × 1e-8 (worn)."""
    # P0 = 80 kN, R = 0.43 m, conical: G = 4.57 · 0.43^−0.149 · 1e-8 = 4.57 · 1.13400 · 1e-8 = 5.1824e-8 m/N^(2/3)
    g_con = 4.57 * 0.43 ** (-0.149) * 1e-8
    assert hertz_constant(0.43) == pytest.approx(g_con, rel=1e-14)
    assert g_con == pytest.approx(5.1824e-8, rel=1e-4)
    k = 1.5 * 80e3 ** (1 / 3) / g_con
    assert hertz_stiffness(80e3, wheel_radius=0.43) == pytest.approx(k, rel=1e-14)
    assert k == pytest.approx(1.2472e9, rel=1e-4)  # 1.5 · 43.0887 / 5.1824e-8 N/m
    assert hertz_stiffness(80e3, G=5e-8) == pytest.approx(1.5 * 80e3 ** (1 / 3) / 5e-8, rel=1e-14)
    assert hertz_constant(0.46, "worn") == pytest.approx(3.86 * 0.46 ** (-0.115) * 1e-8, rel=1e-14)
    # the tangent of P(δ) = (δ/G)^(3/2) at P0, by a central difference of the law itself
    d0 = g_con * 80e3 ** (2 / 3)
    h = 1e-4 * d0
    slope = (((d0 + h) / g_con) ** 1.5 - ((d0 - h) / g_con) ** 1.5) / (2 * h)
    assert hertz_stiffness(80e3, wheel_radius=0.43) == pytest.approx(slope, rel=1e-8)


def test_hertz_constant_against_classical_hertz():
    """Second source: Hertz's contact of two crossed steel cylinders (wheel R_w = 0.43 m, rail crown
    R_r = 0.30 m; E = 210 GPa, ν = 0.3) approached as a sphere of radius R_e = √(R_w R_r) on a plane
    (Johnson 1985, Contact Mechanics, ch. 4, Hertz theory, in the circular-contact approximation):
    δ = (9 P² / (16 E*² R_e))^(1/3), so G = (9 / (16 E*² R_e))^(1/3) = 4.90e-8 m/N^(2/3).
    Zhai's fit (5.18e-8) includes the real profile's conformity; they agree within 6 %."""
    e_star = 210e9 / (2 * (1 - 0.3**2))
    g_hertz = (9.0 / (16.0 * e_star**2 * np.sqrt(0.43 * 0.30))) ** (1 / 3)
    assert g_hertz == pytest.approx(4.90e-8, rel=5e-3)
    assert hertz_constant(0.43) == pytest.approx(g_hertz, rel=0.07)


def test_hertz_contact_per_wheelset_is_two_wheels():
    """A wheelset's contact is its two wheels in parallel, each at half the axle load."""
    car = _car(wheel_radius=0.46)
    p = car.static_axle_loads()
    k = car.contact_stiffness()
    g_con = 4.57 * 0.46 ** (-0.149) * 1e-8
    np.testing.assert_allclose(k, 2 * 1.5 * (p / 2) ** (1 / 3) / g_con, rtol=1e-13)
    np.testing.assert_allclose([w.stiffness for w in rail_car(car).wheels], k, rtol=0)


@pytest.mark.parametrize("name", sorted(RAIL_CAR_PRESETS))
def test_presets_weight_and_source(name):
    """Each preset's static axle loads sum to its weight and it names its source."""
    p = RAIL_CAR_PRESETS[name]
    v = rail_car(p)
    assert v.total_weight == pytest.approx((p.body_mass + 2 * p.bogie_mass + 4 * p.wheelset_mass) * G, rel=1e-12)
    assert p.source


def test_preset_ice3_numbers():
    """ICE3 / AVE S-103 intermediate coach (Goicolea 2014): 47.8 t body, 2 × 3.5 t bogies, 4 × 1.8 t
    wheelsets → 62 t, axle load 62 000 · 9.81 / 4 = 152 055 N; bogie centres 17.375 m apart."""
    p = RAIL_CAR_PRESETS["ice3-coach"]
    np.testing.assert_allclose(rail_car(p).static_wheel_loads(), [152_055.0] * 4, rtol=1e-12)
    np.testing.assert_allclose(p.axle_offsets, [0.0, 2.5, 17.375, 19.875])


@pytest.mark.parametrize("bad", [dict(body_mass=-1.0), dict(contact="stiff"), dict(contact=-5.0),
                                 dict(body_cg_offset=9.0), dict(axle_half_spacing=9.0), dict(tread="flat")])
def test_bad_parameters_refused(bad):
    with pytest.raises(ValueError, match="rail car|tread"):
        _car(**bad)


def test_replace_keeps_validation():
    with pytest.raises(ValueError):
        dataclasses.replace(_car(), secondary_damping=-1.0)
