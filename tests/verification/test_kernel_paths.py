# Paths of the kernels and models that the other verification tests leave out (found by the
# NUMBA_DISABLE_JIT coverage job, tests/verification/test_kernel_coverage.py): the implicit
# integrators with disk and rigid-disk tires and with loss of contact, the batch solver with a
# user step, parapets, the eigen solver's widening search for max_frequency, contact-length
# outputs.  The crossings are small (they also run, in pure Python, in the coverage job).
# References, none from vbikit output:
# * a vehicle at rest on flat ground carries its static wheel loads (statics), whatever the
#   tire model, and stays at rest;
# * a launched wheel carries no force, a tire never pulls (the contact law of docs/theory.md);
# * two integrators of the same equations agree to their discretisation error (repeated damped
#   landings of a rigid disk at a 1 ms step, the implicit step's full Newton, against RK4 at 0.1 ms);
# * lanes of a batch = the many-lane ``implicit`` kernel (another code path) = each road alone, lanes
#   that lift off too (as the batch with a user step: the single-crossing arithmetic);
# * a girder line with a parapet: the simply supported beam with EI + EI_p, m + m_p
#   (ωₙ = (nπ/L)²√(EI/m), Frýba 1972 ch. 1), the composite section worked out by hand;
# * the deformable disk's static patch 2√(2R d_s) (docs/model-data.md §3:
#   docs/tires.md); the multipoint patch = the contact length (paper Eq. 6).
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from vbikit.analysis import histories, point_response, summary
from vbikit.bridge import EulerBernoulliBeam, SlabOnGirderBridge
from vbikit.contact import DiskTire, MultiPointTire, PointTire, RigidDiskTire
from vbikit.road import Defect, RoadProfile, RoadPSD, random_profile, with_defects
from vbikit.solve import INTEGRATORS, Crossing, integrators, simulate
from vbikit.solve.batch import BatchSolver
from vbikit.vehicle import GRAVITY, quarter_car

from tests.unit.test_lean_lanes import _batch

TIRES = [PointTire(), MultiPointTire(4), DiskTire(spacing=0.02), RigidDiskTire(spacing=0.02)]
CAR = quarter_car(sprung_mass=400.0, unsprung_mass=50.0, suspension_stiffness=40e3, suspension_damping=2e3,
                  tire_stiffness=400e3, tire_damping=500.0)
SHORT = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, damping_ratio=0.02, n_modes=2)


@pytest.mark.parametrize("tire", TIRES, ids=lambda t: t.name)
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_at_rest_on_flat_ground_every_tire_and_integrator(integrator, tire):
    r = simulate(Crossing(SHORT, CAR, tire=tire, speed=5.0, approach=1.5, free_vibration=0.0, dt=5e-4,
                          integrator=integrator))
    before = r.front_position[:, 0] < -0.4  # the whole tire (|ξ| ≤ 0.3 m) still on the approach
    loads = CAR.static_wheel_loads()
    assert loads[0] == pytest.approx(450.0 * GRAVITY, rel=1e-12)  # statics: both masses on one tire
    np.testing.assert_allclose(r.wheel_forces[before, 0], loads[0], rtol=1e-9)  # measured ≤ 1e-12
    assert np.abs(r.q[before] - r.q[0]).max() <= 1e-12 and np.abs(r.q_dot[before]).max() <= 1e-12


BUMP_ROAD = with_defects(RoadProfile.flat(-20.0, 20.0), [Defect.of_kind("bump", start=-1.5, size=0.08)])


@pytest.fixture(scope="module")
def bump_runs():
    runs = {}
    for tire in TIRES:
        for integrator in INTEGRATORS:
            runs[tire.name, integrator] = simulate(Crossing(SHORT, CAR, tire=tire, road=BUMP_ROAD, speed=10.0,
                                                            approach=2.0, free_vibration=0.0, dt=2e-4,
                                                            integrator=integrator))
    return runs


