"""A rigid disk starts loaded with the rate its envelope has as the run begins, in every integrator.

The rigid disk's contact height is the envelope of the road under the wheel, taken over candidate
points 1 cm apart (``vbikit.contact.RigidDiskTire``); the tire dashpot reads the rate of the
candidate in contact, v times the slope of the road cell it moves into, clamped to the circle's
slopes g'(ξ) = ξ/√(R² − ξ²) over the candidate's cell [ξ_p − Δξ/2, ξ_p + Δξ/2] (``_envelope``).
A default crossing starts its wheels on stations, where that rate is discontinuous: the static start
(at rest on the road, the dashpot loaded by the road rate) must read the side the run then moves
into, as RK4 does (the slope of the cell ahead) and as the implicit integrators do for every other
tire (``secant_ends`` with a negative span).  Rigid disks were an exception that kept the centred
secant there: on a station it averages the two cells' slopes, so the default integrator started the
vehicle elsewhere than RK4 and converged to another answer (the convergence study's class D rigid
disk, docs/verification.md: IM 0.455441–0.455444 at a 60–30 µs step against RK4's 0.455310–0.455322;
read ahead 0.455325–0.455328, 0.455326 at 15 µs).

The reference is a hand calculation.  The wheel starts on the top of a symmetric ridge of slopes
±SLOPE (steeper than the circle over one cell); the candidate in contact is the one at the ridge
(ξ = 0: the others lie lower by SLOPE·|ξ| + g(ξ)), at the road's height 0.  The cell it moves into
falls at SLOPE, clamped to the circle's slope at the cell's rear end: the rate is
ṙ = v g'(−Δξ/2) = −v (Δξ/2)/√(R² − (Δξ/2)²) (either direction: the mirror), and the tire force
k (r − z_a) + c ṙ carries the car's weight, so both masses sit c ṙ/k from where they sit on a smooth
road (r = ṙ = 0).  The centred secant reads the ridge's mean slope, 0: no offset."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.contact.tires import RigidDiskTire
from vbikit.road import RoadProfile
from vbikit.solve import simulate
from vbikit.solve.crossing import Crossing, VehicleMotion
from vbikit.vehicle import quarter_car

SPAN, APPROACH, SPEED = 8.0, 2.0, 25.0  #: [m], [m], [m/s]
SLOPE = 0.05  #: the ridge's slopes either side of its top, ≫ the circle's 0.01 over a cell
C_TIRE, K_TIRE = 3e3, 1.75e6  #: quarter_car's tire damping [N s/m] and stiffness [N/m] (its defaults)
TIRE = RigidDiskTire()  #: R = 0.5 m, Δξ = 0.01 m


def _road(top: float) -> RoadProfile:
    """Flat but for a ridge 2 m wide with its top at x = ``top`` (on a station); stations 1 cm apart."""
    x = np.round(np.arange(-6.0, 14.0 + 1e-9, 0.01), 10)
    return RoadProfile(x, -SLOPE * np.minimum(np.abs(x - top), 1.0), "ridge")


def _crossing(road: RoadProfile | None, direction: str, integrator: str) -> Crossing:
    beam = EulerBernoulliBeam(SPAN, 2e9, 4e3, 0.02, n_modes=4)
    return Crossing(beam, vehicles=(VehicleMotion(quarter_car(), SPEED, direction=direction, tire=TIRE),), road=road,
                    speed=SPEED, approach=APPROACH, free_vibration=0.05, integrator=integrator, dt=2e-4)


START = {"+x": -APPROACH, "-x": SPAN + APPROACH}  #: [m] the wheel's start: the ridge's top


@pytest.mark.parametrize("direction", ["+x", "-x"])
@pytest.mark.parametrize("integrator", ["exact", "newmark", "rk4"])
def test_rigid_disk_starts_with_its_envelopes_rate_ahead(direction, integrator):
    rough = simulate(_crossing(_road(START[direction]), direction, integrator))
    smooth = simulate(_crossing(None, direction, integrator))
    assert rough.front_position[0, 0] == START[direction]
    half = TIRE.spacing / 2
    rate = -SPEED * half / np.sqrt(TIRE.radius**2 - half**2)  # by hand: −0.250 m/s
    lift = C_TIRE * rate / K_TIRE  # −0.43 mm (the centred secant: 0)
    np.testing.assert_allclose(rough.q[0] - smooth.q[0], [lift, lift], rtol=1e-9, atol=1e-12)


def test_default_converges_to_rk4_from_a_ridge_start():
    """The default integrator's histories at a fine step within 5e-4 of RK4's swing (body and axle) and
    of the deck's peak; measured 2026-12-05 at dt = 100 µs: 1.2e-5 and 5.8e-5 of the body's and axle's
    swing and 2.2e-5 of the deck's peak, halving with the step (the envelope's switches resolved to
    the step: first order in both integrators); with the centred start the same run differed by
    4.9e-3, 6.7e-3 and 1.9e-3, the same at 50 µs: another start, not a step error."""
    road = _road(START["+x"])
    exact, rk4 = (simulate(replace(_crossing(road, "+x", integrator), dt=1e-4)) for integrator in ("exact", "rk4"))
    swing = np.abs(rk4.q - rk4.q[0]).max(axis=0)
    assert np.all(np.abs(exact.q - rk4.q).max(axis=0) <= 5e-4 * swing)
    assert np.abs(exact.displacement() - rk4.displacement()).max() <= 5e-4 * np.abs(rk4.displacement()).max()
