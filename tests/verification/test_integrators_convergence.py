# References: textbook properties of the integrators and of the modal series, no vbikit output:
# * classical Runge–Kutta is 4th order, Newmark average acceleration (γ = 1/2, β = 1/4) 2nd
#   order (Hairer, Nørsett & Wanner, *Solving ODEs I*; Newmark 1959, J. Eng. Mech. Div. 85(3));
#   exact modal stepping is exact for each subsystem and, through the hold of the coupling loads,
#   2nd order with the wheels' loads held linear (the default; the trapezoidal rule's order;
#   docs/theory.md) and 3rd order with both the deck's and the wheels' held quadratic (the parabola
#   through three step ends: the error of polynomial interpolation of degree 2, O(h³) per unit time).
#   With errors e_k = C (dt/2^k)^p measured against a reference at dt/8, the ratios e_0/e_1,
#   e_1/e_2 are exactly (1 − 8^-p)/(2^-p − 8^-p) and (2^-p − 8^-p)/(4^-p − 8^-p):
#   16.06 and 17.0 for p = 4, 8.11 and 9.0 for p = 3, 4.2 and 5.0 for p = 2;
# * RK4 stability on the imaginary axis |ω dt| ≤ 2√2 (absolute-stability region of RK4);
# * static midspan deflection of a simply supported beam under a central load P, m modes:
#   (PL³/48EI) · (96/π⁴) Σ_{odd j ≤ m} 1/j⁴ → PL³/48EI (Frýba 1972, ch. 1; Σ_{odd} 1/j⁴ = π⁴/96).
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam, paper_beam
from vbikit.solve import Crossing, UnstableTimeStepError, rk4_stability_limit, simulate
from vbikit.vehicle import hs20_44, quarter_car


def test_rk4_and_newmark_agree_on_hs20():
    beam = paper_beam(16.76, "II")  # 10 modes, 2 % damping
    runs = {i: simulate(Crossing(beam, hs20_44(), speed=20.0, approach=5.0, dt=1e-4, integrator=i))
            for i in ("rk4", "newmark")}
    a, b = (runs[i].displacement() for i in ("rk4", "newmark"))
    # at dt = 1e-4 s Newmark's period error (ω dt)²/12 is 2e-6 for the first mode (46 rad/s) and
    # its accumulated phase error over the 1.7 s run ≲ 1e-4 (a bound; the 2 % damping keeps the
    # drift much smaller); RK4's is far smaller.  Measured: peak 1.7e-7, history 1.2e-6.
    assert abs(a.min() - b.min()) / abs(a.min()) < 1e-6
    assert np.abs(a - b).max() / np.abs(a).max() < 5e-6