@pytest.mark.parametrize("tire", TIRES, ids=lambda t: t.name)
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_loss_of_contact_every_tire_and_integrator(bump_runs, integrator, tire):
    """An 80 mm bump at 10 m/s launches the light quarter car's wheel: no force while airborne,
    never a pull, and the integrators agree on when and for how long."""
    r = bump_runs[tire.name, integrator]
    force = r.wheel_forces[:, 0]
    assert force.min() >= 0.0
    off = force == 0.0
    assert off.sum() * r.dt >= 0.010  # ≥ 10 ms airborne (≥ 27 ms for a point tire, see test_tire_models)
    ref = bump_runs[tire.name, "rk4"]
    ref_off = ref.wheel_forces[:, 0] == 0.0
    # the same bump, the same flight.  Measured Newmark vs RK4 at dt = 0.2 ms: first loss at the
    # same step (point, multipoint), 5 / 7 steps apart (disk, rigid disk: their patch leaves the
    # bump's edge gradually); airborne time within 2.2 %; peak force within 5.6 % (rigid disk,
    # whose envelope has kinks that the 2nd-order Newmark resolves less well)
    assert abs(int(np.argmax(off)) - int(np.argmax(ref_off))) <= 10
    assert off.sum() == pytest.approx(ref_off.sum(), rel=0.05)
    assert force.max() == pytest.approx(ref.wheel_forces[:, 0].max(), rel=0.1)


@pytest.mark.usefixtures("linear_wheel_loads")
def test_a_landing_the_lean_kernel_hands_over_equals_the_full_kernel():
    """The multipoint tire over the 80 mm bump at a 1 ms step (10 mm of road a step): at the landing a
    contact closes within the step's updates, so the lean kernel stops and ``implicit`` (its full
    Newton) finishes the step window (``integrators._finish_lane``); the histories equal a run of
    ``implicit`` alone within the tolerance's order.  (The kernel-coverage job reaches the full kernel's
    contact solve through this crossing: with the secant road rate the other small crossings here
    settle every landing in one evaluation.)"""

    crossing = Crossing(SHORT, CAR, tire=MultiPointTire(4), road=BUMP_ROAD, speed=10.0, approach=2.0,
                        free_vibration=0.0, dt=1e-3)
    before = dict(integrators.LEAN_COUNTS)
    handed = simulate(crossing)
    assert integrators.LEAN_COUNTS["fallback"] == before["fallback"] + 1
    with integrators.without_lean():
        full = simulate(crossing)
    assert np.any(full.wheel_forces[:, 0] == 0.0)  # the wheel does leave the road
    for name in ("xi", "q", "wheel_forces"):
        a, b = getattr(handed, name), getattr(full, name)
        assert np.abs(a - b).max() <= 1e-9 * np.abs(b).max()


#: six 5 cm cosine bumps, 0.3 m long, 0.3 m apart: the wheel hops off each
HOP_ROAD = with_defects(RoadProfile.flat(-20.0, 20.0), [Defect.of_kind("bump", start=s, size=0.05, length=0.3,
                                                                       shape="cosine")
                                                        for s in (-1.7, -1.1, -0.5, 0.1, 0.7, 1.3)])


