"""The quadratic load hold of the exact step (``vbikit.solve.modal_step.quadratic_hold``, ``vehicle_step``'s
``hold``) against independent numbers: quadrature of the convolution integral, the closed form of an
undamped mode under a sine load, and an ODE integrator (scipy's ``solve_ivp``) for a vehicle."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from vbikit.solve.modal_step import LINEAR, QUADRATIC, exact_step, vehicle_step

#: the hold's Lagrange basis on s = (t − t_n)/h through s = −1, 0, 1 (p_{n−1}, p_n, p_{n+1})
BASIS = {"d": lambda s: s * (s - 1.0) / 2.0, "b": lambda s: 1.0 - s * s, "c": lambda s: s * (s + 1.0) / 2.0}


def _impulse(omega: float, zeta: float):
    """The unit impulse response g(t) of x'' + 2ζωx' + ω²x and its derivative (closed forms)."""
    if zeta < 1.0:
        wd = omega * np.sqrt(1.0 - zeta**2)
        return (lambda t: np.exp(-zeta * omega * t) * np.sin(wd * t) / wd,
                lambda t: np.exp(-zeta * omega * t) * (np.cos(wd * t) - zeta * omega / wd * np.sin(wd * t)))
    if zeta == 1.0:
        return (lambda t: t * np.exp(-omega * t), lambda t: (1.0 - omega * t) * np.exp(-omega * t))
    r = omega * np.sqrt(zeta**2 - 1.0)
    s1, s2 = -zeta * omega + r, -zeta * omega - r
    return (lambda t: (np.exp(s1 * t) - np.exp(s2 * t)) / (s1 - s2),
            lambda t: (s1 * np.exp(s1 * t) - s2 * np.exp(s2 * t)) / (s1 - s2))


@pytest.mark.parametrize("zeta", [0.0, 0.05, 1.0, 2.0])
@pytest.mark.parametrize("theta", [0.02, 1.0, 30.0])
def test_modal_coefficients_are_the_convolution_of_the_lagrange_basis(zeta, theta):
    """d, b, c of ξ and ξ̇ = ∫₀ʰ g(h − τ) L(τ/h) dτ (and g') for each basis polynomial L, by adaptive
    quadrature, for ωh from 0.02 (the series branch) to 30 (quasi-static modes)."""
    omega, h = 7.0, theta / 7.0
    step = exact_step(np.array([omega]), np.array([zeta]), h, QUADRATIC)
    g, dg = _impulse(omega, zeta)
    for name, basis in BASIS.items():
        for resp, row in ((g, 1), (dg, 2)):
            ref = quad(lambda tau: resp(h - tau) * basis(tau / h), 0.0, h, epsabs=0.0, epsrel=1e-12, limit=400)[0]
            got = float(getattr(step, f"{name}{row}")[0])
            scale = abs(quad(lambda tau: abs(resp(h - tau)), 0.0, h, limit=200)[0])  # the load part's size
            assert abs(got - ref) <= 1e-11 * scale, (name, row, got, ref)


def test_the_linear_hold_is_the_quadratic_through_its_own_extrapolation():
    """With p_{n−1} = 2p_n − p_{n+1} the parabola is the line: b_lin = b + 2d, c_lin = c − d (and the
    free part is the same map)."""
    omega = np.array([0.5, 3.0, 40.0, 900.0])
    zeta = np.array([0.0, 0.02, 0.3, 1.5])
    for h in (1e-4, 1e-3, 2e-2):
        lin, quadr = exact_step(omega, zeta, h, LINEAR), exact_step(omega, zeta, h, QUADRATIC)
        np.testing.assert_array_equal(lin.d1, 0.0)
        for a in ("a11", "a12", "a21", "a22"):
            np.testing.assert_array_equal(getattr(lin, a), getattr(quadr, a))
        for row in (1, 2):
            b, c, d = (getattr(quadr, f"{k}{row}") for k in "bcd")
            np.testing.assert_allclose(b + 2.0 * d, getattr(lin, f"b{row}"), rtol=1e-12, atol=0.0)
            np.testing.assert_allclose(c - d, getattr(lin, f"c{row}"), rtol=1e-12, atol=0.0)
            assert np.all(d != 0.0)


