"""Unit tests for time-step selection (vbikit.solve.timestep) and Crossing validation."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from vbikit.bridge import EulerBernoulliBeam, paper_beam
from vbikit.contact import MultiPointTire
from vbikit.road import RoadProfile, RoadPSD, random_profile
from vbikit.solve import (
    Crossing,
    UnstableTimeStepError,
    accuracy_time_step,
    choose_time_step,
    rk4_stability_limit,
    simulate,
)
from vbikit.vehicle import hs20_44, moving_force, sprung_mass

SPEED = 75 / 3.6


@pytest.fixture(scope="module")
def road():
    return random_profile(RoadPSD.iso("C"), seed=1)


def _rk4_growth(z):
    return np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


def test_auto_dt_resolves_highest_bridge_mode(road):
    beam = paper_beam(16.76, "II", n_modes=20)
    c = Crossing(beam, hs20_44(), MultiPointTire(n_points=6), road, speed=SPEED, integrator="rk4")
    dt = choose_time_step(c)
    t_min = 2 * np.pi / beam.omega.max()
    assert dt <= t_min / 5 * (1 + 1e-12)
    assert dt <= road.spacing / SPEED
    assert dt <= 0.9 * rk4_stability_limit(c)
    assert dt == pytest.approx(t_min / 5, rel=1e-12)  # the bridge rule governs here


def test_auto_dt_limited_by_road_spacing(road):
    beam = paper_beam(16.76, "II", n_modes=3)  # f3 ≈ 66 Hz: T/5 ≈ 3 ms, longer than 0.01 m / v ≈ 0.48 ms
    c = Crossing(beam, hs20_44(), road=road, speed=SPEED, integrator="rk4")
    dt = choose_time_step(c)
    assert dt <= 2 * np.pi / beam.omega.max() / 5
    assert dt == pytest.approx(road.spacing / SPEED, rel=1e-12)
    assert simulate(c).dt == dt


def test_auto_dt_uses_highest_speed_when_accelerating(road):
    beam = paper_beam(16.76, "II", n_modes=3)
    c = Crossing(beam, hs20_44(), road=road, speed=15.0, acceleration=2.0)
    v_max = float(c.travel_speed(c.duration)[0, 0])
    assert v_max > 15.0
    assert accuracy_time_step(c) <= road.spacing / v_max * (1 + 1e-12)


def test_auto_dt_resolves_vehicle_modes():
    beam = paper_beam(16.76, "II", n_modes=2)
    v = sprung_mass(mass=100.0, stiffness=4e6)  # 31.8 Hz
    c = Crossing(beam, v, speed=SPEED)
    assert accuracy_time_step(c) <= 1.0 / v.natural_frequencies().max() / 20 * (1 + 1e-12)


def test_rk4_limit_undamped_beam_under_moving_force():
    # bare beam + moving force: eigenvalues ±iωₙ, on the imaginary axis; RK4 is stable there for
    # |ω dt| ≤ 2√2 ≈ 2.828 (the real-axis limit 2.785 applies to real negative eigenvalues, not here)
    beam = paper_beam(16.76, "II", n_modes=20, damping_ratio=0.0)
    c = Crossing(beam, moving_force(), speed=SPEED)
    limit = rk4_stability_limit(c) * beam.omega.max()
    assert limit == pytest.approx(2 * np.sqrt(2), rel=0.01)
    assert abs(limit - 2.785) / 2.785 > 0.01  # and distinguishably not the real-axis value


def test_rk4_limit_damped_beam_under_moving_force():
    zeta = 0.02
    beam = paper_beam(16.76, "II", n_modes=20, damping_ratio=zeta)
    c = Crossing(beam, moving_force(), speed=SPEED)
    w = beam.omega.max()
    lam = w * (-zeta + 1j * np.sqrt(1 - zeta**2))  # least stable eigenvalue: the highest mode
    expected = brentq(lambda dt: _rk4_growth(lam * dt) - 1.0, 2.0 / w, 3.5 / w, xtol=1e-16)
    assert rk4_stability_limit(c) == pytest.approx(expected, rel=0.01)
    assert rk4_stability_limit(c) * w > 2 * np.sqrt(2)  # damping enlarges the limit slightly


def test_user_dt_above_rk4_limit_is_refused():
    beam = paper_beam(16.76, "II", n_modes=20)
    limit = rk4_stability_limit(Crossing(beam, moving_force(), speed=SPEED))
    with pytest.raises(UnstableTimeStepError, match="stability limit"):
        choose_time_step(Crossing(beam, moving_force(), speed=SPEED, dt=1.1 * limit, integrator="rk4"))
    assert choose_time_step(Crossing(beam, moving_force(), speed=SPEED, dt=0.5 * limit, integrator="rk4")) == 0.5 * limit
    # Newmark and exact modal stepping take any step
    for integrator in ("newmark", "exact"):
        crossing = Crossing(beam, moving_force(), speed=SPEED, dt=1.1 * limit, integrator=integrator)
        assert choose_time_step(crossing) == 1.1 * limit


def test_braking_to_a_stop_before_leaving_raises(road):
    beam = paper_beam(16.76, "II", n_modes=5)
    # 10 m/s at −2 m/s² stops after 25 m; the last axle needs 10 + 16.76 + 8.53 m
    c = Crossing(beam, hs20_44(), speed=10.0, acceleration=-2.0)
    with pytest.raises(ValueError, match="stops"):
        c.exit_time()
    with pytest.raises(ValueError, match="stops"):
        simulate(c)
    with pytest.raises(ValueError, match="stops"):
        Crossing(beam, hs20_44(), road=road, speed=10.0, acceleration=-2.0)  # road coverage check runs it


def test_gentle_braking_is_accepted():
    beam = paper_beam(16.76, "II", n_modes=5)
    c = Crossing(beam, hs20_44(), speed=20.0, acceleration=-2.0)  # stops after 100 m
    distance = c.approach + beam.span + hs20_44().length
    t = c.exit_time()
    assert float(c.front_positions(t)[0, 0]) + c.approach == pytest.approx(distance)
    assert float(c.travel_speed(t)[0, 0]) > 0.0


BEAM = EulerBernoulliBeam(span=20.0, EI=1e10, mass_per_length=5000.0, n_modes=3)


@pytest.mark.parametrize("speed", [0.0, -5.0, np.nan, np.inf])
def test_crossing_rejects_bad_speed(speed):
    with pytest.raises(ValueError, match="speed"):
        Crossing(BEAM, moving_force(), speed=speed)


@pytest.mark.parametrize("dt", [0.0, -1e-4, np.nan])
def test_crossing_rejects_bad_dt(dt):
    with pytest.raises(ValueError, match="dt"):
        Crossing(BEAM, moving_force(), speed=10.0, dt=dt)


@pytest.mark.parametrize("integrator", ["euler", "RK4", ""])
def test_crossing_rejects_unknown_integrator(integrator):
    with pytest.raises(ValueError, match="integrator"):
        Crossing(BEAM, moving_force(), speed=10.0, integrator=integrator)


def test_crossing_rejects_other_bad_inputs():
    with pytest.raises(ValueError, match="approach"):
        Crossing(BEAM, moving_force(), approach=-1.0)
    with pytest.raises(ValueError, match="free_vibration"):
        Crossing(BEAM, moving_force(), free_vibration=-0.1)
    with pytest.raises(ValueError, match="acceleration"):
        Crossing(BEAM, moving_force(), acceleration=np.nan)
    short = random_profile(RoadPSD.iso("A"), seed=1, length=20.0, x_start=-5.0)
    with pytest.raises(ValueError, match="covers"):
        Crossing(BEAM, hs20_44(), road=short, approach=10.0)


def test_with_road_checks_like_the_constructor_and_keeps_the_contact_points():
    """Crossing.with_road (the batch path's cheap copy) refuses a road that does not cover the
    crossing, or a right line without a left one, exactly as the constructor does."""
    good = random_profile(RoadPSD.iso("A"), seed=1)
    short = random_profile(RoadPSD.iso("A"), seed=1, length=20.0, x_start=-5.0)
    base = Crossing(BEAM, hs20_44(), road=good, approach=10.0)
    contact = base.contact
    other = base.with_road(random_profile(RoadPSD.iso("B"), seed=2))
    assert other.contact is contact and other.road is not base.road and base.road is good
    with pytest.raises(ValueError, match="covers"):
        base.with_road(short)
    with pytest.raises(ValueError, match="needs a road profile for the left line"):
        base.with_road(None, good)


@pytest.mark.parametrize("spacing, speed", [(0.01, 22.0), (0.2, 8.0), (0.5, 3.0)])
def test_automatic_steps_equal_the_eigenvalue_rule_whether_or_not_the_vehicle_binds(spacing, speed):
    """``implicit_time_step`` and ``accuracy_time_step`` solve the vehicle's eigenvalues only when its
    period can bind (``_with_vehicle_periods``); the steps must be those of the rule written out
    here with scipy.linalg.eigh of (K + Σ k_w r_w r_wᵀ, M) on every crossing, bit for bit: two trucks
    (their periods do not bind on a fine road) and a 318 Hz sprung mass (its period binds)."""
    from scipy.linalg import eigh

    from vbikit.solve.timestep import EXACT_ROAD_FEATURES_PER_STEP, EXACT_ROAD_LENGTH_PER_STEP, EXACT_STEPS_PER_SPAN
    from vbikit.solve.timestep import EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD, EXACT_STEPS_PER_VEHICLE_PERIOD
    from vbikit.solve.timestep import implicit_time_step
    from vbikit.vehicle.axles import axle_truck

    beam = paper_beam(16.76, "II", n_modes=3)
    x = np.arange(-60.0, 80.0, spacing)
    road = RoadProfile(x, 1e-3 * np.sin(2.1 * x), "test")  # sampled every ``spacing``
    binds = []
    for vehicle in (axle_truck([60e3, 110e3], [4.2]), hs20_44(), sprung_mass(mass=10.0, stiffness=4e7)):  # 318 Hz
        c = Crossing(beam, vehicle, road=road, speed=speed)
        rows = np.array([w.row for w in vehicle.wheels])
        k_w = np.array([w.stiffness for w in vehicle.wheels])
        f_max = np.sqrt(eigh(vehicle.stiffness + rows.T @ (k_w[:, None] * rows), vehicle.mass, eigvals_only=True).max()) / (2 * np.pi)
        v = c.max_speed
        exact = [beam.span / (EXACT_STEPS_PER_SPAN * v), 2 * np.pi / beam.omega.min() / EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD["effects"],
                 min(EXACT_ROAD_LENGTH_PER_STEP, EXACT_ROAD_FEATURES_PER_STEP * road.spacing) / v]
        accurate = [2 * np.pi / beam.omega.max() / 5.0, beam.span / (100.0 * v), road.spacing / v]
        fresh = Crossing(beam, vehicle.__class__(**{f: getattr(vehicle, f) for f in vehicle.__dataclass_fields__}),
                         road=road, speed=speed)  # its frequencies not yet solved
        assert implicit_time_step(fresh) == min(exact + [1.0 / f_max / EXACT_STEPS_PER_VEHICLE_PERIOD])
        assert accuracy_time_step(c) == min(accurate + [1.0 / f_max / 20.0])
        binds.append(1.0 / f_max / EXACT_STEPS_PER_VEHICLE_PERIOD < min(exact))
    assert binds[2]  # the 318 Hz mass binds
    assert not any(binds[:2]) or spacing > 0.01  # the trucks do not on the fine road


def test_exact_step_takes_3_cm_of_a_generated_road_up_to_class_c_and_two_features_of_a_measured_one():
    """The exact integrator's road terms (vbikit.solve.timestep.exact_road_per_step): 3 cm of a
    generated random road up to ISO 8608 class C (1 cm stations that sample a band without wavelengths
    below 1/n_max), 2 cm of class D where tires can leave the road; two stations of the same samples given as arrays or carrying a
    defect (every station may be an edge), and 1/8 of the shortest wavelength of a finer band."""
    import dataclasses as dc

    from vbikit.road.defects import Defect, with_defects
    from vbikit.road.profile import RoadProfile
    from vbikit.road.psd import RoadPSD, random_profile
    from vbikit.solve.timestep import exact_road_per_step

    def road(cls, **band):
        return random_profile(RoadPSD.iso(cls, **band), 3, length=200.0, window=(0.0, 50.0))

    for cls, length in (("A", 0.03), ("C", 0.03), ("D", 0.02), ("H", 0.02)):
        assert road(cls).band_limited and exact_road_per_step(road(cls)) == pytest.approx(length), cls
        # tires that cannot leave the road (linear springs that may pull): no wheel hop, 3 cm on any class
        assert exact_road_per_step(road(cls), loss_of_contact=False) == pytest.approx(0.03), cls
    upper_c = dc.replace(RoadPSD.iso("C"), phi0=1.99 * RoadPSD.iso("C").phi0)  # just inside class C (limit 2x)
    assert exact_road_per_step(random_profile(upper_c, 3, length=200.0, window=(0.0, 50.0))) == pytest.approx(0.03)
    lower_d = dc.replace(RoadPSD.iso("C"), phi0=2.01 * RoadPSD.iso("C").phi0)  # just inside class D
    assert exact_road_per_step(random_profile(lower_d, 3, length=200.0, window=(0.0, 50.0))) == pytest.approx(0.02)
    c = road("C")
    as_arrays = RoadProfile(c.x, c.z, "the same samples")
    assert not as_arrays.band_limited and exact_road_per_step(as_arrays) == pytest.approx(0.02)
    half_cm = RoadProfile(c.x[::1] * 0.5, c.z, "stations 5 mm apart")
    assert exact_road_per_step(half_cm) == pytest.approx(0.01)
    bumped = with_defects(c, [Defect.of_kind("bump", 10.0)])
    assert not bumped.band_limited and exact_road_per_step(bumped) <= 0.02
    assert exact_road_per_step(road("C", n_max=10.0)) == pytest.approx(0.1 / 8)
