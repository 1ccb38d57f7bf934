"""Exact modal stepping (vbikit.solve.modal_step, kernels.implicit) against closed forms.

References (no vbikit output):
* Chopra, *Dynamics of Structures* (4th ed.), §5.2, Table 5.2.1: the recurrence coefficients
  A, B, C, D, A′, B′, C′, D′ of the "piecewise exact" method (Nigam & Jennings 1969) for an
  underdamped SDOF system with a load linear over each step, written out below;
* free vibration of a damped oscillator released from u0 at rest:
  u(t) = u0 e^{−ζωt} (cos ω_D t + ζ/√(1−ζ²) sin ω_D t);
* an undamped oscillator from rest under a ramp p = αt: u(t) = (α/ω²)(t − sin(ωt)/ω).
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.solve import kernels
from vbikit.solve.kernels import Modes, Motion, Points, Road, Vehicles
from vbikit.solve.modal_step import exact_step, newmark_step, vehicle_step


def chopra(omega, zeta, h):
    """Chopra Table 5.2.1 (k = ω², unit mass): u_{i+1} = A u + B u̇ + C p_i + D p_{i+1}, u̇ likewise."""
    k = omega**2
    s1 = np.sqrt(1 - zeta**2)
    wd = omega * s1
    e = np.exp(-zeta * omega * h)
    sn, cs = np.sin(wd * h), np.cos(wd * h)
    A = e * (zeta / s1 * sn + cs)
    B = e * sn / wd
    C = (2 * zeta / (omega * h) + e * (((1 - 2 * zeta**2) / (wd * h) - zeta / s1) * sn
                                       - (1 + 2 * zeta / (omega * h)) * cs)) / k
    D = (1 - 2 * zeta / (omega * h) + e * ((2 * zeta**2 - 1) / (wd * h) * sn + 2 * zeta / (omega * h) * cs)) / k
    Ap = -e * omega / s1 * sn
    Bp = e * (cs - zeta / s1 * sn)
    Cp = (-1 / h + e * ((omega / s1 + zeta / (h * s1)) * sn + cs / h)) / k
    Dp = (1 - e * (zeta / s1 * sn + cs)) / (k * h)
    return A, B, C, D, Ap, Bp, Cp, Dp


@pytest.mark.parametrize("zeta", [0.0, 0.02, 0.3])
def test_exact_step_is_chopras_recurrence(zeta):
    omega = np.array([3.0, 46.0, 700.0, 1.8e4])
    for h in (1e-3, 2e-3, 0.01):
        s = exact_step(omega, np.full(omega.size, zeta), h)
        A, B, C, D, Ap, Bp, Cp, Dp = chopra(omega, zeta, h)
        theta = omega * h
        # Chopra's C, D, C', D' cancel to O((ωh)²) of their terms: compare where they do not (ωh ≥ 0.1)
        ok = theta >= 0.1
        np.testing.assert_allclose(s.a11, A, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(s.a12, B, rtol=1e-11, atol=1e-18)
        np.testing.assert_allclose(s.a21, Ap, rtol=1e-11, atol=1e-12)
        np.testing.assert_allclose(s.a22, Bp, rtol=1e-12, atol=1e-14)
        for ours, ref in ((s.b1, C), (s.c1, D), (s.b2, Cp), (s.c2, Dp)):
            np.testing.assert_allclose(ours[ok], ref[ok], rtol=1e-8, atol=0)


def _single_mode_run(omega, zeta, dt, n_steps, xi0, dxi0=0.0):
    """One mode released from (ξ0, ξ̇0) through the coupled kernel (kernels.implicit), with one
    unloaded contact point standing on the deck (no vehicle DOFs)."""
    span = 10.0
    grid = np.linspace(0.0, span, 11)
    values = np.full((1, grid.size, 1), -1.0)
    modes = Modes(np.array([omega]), np.array([zeta]), np.zeros(1), np.full(1, span), 1.0, values, np.zeros_like(values), np.ones(1))
    z = np.zeros((0, 0))
    vehicles = Vehicles(z, z, z, z, np.zeros(0), np.zeros((1, 0)), np.zeros(1, np.int64), np.ones(1, np.int64),
                        np.zeros(1, bool), np.zeros(1), np.zeros(1))
    points = Points(np.array([5.0]), np.ones(1), np.zeros(1, np.int64), np.zeros(1, np.int64), np.zeros(1, np.int64),
                    np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1, bool), np.zeros(1, np.int64),
                    np.zeros(1), np.zeros((1, 2)))
    road = Road(np.array([-100.0, 100.0]), np.zeros((1, 2, 1)), 0.0)
    motion = Motion(np.zeros((2 * n_steps + 1, 1)), np.zeros((2 * n_steps + 1, 1)))
    xi, dxi, ddxi = (np.zeros((1, n_steps + 1, 1)) for _ in range(3))
    q, dq, ddq = (np.zeros((1, n_steps + 1, 0)) for _ in range(3))
    wf, wl = np.zeros((1, n_steps + 1, 1)), np.zeros((1, n_steps + 1, 1))
    xi[0, 0, 0], dxi[0, 0, 0] = xi0, dxi0
    step = exact_step(np.array([omega]), np.array([zeta]), dt)
    kernels.implicit(dt, motion, modes, vehicles, points, road, True, step, vehicle_step(vehicles, dt), xi, dxi, q,
                     dq, ddxi, ddq, wf, wl, np.zeros((1, 1)), np.zeros((0, 1)), False, points.origin.copy(), 1e-9, 50,
                     kernels.MANY_LANES, 1, 0.0)  # stride 1, span 0: the defaults, given
    # as the solver gives them (an int and a float), so that this call runs the kernel variant the solver runs and
    # the shared warm-up compiles, not one of its own (omitted arguments are a type of their own to numba)
    return xi[0, :, 0], dxi[0, :, 0], ddxi[0, :, 0]


@pytest.mark.parametrize("zeta", [0.0, 0.05])
@pytest.mark.parametrize("steps_per_period", [0.37, 3.0, 40.0])
def test_single_mode_free_vibration_is_exact_at_any_step(zeta, steps_per_period):
    omega, u0 = 2 * np.pi * 7.3, 1e-3
    dt = 2 * np.pi / omega / steps_per_period
    n = 200
    xi, dxi, ddxi = _single_mode_run(omega, zeta, dt, n, u0)
    t = dt * np.arange(n + 1)
    wd = omega * np.sqrt(1 - zeta**2)
    exact = u0 * np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta / np.sqrt(1 - zeta**2) * np.sin(wd * t))
    # round-off: 200 products of a 2×2 map with entries ≤ 1, and the reference's cos(ω_D t)
    # at ω_D t up to 1.2e3 rad (≈ 3e-13)
    assert np.abs(xi - exact).max() <= 1e-12 * u0
    assert np.abs(ddxi + 2 * zeta * omega * dxi + omega**2 * xi).max() <= 1e-12 * omega**2 * u0


def test_ramp_load_is_exact_with_first_order_hold():
    omega, alpha, h = 2 * np.pi * 4.0, 3.0, 0.013
    s = exact_step(np.array([omega]), np.zeros(1), h)
    u = v = 0.0
    for n in range(300):
        p0, p1 = alpha * n * h, alpha * (n + 1) * h
        u, v = (s.a11[0] * u + s.a12[0] * v + s.b1[0] * p0 + s.c1[0] * p1,
                s.a21[0] * u + s.a22[0] * v + s.b2[0] * p0 + s.c2[0] * p1)
    t = 300 * h
    exact_u = alpha / omega**2 * (t - np.sin(omega * t) / omega)
    exact_v = alpha / omega**2 * (1 - np.cos(omega * t))
    assert u == pytest.approx(exact_u, rel=1e-12)
    assert v == pytest.approx(exact_v, rel=1e-12, abs=1e-15)


def test_newmark_step_is_the_average_acceleration_rule():
    # undamped: the average-acceleration rule conserves energy and elongates the period by
    # T̄/T = (ωh/2)/atan(ωh/2) (Newmark 1959; Chopra §5.4): check both on the map's eigenvalues
    omega, h = 50.0, 0.01
    s = newmark_step(np.array([omega]), np.zeros(1), h)
    lam = np.linalg.eigvals(np.array([[s.a11[0], s.a12[0]], [s.a21[0], s.a22[0]]]))
    assert np.abs(lam) == pytest.approx([1.0, 1.0], rel=1e-14)
    assert np.abs(np.angle(lam[0])) == pytest.approx(2 * np.arctan(omega * h / 2), rel=1e-13)


@pytest.mark.parametrize("zeta", [0.0, 0.02, 1.5])
def test_exact_step_is_the_exponential_of_the_augmented_system(zeta):
    # independent of the library's branches (closed form for ωh ≥ 0.5, scaled exponential below):
    # the dimensional 4×4 system (ξ, ξ̇, p, ṗ) with ṗ constant over the step
    from scipy.linalg import expm

    for omega in (3.0, 46.0, 700.0):
        for h in (1e-3, 4e-3, 0.01):
            a = np.array([[0, 1, 0, 0], [-omega**2, -2 * zeta * omega, 1, 0], [0, 0, 0, 1], [0, 0, 0, 0]], float)
            e = expm(a * h)
            s = exact_step(np.array([omega]), np.array([zeta]), h)
            ref = (e[0, 0], e[0, 1], e[1, 0], e[1, 1], e[0, 2] - e[0, 3] / h, e[1, 2] - e[1, 3] / h, e[0, 3] / h,
                   e[1, 3] / h)
            ours = (s.a11, s.a12, s.a21, s.a22, s.b1, s.b2, s.c1, s.c2)
            for o, r in zip(ours, ref):
                assert o[0] == pytest.approx(r, rel=1e-9, abs=1e-13 * max(abs(r), 1e-12))


def test_step_maps_are_made_once_per_inputs_and_no_crossing_writes_to_the_shared_ones():
    """``exact_step`` and ``vehicle_step`` keep their maps per input bytes and step; a crossing
    (static start, lean kernel, outputs) must leave the shared arrays as made: each equals a map
    made afresh after the run, bit for bit."""
    from vbikit.scenario import demo_scenario_text, scenario_from_toml
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import modal_step, simulate
    from vbikit.solve.system import kernel_data

    built = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built
    data = kernel_data(built.crossing)
    h = 0.00096
    hold = modal_step.QUADRATIC  # the exact integrator's
    step = modal_step.exact_step(data.modes.omega, data.modes.zeta, h, hold)
    vstep = modal_step.vehicle_step(data.vehicles, h, hold)
    assert modal_step.exact_step(data.modes.omega.copy(), data.modes.zeta.copy(), h, hold) is step
    assert modal_step.vehicle_step(data.vehicles, h, hold) is vstep
    assert modal_step.exact_step(data.modes.omega, data.modes.zeta, 2 * h, hold) is not step
    assert modal_step.vehicle_step(data.vehicles, 2 * h, hold) is not vstep
    assert modal_step.exact_step(data.modes.omega, data.modes.zeta, h) is not step  # (the linear hold's)
    assert modal_step.vehicle_step(data.vehicles, h) is not vstep
    simulate(built.crossing)
    simulate(built.crossing)
    mine = modal_step._input_key("", 0.0, (data.modes.omega, data.modes.zeta))[2:]
    runs = [(key[1], kept) for key, kept in modal_step._MODAL_MAPS.items() if key[0] == f"exact{hold}" and key[2:] == mine]
    assert len(runs) >= 2  # the h above and the crossing's own step
    for dt, kept in runs:
        for a, b in zip(kept, modal_step._exact_step(data.modes.omega, data.modes.zeta, dt, hold)):
            np.testing.assert_array_equal(a, b)
    mine = modal_step._input_key("", 0.0, (data.vehicles.mass_inv, data.vehicles.damping, data.vehicles.stiffness,
                                           data.vehicles.wheel_rows, data.vehicles.wheel_damping,
                                           data.vehicles.wheel_stiffness, data.vehicles.gravity))[2:]
    runs = [(key[1], kept) for key, kept in modal_step._MAPS.items() if key[0] == f"vehicle{hold}" and key[2:] == mine]
    assert len(runs) >= 2
    for dt, kept in runs:
        for a, b in zip(kept, modal_step._vehicle_step(data.vehicles, dt, hold)):
            np.testing.assert_array_equal(a, b)


#: pairs of different axle trucks: of different sizes (their blocks exponentiated one by one) and of one
#: size (in one stack, ``expm_each``)
TRUCK_PAIRS = {
    "2 and 5 axles": (([60e3, 110e3], [4.2]), ([55e3, 95e3, 95e3, 80e3, 80e3], [3.6, 1.3, 6.0, 1.3])),
    "two 5-axle": (([40e3, 45e3, 45e3, 40e3, 40e3], [5.2, 1.3, 9.9, 1.3]),
                   ([55e3, 95e3, 95e3, 80e3, 80e3], [3.6, 1.3, 6.0, 1.3])),
}


def _combined_vehicles(pair: str = "2 and 5 axles"):
    """Two different axle trucks (``TRUCK_PAIRS``) combined, with their point-tire contact."""
    from vbikit.contact.points import contact_points, stack_contact_points
    from vbikit.contact.tires import PointTire
    from vbikit.solve.system import vehicles_data
    from vbikit.vehicle.axles import axle_truck
    from vbikit.vehicle.model import combine_vehicles

    trucks = [axle_truck(loads, spacings) for loads, spacings in TRUCK_PAIRS[pair]]
    combined = combine_vehicles(trucks)
    contact = stack_contact_points([contact_points(t, PointTire()) for t in trucks], combined.dof_offsets)
    return trucks, combined, vehicles_data(combined, contact)


@pytest.mark.parametrize("pair", list(TRUCK_PAIRS))
@pytest.mark.parametrize("h", [0.002, 0.0137])
def test_vehicle_step_of_combined_trucks_is_the_exponential_of_the_whole_augmented_system(h, pair):
    """Several vehicles' step map is made block by block (``_blocks``); it must equal the map read
    from scipy.linalg.expm (Padé, Al-Mohy & Higham 2009: another code) of the whole augmented
    first-order system (q, q̇, G, Ġ, 1) of the combined vehicle, written out here; the blocks'
    cross terms must be exactly zero, and the settle map P = (I − L1 K_z)⁻¹ the direct inverse."""
    from scipy.linalg import expm as scipy_expm

    from vbikit.solve import modal_step

    trucks, combined, veh = _combined_vehicles(pair)
    n_d, n_w = veh.gravity.size, veh.wheel_rows.shape[0]
    assert modal_step._blocks(veh, *modal_step._nominal(veh)) == [(0, trucks[0].n_dof), (trucks[0].n_dof, n_d)]
    rows = veh.wheel_rows
    c_hat = veh.damping + rows.T @ (veh.wheel_damping[:, None] * rows)
    k_hat = veh.stiffness + rows.T @ (veh.wheel_stiffness[:, None] * rows)
    m_inv = np.linalg.inv(combined.mass)
    n = 2 * n_d + 2 * n_w + 1
    a = np.zeros((n, n))
    a[:n_d, n_d:2 * n_d] = np.eye(n_d)
    a[n_d:2 * n_d, :n_d] = -m_inv @ k_hat
    a[n_d:2 * n_d, n_d:2 * n_d] = -m_inv @ c_hat
    a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = m_inv @ rows.T
    a[n_d:2 * n_d, -1] = m_inv @ combined.gravity
    a[2 * n_d:2 * n_d + n_w, 2 * n_d + n_w:-1] = np.eye(n_w)
    e = scipy_expm(a * h)
    z = slice(0, 2 * n_d)
    transition, load1 = e[z, z], e[z, 2 * n_d + n_w:-1] / h
    load0, constant = e[z, 2 * n_d:2 * n_d + n_w] - load1, e[z, -1]
    step = modal_step._vehicle_step(veh, h)
    for mine, ref in ((step.transition, transition), (step.load0, load0), (step.load1, load1)):
        np.testing.assert_allclose(mine, ref, rtol=1e-10, atol=1e-12 * np.abs(ref).max())
    np.testing.assert_allclose(step.constant, constant, rtol=1e-10, atol=1e-12 * np.abs(constant).max())
    k_z = np.hstack([veh.wheel_stiffness[:, None] * rows, veh.wheel_damping[:, None] * rows])
    settle = np.linalg.inv(np.eye(2 * n_d) - load1 @ k_z)
    np.testing.assert_allclose(step.settle, settle, rtol=1e-10, atol=1e-12 * np.abs(settle).max())
    # no term couples the first truck's q, q̇ (and wheels) to the second's
    first = np.r_[0:trucks[0].n_dof, n_d:n_d + trucks[0].n_dof]
    second = np.setdiff1d(np.arange(2 * n_d), first)
    w1 = len(trucks[0].wheels)
    for m in (step.transition, step.settle):
        assert not np.any(m[np.ix_(first, second)]) and not np.any(m[np.ix_(second, first)])
    assert not np.any(step.load1[first, w1:]) and not np.any(step.load1[second, :w1])
    # the reference itself: the two trucks' exact blocks are not copies of each other
    assert trucks[0].n_dof != trucks[1].n_dof or not np.allclose(trucks[0].mass, trucks[1].mass)


def test_vehicle_step_of_one_vehicle_is_one_block():
    """One truck alone: a single block (its DOFs are all coupled), the map unchanged."""
    from vbikit.solve import modal_step

    trucks, _, _ = _combined_vehicles()
    from vbikit.contact.points import contact_points
    from vbikit.contact.tires import PointTire
    from vbikit.solve.system import vehicles_data

    veh = vehicles_data(trucks[1], contact_points(trucks[1], PointTire()))
    assert modal_step._blocks(veh, *modal_step._nominal(veh)) == [(0, trucks[1].n_dof)]


@pytest.mark.parametrize("theta", [1e-3, 0.4, 5.0, 40.0, 300.0])  # ‖A‖₁ up to a truck's augmented system
def test_expm_is_the_rotation_and_the_damped_oscillator(theta):
    """``expm`` (Taylor series with scaling and squaring) against closed forms: exp([[0, θ], [−θ, 0]]) is
    the rotation [[cos θ, sin θ], [−sin θ, cos θ]]; exp(t [[0, 1], [−ω², −2ζω]]) the damped
    oscillator's free response (x, ẋ columns, Chopra Eq. 2.2.4); and a stack of both at once."""
    from vbikit.solve.modal_step import expm

    rot = expm(np.array([[0.0, theta], [-theta, 0.0]]))
    np.testing.assert_allclose(rot, [[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]],
                               rtol=0, atol=4e-15 * max(1.0, theta))
    w, z = 7.0, 0.05
    t = theta / w
    wd, e = w * np.sqrt(1 - z * z), np.exp(-z * w * t)
    sn, cs = np.sin(wd * t), np.cos(wd * t)
    free = np.array([[e * (cs + z * w / wd * sn), e * sn / wd],
                     [-e * w * w / wd * sn, e * (cs - z * w / wd * sn)]])
    stack = expm(np.stack([np.array([[0.0, 1.0], [-w * w, -2 * z * w]]) * t, np.array([[0.0, theta], [-theta, 0.0]])]))
    np.testing.assert_allclose(stack[0], free, rtol=0, atol=4e-15 * max(1.0, theta) * np.abs(free).max() + 1e-300)
    np.testing.assert_allclose(stack[1], rot, rtol=0, atol=1e-15 * max(1.0, theta))
