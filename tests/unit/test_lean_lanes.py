"""The many-lane lean kernel (vbikit.solve.kernels.lean_lanes) against the full implicit kernel.

A batch of roads (``BatchSolver.run_many``: lanes of one kernel call) runs through ``lean_lanes``
(``lean``'s step for every lane at once, the lane index innermost, ``LANES_CHUNK`` steps a call); a
lane whose step needs more is frozen there, runs alone from its last stored row to the end of the
chunk — ``implicit`` for the contact event's ``LEAN_WINDOW`` steps, then the one-lane ``lean`` — and
rejoins the lanes at the next call (``integrators._run_lanes``, ``_finish_lane``).
With ``integrators.USE_LEAN`` off the same batch runs through the many-lane ``implicit`` kernel: the
independent code path (its own contact law ``contact_forces``, state and update helpers), the
reference here, and so is each road run alone (``simulate``: one lane, ``lean``).

Lanes that ``lean_lanes`` completes take the same arithmetic as both (the same first guess,
quasi-Newton updates and exact increments, to the same tolerance): measured ≤ 3.8e-13 of each
history's peak (fastmath reorders the sums; ``lean_lanes`` forms P Φ and P L0 once), asserted ≤ 1e-10, as for one lane
(tests/unit/test_lean_kernel.py).  A frozen lane restarts from a stored state (the law there, the
forces extrapolated from it alone) and so differs from an uninterrupted ``implicit`` run by the
tolerance's order (IMPLICIT_TOLERANCE = 1e-10 of the largest wheel load; accelerations amplify it):
measured ≤ 4e-10 of the peak, asserted ≤ 1e-9 as for one lane; from its road run alone, which hands
over at the same steps, by round-off (it rejoins the lanes with the state its one-lane run leaves).
"""
from __future__ import annotations

import tomllib

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.scenario import demo_scenario_text, parse_scenario
from vbikit.scenario.preflight import preflight
from vbikit.solve import Crossing, integrators, simulate
from vbikit.solve.batch import BatchSolver
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import hs20_44, semitrailer_3s2

HISTORIES = ("xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces", "contact_lengths")


def _worst(a, b) -> float:
    """max |a − b| / peak |b| over every history."""
    return max(float(np.max(np.abs(getattr(a, h) - getattr(b, h)))) / max(float(np.max(np.abs(getattr(b, h)))), 1e-300)
               for h in HISTORIES)


def _crossing(spec: dict):
    return preflight(parse_scenario(spec)).built.crossing


def _roads(spec: dict, classes_seeds) -> list:
    """The scenario's road for each (ISO class, seed): same stations and spacing."""
    return [_crossing({**spec, "road": {"class": c, "seed": s}}).road for c, s in classes_seeds]


def _batch(crossing, roads, singles: bool = True):
    """The roads as lanes by the default dispatch (``lean_lanes``) and by ``implicit`` alone, each
    road alone (``simulate``) when ``singles``, and the per-lane counts of the first run."""
    solver = BatchSolver(crossing)
    before = dict(integrators.LEAN_COUNTS)
    lanes = solver.run_many(roads)
    ran = {k: integrators.LEAN_COUNTS[k] - before[k] for k in before}
    with integrators.without_lean():
        full = solver.run_many(roads)
    alone = [simulate(crossing.with_road(*(r if isinstance(r, tuple) else (r,)))) for r in roads] if singles else None
    return lanes, full, alone, ran


def _paper(tire: str, speed: float = 75.0, model: str = "paper-bridge-1-beam") -> dict:
    return {"bridge": {"model": model}, "vehicle": {"model": "hs20-44"}, "tire": {"model": tire},
            "road": {"class": "C", "seed": 1}, "crossing": {"speed_kmh": speed}}