def test_damped_rigid_disk_landings_settle_and_agree_with_rk4(caplog):
    """Repeated landings of a rigid disk (the acting point moves) with a critically damped tire
    (k = 5e5 N/m, c = 1e4 N s/m on a 50 kg wheel: ζ = c / 2√(k m) = 1.0) at a 1 ms step: the
    quasi-Newton updates do not settle some of these landings (the contact set changes within the
    step's updates), so the implicit step's full Newton does (``newton._full_newton``: 24 updates
    with NUMBA_DISABLE_JIT, measured 2026-12-05; the path the kernel-coverage job needs, the secant
    road rate settling the crossings above without it).  Reference: RK4 at 0.1 ms (another
    integrator, the same equations; RK4 at 0.01 ms differs from it by 2.2e-3 of the peak in the
    wheel's displacement, ≤ 1.1e-3 in the other measures here).  Measured: no step left
    unconverged; vehicle displacements within 4.1e-3 (body) and 3.0e-2 (wheel) of their peaks (the
    1 ms step holds a landing that the fine step resolves as micro-bounces: 8 landings against 13);
    airborne time 0.2740 s against 0.2737 s; wheel-force impulse within 2.6e-3; peak force 51.9 kN
    against 58.0 kN (the landing impacts, a step long)."""
    car = quarter_car(sprung_mass=400.0, unsprung_mass=50.0, suspension_stiffness=40e3, suspension_damping=2e3,
                      tire_stiffness=5e5, tire_damping=1e4)
    crossing = Crossing(SHORT, car, tire=RigidDiskTire(spacing=0.02), road=HOP_ROAD, speed=10.0, approach=2.0,
                        free_vibration=0.0, dt=1e-3)
    with caplog.at_level("WARNING", logger="vbikit"):
        coarse = simulate(crossing)
    assert not [r for r in caplog.records if "did not converge" in r.getMessage()]
    fine = simulate(replace(crossing, dt=1e-4, integrator="rk4"))
    every = 10
    ref_q = fine.q[::every][:coarse.q.shape[0]]
    assert ref_q.shape == coarse.q.shape
    err = np.abs(coarse.q - ref_q).max(axis=0) / np.abs(fine.q).max(axis=0)
    assert err[0] <= 1e-2 and err[1] <= 6e-2  # body, wheel (measured 4.1e-3, 3.0e-2)
    force, ref = coarse.wheel_forces[:, 0], fine.wheel_forces[:, 0]
    assert np.sum(force == 0.0) * coarse.dt >= 0.2  # heavy hop indeed: airborne > 0.2 s of 0.4 s
    assert np.sum(force == 0.0) * coarse.dt == pytest.approx(np.sum(ref == 0.0) * fine.dt, abs=3e-3)  # 3 steps
    assert force.sum() * coarse.dt == pytest.approx(ref.sum() * fine.dt, rel=1e-2)  # impulse (measured 2.6e-3)
    assert force.max() == pytest.approx(ref.max(), rel=0.2)  # measured −10.5 %
    assert force.min() >= 0.0


def test_batch_solver_with_a_user_time_step_equals_simulate():
    template = Crossing(SHORT, CAR, tire=MultiPointTire(3), speed=10.0, approach=1.0, free_vibration=0.05, dt=4e-4)
    roads = [random_profile(RoadPSD.iso("C"), seed=s, length=100.0) for s in (1, 2, 3)]
    batch = BatchSolver(template)
    assert batch.time_step(template.with_road(roads[0])) == 4e-4  # the user's step, not the automatic one
    results = batch.run_many(roads)
    for road, res in zip(roads, results):
        alone = simulate(template.with_road(road))
        assert res.dt == alone.dt == 4e-4
        # lanes = the single-crossing arithmetic: round-off (measured ≤ 1e-15 of the peak)
        for field in ("xi", "q", "wheel_forces"):
            a, b = getattr(res, field), getattr(alone, field)
            assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), field


def _worst(a, b) -> float:
    """max |a − b| / peak |b| over the histories of two results."""
    return max(float(np.abs(getattr(a, h) - getattr(b, h)).max() / np.abs(getattr(b, h)).max())
               for h in ("xi", "q", "wheel_forces"))


