# Lift-off as a complementarity condition (exact modal integrator's active-set contact solve).
#
# A quarter car drives off a 5 cm drop in the road before the bridge.  The tire (point contact,
# stiffness k_t) is compressed by (M + m) g / k_t = 2.2 cm at rest, less than the drop, so the
# wheel leaves the road.  In flight no contact force acts and the 2-DOF vehicle moves in closed
# form (no vbikit code): its centre of mass falls freely, z_c(t) = z_c0 + ż_c0 t − g t²/2, and
# the suspension's relative coordinate u = z_body − z_axle oscillates undamped at
# ω = √(k_s (M + m) / (M m)) about its unstretched value u = 0:
#   u(t) = u0 cos ωt + (u̇0/ω) sin ωt,   z_axle = z_c − M u / (M + m).
# The wheel lands when the unstretched tire touches the lower road, z_axle = 0 (brentq on the
# closed form).  The closed form starts from vbikit's state at the first step of the flight, so
# the comparison is of the flight and the landing only (not of the take-off's time grid).
from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road import RoadProfile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import GRAVITY, quarter_car

M_BODY, M_AXLE, K_SUSP, K_TIRE = 10_000.0, 1_000.0, 400e3, 5e6
DROP, V, DT = 0.05, 20.0, 2e-5
EDGE = -5.0 - 0.5 * V * DT  # the drop half a step before a step time: the take-off impulse is exact


def _drop_road() -> RoadProfile:
    x = np.array([-40.0, EDGE, EDGE + 1e-9, 200.0])
    return RoadProfile(x, np.array([DROP, DROP, 0.0, 0.0]), "5 cm drop", resolution=0.02)


@pytest.fixture(scope="module")
def flight():
    car = quarter_car(M_BODY, M_AXLE, K_SUSP, 0.0, K_TIRE, 0.0)
    beam = EulerBernoulliBeam(20.0, 4.865e10, 18_358.0, 0.02, n_modes=4)
    result = simulate(Crossing(beam, car, road=_drop_road(), speed=V, approach=10.0, dt=DT))
    return result


def _first_flight(flight) -> tuple[int, int]:
    """First and last step of the first flight (the undamped tire bounces again later)."""
    force = flight.wheel_forces[:, 0]
    first = int(np.flatnonzero(force == 0.0)[0])
    last = first + int(np.flatnonzero(force[first:] > 0.0)[0]) - 1
    return first, last


def test_takes_off_at_the_edge(flight):
    first, last = _first_flight(flight)
    assert last - first > 100  # it does fly
    # leaves the road at the edge (x = −5 m, 0.25 s after the start at x = −10 m)
    assert flight.time[first] == pytest.approx(0.25, abs=DT)


def _closed_form(flight):
    """z_axle(t) of the free flight from vbikit's state at its first airborne step."""
    i0, _ = _first_flight(flight)
    names = list(flight.crossing.vehicle.dof_names)
    b, a = names.index("body_heave"), names.index("axle_heave")
    zb, za = flight.q[i0, b], flight.q[i0, a]
    vb, va = flight.q_dot[i0, b], flight.q_dot[i0, a]
    mt = M_BODY + M_AXLE
    zc0, vc0 = (M_BODY * zb + M_AXLE * za) / mt, (M_BODY * vb + M_AXLE * va) / mt
    u0, du0 = zb - za, vb - va
    omega = np.sqrt(K_SUSP * mt / (M_BODY * M_AXLE))
    t0 = flight.time[i0]

    def z_axle(t):
        s = t - t0
        zc = zc0 + vc0 * s - 0.5 * GRAVITY * s**2
        u = u0 * np.cos(omega * s) + du0 / omega * np.sin(omega * s)
        return zc - M_BODY * u / mt

    return i0, a, z_axle


def test_flight_against_closed_form(flight):
    i0, a, z_axle = _closed_form(flight)
    _, i1 = _first_flight(flight)
    t = flight.time[i0:i1 + 1]
    # the vehicle map carries the nominal tire and takes its force (taken back out in flight) linear
    # over each step: O(h²) per step, 4.6e-9 m after 1,158 steps of 2e-5 s
    np.testing.assert_allclose(flight.q[i0:i1 + 1, a], z_axle(t), rtol=0, atol=1e-8)


def test_landing_time(flight):
    i0, a, z_axle = _closed_form(flight)
    _, i1 = _first_flight(flight)
    t_land = brentq(z_axle, flight.time[i1] - 10 * DT, flight.time[i1] + 10 * DT, xtol=1e-14)
    # vbikit's landing: the root of the axle's height (cubic Hermite in its positions and
    # velocities) between the last airborne step and the first step in contact
    seg = slice(i1, i1 + 2)
    spline = CubicHermiteSpline(flight.time[seg], flight.q[seg, a], flight.q_dot[seg, a])
    t_vbikit = brentq(spline, flight.time[i1], flight.time[i1 + 1], xtol=1e-14)
    assert t_vbikit == pytest.approx(t_land, abs=1e-6)
    assert flight.wheel_forces[i1 + 1, 0] > 0.0  # and it presses once landed