def _sine_load_error(step, h: float, omega: float, big_omega: float, t_end: float) -> float:
    """The recurrence of ``step`` for ξ'' + ω²ξ = sin(Ωt) from rest, against its closed form
    (sin Ωt − (Ω/ω) sin ωt)/(ω² − Ω²); the load before t = 0 as the sine's (a smooth load)."""
    n = int(round(t_end / h))
    t = h * np.arange(n + 1)
    p = np.sin(big_omega * t)
    x, v, past = 0.0, 0.0, np.sin(-big_omega * h)
    worst = 0.0
    for k in range(n):
        x, v = (float(step.a11[0] * x + step.a12[0] * v + step.d1[0] * past + step.b1[0] * p[k] + step.c1[0] * p[k + 1]),
                float(step.a21[0] * x + step.a22[0] * v + step.d2[0] * past + step.b2[0] * p[k] + step.c2[0] * p[k + 1]))
        past = p[k]
        exact = (np.sin(big_omega * t[k + 1]) - big_omega / omega * np.sin(omega * t[k + 1])) / (omega**2 - big_omega**2)
        worst = max(worst, abs(x - exact))
    return worst


def test_the_quadratic_hold_is_third_order_and_the_linear_second():
    """Halving the step divides the largest error by ≈ 8 with the quadratic hold and by ≈ 4 with the
    linear one (one undamped mode at 4 Hz under a 0.7 Hz sine, 2 s)."""
    omega, big_omega = 2 * np.pi * 4.0, 2 * np.pi * 0.7
    ratios = {}
    for hold in (LINEAR, QUADRATIC):
        errors = [_sine_load_error(exact_step(np.array([omega]), np.array([0.0]), h, hold), h, omega, big_omega, 2.0)
                  for h in (4e-3, 2e-3)]
        ratios[hold] = errors[0] / errors[1]
    assert 3.6 < ratios[LINEAR] < 4.4
    assert 7.0 < ratios[QUADRATIC] < 9.0


def test_vehicle_maps_are_the_response_to_each_basis_load():
    """``vehicle_step(…, QUADRATIC)``: the columns of ``load_past``, ``load0``, ``load1`` are the end state
    (q, q̇) from rest under the wheel load L(t/h) (each Lagrange basis polynomial) on one wheel, with no
    gravity, by ``solve_ivp`` (DOP853, rtol 1e-12) on M q̈ + Ĉ q̇ + K̂ q = Hᵀ G; ``transition`` is the
    linear hold's (the same free map)."""
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.solve import Crossing
    from vbikit.solve.system import vehicles_data
    from vbikit.vehicle import hs20_44

    crossing = Crossing(EulerBernoulliBeam(span=20.0, EI=2e10, mass_per_length=1e4, damping_ratio=0.02, n_modes=2),
                        hs20_44(), speed=20.0)
    vehicles = vehicles_data(crossing.vehicle, crossing.contact)
    h = 2e-3
    quadr, lin = vehicle_step(vehicles, h, QUADRATIC), vehicle_step(vehicles, h, LINEAR)
    np.testing.assert_allclose(quadr.transition, lin.transition, rtol=0.0, atol=1e-13)
    np.testing.assert_array_equal(lin.load_past, 0.0)
    rows = vehicles.wheel_rows
    n_d = rows.shape[1]
    c_hat = vehicles.damping + rows.T @ (vehicles.wheel_damping[:, None] * rows)
    k_hat = vehicles.stiffness + rows.T @ (vehicles.wheel_stiffness[:, None] * rows)
    for w in range(rows.shape[0]):
        for name, basis in (("load_past", BASIS["d"]), ("load0", BASIS["b"]), ("load1", BASIS["c"])):
            def rhs(t, y):
                force = rows[w] * basis(t / h)
                return np.concatenate([y[n_d:], vehicles.mass_inv @ (force - c_hat @ y[n_d:] - k_hat @ y[:n_d])])

            end = solve_ivp(rhs, (0.0, h), np.zeros(2 * n_d), method="DOP853", rtol=1e-12, atol=1e-20).y[:, -1]
            got = getattr(quadr, name)[:, w]
            assert np.abs(got - end).max() <= 1e-8 * np.abs(end).max(), (w, name)