@pytest.mark.usefixtures("linear_wheel_loads")
@pytest.mark.parametrize("tire", [DiskTire(spacing=0.02), RigidDiskTire(spacing=0.02)], ids=lambda t: t.name)
def test_batch_lanes_that_lift_off_equal_the_full_kernel_and_single_runs(tire):
    """Lanes of one batch over bumps of 0 (flat), 2, 80 and 5 mm: the 80 mm bump launches the wheel
    and the others do not, so the lanes' contact sets differ.  Disk tires: the many-lane lean kernel
    freezes the launched lane at the step a contact closes within the updates and ``implicit`` finishes
    it (``integrators._run_lanes``).  Rigid disks, and ``without_lean`` for both: the many-lane
    ``implicit`` kernel (lanes with unequal contact sets updated one by one).  References: the many-lane
    ``implicit`` kernel (its own contact law and updates) and each road run alone (``simulate``); lanes
    equal them to round-off, a lane handed over to the tolerance's order (as tests/unit/test_lean_lanes.py:
    ≤ 1e-10, ≤ 1e-9 of each history's peak)."""
    heights = (0.0, 0.002, 0.08, 0.005)
    roads = [with_defects(RoadProfile.flat(-20.0, 20.0), [Defect.of_kind("bump", start=-1.5, size=h)]) if h else
             RoadProfile.flat(-20.0, 20.0) for h in heights]
    template = Crossing(SHORT, CAR, tire=tire, road=roads[2], speed=10.0, approach=2.0, free_vibration=0.0, dt=5e-4)
    lanes, full, alone, ran = _batch(template, roads)
    lifted = [bool(np.any(r.wheel_forces[:, 0] == 0.0)) for r in full]
    assert lifted == [False, False, True, False]
    if isinstance(tire, RigidDiskTire):
        assert ran["implicit"] >= 1 and ran["lanes"] == ran["lanes_fallback"] == 0
    else:
        assert ran["lanes_fallback"] >= 1  # the launched lane was handed over
    for k, (lane, ref, single) in enumerate(zip(lanes, full, alone)):
        tol = 1e-9 if lifted[k] else 1e-10
        assert _worst(lane, ref) <= tol and _worst(lane, single) <= tol, k
    assert _worst(lanes[2], lanes[3]) > 1e-2  # the lanes do differ


def test_parapets_add_to_the_edge_girder_lines():
    """One girder line (both edges at once) with a parapet of EI_p, m_p on each edge: its bending
    modes are those of the beam with EI + 2 EI_p and m + 2 m_p."""
    span, t, b, E = 16.76, 0.20, 2.13, 33e9
    IN = 0.0254  # AASHTO Type II (PCI tables): A 369 in², y_b 15.83 in, h 36 in, I 50 979 in⁴
    A, yb, h, Ig = 369 * IN**2, 15.83 * IN, 36 * IN, 50979 * IN**4
    yna = (A * yb + b * t * (h + t / 2)) / (A + b * t)
    EI = E * (Ig + A * (yna - yb) ** 2 + b * t**3 / 12 + b * t * (h + t / 2 - yna) ** 2)
    m = 2400.0 * (A + b * t)
    EIp, mp = 2.0e9, 300.0
    deck = SlabOnGirderBridge(span=span, n_girders=1, overhang=b / 2, E_girder=E, E_deck=E, n_modes=8,
                              parapet_EI=EIp, parapet_mass=mp, use_cache=False)
    bending = [k for k, d in enumerate(deck.mode_descriptions()) if d.startswith("bending")][:2]
    f = deck.frequencies_hz[bending]
    closed = (np.arange(1, 3) * np.pi / span) ** 2 * np.sqrt((EI + 2 * EIp) / (m + 2 * mp)) / (2 * np.pi)
    assert f == pytest.approx(closed, rel=2e-5)  # as the grillage without parapets (measured 1e-6)
    bare = (np.arange(1, 3) * np.pi / span) ** 2 * np.sqrt(EI / m) / (2 * np.pi)
    assert np.all(np.abs(f / bare - 1) > 0.05)  # the parapets matter here


