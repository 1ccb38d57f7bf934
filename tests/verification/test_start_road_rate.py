"""The road rate at the run's start: the road ahead of each point only.

The implicit integrators read a tire dashpot's road rate at a step end as the road's secant over
the half steps around it (``vbikit.solve.kernels.road_point``).  At the run's start the point has
no road behind it: the static start and the kernels' first evaluation read the secant over the road
ahead only, the first half step's road, which is the limit from the start's side that RK4's cell
slope reads there.  With the centred secant a point starting on a station of a rough road (every
default crossing: 1 cm stations, whole-centimetre approaches) started from the mean of the two
cells' slopes, and the default integrator converged to another answer than RK4: on the paper's
Fig. 7 (Bridge 3, point tire, 105 km/h, class D, 2nd profile) IM 0.71222 against RK4's 0.71322 at
a 21 µs step for both (docs/verification.md, "The paper programme against RK4").

References here are independent of the integrator under study: slopes by hand on a V-shaped road,
and classical RK4 (which reads the cell's slope) on the same crossing."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road import RoadProfile
from vbikit.solve import simulate
from vbikit.solve.crossing import Crossing
from vbikit.vehicle import quarter_car

APPROACH = 2.0  #: the wheel starts at x = −APPROACH, on the V's kink
SPEED = 25.0  #: [m/s]
LEFT, RIGHT = -0.05, 0.03  #: the road's slopes behind and ahead of the kink


def _v_road() -> RoadProfile:
    """A road with a kink at x = −APPROACH (slope LEFT before it, RIGHT after it) and a gentle
    1 cm-station ripple elsewhere, stations 1 cm apart."""
    x = np.round(np.arange(-6.0, 14.0 + 1e-9, 0.01), 10)
    z = np.where(x < -APPROACH, LEFT * (x + APPROACH), RIGHT * (x + APPROACH))
    z = z - np.where(x > -APPROACH + 0.5, RIGHT * (x + APPROACH - 0.5), 0.0)  # level again 0.5 m on
    return RoadProfile(x, z, "V at the start")


def test_secant_rate_at_the_start_reads_the_road_ahead_by_hand():
    road = _v_road()
    x0, a_time = -APPROACH, 1e-3  # span [s]: a = 2.5 cm of road either side
    # centred: the mean of the two slopes over ±a (both within 0.5 m of straight road)
    assert road.secant_rate(x0, SPEED, a_time) == pytest.approx(SPEED * (LEFT + RIGHT) / 2, rel=1e-9)
    # the start, driving +x: the road ahead is the right slope; driving −x: the left one
    assert road.secant_rate(x0, SPEED, -a_time) == pytest.approx(SPEED * RIGHT, rel=1e-9)
    assert road.secant_rate(x0, -SPEED, -a_time) == pytest.approx(-SPEED * LEFT, rel=1e-9)


def test_run_rates_read_ahead_at_the_first_step_end_only():
    # a point on the kink at three step ends (time along either axis): the start reads the slope ahead,
    # the later step ends (on the kink again, the same position) the centred secant; both by hand
    road, span = _v_road(), 1e-3
    x = np.full(3, -APPROACH)
    ahead, centred = SPEED * RIGHT, SPEED * (LEFT + RIGHT) / 2
    np.testing.assert_allclose(road.run_rates(x, SPEED, span), [ahead, centred, centred], rtol=1e-9)
    np.testing.assert_allclose(road.run_rates(np.stack([x, x]), SPEED, span, axis=1),
                               [[ahead, centred, centred]] * 2, rtol=1e-9)


def _crossing(integrator: str, dt: float) -> Crossing:
    beam = EulerBernoulliBeam(8.0, 2e9, 4e3, 0.02, n_modes=4)
    return Crossing(beam, quarter_car(), road=_v_road(), speed=SPEED, approach=APPROACH, free_vibration=0.1,
                    integrator=integrator, dt=dt)


@pytest.mark.parametrize("integrator", ["exact", "newmark"])
def test_implicit_start_is_rk4s_start_on_a_kink(integrator):
    """The static start (rest on the road, the dashpot loaded by the road rate) of an implicit
    integrator equals RK4's, whose rate is the slope of the cell ahead; with the centred secant the
    tire's deflection differed by c·v·(RIGHT − LEFT)/2 / k = 1.7 mm (c = 3 kN s/m, k = 1.75 MN/m)."""
    dt = 2e-4
    implicit, rk4 = simulate(_crossing(integrator, dt)), simulate(_crossing("rk4", dt))
    assert np.abs(implicit.q[0] - rk4.q[0]).max() <= 1e-12
    centred = 3e3 * SPEED * (RIGHT - LEFT) / 2 / 1.75e6  # the deflection the centred secant would add
    assert centred > 1e-3  # (what this test would see with the centred start)
    assert implicit.wheel_forces[0] == pytest.approx(rk4.wheel_forces[0], rel=1e-12)
    assert np.abs(implicit.q_ddot[0]).max() <= 1e-9  # and at rest in the kernel's own reading


def test_default_converges_to_rk4_on_a_kink_start():
    """The states at a fine step: the default integrator's vehicle and deck histories within 1e-3 and
    1e-4 of RK4's (measured 2026-12-05 at dt = 50 µs: 1.8e-5 of the body's and 2.4e-6 of the axle's
    swing, 2.2e-6 of the deck's peak, halving with the step; with the centred start the same run
    differed by 9.3e-2, 7.0e-2 and 8.8e-3, whatever the step: another answer, not a step error).
    (Wheel forces are not compared sample by sample: at a sample exactly on the road's second kink
    the rate is discontinuous and the two readings differ by c·v·Δslope/2 at that sample alone.)"""
    dt = 5e-5
    exact, rk4 = simulate(_crossing("exact", dt)), simulate(_crossing("rk4", dt))
    swing = np.abs(rk4.q - rk4.q[0]).max(axis=0)
    assert np.all(np.abs(exact.q - rk4.q).max(axis=0) <= 1e-3 * swing)
    assert np.abs(exact.displacement() - rk4.displacement()).max() <= 1e-4 * np.abs(rk4.displacement()).max()