@pytest.mark.usefixtures("linear_wheel_loads")
def test_demo_crossing_on_roads_b_to_d_equals_implicit_and_single_runs():
    """`vbikit demo` (HS20-44, multipoint n = 6: 36 gated points, 75 km/h) on 6 roads of classes
    B–D: every lane completed by ``lean_lanes``; the class D roads take their own step (2 cm of road,
    ``vbikit.solve.timestep.exact_road_per_step``), so two calls, each padded to 8 lanes."""
    spec = tomllib.loads(demo_scenario_text())
    crossing = _crossing(spec)
    roads = [crossing.road] + _roads(spec, [("B", 2), ("B", 3), ("C", 4), ("D", 5), ("D", 6)])
    lanes, full, alone, ran = _batch(crossing, roads)
    assert ran["lanes"] == 16 and ran["lanes_fallback"] == 0 and ran["implicit"] == 0
    assert lanes[4].dt == lanes[5].dt < lanes[3].dt == lanes[0].dt
    for lane, ref, single in zip(lanes, full, alone):
        assert _worst(lane, ref) <= 1e-10
        assert _worst(lane, single) <= 1e-10
    assert _worst(lanes[1], lanes[3]) > 1e-3 and _worst(lanes[4], lanes[5]) > 1e-3  # the lanes differ (another road each)


@pytest.mark.usefixtures("linear_wheel_loads")
def test_point_tires_equal_implicit_and_single_runs():
    spec = _paper("point", 60.0)
    roads = _roads(spec, [("B", 3), ("C", 7), ("D", 8)])
    lanes, full, alone, ran = _batch(_crossing(spec), roads)
    assert ran["lanes"] == 8 and ran["lanes_fallback"] == 0
    for lane, ref, single in zip(lanes, full, alone):
        assert _worst(lane, ref) <= 1e-10
        assert _worst(lane, single) <= 1e-10


@pytest.mark.usefixtures("linear_wheel_loads")
def test_lift_off_freezes_some_lanes_only_and_the_full_kernel_finishes_them():
    """Disk tires at 100 km/h: on some class E roads (seeds 3 and 7; not 1 or 6; with the start's road
    rate read ahead, 2026-12-05 — before, 6 and 7) a landing closes a
    contact within a step's updates (the lane is frozen there and runs alone to the end of the chunk), on these class A
    roads nothing does (seed 8 of class A hands over at its first step: a point at a disk patch's edge
    changes its contact there).  Frozen lanes differ from ``implicit`` by the tolerance's order,
    the others by round-off; each lane equals its road run alone (one lane: ``lean``, handing over
    to ``implicit`` the same way) to round-off, frozen or not (measured ≤ 2.6e-13 of the peak: a frozen lane
    rejoins with the state its one-lane run leaves, or sits out the calls to the end of a window that
    crosses a chunk's end, ``integrators._run_lanes``; before 2026-12-07 it restarted afresh at its
    chunk's end and differed by the tolerance's order)."""
    spec = _paper("disk", 100.0)
    roads = _roads(spec, [("E", 6), ("A", 2), ("E", 7), ("A", 4), ("E", 1), ("A", 6), ("E", 3), ("A", 10)])
    stops: list = []
    from vbikit.solve import kernels

    original = kernels.lean_lanes

    def spy(*args):  # the lanes each call (a chunk of steps) stops: ``stop``, after tol and stride
        out = original(*args)
        stops.append(args[-10].copy())
        return out

    kernels.lean_lanes = spy
    try:
        lanes, full, alone, ran = _batch(_crossing(spec), roads)
    finally:
        kernels.lean_lanes = original
    frozen = np.any(np.array(stops) >= 0, axis=0)
    assert len(stops) > 1  # chunks of LANES_CHUNK steps
    assert 0 < ran["lanes_fallback"] == int(frozen.sum()) < 8
    assert not frozen[1::2].any()  # the class A roads stay lean
    for k, (lane, ref, single) in enumerate(zip(lanes, full, alone)):
        assert _worst(lane, ref) <= (1e-9 if frozen[k] else 1e-10)
        assert _worst(lane, single) <= 1e-10
    assert any(int(np.sum(r.wheel_forces[1:] == 0.0)) > 10 for r in full)  # a wheel does leave the road