def test_max_frequency_widens_the_eigen_search():
    """max_frequency above what the first n_modes reach: the solver asks for more modes until
    it passes the limit; the result is every mode below it (the same as a large fixed count)."""
    kw = dict(span=9.16, n_girders=3, n_elements=12, use_cache=False)
    ref = SlabOnGirderBridge(n_modes=40, **kw).frequencies_hz
    limit = 0.5 * (ref[24] + ref[25])  # 25 modes below: more than the first request of 10
    b = SlabOnGirderBridge(n_modes=4, max_frequency=limit, **kw)
    assert b.frequencies_hz.size == 25
    assert b.frequencies_hz == pytest.approx(ref[:25], rel=1e-9)


@pytest.mark.parametrize("tire", [MultiPointTire(4), DiskTire(spacing=0.02)], ids=lambda t: t.name)
def test_contact_length_outputs(tire):
    r = simulate(Crossing(SHORT, CAR, tire=tire, speed=5.0, approach=1.5, free_vibration=0.0))
    s = summary(r, point_response(r))
    cols = histories(r, point_response(r))
    before = r.front_position[:, 0] < -0.4
    length = r.contact_lengths[before, 0]
    if isinstance(tire, MultiPointTire):
        expected = tire.contact_length  # n points of width a/n
        assert length == pytest.approx(expected, rel=1e-12)
    else:
        load, k = float(CAR.static_wheel_loads()[0]), CAR.wheels[0].stiffness
        expected = 2 * math.sqrt(2 * tire.radius * tire.static_compression(k, load))  # 2√(2R d_s)
        assert abs(length[0] - expected) <= tire.spacing + 0.02 * expected
    name = CAR.wheels[0].name
    assert np.array_equal(cols[f"contact_length_{name}"], r.contact_lengths[:, 0])
    lo, hi = s["contact_length_range"][name]
    assert lo == r.contact_lengths[:, 0].min() and hi == r.contact_lengths[:, 0].max() and hi >= length[0]
    point = simulate(Crossing(SHORT, CAR, speed=5.0, approach=1.5, free_vibration=0.0))
    assert not any(k.startswith("contact_length") for k in histories(point, point_response(point)))


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_moving_force_on_one_mode_against_closed_form(integrator):
    """A vehicle without DOFs (a moving force) on one mode: ξ'' + ω²ξ = −P a sin(Ωt), zero start,
    q(t) = −P a [sin Ωt − S sin ωt] / (ω² − Ω²), S = Ω/ω (Biggs 1964 §8.5)."""
    from vbikit.vehicle import moving_force

    beam = EulerBernoulliBeam(span=10.0, EI=1e9, mass_per_length=2000.0, damping_ratio=0.0, n_modes=1)
    P, v = 5e4, 20.0
    r = simulate(Crossing(beam, moving_force(P), speed=v, approach=0.0, free_vibration=0.0, dt=2e-4,
                          integrator=integrator))
    on = r.time <= beam.span / v
    t = r.time[on]
    w, big, a = beam.omega[0], math.pi * v / beam.span, math.sqrt(2 / (2000.0 * 10.0))
    ref = -P * a * (np.sin(big * t) - big / w * np.sin(w * t)) / (w * w - big * big)
    err = np.abs(r.xi[on, 0] - ref).max() / np.abs(ref).max()
    # measured: RK4 9.1e-10, Newmark 4.6e-5 (its period error (ω dt)²/12 accumulated over 0.5 s)
    assert err <= {"rk4": 5e-9, "newmark": 2e-4}.get(integrator, 2e-4)


