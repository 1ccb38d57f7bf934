"""The default integrator (exact modal stepping) against a converged reference, at its automatic step.

Reference: classical RK4 at its own automatic step (≤ 1/5 of the highest mode's period, ≤ one
road sample per step), converged on these cases to ≈ 1e-4 in IM (RK4 at a quarter of its step
changes the IMs below by at most 1.0e-4; docs/scripts/convergence_numbers.py, whose stored numbers
docs/verification.md quotes).  The issue's requirement: IM within 1e-3 of the converged value at the
automatic step.  Measured differences are in the comments.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.contact import RigidDiskTire
from vbikit.scenario import build, load_scenario, parse_scenario
from vbikit.solve import Crossing, simulate

TOLERANCE = 1e-3


def _im(built, **crossing):
    res = simulate(dataclasses.replace(built.crossing, **crossing))
    return point_response(res, built.response_x, built.response_y).displacement_impact.impact_factor, res


def _scenario(bridge, vehicle, tire, road_class, depression=False, girder=None):
    d = {"bridge": {"model": bridge, "n_modes": 20}, "vehicle": {"model": vehicle}, "tire": tire,
         "road": {"class": road_class, "seed": 1}, "crossing": {"speed_kmh": 75}}
    if depression:
        d["road"]["defects"] = [{"kind": "depression"}]
    if girder:
        d["response"] = {"girder": girder}
    return build(parse_scenario(d))


def _check(built, tolerance=TOLERANCE):
    assert built.crossing.integrator == "exact"  # the default
    im, res = _im(built)
    im_ref, ref = _im(built, integrator="rk4")
    assert res.n_steps < ref.n_steps
    assert abs(im - im_ref) <= tolerance, (im, im_ref)
    return im - im_ref, res.n_steps, ref.n_steps


def test_yang_yau_at_the_automatic_step():
    # measured: 669 steps (100 per period of mode 1) against RK4's 3345, ΔIM = −5.6e-6
    _check(build(load_scenario("examples/verification/yang_yau_sprung_mass.toml")))


def test_hs20_on_the_16_76_m_beam_class_c_multipoint():
    # measured: 1914 steps (2 cm of road per step) against RK4's 26,840, ΔIM = −4.9e-5
    _check(_scenario("paper-bridge-2-beam", "hs20-44", {"model": "multipoint", "n_points": 6}, "C"))


TIRES = {"point": {"model": "point"}, "multipoint": {"model": "multipoint", "n_points": 6},
         "disk": {"model": "disk"}, "rigid-disk": {"model": "rigid-disk"}}


@pytest.mark.parametrize("road_class", ["C", pytest.param("D", marks=pytest.mark.slow)])
@pytest.mark.parametrize("tire", list(TIRES))
def test_hs20_on_paper_bridge_2_girder_4_with_the_depression(tire, road_class):
    # measured ΔIM (1908–1923 steps against RK4's 3815–3845): C −1.1e-4 / −9.0e-5 / −6.0e-5 / −2.2e-4,
    # D +1.3e-5 / −5.9e-5 / −2.0e-5 / −4.0e-4 (point / multipoint / disk / rigid disk); the rigid disk
    # since it starts loaded with the rate ahead (docs/figures/convergence-numbers.json): C −2.7e-4, D −1.8e-4
    _check(_scenario("paper-bridge-2", "hs20-44", TIRES[tire], road_class, depression=True, girder=4))


@pytest.mark.slow
def test_dump_truck_on_cypress_bayou():
    # measured: 1861 steps against 3721, ΔIM = −9.5e-5
    _check(_scenario("cypress-bayou", "dump-truck", {"model": "multipoint", "n_points": 6}, "C"))


def test_integrators_agree_for_the_rigid_disk_on_a_bump():
    # the 80 mm bump of the loss-of-contact tests, a light quarter car at 10 m/s; every
    # integrator through the same contact law (envelope and its clamped rate included), at the
    # same small step: they must agree as closely as they do for the point tire
    from test_tire_models import BUMP_ROAD, LIGHT_CAR  # noqa: PLC0415 (shared case)

    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.contact import PointTire

    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    spread = {}
    for tire in (PointTire(), RigidDiskTire()):
        runs = [simulate(Crossing(beam, LIGHT_CAR, tire=tire, road=BUMP_ROAD, speed=10.0, approach=6.0,
                                  free_vibration=0.0, dt=2e-5, integrator=i)) for i in ("rk4", "newmark", "exact")]
        z = [r.q[:, 1] for r in runs]  # the axle
        peak = np.abs(z[0] - z[0][0]).max()
        spread[tire.name] = max(np.abs(a - z[0]).max() for a in z[1:]) / peak
    # measured: largest axle-history difference from RK4, of the axle's excursion: point 2.1e-4,
    # multipoint 2.7e-4, disk 8.8e-4, rigid disk 5.8e-5 (Newmark and exact alike)
    assert spread["rigid-disk"] <= 2.0 * spread["point"]


def test_the_vehicle_term_of_the_step_resolves_a_stiff_hopping_vehicle():
    """The automatic step's vehicle term (T_vehicle,min / 20, ``EXACT_STEPS_PER_VEHICLE_PERIOD``)
    carries accuracy where it binds: a 318 Hz sprung mass (10 kg on 4e7 N/m) hopping on a 1 mm sine
    road (2.1 rad/m) over the 16.76 m beam at 22 m/s.  Reference: RK4 (an independent integrator)
    at 1/8 of its automatic step; its change from 1/4 to 1/8 is 8e-4 of the peak wheel force.
    Measured 2026-12-06: at the automatic step (0.157 ms, set by this term) the exact integrator's
    peak wheel force is 1.0 % below the reference and the mid-span peak displacement 0.63 %; with
    10 steps a period the peak wheel force is 38 % off, without the term (the road's 0.909 ms) 11×.
    Tolerances: three times the measured errors."""
    from vbikit.bridge import paper_beam
    from vbikit.road import RoadProfile
    from vbikit.solve.timestep import EXACT_STEPS_PER_VEHICLE_PERIOD, accuracy_time_step, implicit_time_step
    from vbikit.vehicle import sprung_mass

    beam = paper_beam(16.76, "II", n_modes=3)
    x = np.arange(-60.0, 80.0, 0.01)
    road = RoadProfile(x, 1e-3 * np.sin(2.1 * x), "sine")
    c = Crossing(beam, sprung_mass(mass=10.0, stiffness=4e7), road=road, speed=22.0)
    f_vehicle = np.sqrt(4e7 / 10.0) / (2 * np.pi)
    assert implicit_time_step(c) == pytest.approx(1.0 / f_vehicle / EXACT_STEPS_PER_VEHICLE_PERIOD, rel=1e-9)  # it binds
    exact = simulate(c)
    ref = simulate(dataclasses.replace(c, integrator="rk4", dt=accuracy_time_step(c) / 8))
    np.testing.assert_allclose(exact.wheel_forces.max(), ref.wheel_forces.max(), rtol=0.03)
    mid = beam.span / 2
    np.testing.assert_allclose(np.abs(exact.displacement(mid)).max(), np.abs(ref.displacement(mid)).max(), rtol=0.02)
