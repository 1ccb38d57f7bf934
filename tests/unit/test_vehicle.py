"""Unit tests for vbikit.vehicle: presets, matrices, static loads, the builder's kinematics."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.vehicle import GRAVITY, VEHICLE_PRESETS, Vehicle, VehicleBuilder, hs20_44, quarter_car, two_axle_truck

#: total mass [kg] of each preset (sum of its body and axle masses, from the preset docstrings)
TOTAL_MASS = {
    "moving-force": 100e3 / GRAVITY,  # default force 100 kN
    "sprung-mass": 5750.0,
    "quarter-car": 11_000.0,
    "hs20-44": 2612.0 + 26113.0 + 490.0 + 808.0 + 653.0,
    "two-axle": 16837.0 + 490.0 + 808.0,
    "dump-truck": (80.0e3 + 2 * 95.6e3) / GRAVITY,  # paper §4.2 axle loads; sprung 24,745 kg (+0.26) + axles 2,900 kg
    "3s2": 3100.0 + 20000.0 + 3 * 750.0 + 2 * 1100.0,  # VBI-2D's five-axle vehicle (E01_Example.m)
    "axles": (53.4e3 + 4 * 75.6e3) / GRAVITY,  # the preset's example: axle loads given
    # trains as moving axle loads: EN 1991-2 Table E.1, HSLM-A: 2N + 14 axles of P [kN] (N, P written out)
    **{f"hslm-a{k}": (2 * n + 14) * p * 1e3 / GRAVITY for k, (n, p) in
       {1: (18, 170), 2: (17, 200), 3: (16, 180), 4: (15, 190), 5: (14, 170), 6: (13, 180), 7: (13, 190),
        8: (12, 190), 9: (11, 210), 10: (11, 210)}.items()},
    # ICE 3 (Goicolea 2014): 24 axles of g((23900 + 3500)/2 + 1800) kg and 8 of 135,868.5 N (cars 4 and 5)
    "ice3": (24 * 9.81 * ((23900 + 3500) / 2 + 1800) + 8 * 135868.5) / GRAVITY,
}


@pytest.fixture(params=sorted(VEHICLE_PRESETS))
def preset(request) -> tuple[str, Vehicle]:
    return request.param, VEHICLE_PRESETS[request.param].example_vehicle()


#: presets with degrees of freedom (all but the moving force)
DOF_PRESETS = sorted(n for n, p in VEHICLE_PRESETS.items() if p.example_vehicle().n_dof > 0)  # not the moving forces


@pytest.fixture(params=DOF_PRESETS)
def dof_preset(request) -> tuple[str, Vehicle]:
    return request.param, VEHICLE_PRESETS[request.param].example_vehicle()


def test_every_preset_builds_consistently(preset):
    name, v = preset
    assert isinstance(v, Vehicle)
    n = v.n_dof
    assert len(v.dof_names) == len(set(v.dof_names)) == n
    for mat in (v.mass, v.damping, v.stiffness):
        assert mat.shape == (n, n)
        assert np.all(np.isfinite(mat))
    assert v.gravity.shape == (n,)
    assert len(v.wheels) >= 1
    for w in v.wheels:
        assert w.row.shape == (n,)
        assert w.offset >= 0.0
        assert w.stiffness >= 0.0 and w.damping >= 0.0
    assert name in TOTAL_MASS, "new preset: add its total mass to TOTAL_MASS"


def test_moving_force_has_no_dofs_and_a_fixed_load():
    v = VEHICLE_PRESETS["moving-force"].build(force=50e3)
    assert v.n_dof == 0
    assert v.static_wheel_loads() == pytest.approx([50e3])
    assert v.natural_frequencies().size == 0


def test_matrices_symmetric_and_mass_positive_definite(dof_preset):
    _, v = dof_preset
    assert v.n_dof > 0
    for mat in (v.mass, v.damping, v.stiffness):
        np.testing.assert_allclose(mat, mat.T, rtol=0, atol=1e-9 * np.abs(mat).max())
    assert np.linalg.eigvalsh(v.mass).min() > 0.0
    assert np.linalg.eigvalsh(v.stiffness).min() >= -1e-6 * np.abs(v.stiffness).max()  # suspension: PSD
    # on its tires the vehicle is a stable structure
    assert np.linalg.eigvalsh(v.stiffness + v.tire_stiffness_matrix()).min() > 0.0


def test_static_wheel_loads_sum_to_weight(preset):
    name, v = preset
    loads = v.static_wheel_loads()
    assert np.all(loads > 0.0)
    assert loads.sum() == pytest.approx(TOTAL_MASS[name] * GRAVITY, rel=1e-10)
    assert v.total_weight == pytest.approx(TOTAL_MASS[name] * GRAVITY, rel=1e-10)


def test_static_state_is_equilibrium(dof_preset):
    _, v = dof_preset
    ground = np.linspace(-0.01, 0.02, len(v.wheels))
    q = v.static_state(ground)
    tire_forces = [w.stiffness * (g - w.row @ q) for w, g in zip(v.wheels, ground)]
    residual = v.gravity - v.stiffness @ q + sum(w.row * f for w, f in zip(v.wheels, tire_forces))
    assert np.abs(residual).max() < 1e-7 * np.abs(v.gravity).max()


def _axle_loads_kN(v: Vehicle) -> list[float]:
    loads = v.static_wheel_loads()
    axles: dict[str, float] = {}
    for w, p in zip(v.wheels, loads):
        axle = w.name.rsplit("_", 1)[0]
        axles[axle] = axles.get(axle, 0.0) + p / 1e3
    return [axles[k] for k in sorted(axles)]


def test_hs20_44_axle_loads():
    # model data §2 [computed]: 30.7 / 134.2 / 136.0 kN
    np.testing.assert_allclose(_axle_loads_kN(hs20_44()), [30.7, 134.2, 136.0], atol=0.2)


def test_hs20_44_layout():
    v = hs20_44()
    assert v.n_dof == 11
    offsets = sorted({round(w.offset, 6) for w in v.wheels})
    np.testing.assert_allclose(offsets, [0.0, 4.267, 8.534], atol=1e-9)
    assert sorted({w.lateral for w in v.wheels}) == [-1.1, 1.1]
    # left and right wheels carry the same static load (symmetric vehicle)
    loads = v.static_wheel_loads()
    np.testing.assert_allclose(loads[0::2], loads[1::2], rtol=1e-10)


def test_two_axle_truck_axle_loads():
    # model data §2 [substitute]: H20-44 loads 35.6 / 142.3 kN
    np.testing.assert_allclose(_axle_loads_kN(two_axle_truck()), [35.6, 142.3], atol=0.2)


def test_quarter_car_frequencies_closed_form():
    m1, m2, ks, kt = 9000.0, 1100.0, 350e3, 1.9e6
    v = quarter_car(sprung_mass=m1, unsprung_mass=m2, suspension_stiffness=ks, tire_stiffness=kt)
    # chain ground–kt–m2–ks–m1: m1 m2 ω⁴ − (m1 (ks + kt) + m2 ks) ω² + ks kt = 0
    a, b, c = m1 * m2, -(m1 * (ks + kt) + m2 * ks), ks * kt
    w2 = np.sort(np.roots([a, b, c]).real)
    np.testing.assert_allclose(v.natural_frequencies(), np.sqrt(w2) / (2 * np.pi), rtol=1e-10)


def test_quarter_car_default_frequencies_as_documented():
    f = quarter_car().natural_frequencies()
    np.testing.assert_allclose(f, [0.9, 7.4], atol=0.1)  # docstring: ≈ 0.9 Hz and ≈ 7.4 Hz


def test_sprung_mass_frequency():
    v = VEHICLE_PRESETS["sprung-mass"].build()
    # Yang & Yau: f_v = 2.65 Hz (model data §5)
    assert v.natural_frequencies()[0] == pytest.approx(np.sqrt(1595e3 / 5750) / (2 * np.pi), rel=1e-12)
    assert v.natural_frequencies()[0] == pytest.approx(2.65, abs=0.01)


# ------------------------------------------------------------------ builder: hinged trailer
S1, S_HINGE, S_AXLE2 = 1.5, 3.5, 4.0  # tractor CG, fifth wheel, tractor rear axle [m behind the front axle]
S2, S_AXLE3 = 8.0, 12.0  # trailer CG, trailer axle
M1, M2, J1, J2 = 4000.0, 20000.0, 9000.0, 150000.0


def _tractor_trailer():
    vb = VehicleBuilder("test-semi")
    tractor = vb.body("tractor", M1, S1, pitch_inertia=J1, pitch=True)
    trailer = vb.hinged_body("trailer", M2, S2, tractor, S_HINGE, pitch_inertia=J2)
    for name, body, s, k in (("a1", tractor, 0.0, 1e6), ("a2", tractor, S_AXLE2, 3e6), ("a3", trailer, S_AXLE3, 2e6)):
        vb.wheel(name, body.point(s), s, 0.0, k, 1e3)
    return vb, tractor, trailer, vb.build()


def _dense(row, n):
    out = np.zeros(n)
    for i, c in row.items():
        out[i] += c
    return out


def test_hinged_trailer_heave_row():
    vb, tractor, trailer, v = _tractor_trailer()
    assert v.dof_names == ("tractor_heave", "tractor_pitch", "trailer_pitch")
    # z_cg,trailer = z_tractor + (s_cg1 − s_h) θ1 − (s_cg2 − s_h) θ2
    np.testing.assert_allclose(_dense(trailer.heave, 3), [1.0, S1 - S_HINGE, -(S2 - S_HINGE)], rtol=1e-15)
    # the two bodies share the hinge point for any motion
    np.testing.assert_allclose(_dense(trailer.point(S_HINGE), 3), _dense(tractor.point(S_HINGE), 3), atol=1e-15)
    # the trailer pitches about the hinge: its axle goes down by (s_axle − s_h) per radian nose-up
    assert _dense(trailer.point(S_AXLE3), 3)[2] == pytest.approx(-(S_AXLE3 - S_HINGE))


def test_hinged_trailer_mass_and_gravity():
    _, _, trailer, v = _tractor_trailer()
    h2 = _dense(trailer.heave, 3)
    m = np.zeros((3, 3))
    m[0, 0] += M1
    m[1, 1] += J1
    m += M2 * np.outer(h2, h2)
    m[2, 2] += J2
    np.testing.assert_allclose(v.mass, m, rtol=1e-14)
    np.testing.assert_allclose(v.gravity, -GRAVITY * (M1 * np.array([1.0, 0.0, 0.0]) + M2 * h2), rtol=1e-14)


def test_hinged_trailer_static_loads_by_lever_rule():
    # three axles and three DOFs: statically determinate, loads independent of the springs
    _, _, _, v = _tractor_trailer()
    w1, w2 = M1 * GRAVITY, M2 * GRAVITY
    r_hinge = w2 * (S_AXLE3 - S2) / (S_AXLE3 - S_HINGE)
    axle3 = w2 - r_hinge
    axle2 = (w1 * S1 + r_hinge * S_HINGE) / S_AXLE2
    axle1 = w1 + r_hinge - axle2
    np.testing.assert_allclose(v.static_wheel_loads(), [axle1, axle2, axle3], rtol=1e-9)


def test_builder_spring_between_points_and_ground():
    vb = VehicleBuilder("two-mass")
    a = vb.body("a", 100.0, 0.0)
    b = vb.body("b", 50.0, 0.0)
    vb.spring(a.heave, b.heave, 1000.0, 10.0)
    vb.spring(b.heave, None, 3000.0, 20.0)
    v = vb.build()
    np.testing.assert_allclose(v.stiffness, [[1000.0, -1000.0], [-1000.0, 4000.0]])
    np.testing.assert_allclose(v.damping, [[10.0, -10.0], [-10.0, 30.0]])
    np.testing.assert_allclose(v.mass, np.diag([100.0, 50.0]))


def test_combined_vehicle_is_its_parts_against_the_whole_block_diagonal_system():
    """Several vehicles side by side (``combine_vehicles``) take their static state and wheel loads
    from each vehicle's own; the whole block-diagonal system solved directly (numpy.linalg.solve of
    the static equilibrium on the combined matrices, written out here) must give the same, and a copy
    of the combined vehicle with other matrices (``dataclasses.replace``) its own, not its parts'."""
    import dataclasses

    from vbikit.vehicle.axles import axle_truck
    from vbikit.vehicle.model import combine_vehicles

    parts = [axle_truck([60e3, 110e3], [4.2]), quarter_car(), axle_truck([55e3, 95e3, 95e3, 80e3, 80e3], [3.6, 1.3, 6.0, 1.3]),
             VEHICLE_PRESETS["moving-force"].build()]
    c = combine_vehicles(parts)
    rows = np.array([w.row for w in c.wheels])
    k_w = np.array([w.stiffness for w in c.wheels])
    k_hat = c.stiffness + rows.T @ (k_w[:, None] * rows)
    ground = np.linspace(-0.01, 0.02, len(c.wheels))
    q = np.linalg.solve(k_hat, c.gravity + rows.T @ (k_w * ground))
    np.testing.assert_allclose(c.static_state(ground), q, rtol=1e-11, atol=1e-14)
    q0 = np.linalg.solve(k_hat, c.gravity)
    fixed = np.array([w.fixed_load for w in c.wheels])
    np.testing.assert_allclose(c.static_wheel_loads(), fixed - k_w * (rows @ q0), rtol=1e-11)
    assert c.static_wheel_loads().sum() == pytest.approx(sum(p.total_weight for p in parts), rel=1e-12)
    stiffer = dataclasses.replace(c, stiffness=2.0 * c.stiffness)
    q2 = np.linalg.solve(2.0 * c.stiffness + rows.T @ (k_w[:, None] * rows), c.gravity)
    np.testing.assert_allclose(stiffer.static_wheel_loads(), fixed - k_w * (rows @ q2), rtol=1e-11)