def test_static_start_falls_back_to_rest_when_a_tire_would_pull(caplog, monkeypatch):
    """A profile with 5 m steps (millimetres read as metres): the dashpot forces c·v·r' at t = 0
    would pull, so no equilibrium at speed exists; the start is the one at rest, with a warning."""
    from vbikit.solve import system

    monkeypatch.setattr(system, "_START_LOGGED", set())  # (as in a fresh process)
    x = np.arange(-20.0, 20.0, 1.0)
    road = RoadProfile(x, 5.0 * ((x // 2) % 2), "steps")
    # at x = −3 m the road rises 5 m over 1 m: the dashpot (c = 500 N·s/m) would push with
    # c·v·r' = 25 kN against a weight of 4.4 kN, so the spring would have to pull
    assert road.slope(-3.0) == 5.0
    with caplog.at_level("WARNING", logger="vbikit.solve.system"):
        r = simulate(Crossing(SHORT, CAR, road=road, speed=10.0, approach=3.0, free_vibration=0.0))
    assert "equilibrium at rest" in caplog.text
    assert np.all(r.q_dot[0] == 0.0)
    on_rest = CAR.static_state(ground=[road.elevation(-3.0)])  # the rest equilibrium on the road there
    np.testing.assert_allclose(r.q[0], on_rest, rtol=1e-12, atol=1e-12)


def test_the_rest_start_warning_names_the_speed_in_words_and_comes_once(caplog, monkeypatch):
    """``vbikit study paper-all`` printed "no equilibrium with the tire dashpots' forces from the road
    rate at t = 0 (a tire would pull); …" twelve times from its workers, no speed, no cause named.
    The warning now says, in an engineer's words, at which speed the vehicle cannot start in
    equilibrium and why it may happen, once a process for the same speed."""
    from vbikit.solve import system

    monkeypatch.setattr(system, "_START_LOGGED", set())
    x = np.arange(-20.0, 20.0, 1.0)
    road = RoadProfile(x, 5.0 * ((x // 2) % 2), "steps")
    with caplog.at_level("WARNING", logger="vbikit.solve.system"):
        for _ in range(2):
            simulate(Crossing(SHORT, CAR, road=road, speed=10.0, approach=3.0, free_vibration=0.0))
    (record,) = [r for r in caplog.records if r.name == "vbikit.solve.system"]
    text = record.getMessage()
    assert "cannot start at 36 km/h" in text and "tire dampers' forces" in text and "equilibrium at rest" in text


def test_no_rest_start_warning_when_a_run_in_sets_the_start(caplog, monkeypatch):
    """With a run-in the vehicles' start state is the run-in's (``vbikit.solve.run_in``) and every contact point
    starts off the deck, so the static start's fallback to rest changes nothing: no warning (a trial's traffic
    stream on a class F road printed it, though every truck started settled; the warning is kept for a start
    without a run-in, the test above)."""
    from vbikit.solve import system

    monkeypatch.setattr(system, "_START_LOGGED", set())
    x = np.arange(-20.0, 20.0, 1.0)
    road = RoadProfile(x, 5.0 * ((x // 2) % 2), "steps")
    with caplog.at_level("WARNING", logger="vbikit.solve.system"):
        r = simulate(Crossing(SHORT, CAR, road=road, speed=10.0, approach=3.0, free_vibration=0.0, run_in=10.0))
    assert "equilibrium at rest" not in caplog.text
    assert np.any(r.q_dot[0] != 0.0)  # (the run-in's moving state, not the rest the fallback would give)


@pytest.mark.parametrize("vx, cell", [(20.0, 1), (-20.0, 0), (0.0, 1)])
def test_road_rate_on_a_station_is_that_of_the_cell_entered(vx, cell):
    """A point exactly on a road station (a kink of the piecewise-linear profile) takes the slope of
    the cell it moves into — +x side driving +x (or at rest), −x side driving −x — so a vehicle
    driving −x sees the mirror image of one driving +x; the elevation is the station's either way."""
    from vbikit.solve.kernels import Road, road_point

    stations = np.array([0.0, 1.0, 2.0])
    z = np.array([0.0, 0.01, -0.02])  # slopes +0.01 then −0.03
    road = Road(stations, z.reshape(1, 3, 1), float(z.max()))
    idx = np.full(1, -1, np.int64)
    rv, rr = np.zeros((1, 1)), np.zeros((1, 1))
    road_point(1.0, vx, 0, 0, road, idx, rv, rr, (0,), 0.0)  # span 0: the cell's slope (RK4's rate)
    slope = np.diff(z)[cell]
    assert rv[0, 0] == pytest.approx(0.01, abs=1e-15)
    assert rr[0, 0] == pytest.approx(vx * slope, abs=1e-15)


@pytest.mark.parametrize("vx", [20.0, -20.0])
def test_secant_road_rate_spans_the_kink_by_hand(vx):
    """With span s > 0 (the implicit integrators' dt/2) the rate is v (r(x + a) − r(x − a)) / 2a,
    a = |v| s: on the kink at x = 1 m of slopes +0.01 and −0.03 with a = 1 cm, by hand
    r(1.01) = 0.0097, r(0.99) = 0.0099, so dr/dx = −0.01 for either direction (the cell's slope would
    be +0.01 or −0.03 by direction); the elevation stays the station's."""
    from vbikit.solve.kernels import Road, road_point

    stations = np.array([0.0, 1.0, 2.0])
    z = np.array([0.0, 0.01, -0.02])
    road = Road(stations, z.reshape(1, 3, 1), float(z.max()))
    rv, rr = np.zeros((1, 1)), np.zeros((1, 1))
    road_point(1.0, vx, 0, 0, road, np.full(1, -1, np.int64), rv, rr, (0,), 0.01 / 20.0)
    assert rv[0, 0] == pytest.approx(0.01, abs=1e-15)
    assert rr[0, 0] == pytest.approx(vx * -0.01, abs=1e-13)


@pytest.mark.parametrize("k", [0.9, 0.98, 1.0, 1.02, 1.5])
def test_secant_road_rate_trapezoid_follows_the_road_crossed(k):
    """The implicit integrators take a dashpot's load as linear over each step, so the road rates they read
    at the step ends integrate by the trapezoid.  With the secant rate over x ∓ v dt/2 that sum telescopes:
    Σ_{n<N} dt (ṙ_n + ṙ_{n+1})/2 = [r(x_{N−½}) + r(x_{N+½}) − r(x_{−½}) − r(x_{½})]/2 exactly (r read here
    from the profile itself, ``RoadProfile.evaluate``), at any step — also one that is not a whole number
    of 1 cm stations (k × 2 cm), where the cells' slopes drift off by their in-cell offsets."""
    from vbikit.road import RoadPSD, random_profile
    from vbikit.solve.kernels import Road, road_point

    profile = random_profile(RoadPSD.iso("C"), length=30.0, seed=3)
    road = Road(np.ascontiguousarray(profile.x, float), np.asarray(profile.z, float).reshape(1, -1, 1).copy(),
                float(np.max(profile.z)))
    v = 20.0
    dt = k * 0.02 / v
    x = 5.0 + v * dt * np.arange(400)
    rr, rr_cell = np.zeros(x.size), np.zeros(x.size)
    for out, span in ((rr, 0.5 * dt), (rr_cell, 0.0)):
        idx = np.full(1, -1, np.int64)
        for n, xn in enumerate(x):
            rv1, rr1 = np.zeros((1, 1)), np.zeros((1, 1))
            road_point(xn, v, 0, 0, road, idx, rv1, rr1, (0,), span)
            out[n] = rr1[0, 0]
    r = lambda s: profile.evaluate(np.atleast_1d(s))[0][0]  # noqa: E731
    h = 0.5 * v * dt
    expected = 0.5 * (r(x[-1] - h) + r(x[-1] + h) - r(x[0] - h) - r(x[0] + h))
    trapezoid = 0.5 * dt * float(np.sum(rr[1:] + rr[:-1]))
    assert trapezoid == pytest.approx(expected, abs=1e-12)
    drift = np.cumsum(0.5 * dt * (rr_cell[1:] + rr_cell[:-1]) - np.diff([r(s) for s in x]))
    if k not in (1.0, 1.5):  # steps of a whole number of stations: the cells' offsets do not drift
        assert np.max(np.abs(drift)) > 1e-5  # the cell slope's trapezoid strays from the road crossed