def _errors(integrator: str, dt0: float) -> np.ndarray:
    """Max midspan-deflection errors at dt0, dt0/2, dt0/4 against dt0/8, relative to the peak.

    Quarter car (damped) entering at t = 0 (approach 0) and leaving at L/v = 0.838 s, a whole
    number of steps for every dt here, so the right-hand side is smooth between steps: an axle
    entering or leaving between two steps makes it non-smooth (see the report) and lowers the
    observed order.  3 modes: ω_3 dt0 = 0.21, deep in the asymptotic range (the next error term
    is O((ω dt)²) ≈ 4 % of the leading one).
    """
    beam = paper_beam(16.76, "II", n_modes=3)
    runs = [simulate(Crossing(beam, quarter_car(), speed=20.0, approach=0.0, free_vibration=0.2,
                              dt=dt0 / 2**k, integrator=integrator)) for k in range(4)]
    ref = runs[3]
    peak = np.abs(ref.displacement()).max()
    errs = []
    for k in range(3):
        step = 2 ** (3 - k)
        n = min(runs[k].time.size, (ref.time.size - 1) // step + 1)
        assert np.allclose(runs[k].time[:n], ref.time[::step][:n], rtol=0, atol=1e-12)
        errs.append(np.abs(runs[k].displacement()[:n] - ref.displacement()[::step][:n]).max() / peak)
    return np.array(errs)


def _expected_ratios(p: int) -> tuple[float, float]:
    return (1 - 8.0**-p) / (2.0**-p - 8.0**-p), (2.0**-p - 8.0**-p) / (4.0**-p - 8.0**-p)


@pytest.mark.parametrize("integrator, order, quadratic_wheel_loads",
                         [("rk4", 4, False), ("newmark", 2, False), ("exact", 2, False), ("exact", 3, True)])
def test_convergence_order(integrator, order, quadratic_wheel_loads, monkeypatch):
    """(The exact integrator's wheel loads held linear, its default, or quadratic on its lean steps:
    ``builtin_integrators.QUADRATIC_WHEEL_LOADS``; this smooth crossing has no landing, so no step of
    the full kernel.)"""
    monkeypatch.setattr("vbikit.solve.builtin_integrators.QUADRATIC_WHEEL_LOADS", quadratic_wheel_loads)
    e = _errors(integrator, 5e-4)
    ratios = e[:-1] / e[1:]
    # ±10 %: the O((ω dt)²) ≈ 4 % correction to the leading term, with margin
    assert ratios == pytest.approx(_expected_ratios(order), rel=0.10)
    assert e[-1] > 1e-12  # above round-off: the ratios are meaningful


def test_modal_convergence_of_static_midspan_deflection():
    span, EI, mass, load = 20.0, 1e10, 1e4, 1e5
    exact = load * span**3 / (48 * EI)
    errors = []
    for n in range(1, 31):
        beam = EulerBernoulliBeam(span, EI, mass, n_modes=n)
        xi = beam.static_modal_coordinates([span / 2], [0.0], [-load])
        w = float(xi @ beam.mode_shapes([span / 2])[0])
        series = -exact * 96 / np.pi**4 * sum(1 / j**4 for j in range(1, n + 1, 2))
        assert w == pytest.approx(series, rel=1e-12)
        errors.append(abs(w + exact) / exact)
    errors = np.array(errors)
    assert np.all(np.diff(errors) <= 1e-15)  # never grows (even modes add nothing at midspan)
    assert np.all(np.diff(errors)[1::2] < 0)  # strictly falls when an odd mode is added (n → n+1 odd)
    assert errors[19] < 2e-3  # 20 modes (the series gives 2.1e-5)
    assert errors[0] == pytest.approx(1 - 96 / np.pi**4, rel=1e-12)  # 1.45 % with one mode


def test_user_time_step_above_rk4_limit_is_refused():
    beam = paper_beam(16.76, "II")
    crossing = Crossing(beam, hs20_44(), speed=20.0, approach=5.0, integrator="rk4")
    limit = rk4_stability_limit(crossing)
    # the highest bridge mode alone bounds it: |ω_max dt| ≤ 2√2 on the imaginary axis (the light
    # 2 % damping moves the eigenvalue slightly left, where the region is a little wider)
    assert limit == pytest.approx(2 * np.sqrt(2) / beam.omega.max(), rel=0.05)
    with pytest.raises(UnstableTimeStepError):
        simulate(Crossing(beam, hs20_44(), speed=20.0, approach=5.0, dt=1.05 * limit, integrator="rk4"))
    # below the limit RK4 runs and stays bounded; Newmark and exact modal stepping accept any step
    ok = simulate(Crossing(beam, hs20_44(), speed=20.0, approach=5.0, dt=0.95 * limit, free_vibration=0.1,
                           integrator="rk4"))
    assert np.all(np.isfinite(ok.xi)) and np.abs(ok.displacement()).max() < 0.01
    for integrator in ("newmark", "exact"):
        big = simulate(Crossing(beam, hs20_44(), speed=20.0, approach=5.0, dt=1.05 * limit, integrator=integrator,
                                free_vibration=0.1))
        assert np.all(np.isfinite(big.xi)) and np.abs(big.displacement()).max() < 0.01
