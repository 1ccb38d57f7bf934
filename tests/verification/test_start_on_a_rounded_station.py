"""A point that starts on a road station reads the cell it moves into, whatever the rounding.

Stations are made as x0 + h·i and a wheel's start as its origin ± the travel: a wheel that starts a
whole number of stations from the road's origin (the default crossings: 1 cm stations,
whole-centimetre approaches and axle spacings) lies some 1e-14 m to one side of its station, and a
cell chosen by exact comparison (``vbikit.solve.kernels.contact.road_cell``) was then, on one side,
the cell behind the wheel.  RK4 reads the road rate as its cell's slope, so its static start loaded
the tire dashpot with the slope behind, while the implicit integrators read the road ahead over half
a step (``secant_ends``): the two started a c·v·Δslope/k apart and converged to different impact
factors.  On events 2 and 3 of ``benchmarks/bench_traffic.py``'s stream (a −x truck whose front
axle starts at 26.76 m, 1.1e-14 m past the station there; a +x truck with axles 6.56 m and 16.05 m
behind its front one, 5.7e-14 m and 4.6e-14 m short of theirs) RK4 at dt/32 gave IM 1.2e-4 and
1.45e-4 above the default integrator at dt/16; with the tolerance, 1.3e-6 and 2.2e-6
(``bench_rate_alignment.py --events 2 3``, docs/verification.md).

The reference is a hand calculation: at rest on the road with the dashpot loaded by the road rate
ṙ = dir·v·(the slope ahead), the quarter car's tire force k (r − z_a) + c ṙ carries the car's weight,
so both masses sit c·ṙ/k above where they sit on a smooth road (r = ṙ = 0)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road import RoadProfile
from vbikit.solve import simulate
from vbikit.solve.crossing import Crossing, VehicleMotion
from vbikit.vehicle import quarter_car

SPAN, APPROACH, SPEED = 8.0, 2.0, 25.0  #: [m], [m], [m/s]
LEFT, RIGHT = -0.05, 0.03  #: the road's slopes below and above the kink in x
C_TIRE, K_TIRE = 3e3, 1.75e6  #: quarter_car's tire damping [N s/m] and stiffness [N/m] (its defaults)
ROUNDING = 4e-14  #: [m] how far the kink's station lies from the wheel's start (≈ 20 ulp of 10 m)


def _road(kink: float, station: float) -> RoadProfile:
    """A road with a kink at x = ``kink`` (slope LEFT below it, RIGHT above it), stations 1 cm apart,
    the station of the kink moved to ``station`` (a rounding error away; the elevations as at the kink)."""
    x = np.round(np.arange(-6.0, 14.0 + 1e-9, 0.01), 10)
    z = np.where(x < kink, LEFT * (x - kink), RIGHT * (x - kink))
    k = int(np.argmin(np.abs(x - kink)))
    assert x[k] == kink
    x[k] = station
    return RoadProfile(x, z, "kink on a rounded station")


def _crossing(road: RoadProfile | None, direction: str, integrator: str) -> Crossing:
    beam = EulerBernoulliBeam(SPAN, 2e9, 4e3, 0.02, n_modes=4)
    return Crossing(beam, vehicles=(VehicleMotion(quarter_car(), SPEED, direction=direction),), road=road,
                    speed=SPEED, approach=APPROACH, free_vibration=0.05, integrator=integrator, dt=2e-4)


# +x: the wheel starts at −APPROACH, the station just ahead of it (the wheel in the cell below the
# kink by rounding); −x: at SPAN + APPROACH, the station just behind it in x (the wheel in the cell
# above).  The cell it moves into: above the kink driving +x (RIGHT), below it driving −x (LEFT).
CASES = {"+x": (-APPROACH, ROUNDING, SPEED * RIGHT), "-x": (SPAN + APPROACH, -ROUNDING, -SPEED * LEFT)}


@pytest.mark.parametrize("direction", ["+x", "-x"])
@pytest.mark.parametrize("integrator", ["rk4", "exact"])
def test_start_reads_the_cell_ahead_of_a_wheel_a_rounding_off_its_station(direction, integrator):
    kink, off, rate = CASES[direction]
    rough = simulate(_crossing(_road(kink, kink + off), direction, integrator))
    smooth = simulate(_crossing(None, direction, integrator))
    assert rough.front_position[0, 0] == kink  # the wheel starts on the kink's nominal station
    lift = C_TIRE * rate / K_TIRE  # by hand: 1.29 mm (+x), 2.14 mm (−x)
    behind = C_TIRE * SPEED * abs(RIGHT - LEFT) / K_TIRE  # what reading the cell behind changed: 3.4 mm
    assert behind > 3e-3
    np.testing.assert_allclose(rough.q[0] - smooth.q[0], [lift, lift], rtol=1e-9, atol=1e-12)