@pytest.mark.usefixtures("linear_wheel_loads")
def test_a_frozen_lane_runs_the_full_kernel_for_the_contact_events_window_only(monkeypatch):
    """The lift-off batch in one chunk (``LANES_CHUNK`` above the run's steps): a frozen lane goes on
    with ``implicit`` for the event's ``LEAN_WINDOW`` steps a call, then with the one-lane ``lean``
    (until 2026-12-06 ``implicit`` ran it to the chunk's end), and still equals ``implicit`` and its
    road run alone by the tolerance's order."""
    from vbikit.solve import kernels

    monkeypatch.setattr(integrators, "LANES_CHUNK", 10**6)
    spec = _paper("disk", 100.0)
    roads = _roads(spec, [("E", 6), ("A", 2), ("E", 7), ("A", 4), ("E", 1), ("A", 6), ("E", 3), ("A", 10)])
    crossing = _crossing(spec)
    full_kernel, full_steps = kernels.implicit, []

    def full_spy(dt, motion, *args):  # steps a call of the full kernel runs (half-step rows 2·steps + 1)
        full_steps.append((motion.travel.shape[0] - 1) // 2)
        return full_kernel(dt, motion, *args)

    before = integrators.LEAN_COUNTS["lanes_fallback"]
    monkeypatch.setattr(kernels, "implicit", full_spy)
    lanes = BatchSolver(crossing).run_many(roads)
    monkeypatch.setattr(kernels, "implicit", full_kernel)
    assert integrators.LEAN_COUNTS["lanes_fallback"] > before  # lanes were handed over
    assert full_steps and max(full_steps) <= integrators.LEAN_WINDOW
    _, full, alone, _ = _batch(crossing, roads)
    for lane, ref, single in zip(lanes, full, alone):
        assert _worst(lane, ref) <= 1e-9
        assert _worst(lane, single) <= 1e-9


@pytest.mark.usefixtures("linear_wheel_loads")
def test_asymmetric_vehicles_equal_implicit_and_single_runs():
    """A 3S2 driving +x 1.2 m off the centreline and an HS20-44 driving −x, entering later, at other
    speeds (stacked vehicles, two directions) over 3 roads."""
    beam = EulerBernoulliBeam(span=30.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=12)
    roads = [random_profile(RoadPSD.iso(c), length=120.0, seed=s, x_start=-50.0) for c, s in (("B", 4), ("C", 5), ("B", 6))]
    crossing = Crossing(beam, road=roads[0], approach=3.0, free_vibration=0.1,
                        vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=1.2),
                                  VehicleMotion(hs20_44(), 17.0, direction="-x", entry_time=0.4)))
    lanes, full, alone, ran = _batch(crossing, roads)
    assert ran["lanes"] == 8 and ran["lanes_fallback"] == 0
    for lane, ref, single in zip(lanes, full, alone):
        assert _worst(lane, ref) <= 1e-10
        assert _worst(lane, single) <= 1e-10


@pytest.mark.parametrize("every", [3])
def test_thinned_lanes_are_rows_of_the_full_histories(every):
    """Stored every 3rd step (``integrate``'s ``stride``): the rows of every step, thinned."""
    from vbikit.solve.simulate import integrate

    spec = _paper("point", 60.0)
    crossing = _crossing(spec)
    roads = _roads(spec, [("B", 3), ("C", 7)])
    solver = BatchSolver(crossing)
    crossings = [solver.crossing(r) for r in roads]
    grid = solver._grid(solver.time_step(crossings[0]))
    every_step = integrate(crossings, solver.data, grid)
    thin = integrate(crossings, solver.data, grid, every)
    for a, b in zip(thin, every_step):
        for h in HISTORIES:
            np.testing.assert_array_equal(getattr(a, h), getattr(b, h)[::every])


def test_chunks_carry_the_lanes_exactly(monkeypatch):
    """``lean_lanes`` takes ``LANES_CHUNK`` steps a call and carries each lane's state (last two
    steps' forces, modal and wheel loads) to the next: lanes no step froze are the same to the last
    bit whatever the chunk (here 1,914 steps in one call, in calls of 128 and of 7 steps)."""
    spec = _paper("multipoint")
    crossing = _crossing(spec)
    roads = _roads(spec, [("B", 3), ("C", 7), ("D", 8)])
    runs = []
    for chunk in (10**6, 128, 7):
        monkeypatch.setattr(integrators, "LANES_CHUNK", chunk)
        before = integrators.LEAN_COUNTS["lanes_fallback"]
        runs.append(BatchSolver(crossing).run_many(roads))
        assert integrators.LEAN_COUNTS["lanes_fallback"] == before
    for other in runs[1:]:
        for a, b in zip(other, runs[0]):
            for h in HISTORIES:
                np.testing.assert_array_equal(getattr(a, h), getattr(b, h))


@pytest.mark.usefixtures("linear_wheel_loads")
def test_lift_off_with_thinned_histories_equals_implicit():
    """The lift-off batch stored every 7th step (``integrate``'s ``stride``: chunks of 126 steps, a
    frozen lane restarting from the last stored row): measured ≤ 8.8e-11 of the peak on the lanes
    handed over, 3.7e-13 on the others, against ``implicit`` with the same stride."""
    from vbikit.solve.simulate import integrate

    spec = _paper("disk", 100.0)
    roads = _roads(spec, [("E", 6), ("A", 2), ("E", 7), ("A", 6)])
    solver = BatchSolver(_crossing(spec))
    crossings = [solver.crossing(r) for r in roads]
    grid = solver._grid(solver.time_step(crossings[0]))
    before = dict(integrators.LEAN_COUNTS)
    lanes = integrate(crossings, solver.data, grid, 7)
    handed = integrators.LEAN_COUNTS["lanes_fallback"] - before["lanes_fallback"]
    with integrators.without_lean():
        full = integrate(crossings, solver.data, grid, 7)
    assert handed > 0
    for lane, ref in zip(lanes, full):
        assert _worst(lane, ref) <= 1e-9
    for k in (1, 3):  # class A roads: not handed over
        assert _worst(lanes[k], full[k]) <= 1e-10



def _bumped(road, start: float, height: float, width: float):
    """``road`` plus a cosine bump of ``height`` [m] over ``width`` [m] from ``start`` [m], on its own
    stations (the road's resolution, so the time step stays)."""
    from vbikit.road.profile import RoadProfile

    u = (road.x - start) / width
    bump = np.where((u >= 0.0) & (u <= 1.0), 0.5 * height * (1.0 - np.cos(2.0 * np.pi * np.clip(u, 0.0, 1.0))), 0.0)
    return RoadProfile(road.x, road.z + bump, road.label + " + bump", road.resolution)


@pytest.mark.usefixtures("linear_wheel_loads")
def test_disk_points_on_bumps_are_not_left_out():
    """The shared lazy test leaves a disk point out only when it cannot touch in any lane (bound
    r_p − g_p − z_w + Σ amp |ξ| ≤ 0 with the road r_p under the point).  A narrow bump (6 cm high,
    4 cm wide) on the deck meets the disk's leading points first, whose gaps g_p = R − √(R² − ξ²)
    (up to 0.1 m) are far above the static compression (≈ 3 cm), while the patch at the bottom still
    presses: a point wrongly left out would miss a force of order k_p δ_p ≈ 1 kN, ≈ 1e-2 of the
    peak wheel load, against ``implicit`` (its own contact law, lazy bound with the highest
    elevation r_max).  Lanes 0–3 carry the bumps (four positions on the 9.16 m deck), lanes 4–7
    the same roads without: the bumps change the wheel loads by more than 5 kN, and at least
    one bumped lane runs lean throughout."""
    from vbikit.solve import kernels

    spec = _paper("disk", 100.0)
    roads = _roads(spec, [("A", 2), ("B", 4), ("A", 6), ("B", 8)])
    bumped = [_bumped(r, s, 0.06, 0.04) for r, s in zip(roads, (2.0, 4.5, 6.1, 8.0))]
    stops: list = []
    original = kernels.lean_lanes

    def spy(*args):
        out = original(*args)
        stops.append(args[-10].copy())
        return out

    kernels.lean_lanes = spy
    try:
        lanes, full, _, _ = _batch(_crossing(spec), bumped + roads, singles=False)
    finally:
        kernels.lean_lanes = original
    frozen = np.any(np.array(stops) >= 0, axis=0)
    assert not frozen[:4].all()
    for k, (lane, ref) in enumerate(zip(lanes, full)):
        assert _worst(lane, ref) <= (1e-9 if frozen[k] else 1e-10)
    for k in range(4):  # the bump does load the wheels
        assert float(np.max(np.abs(lanes[k].wheel_forces - lanes[k + 4].wheel_forces))) > 5e3
